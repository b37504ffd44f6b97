// Exact face-by-face inner products (core/schemes/tri/tri_gram.h) and the k-disc wavelets of paper 004
// (core/schemes/tri/tri_wavelets.h).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <array>
#include <map>
#include <random>
#include <algorithm>
#include <span>
#include <set>
#include <string>
#include <variant>

#include "core/complex/complex_build.h"
#include "core/analysis/inner_products.h"
#include "core/complex/refine_tri.h"
#include "core/io/lattice/shape_io.h"
#include "core/schemes/tri/new_signatures.h"
#include "core/schemes/tri/tri_gram.h"
#include "core/schemes/tri/tri_local.h"
#include "core/schemes/tri/tri_rules.h"
#include "core/schemes/tri/tri_wavelets.h"
#include "core/schemes/tri/tri_transform.h"
#include "core/engine/executor.h"
#include "core/analysis/sphere_resample.h"
#include "core/schemes/registry.h"
#include "core/base/parallel.h"

using namespace sublift;

namespace {

// A flat torus of w x h lattice cells, every vertex of valence 6; vertex (i, j) = i + w j, the
// triangles of inner_products.h's lattice ({(i,j),(i+1,j),(i,j+1)}, {(i+1,j),(i+1,j+1),(i,j+1)}).
Complex regular_torus(int w, int h) {
  Csr faces;
  const auto v = [&](int i, int j) { return static_cast<std::uint32_t>(((i + w) % w) + w * ((j + h) % h)); };
  const auto tri = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    faces.items.insert(faces.items.end(), {a, b, c});
    faces.offsets.push_back(static_cast<std::uint32_t>(faces.items.size()));
  };
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      tri(v(i, j), v(i + 1, j), v(i, j + 1));
      tri(v(i + 1, j), v(i + 1, j + 1), v(i, j + 1));
    }
  return complex_from_polygons(static_cast<std::uint32_t>(w * h), faces);
}

// regular_torus with `flips` random edge flips, each keeping every valence at 4 or more and
// making no edge twice: irregular everywhere, so nearly every edge and face has a
// neighbourhood of its own (as on a fitted base).
Complex flipped_torus(int w, int h, int flips, unsigned seed) {
  const Complex reg = regular_torus(w, h);
  std::vector<std::array<std::uint32_t, 3>> tris;
  for (std::uint32_t f = 0; f < reg.num_faces(); ++f) tris.push_back({reg.faces.row(f)[0], reg.faces.row(f)[1], reg.faces.row(f)[2]});
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;  // undirected
  std::vector<int> valence(reg.num_vertices, 0);
  const auto key = [](std::uint32_t a, std::uint32_t b) { return std::make_pair(std::min(a, b), std::max(a, b)); };
  for (const auto& t : tris)
    for (int k = 0; k < 3; ++k)
      if (edges[key(t[k], t[(k + 1) % 3])]++ == 0) {
        ++valence[t[k]];
        ++valence[t[(k + 1) % 3]];
      }
  std::mt19937 rng(seed);
  for (int done = 0, tries = 0; done < flips && tries < 100 * flips; ++tries) {
    const std::size_t ti = rng() % tris.size();
    const int k = static_cast<int>(rng() % 3);
    const std::uint32_t a = tris[ti][k], b = tris[ti][(k + 1) % 3], c = tris[ti][(k + 2) % 3];
    std::size_t ui = tris.size();
    int kd = 0;
    for (std::size_t u = 0; u < tris.size() && ui == tris.size(); ++u)
      for (int q = 0; q < 3; ++q)
        if (tris[u][q] == b && tris[u][(q + 1) % 3] == a) {
          ui = u;
          kd = (q + 2) % 3;
        }
    const std::uint32_t d = tris[ui][kd];
    if (c == d || valence[a] <= 4 || valence[b] <= 4 || edges.count(key(c, d))) continue;
    tris[ti] = {c, a, d};  // (a, b, c) and (b, a, d) become (c, a, d) and (d, b, c)
    tris[ui] = {d, b, c};
    edges.erase(key(a, b));
    edges[key(c, d)] = 2;
    --valence[a];
    --valence[b];
    ++valence[c];
    ++valence[d];
    ++done;
  }
  Csr faces;
  for (const auto& t : tris) {
    faces.items.insert(faces.items.end(), t.begin(), t.end());
    faces.offsets.push_back(static_cast<std::uint32_t>(faces.items.size()));
  }
  return complex_from_polygons(reg.num_vertices, faces);
}

// All pairwise inner products of a mesh's scaling functions, face by face.
std::map<std::pair<std::uint32_t, std::uint32_t>, double> assemble(FaceGramCache& cache, const Complex& c) {
  const TriRings r = build_tri_rings(c);
  std::map<std::pair<std::uint32_t, std::uint32_t>, double> g;
  for (std::uint32_t f = 0; f < c.num_faces(); ++f) {
    const auto fg = cache.face_gram(c, r, f);
    for (std::size_t p = 0; p < fg.verts.size(); ++p)
      for (std::size_t q = 0; q < fg.verts.size(); ++q)
        g[{fg.verts[p], fg.verts[q]}] += (*fg.G)(static_cast<int>(p), static_cast<int>(q));
  }
  return g;
}

}  // namespace

// On the regular lattice the face-by-face Grams must sum to the lattice solution I(d) of
// core/inner_products (a different solver: one unknown per offset, Dahmen-Micchelli style).
TEST(TriGram, RegularTorusEqualsLatticeSolution) {
  const int w = 16, h = 16;
  const Complex torus = regular_torus(w, h);
  for (Scheme s : {Scheme::LinearTri, Scheme::Loop, Scheme::Butterfly}) {
    SCOPED_TRACE(static_cast<int>(s));
    FaceGramCache cache(s);
    const auto g = assemble(cache, torus);
    const ip::LatticeInnerProducts& lat = ip::cached_inner_products({s, 6});
    EXPECT_LE(cache.last_change(), 1e-16);
    double worst = 0;
    for (int dj = -5; dj <= 5; ++dj)
      for (int di = -5; di <= 5; ++di) {
        const std::uint32_t a = static_cast<std::uint32_t>(3 + w * 4);
        const std::uint32_t b = static_cast<std::uint32_t>(((3 + di + w) % w) + w * ((4 + dj + h) % h));
        const auto it = g.find({a, b});
        const double ours = it == g.end() ? 0.0 : it->second;
        worst = std::max(worst, std::abs(ours - lat.at({di, dj})));
      }
    EXPECT_LT(worst, 1e-14);
    // One type only: every face of a regular mesh looks the same.
    EXPECT_LE(cache.num_types(), 2u);
  }
}

// A torus only a few cells round: every face's patch wraps around it and closes up, so the
// patch is an annulus or the whole torus, not a disc. Every vertex is
// regular, so <phi_a, phi_b> on the torus is the lattice solution I(d) of core/inner_products
// (a different solver) summed over every lattice offset d that lands on b from a.
TEST(TriGram, ThinTorusEqualsWrappedLatticeSolution) {
  for (Scheme s : {Scheme::LinearTri, Scheme::Loop, Scheme::Butterfly}) {
    const ip::LatticeInnerProducts& lat = ip::cached_inner_products({s, 6});
    std::vector<std::pair<int, int>> sizes = {{3, 3}, {4, 5}, {16, 5}};
    for (int w = 3; w <= 14; ++w) sizes.emplace_back(w, 16);
    for (const auto& wh : sizes) {
      const int w = wh.first, h = wh.second;  // not a structured binding: clang 14 cannot capture one
      SCOPED_TRACE(std::to_string(static_cast<int>(s)) + " torus " + std::to_string(w) + " x " + std::to_string(h));
      const Complex torus = regular_torus(w, h);
      FaceGramCache cache(s);
      const auto g = assemble(cache, torus);
      EXPECT_LE(cache.last_change(), 1e-16);
      const auto id = [&](int i, int j) { return static_cast<std::uint32_t>(((i % w) + w) % w + w * (((j % h) + h) % h)); };
      for (const auto& [ai, aj] : {std::pair{0, 0}, std::pair{2, 1}}) {
        std::map<std::uint32_t, double> expected;
        for (std::size_t k = 0; k < lat.offsets.size(); ++k)
          expected[id(ai + lat.offsets[k].i, aj + lat.offsets[k].j)] += lat.values[k];
        double worst = 0;
        for (std::uint32_t b = 0; b < torus.num_vertices; ++b) {
          const auto it = g.find({id(ai, aj), b});
          const double ours = it == g.end() ? 0.0 : it->second;
          worst = std::max(worst, std::abs(ours - expected[b]));
        }
        EXPECT_LT(worst, 1e-14);
      }
    }
  }
}

// A torus decimated to 20 vertices (Sublift's own base mesh of a generated 60 x 20 torus): the
// patches its faces' Grams subdivide meet themselves at their rims, so the patch splits rim
// vertices (core/schemes/tri/tri_local.h); before it did, these Grams threw. Oracle: the
// two-scale relation on the whole mesh. Three levels finer every face's patch is a disc
// (checked), so G3 comes from unsplit patches, and the base's inner products must be
// G0 = S^T G3 S / 64 with S the three subdivision steps (each quarters the area).
TEST(TriGram, CoarseTorusMatchesTwoScaleRelation) {
  const std::vector<std::uint32_t> tris = {
      15, 0, 3,  13, 1, 0,   17, 6, 5,   18, 16, 2,  2, 19, 4,   19, 3, 4,   18, 2, 6,   3, 0, 4,
      0, 7, 4,   0, 1, 5,    0, 5, 7,    5, 6, 8,    6, 11, 8,   6, 9, 11,   6, 2, 9,    2, 4, 9,
      4, 10, 9,  4, 7, 10,   7, 5, 12,   5, 8, 12,   9, 14, 11,  12, 8, 16,  8, 11, 16,  10, 15, 9,
      10, 7, 15, 7, 13, 15,  7, 12, 13,  16, 11, 14, 9, 15, 14,  13, 12, 1,  12, 16, 17, 16, 18, 17,
      16, 14, 2, 14, 19, 2,  12, 17, 1,  14, 3, 19,  14, 15, 3,  15, 13, 0,  1, 17, 5,   17, 18, 6};
  Csr faces;
  for (std::size_t k = 0; k < tris.size(); k += 3) {
    faces.items.insert(faces.items.end(), tris.begin() + static_cast<long>(k), tris.begin() + static_cast<long>(k) + 3);
    faces.offsets.push_back(static_cast<std::uint32_t>(faces.items.size()));
  }
  std::vector<Complex> levels = {complex_from_polygons(20, faces)};
  for (int j = 0; j < 3; ++j) levels.push_back(refine_tri(levels.back()));
  const auto dense = [](const std::map<std::pair<std::uint32_t, std::uint32_t>, double>& g, std::uint32_t n) {
    Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n, n);
    for (const auto& [ab, v] : g) m(ab.first, ab.second) = v;
    return m;
  };
  // How many faces' patches had to split a rim vertex.
  const auto split_faces = [](const Complex& c, int radius) {
    const TriRings r = build_tri_rings(c);
    int n = 0;
    for (std::uint32_t f = 0; f < c.num_faces(); ++f) {
      std::uint32_t seeds[3], starts[3];
      face_seeds(c, f, seeds, starts);
      const LocalOrder o = local_order(r, seeds, starts, radius);
      n += local_patch(c, r, o).num_vertices != o.vertex.size();
    }
    return n;
  };
  for (Scheme s : {Scheme::LinearTri, Scheme::Loop, Scheme::Butterfly}) {
    SCOPED_TRACE(static_cast<int>(s));
    const int radius = tri_gram_radii(s).patch;
    // Patches of the base's refined faces (which its Gram's recursion builds) meet themselves at
    // level 1 (radius 4) or 2 (radius 6); at level 3 none do.
    EXPECT_GT(split_faces(levels[1], radius) + split_faces(levels[2], radius), 0);
    EXPECT_EQ(split_faces(levels[3], radius), 0);
    FaceGramCache cache(s);
    const Eigen::MatrixXd g0 = dense(assemble(cache, levels[0]), levels[0].num_vertices);
    const Eigen::MatrixXd g3 = dense(assemble(cache, levels[3]), levels[3].num_vertices);
    Eigen::MatrixXd sub = Eigen::MatrixXd::Identity(levels[0].num_vertices, levels[0].num_vertices);
    for (int j = 0; j < 3; ++j) {
      const Complex& c = levels[static_cast<std::size_t>(j)];
      const TriStencils st = build_tri_stencils(c, s);
      const std::uint32_t nf = levels[static_cast<std::size_t>(j) + 1].num_vertices;
      Eigen::MatrixXd step = Eigen::MatrixXd::Zero(nf, c.num_vertices);
      for (std::uint32_t v = 0; v < nf; ++v)
        for_each_stencil_weight(st, c.num_vertices, v, [&](std::uint32_t i, double w) { step(v, i) += w; });
      sub = step * sub;
    }
    const Eigen::MatrixXd expected = sub.transpose() * g3 * sub / 64.0;
    EXPECT_NEAR(g0.sum(), 40.0, 1e-12);  // partition of unity: the area, one per face
    EXPECT_EQ((g0 - g0.transpose()).cwiseAbs().maxCoeff(), 0.0);
    EXPECT_LT((g0 - expected).cwiseAbs().maxCoeff(), 1e-14);
  }
}

// Around an extraordinary vertex: the inner products sum to the area (partition of unity),
// are symmetric, and the n wedges give the same numbers (rotational symmetry).
TEST(TriGram, ExtraordinaryVertexSymmetricAndSumsToArea) {
  for (Scheme s : {Scheme::Loop, Scheme::Butterfly}) {
    for (int n : {3, 4, 5, 7, 9}) {
      SCOPED_TRACE(std::to_string(static_cast<int>(s)) + " valence " + std::to_string(n));
      const Complex disc = extraordinary_disc(n, 14);
      FaceGramCache cache(s);
      const TriRings r = build_tri_rings(disc);
      // Faces around the centre: vertex 0's fan.
      double total = 0;
      std::vector<double> self_of_spoke;
      std::map<std::pair<std::uint32_t, std::uint32_t>, double> g;
      for (std::uint32_t f : disc.vertex_faces.row(0)) {
        const auto fg = cache.face_gram(disc, r, f);
        total += fg.G->sum();
        EXPECT_EQ((*fg.G - fg.G->transpose()).cwiseAbs().maxCoeff(), 0.0);  // exactly: it is symmetrised
        for (std::size_t p = 0; p < fg.verts.size(); ++p)
          for (std::size_t q = 0; q < fg.verts.size(); ++q)
            g[{fg.verts[p], fg.verts[q]}] += (*fg.G)(static_cast<int>(p), static_cast<int>(q));
      }
      EXPECT_NEAR(total, n, 1e-13);
      // <phi_0, phi_spoke> is the same for each spoke (the fan's faces are one type rotated).
      const auto ring = r.ring.row(0);
      const auto at = [&](std::uint32_t x, std::uint32_t y) { return g[std::make_pair(x, y)]; };
      for (std::uint32_t k = 1; k < ring.size(); ++k) EXPECT_NEAR(at(0, ring[k]), at(0, ring[0]), 1e-15);
      EXPECT_LT(cache.last_change(), 1e-16);
    }
  }
}

// The k-disc wavelet is orthogonal to every scaling function of its disc (by construction, to
// rounding) and has a positive norm; with n = 6 it equals the regular one.
TEST(TriWavelets, OrthogonalToItsDiscAndRegularAtValenceSix) {
  for (Scheme s : {Scheme::LinearTri, Scheme::Loop, Scheme::Butterfly}) {
    for (int k : {1, 2, 3}) {
      TriWaveletBuilder b(s, k);
      for (int n : {3, 4, 6, 8}) {
        SCOPED_TRACE(std::to_string(static_cast<int>(s)) + " k " + std::to_string(k) + " n " + std::to_string(n));
        const Complex disc = extraordinary_disc(n, b.edge_radius() + 3);
        const TriRings r = build_tri_rings(disc);
        std::uint32_t e = UINT32_MAX;
        for (std::uint32_t x : disc.vertex_edges.row(0))
          if (disc.edge_verts[2 * x] == 1 || disc.edge_verts[2 * x + 1] == 1) e = x;
        ASSERT_NE(e, UINT32_MAX);
        std::vector<std::uint32_t> d;
        const EdgeWavelet& w = b.edge_wavelet(disc, r, e, &d);
        EXPECT_EQ(w.alpha.size(), d.size());
        EXPECT_LT(w.residual, 1e-12);
        EXPECT_GT(w.norm2, 0.0);
        EXPECT_LT(w.norm2, w.self);
      }
    }
  }
}

// The face-by-face solution at an extraordinary vertex against numerical integration: the
// level-K control values of phi_a, phi_b (subdivision of a unit coefficient with the library's
// stencils) integrated as piecewise-linear functions over the descendants of the centre's fan,
// then Richardson extrapolation. Butterfly interpolates, so the error is the piecewise-linear
// one: K = 3, 4, 5 with ratios 1/4, 1/16. Loop's control values approach the limit like
// lambda^K next to the extraordinary vertex (lambda = 3/8 + cos(2 pi / n) / 4, its subdominant
// eigenvalue), over an area 4^-K: K = 3..6 with ratios 1/4, lambda/4, 1/16.
// The wavelets of a level's new neighbourhoods, solved together (their edges' parts on two
// threads), equal those solved one edge at a time on one thread, bit for bit, and the face
// type cache grows the same way: the types that are new are made in the same order.
TEST(TriWavelets, SolvedTogetherOnTwoThreadsAsOneByOne) {
  const int threads = parallel_threads();
  // Butterfly's wide neighbourhoods make a type of nearly every face near a flip: fewer flips.
  for (const auto& [s, flips] : {std::pair{Scheme::LinearTri, 40}, {Scheme::Loop, 40}, {Scheme::Butterfly, 4}}) {
    SCOPED_TRACE(scheme_name(s));
    const Complex c = flipped_torus(12, 10, flips, 7);
    const Complex fine = refine_tri(c);
    const TriRings rings = build_tri_rings(c);
    const TriStencils st = build_tri_stencils(c, s);
    const auto level = [&] {
      auto lv = std::make_unique<TriLevel>();
      lv->coarse = &c;
      lv->coarse_rings = &rings;
      lv->fine = &fine;
      lv->stencils = &st;
      return lv;
    };
    set_parallel_threads(1);
    TriWaveletBuilder one(s, 1);
    const auto lv1 = level();
    std::vector<const EdgeWavelet*> by_one;
    for (std::uint32_t e = 0; e < c.num_edges(); ++e) by_one.push_back(&one.edge_wavelet(*lv1, e, nullptr));

    set_parallel_threads(2);
    TriWaveletBuilder two(s, 1);
    const auto lv2 = level();
    std::vector<std::uint32_t> todo;
    std::vector<std::string> signatures;
    std::map<std::string, std::size_t> first;
    std::vector<std::size_t> at(c.num_edges());
    for (std::uint32_t e = 0; e < c.num_edges(); ++e) {
      std::string sig = two.edge_key(*lv2, e).signature;
      const auto [it, inserted] = first.try_emplace(sig, todo.size());
      if (inserted) {
        todo.push_back(e);
        signatures.push_back(sig);
      }
      at[e] = it->second;
    }
    EXPECT_GT(todo.size(), c.num_edges() / 2) << "most neighbourhoods should be new";
    const std::vector<const EdgeWavelet*> together = two.solve(*lv2, todo, signatures);
    set_parallel_threads(threads);
    EXPECT_EQ(two.num_face_types(), one.num_face_types());
    for (std::uint32_t e = 0; e < c.num_edges(); ++e) {
      const EdgeWavelet& x = *by_one[e];
      const EdgeWavelet& y = *together[at[e]];
      ASSERT_EQ(x.alpha, y.alpha) << "edge " << e;
      ASSERT_EQ(x.norm2, y.norm2) << "edge " << e;
      ASSERT_EQ(x.self, y.self) << "edge " << e;
      ASSERT_LT(x.residual, 1e-12) << "edge " << e;
    }
  }
}

// The face types a level hands on (fine_face_types -> the next level's coarse_types, looked
// up without signatures) give the next level's new wavelets bit for bit as a builder that finds
// every face's type by its signature: on a torus with flipped edges (valences 4 to 8), two
// levels, for the three schemes.
TEST(TriWavelets, FaceTypesHandedOnSolveAsSignaturesDo) {
  for (const auto& [s, flips] : {std::pair{Scheme::LinearTri, 40}, {Scheme::Loop, 40}, {Scheme::Butterfly, 4}}) {
    SCOPED_TRACE(scheme_name(s));
    const Complex c0 = flipped_torus(12, 10, flips, 7);
    const Complex c1 = refine_tri(c0);
    const Complex c2 = refine_tri(c1);
    const TriRings r0 = build_tri_rings(c0), r1 = build_tri_rings(c1);
    const TriStencils st0 = build_tri_stencils(c0, s), st1 = build_tri_stencils(c1, s);
    // Every edge of `lv` whose signature `b` has not cached, one per signature.
    const auto new_edges = [](TriWaveletBuilder& b, TriLevel& lv, std::vector<std::uint32_t>& todo,
                              std::vector<std::string>& signatures) {
      std::set<std::string> seen;
      for (std::uint32_t e = 0; e < lv.coarse->num_edges(); ++e) {
        std::string sig = b.edge_key(lv, e).signature;
        if (!b.find(sig) && seen.insert(sig).second) todo.push_back(e), signatures.push_back(sig);
      }
    };
    TriWaveletBuilder handing(s, 1), fresh(s, 1);
    TriLevel l0;
    l0.coarse = &c0, l0.coarse_rings = &r0, l0.fine = &c1, l0.stencils = &st0;
    std::vector<std::uint32_t> todo;
    std::vector<std::string> signatures;
    new_edges(handing, l0, todo, signatures);
    handing.solve(l0, todo, signatures);
    const std::vector<std::int32_t> carry = handing.fine_face_types(l0);
    ASSERT_EQ(carry.size(), c1.num_faces());
    EXPECT_GT(std::count_if(carry.begin(), carry.end(), [](std::int32_t t) { return t >= 0; }), 0.9 * double(carry.size()));

    TriLevel with, without;
    for (TriLevel* lv : {&with, &without}) lv->coarse = &c1, lv->coarse_rings = &r1, lv->fine = &c2, lv->stencils = &st1;
    with.coarse_types = &carry;
    todo.clear(), signatures.clear();
    new_edges(handing, with, todo, signatures);
    ASSERT_GT(todo.size(), 50u);
    std::vector<std::string> copy = signatures;
    const auto a = handing.solve(with, todo, signatures);
    const auto b = fresh.solve(without, todo, copy);
    for (std::size_t i = 0; i < todo.size(); ++i) {
      ASSERT_EQ(a[i]->alpha, b[i]->alpha) << "edge " << todo[i];
      ASSERT_EQ(a[i]->norm2, b[i]->norm2) << "edge " << todo[i];
    }
  }
}

// A face type's Gram does not depend on the history of the cache: faces met in reverse order,
// or made on one thread instead of two, give every face the same matrix bit for bit. (Before
// local_patch sorted its faces, 117 of these types got subdivision matrices that differed in the
// last bits with the face that made them. The cycles met here are single self-similar types; the
// sweep order by signature, for cycles of several, is not exercised.)
TEST(TriGram, TypesIndependentOfOrderAndThreads) {
  const int threads = parallel_threads();
  for (Scheme s : {Scheme::Loop, Scheme::Butterfly}) {
    SCOPED_TRACE(scheme_name(s));
    // Butterfly's patches reach 6 rings: a torus wide enough that none wraps round.
    const Complex c = s == Scheme::Loop ? flipped_torus(12, 10, 40, 3) : flipped_torus(26, 24, 3, 3);
    const TriRings r = build_tri_rings(c);
    std::vector<FaceGramCache::FaceRef> forward, backward;
    for (std::uint32_t f = 0; f < c.num_faces(); ++f) forward.push_back({&c, &r, f});
    backward.assign(forward.rbegin(), forward.rend());
    FaceGramCache a(s), b(s), one(s);
    set_parallel_threads(2);
    a.add_types(forward);
    b.add_types(backward);
    set_parallel_threads(1);
    one.add_types(forward);
    set_parallel_threads(threads);
    EXPECT_EQ(a.num_types(), b.num_types());
    EXPECT_EQ(a.num_types(), one.num_types());
    for (std::uint32_t f = 0; f < c.num_faces(); ++f) {
      FaceGramCache::FaceGram ga, gb, g1;
      ASSERT_TRUE(a.find(c, r, f, ga) && b.find(c, r, f, gb) && one.find(c, r, f, g1)) << "face " << f;
      ASSERT_EQ(ga.verts, gb.verts);
      ASSERT_TRUE(*ga.G == *gb.G) << "face " << f << ": met in reverse order, max diff " << (*ga.G - *gb.G).cwiseAbs().maxCoeff();
      ASSERT_TRUE(*ga.G == *g1.G) << "face " << f << ": made on one thread";
    }
  }
}

TEST(TriGram, ExtraordinaryVertexMatchesNumericalIntegration) {
  for (Scheme s : {Scheme::Loop, Scheme::Butterfly}) {
    for (int n : {3, 5, 8}) {
      SCOPED_TRACE(std::to_string(static_cast<int>(s)) + " valence " + std::to_string(n));
      const bool loop = s == Scheme::Loop;
      const Complex disc = extraordinary_disc(n, loop ? 4 : 6);
      const TriRings r = build_tri_rings(disc);
      FaceGramCache cache(s);
      std::vector<std::uint32_t> fan(disc.vertex_faces.row(0).begin(), disc.vertex_faces.row(0).end());
      std::map<std::pair<std::uint32_t, std::uint32_t>, double> exact;
      for (std::uint32_t f : fan) {
        const auto fg = cache.face_gram(disc, r, f);
        for (std::size_t p = 0; p < fg.verts.size(); ++p)
          for (std::size_t q = 0; q < fg.verts.size(); ++q)
            exact[std::make_pair(fg.verts[p], fg.verts[q])] += (*fg.G)(static_cast<int>(p), static_cast<int>(q));
      }
      const std::uint32_t spoke = r.ring.row(0)[0], next = r.ring.row(0)[1];
      const std::uint32_t outer = r.ring.row(spoke)[3];  // a vertex two rings out
      const std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs = {
          {0, 0}, {0, spoke}, {spoke, spoke}, {spoke, next}, {spoke, outer}, {0, outer}};
      // Level-K values of all functions in `pairs` at once (one channel each).
      std::vector<std::uint32_t> funcs = {0, spoke, next, outer};
      const int nf = static_cast<int>(funcs.size());
      std::vector<std::vector<double>> estimates(pairs.size());
      Complex level = disc;
      std::vector<double> values(static_cast<std::size_t>(disc.num_vertices) * nf, 0.0);
      for (int i = 0; i < nf; ++i) values[static_cast<std::size_t>(funcs[static_cast<std::size_t>(i)]) * nf + i] = 1.0;
      for (int K = 1; K <= 6; ++K) {
        const TriStencils st = build_tri_stencils(level, s);
        values = subdivide_tri(st, values.data(), level.num_vertices, nf);
        level = refine_tri(level);
        if (K < 3) continue;
        const double area = std::pow(0.25, K);
        const std::size_t per = std::size_t{1} << (2 * K);
        for (std::size_t pi = 0; pi < pairs.size(); ++pi) {
          int ia = 0, ib = 0;
          for (int i = 0; i < nf; ++i) {
            if (funcs[static_cast<std::size_t>(i)] == pairs[pi].first) ia = i;
            if (funcs[static_cast<std::size_t>(i)] == pairs[pi].second) ib = i;
          }
          double sum = 0;
          for (std::uint32_t f : fan)
            for (std::size_t t = f * per; t < (f + 1) * per; ++t) {
              const auto row = level.faces.row(t);
              double uu = 0, su = 0, sv = 0;
              for (std::uint32_t v : row) {
                const double u = values[std::size_t{v} * nf + ia], w = values[std::size_t{v} * nf + ib];
                uu += u * w;
                su += u;
                sv += w;
              }
              sum += area / 12.0 * (uu + su * sv);
            }
          estimates[pi].push_back(sum);
        }
      }
      for (std::size_t pi = 0; pi < pairs.size(); ++pi) {
        std::vector<double> e = estimates[pi];
        const double lambda = 0.375 + 0.25 * std::cos(2 * M_PI / n);
        const std::vector<double> ratios = {0.25, loop ? lambda / 4 : 0.125, 1.0 / 16};
        for (double q : ratios) {
          for (std::size_t i = 0; i + 1 < e.size(); ++i) e[i] = (e[i + 1] - q * e[i]) / (1 - q);
          e.pop_back();
        }
        const double rich = e[0];
        const double ex = exact[pairs[pi]];
        EXPECT_NEAR(rich, ex, 1e-6) << "pair " << pairs[pi].first << "," << pairs[pi].second << " finest raw " << estimates[pi].back();
      }
    }
  }
}

// Linear k-disc wavelets against an independent computation: the hat functions' Gram matrices in
// closed form (ip::polyhedral_matrix, 004 Figure 4) on level j and on level j+1 (area 1/4), the
// right-hand side pulled back through the midpoint rule, and a dense solve.
TEST(TriWavelets, LinearEqualsClosedFormPolyhedralSolve) {
  for (int n : {3, 5, 6, 7}) {
    for (int k : {1, 2}) {
      SCOPED_TRACE("valence " + std::to_string(n) + " k " + std::to_string(k));
      TriWaveletBuilder b(Scheme::LinearTri, k);
      const Complex disc = extraordinary_disc(n, b.edge_radius() + 3);
      const TriRings r = build_tri_rings(disc);
      std::uint32_t e = UINT32_MAX;
      for (std::uint32_t x : disc.vertex_edges.row(0))
        if (disc.edge_verts[2 * x + 1] == 1) e = x;
      ASSERT_NE(e, UINT32_MAX);
      std::vector<std::uint32_t> d;
      const EdgeWavelet& w = b.edge_wavelet(disc, r, e, &d);
      // Closed form.
      const auto tris = [](const Complex& c) {
        std::vector<std::array<std::uint32_t, 3>> t;
        for (std::uint32_t f = 0; f < c.num_faces(); ++f) {
          const auto row = c.faces.row(f);
          t.push_back({row[0], row[1], row[2]});
        }
        return t;
      };
      const std::size_t nv = disc.num_vertices;
      const std::vector<double> I0 = ip::polyhedral_matrix(nv, tris(disc), 1.0);
      const Complex fine = refine_tri(disc);
      const std::size_t nf = fine.num_vertices;
      const std::vector<double> I1 = ip::polyhedral_matrix(nf, tris(fine), 0.25);
      const std::uint32_t m = static_cast<std::uint32_t>(nv) + e;
      Eigen::MatrixXd G(d.size(), d.size());
      Eigen::VectorXd rhs = Eigen::VectorXd::Zero(static_cast<int>(d.size()));
      for (std::size_t p = 0; p < d.size(); ++p) {
        for (std::size_t q = 0; q < d.size(); ++q) G(static_cast<int>(p), static_cast<int>(q)) = I0[d[p] * nv + d[q]];
        // phi_i^j = phi_i^{j+1} + 1/2 sum over edges (i, x) of phi_{mid}^{j+1}.
        double v = I1[std::size_t(d[p]) * nf + m];
        for (std::uint32_t x = 0; x < disc.num_edges(); ++x)
          if (disc.edge_verts[2 * x] == d[p] || disc.edge_verts[2 * x + 1] == d[p]) v += 0.5 * I1[(nv + x) * nf + m];
        rhs(static_cast<int>(p)) = v;
      }
      const Eigen::VectorXd alpha = G.ldlt().solve(rhs);
      ASSERT_EQ(w.alpha.size(), d.size());
      for (std::size_t p = 0; p < d.size(); ++p) EXPECT_NEAR(w.alpha[p], alpha(static_cast<int>(p)), 1e-13) << p;
    }
  }
}

// ---- Shared update rows (tri_transform.h) ------------------------------------------------

namespace {

// The update step (the transition's first) with each row's terms sorted by source, so rows
// listed in edge order and rows following the shared pattern can be compared term by term.
std::vector<std::vector<std::pair<std::uint32_t, double>>> sorted_update_rows(const Transition& t) {
  const auto& up = std::get<WeightedStep>(t.steps[0].op);
  std::vector<std::vector<std::pair<std::uint32_t, double>>> rows(t.num_coarse);
  for (std::size_t r = 0; r < up.target.size(); ++r) {
    const double* w = row_weights(up, r);
    for (std::uint32_t k = up.sources.offsets[r]; k < up.sources.offsets[r + 1]; ++k)
      rows[up.target[r]].emplace_back(up.sources.items[k], w[k - up.sources.offsets[r]]);
    std::sort(rows[up.target[r]].begin(), rows[up.target[r]].end());
  }
  return rows;
}

// Shared rows against listed rows on one level: the same terms, the weights equal up to the
// rounding of the two symmetric places an alpha is read at, and the same transform.
void expect_shared_rows_match(const Complex& coarse, Scheme s, bool expect_shared) {
  const Complex fine = refine_tri(coarse);
  const TriTransitionResult shared = build_tri_transition(coarse, fine, s, 2, true);
  const TriTransitionResult listed = build_tri_transition(coarse, fine, s, 2, false);
  const auto& up = std::get<WeightedStep>(shared.transition.steps[0].op);
  const auto& ref = std::get<WeightedStep>(listed.transition.steps[0].op);
  ASSERT_TRUE(ref.weight_at.empty());
  ASSERT_EQ(up.sources.items.size(), ref.sources.items.size());
  if (expect_shared) {
    ASSERT_EQ(up.weight_at.size(), up.target.size());
    EXPECT_LT(up.weights.size() * 4, ref.weights.size()) << "most rows should share the pattern";
  } else {
    // The surface closes on itself near every vertex: the listed rows, bit for bit.
    EXPECT_TRUE(up.weight_at.empty());
    EXPECT_EQ(up.sources.items, ref.sources.items);
    EXPECT_EQ(up.weights, ref.weights);
  }
  const auto a = sorted_update_rows(shared.transition), b = sorted_update_rows(listed.transition);
  double worst = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].size(), b[i].size()) << "row " << i;
    for (std::size_t k = 0; k < a[i].size(); ++k) {
      ASSERT_EQ(a[i][k].first, b[i][k].first) << "row " << i;
      worst = std::max(worst, std::abs(a[i][k].second - b[i][k].second));
    }
  }
  EXPECT_LE(worst, 1e-15);
  // The transforms agree to rounding; each is its own exact inverse.
  const std::size_t n = std::size_t(fine.num_vertices) * 3;
  std::vector<double> x(n);
  for (std::size_t k = 0; k < n; ++k) x[k] = std::sin(0.37 * double(k)) + 0.25 * std::cos(1.3 * double(k));
  std::vector<double> y = x, z = x;
  run_synthesis(shared.transition, coarse, y.data(), 3, false, false);
  run_synthesis(listed.transition, coarse, z.data(), 3, false, false);
  double diff = 0;
  for (std::size_t k = 0; k < n; ++k) diff = std::max(diff, std::abs(y[k] - z[k]));
  EXPECT_LE(diff, 1e-13);
  run_analysis(shared.transition, coarse, y.data(), 3, false);
  for (std::size_t k = 0; k < n; ++k) ASSERT_NEAR(y[k], x[k], 1e-12) << k;
}

}  // namespace

TEST(TriTransition, SharedUpdateRowsEqualListedOnARefinedOctahedron) {
  Complex c = octahedron_complex();
  for (int j = 0; j < 6; ++j) c = refine_tri(c);  // 16,386 vertices, six of valence 4
  for (Scheme s : {Scheme::LinearTri, Scheme::Butterfly, Scheme::Loop}) {
    SCOPED_TRACE(scheme_name(s));
    expect_shared_rows_match(c, s, true);
  }
}

TEST(TriTransition, SharedUpdateRowsEqualListedOnARegularTorus) {
  expect_shared_rows_match(regular_torus(24, 20), Scheme::Butterfly, true);
  expect_shared_rows_match(regular_torus(24, 20), Scheme::Loop, true);
}

// Edges keyed through an anchor (an irregular vertex's signature and the edge's ends as its
// labels) find the wavelets their own signatures find: the update rows and norms are bit for bit
// those keyed edge by edge. On the octahedron's deep levels (valence 4, far apart: each anchor
// alone), a disc round a valence-5 vertex (its open rim crowded with anchors) and the creased
// grid (anchors along the creases), for Loop and butterfly; the anchors must serve on each.
TEST(TriTransition, AnchoredKeysFindTheEdgesOwnWavelets) {
  Complex grid = read_shape(std::string(SUBLIFT_ASSETS_DIR) + "/tri_crease_grid.obj").base;
  build_adjacency(grid);
  Complex disc = extraordinary_disc(5, 4);
  build_adjacency(disc);
  // Each to a level whose transition meets anchors alone and known (the octahedron's valence-4
  // vertices are alone within butterfly's 21 rings from level 5); the crowded anchors of the
  // rim and the creases are taken at 8 edges per anchor, below the default.
  struct Case {
    Complex base;
    int levels;
    std::uint32_t per_anchor;
  };
  const Case meshes[] = {{octahedron_complex(), 7, 32}, {disc, 5, 8}, {grid, 6, 8}};
  for (Scheme s : {Scheme::Loop, Scheme::Butterfly}) {
    for (const auto& [base, levels, per_anchor] : meshes) {
      SCOPED_TRACE(scheme_name(s) + " on a mesh of " + std::to_string(base.num_vertices) + " vertices");
      std::uint32_t anchored = 0;
      Complex c = base;
      for (int j = 0; j < levels; ++j) {
        const Complex fine = refine_tri(c);
        const TriTransitionResult with = build_tri_transition(c, fine, s, 2, true, per_anchor);
        const TriTransitionResult own = build_tri_transition(c, fine, s, 2, true, 0);
        EXPECT_EQ(own.anchored_edges, 0u);
        anchored += with.anchored_edges;
        const auto& a = std::get<WeightedStep>(with.transition.steps[0].op);
        const auto& b = std::get<WeightedStep>(own.transition.steps[0].op);
        ASSERT_EQ(a.sources.offsets, b.sources.offsets) << "level " << j;
        ASSERT_EQ(a.sources.items, b.sources.items) << "level " << j;
        ASSERT_EQ(a.weights, b.weights) << "level " << j;
        ASSERT_EQ(a.weight_at, b.weight_at) << "level " << j;
        ASSERT_EQ(with.norm2, own.norm2) << "level " << j;
        c = fine;
      }
      EXPECT_GT(anchored, 100u);
    }
  }
}

// A level's new signatures, met by edges on several threads in any order, each kept once with
// the lowest edge that has it; in_order lists them by that edge and every edge's entry names
// its signature's place there. So what is solved, and in which order, does not depend on the
// threads.
TEST(TriTransition, NewSignaturesKeepEachOnceWithItsFirstEdge) {
  constexpr std::uint32_t kEdges = 20000;
  std::mt19937 rng(7);
  std::vector<std::uint32_t> sig_of(kEdges), order(kEdges);
  for (std::uint32_t k = 0; k < kEdges; ++k) {
    sig_of[k] = rng() % 3000;  // some signatures met by many edges, some by none
    order[k] = k;
  }
  std::shuffle(order.begin(), order.end(), rng);
  const auto text = [](std::uint32_t i) { return std::string(300 + i % 17, char('a' + i % 26)) + std::to_string(i); };
  NewSignatures fresh;
  std::vector<NewSignatures::Entry*> entry(kEdges, nullptr);
  const int threads = parallel_threads();
  set_parallel_threads(2);
  parallel_for(kEdges, 64, [&](std::uint32_t begin, std::uint32_t end) {
    for (std::uint32_t i = begin; i < end; ++i) entry[order[i]] = fresh.add(text(sig_of[order[i]]), order[i]);
  });
  set_parallel_threads(threads);
  std::vector<NewSignatures::Map::node_type> nodes = fresh.in_order();
  std::map<std::uint32_t, std::uint32_t> first;  // signature -> lowest edge, found here directly
  for (std::uint32_t k = 0; k < kEdges; ++k) first.try_emplace(sig_of[k], k);
  ASSERT_EQ(nodes.size(), first.size());
  std::vector<std::uint32_t> firsts;
  for (const auto& [sig, k] : first) firsts.push_back(k);
  std::sort(firsts.begin(), firsts.end());
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    ASSERT_EQ(nodes[i].mapped().first, firsts[i]);
    EXPECT_EQ(nodes[i].key(), text(sig_of[firsts[i]]));
    EXPECT_EQ(nodes[i].mapped().place, i);
  }
  for (std::uint32_t k = 0; k < kEdges; ++k) ASSERT_EQ(nodes[entry[k]->place].key(), text(sig_of[k])) << k;
}

TEST(TriTransition, ATorusTooThinForThePatternListsItsRows) {
  // Six cells round: a vertex's 3-ring closes on itself, so no row can follow the pattern.
  expect_shared_rows_match(regular_torus(6, 6), Scheme::Butterfly, false);
}

// The meshes the local orders are checked on: a refined octahedron (valence 4 and 6), an open
// disc around a valence-5 vertex (open fans at the rim), a creased grid (edge and vertex dims)
// and a thin torus whose neighbourhoods meet themselves.
// Two orders field for field.
::testing::AssertionResult same_order(const LocalOrder& a, const LocalOrder& b) {
  if (a.vertex != b.vertex) return ::testing::AssertionFailure() << "vertices differ";
  if (a.dist != b.dist) return ::testing::AssertionFailure() << "distances differ";
  if (a.start != b.start) return ::testing::AssertionFailure() << "starts differ";
  if (a.fan0 != b.fan0) return ::testing::AssertionFailure() << "fan starts differ";
  return ::testing::AssertionSuccess();
}

std::vector<Complex> local_order_meshes() {
  Complex octa = octahedron_complex();
  for (int j = 0; j < 3; ++j) octa = refine_tri(octa);
  Complex grid = read_shape(std::string(SUBLIFT_ASSETS_DIR) + "/tri_crease_grid.obj").base;
  build_adjacency(grid);
  return {octa, extraordinary_disc(5, 6), grid, regular_torus(6, 5)};
}

// The refined mesh's rings, written from the coarse rings, equal those searched on the refined
// mesh, entry for entry, two steps deep: on the local_order meshes (closed, open, creased, a
// thin torus) and on face patches cut from them (open fans at the rim, rim vertices split where
// a patch meets itself), as face types refine their patches.
TEST(TriLocal, RefinedRingsFromTheCoarseRingsEqualTheSearchedOnes) {
  std::vector<Complex> meshes = local_order_meshes();
  const std::size_t whole = meshes.size();
  for (std::size_t i = 0; i < whole; ++i) {
    const TriRings r = build_tri_rings(meshes[i]);
    for (std::uint32_t f = 0; f < meshes[i].num_faces(); f += 17) {
      std::uint32_t seeds[3], starts[3];
      face_seeds(meshes[i], f, seeds, starts);
      meshes.push_back(local_patch(meshes[i], r, local_order(r, seeds, starts, 4)));
    }
  }
  std::size_t compared = 0, open = 0;
  for (const Complex& mesh : meshes) {
    Complex c = mesh;
    TriRings r = build_tri_rings(c);
    for (int step = 0; step < 2; ++step) {
      const TriRings derived = refine_tri_rings(c, r);
      c = refine_tri(c);
      r = build_tri_rings(c);
      ASSERT_EQ(derived.ring.offsets, r.ring.offsets);
      ASSERT_EQ(derived.ring.items, r.ring.items);
      ASSERT_EQ(derived.ring_edge.offsets, r.ring_edge.offsets);
      ASSERT_EQ(derived.ring_edge.items, r.ring_edge.items);
      ASSERT_EQ(derived.closed, r.closed);
      open += static_cast<std::size_t>(std::count(r.closed.begin(), r.closed.end(), 0));
      ++compared;
    }
  }
  EXPECT_GT(compared, 40u);
  EXPECT_GT(open, 1000u);  // open fans were met
}

// A refined face's type is its parent's child type (what the wavelets' look-ups take instead
// of a signature): on the local_order meshes (closed, open, creased, a thin torus whose patches
// split rim vertices), for Loop and butterfly, every face of one and two refinements: the type
// found by signature, the child type and the labelled vertices agree.
TEST(TriGram, ChildTypesAreTheRefinedFacesTypes) {
  std::size_t compared = 0;
  for (Scheme s : {Scheme::Loop, Scheme::Butterfly}) {
    FaceGramCache cache(s);
    for (Complex c : local_order_meshes()) {
      TriRings r = build_tri_rings(c);
      std::vector<int> type(c.num_faces());
      for (std::uint32_t f = 0; f < c.num_faces(); ++f) type[f] = cache.face_gram(c, r, f).type;
      for (int step = 0; step < (s == Scheme::Loop ? 2 : 1); ++step) {
        const Complex fine = refine_tri(c);
        const TriRings fr = build_tri_rings(fine);
        std::vector<int> fine_type(fine.num_faces());
        for (std::uint32_t g = 0; g < fine.num_faces(); ++g) {
          const FaceGramCache::FaceGram found = cache.face_gram(fine, fr, g);
          const int child = cache.child_type(type[g / 4], static_cast<int>(g % 4));
          ASSERT_EQ(found.type, child) << "face " << g;
          FaceGramCache::FaceGram inherited;
          ASSERT_TRUE(cache.from_type(fine, fr, g, child, inherited));
          ASSERT_EQ(inherited.verts, found.verts);
          ASSERT_EQ(inherited.G, found.G);
          fine_type[g] = found.type;
          ++compared;
        }
        c = fine;
        r = fr;
        type = std::move(fine_type);
      }
    }
  }
  EXPECT_GT(compared, 10000u);
}

// The one-pass order and signature (what the edges' keys use) equal local_order followed by
// local_signature, field for field and byte for byte: on a refined octahedron (valence 4 and
// 6), an open disc around a valence-5 vertex (open fans at the rim), a creased grid (edge and
// vertex dims) and a thin torus whose neighbourhoods meet themselves; from edges (two seeds)
// and faces (three), at radii 0 to 5.
TEST(TriLocal, OrderAndSignatureInOnePassEqualTheTwoCalls) {
  const std::vector<Complex> meshes = local_order_meshes();
  std::size_t compared = 0;
  for (const Complex& c : meshes) {
    const TriRings r = build_tri_rings(c);
    LocalOrder fused;
    std::string fused_signature;
    const auto compare = [&](std::span<const std::uint32_t> seeds, std::span<const std::uint32_t> starts, int radius) {
      const LocalOrder o = local_order(r, seeds, starts, radius);
      local_order_and_signature(c, r, seeds, starts, radius, fused, fused_signature);
      ASSERT_TRUE(same_order(fused, o));
      ASSERT_EQ(fused_signature, local_signature(c, r, o, radius));
      ++compared;
    };
    for (int radius = 0; radius <= 5; ++radius) {
      for (std::uint32_t e = 0; e < c.num_edges(); e += 3) {
        const std::uint32_t seeds[2] = {c.edge_verts[2 * e], c.edge_verts[2 * e + 1]}, starts[2] = {seeds[1], seeds[0]};
        compare(seeds, starts, radius);
      }
      for (std::uint32_t f = 0; f < c.num_faces(); f += 5) {
        std::uint32_t seeds[3], starts[3];
        face_seeds(c, f, seeds, starts);
        compare(seeds, starts, radius);
      }
    }
  }
  EXPECT_GT(compared, 1000u);
}

// A key read back into its signature (tri_local.h says how it is written), given how many
// seeds its order started from: that it can be, is why equal keys are equal signatures.
std::string signature_from_key(const std::string& key, std::uint32_t seeds) {
  std::size_t at = 0;
  const auto varint = [&] {
    std::uint64_t v = 0;
    for (int shift = 0;; shift += 7) {
      const auto byte = static_cast<unsigned char>(key.at(at++));
      v |= std::uint64_t(byte & 0x7f) << shift;
      if (!(byte & 0x80)) return v;
    }
  };
  std::vector<std::int32_t> numbers;
  std::int64_t next = seeds;  // the label the next "labelled here" gets
  while (at < key.size()) {
    const auto d = static_cast<unsigned char>(key[at++]);
    const std::uint64_t head = varint();
    const auto n = static_cast<std::int32_t>(head >> 3);
    numbers.insert(numbers.end(), {-1000 - d, std::int32_t(head >> 2 & 1), n, std::int32_t(head & 3)});
    for (std::int32_t k = 0; k < n; ++k) {
      const std::uint64_t entry = varint(), token = entry >> 2;
      numbers.push_back(token == 0 ? static_cast<std::int32_t>(next++) : token == 1 ? -1 : static_cast<std::int32_t>(token - 2));
      numbers.push_back(static_cast<std::int32_t>(entry & 3));
    }
  }
  const bool narrow = std::all_of(numbers.begin(), numbers.end(), [](std::int32_t x) { return x >= INT16_MIN && x <= INT16_MAX; });
  std::string out(1, narrow ? 'h' : 'w');
  for (std::int32_t x : numbers) {
    char bytes[4];
    if (narrow) {
      const auto h = static_cast<std::int16_t>(x);
      std::memcpy(bytes, &h, 2);
      out.append(bytes, 2);
    } else {
      std::memcpy(bytes, &x, 4);
      out.append(bytes, 4);
    }
  }
  return out;
}

// The compact keys (what the edges' wavelets are cached by) come with the same order as
// local_order and read back into the signature byte for byte, so equal keys are equal
// signatures; on the refined octahedron, the open disc, the creased grid and the thin torus,
// from edges and faces at radii 0 to 6, every pair of one radius is also compared both ways. A
// key is about a third of the signature's bytes.
TEST(TriLocal, KeysPartitionNeighbourhoodsAsSignaturesDo) {
  const std::vector<Complex> meshes = local_order_meshes();
  std::size_t key_bytes = 0, signature_bytes = 0, classes = 0;
  for (int radius = 0; radius <= 6; ++radius) {
    std::map<std::string, std::string> key_of;  // signature -> key
    std::map<std::string, std::string> signature_of;  // key -> signature
    for (const Complex& c : meshes) {
      const TriRings r = build_tri_rings(c);
      LocalOrder o;
      std::string key;
      const auto compare = [&](std::span<const std::uint32_t> seeds, std::span<const std::uint32_t> starts) {
        const LocalOrder ref = local_order(r, seeds, starts, radius);
        local_order_and_key(c, r, seeds, starts, radius, o, key);
        ASSERT_TRUE(same_order(o, ref));
        const std::string sig = local_signature(c, r, ref, radius);
        ASSERT_EQ(signature_from_key(key, static_cast<std::uint32_t>(seeds.size())), sig);
        key_bytes += key.size();
        signature_bytes += sig.size();
        // One key per signature and one signature per key.
        ASSERT_EQ(key_of.try_emplace(sig, key).first->second, key);
        ASSERT_EQ(signature_of.try_emplace(key, sig).first->second, sig);
      };
      for (std::uint32_t e = 0; e < c.num_edges(); ++e) {
        const std::uint32_t seeds[2] = {c.edge_verts[2 * e], c.edge_verts[2 * e + 1]}, starts[2] = {seeds[1], seeds[0]};
        compare(seeds, starts);
      }
      for (std::uint32_t f = 0; f < c.num_faces(); ++f) {
        std::uint32_t seeds[3], starts[3];
        face_seeds(c, f, seeds, starts);
        compare(seeds, starts);
      }
    }
    classes += key_of.size();
  }
  EXPECT_GT(classes, 500u);  // many kinds of neighbourhood, not a few repeated
  EXPECT_LT(3 * key_bytes, signature_bytes + signature_bytes / 5);
}

// Signatures are 16-bit where every number fits and 32-bit otherwise (more than 32767 labels),
// marked by their first byte, so the two kinds never compare equal; the wide kind still tells
// neighbourhoods apart.
TEST(TriLocal, SignaturesWidenForHugeNeighbourhoodsAndStayDistinct) {
  const auto signature = [](int w, int h, int radius) {
    const Complex c = regular_torus(w, h);
    const TriRings r = build_tri_rings(c);
    const std::uint32_t seeds[1] = {0}, starts[1] = {r.ring.row(0)[0]};
    return local_signature(c, r, local_order(r, seeds, starts, radius), radius);
  };
  const std::string small = signature(200, 180, 3), big = signature(200, 180, 150), bigger = signature(200, 181, 150);
  EXPECT_EQ(small.front(), 'h');
  EXPECT_EQ(big.front(), 'w');  // all 36,000 vertices labelled
  EXPECT_NE(big, bigger);
  EXPECT_EQ(signature(200, 180, 150), big);
  EXPECT_EQ(SignatureHash{}(big), SignatureHash{}(signature(200, 180, 150)));
  EXPECT_EQ(signature(200, 180, 3), small);
  // The one-pass form (the edges' keys) widens alike, bit for bit.
  const Complex c = regular_torus(200, 180);
  const TriRings r = build_tri_rings(c);
  const std::uint32_t seeds[1] = {0}, starts[1] = {r.ring.row(0)[0]};
  LocalOrder o;
  std::string fused;
  local_order_and_signature(c, r, seeds, starts, 150, o, fused);
  EXPECT_EQ(fused, big);
  local_order_and_signature(c, r, seeds, starts, 3, o, fused);
  EXPECT_EQ(fused, small);
}
