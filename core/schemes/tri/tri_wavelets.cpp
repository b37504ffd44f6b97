#include "core/schemes/tri/tri_wavelets.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <stdexcept>
#include <unordered_map>

#include <Eigen/Dense>

#include "core/base/epoch_table.h"
#include "core/base/parallel.h"
#include "core/complex/complex_build.h"
#include "core/complex/refine_tri.h"

namespace sublift {

TriWaveletBuilder::TriWaveletBuilder(Scheme s, int disc) : disc_(disc), gram_(s) {
  if (disc < 1 || disc > 3) throw std::invalid_argument("the disc of a wavelet has 1, 2 or 3 rings");
}

int TriWaveletBuilder::edge_radius() const {
  const TriGramRadii& g = gram_.radii();
  return disc_ + g.support + g.patch + 1;
}

int TriWaveletBuilder::signature_radius() const {
  const TriGramRadii& g = gram_.radii();
  return disc_ + g.support + g.signature;
}

// What one edge's wavelet reads: D (coarse vertices, canonical order), the coarse faces that
// touch D's supports and the fine faces around m, each list sorted.
struct TriWaveletBuilder::EdgePlan {
  std::uint32_t edge = 0;
  std::vector<std::uint32_t> disc, coarse_faces, fine_faces;
};

void TriWaveletBuilder::plan(const TriLevel& lv, std::uint32_t e, EdgePlan& out) const {
  const TriGramRadii& g = gram_.radii();
  const Complex& c = *lv.coarse;
  const std::uint32_t a = c.edge_verts[2 * e], b = c.edge_verts[2 * e + 1];
  const std::uint32_t seeds[2] = {a, b}, starts[2] = {b, a};
  thread_local LocalOrder order, around_m;  // reused: one per edge
  local_order(*lv.coarse_rings, seeds, starts, disc_ + g.support, order);
  const std::uint32_t nd = labels_within(order, disc_);
  out.edge = e;
  out.disc.assign(order.vertex.begin(), order.vertex.begin() + nd);
  // Each face once (a face meets up to three of the rows), then sorted.
  thread_local EpochTable seen;
  const auto faces_of = [](const Complex& mesh, const LocalOrder& o, std::vector<std::uint32_t>& faces) {
    faces.clear();
    seen.begin(mesh.num_faces());
    for (std::uint32_t v : o.vertex)
      for (std::uint32_t f : mesh.vertex_faces.row(v))
        if (!seen.has(f)) {
          seen.mark(f);
          faces.push_back(f);
        }
    std::sort(faces.begin(), faces.end());
  };
  faces_of(c, order, out.coarse_faces);
  const std::uint32_t m = c.num_vertices + e;
  const std::uint32_t mseed[1] = {m}, mstart[1] = {lv.fine_rings->ring.row(m)[0]};
  local_order(*lv.fine_rings, mseed, mstart, g.support, around_m);
  faces_of(*lv.fine, around_m, out.fine_faces);
}

EdgeWavelet TriWaveletBuilder::compute(const TriLevel& lv, const EdgePlan& plan) const {
  const Complex& c = *lv.coarse;
  const Complex& fine = *lv.fine;
  const TriStencils& st = *lv.stencils;
  const std::uint32_t nd = static_cast<std::uint32_t>(plan.disc.size());
  // Coarse vertex -> label in D; fine vertex -> its place in with_m (thousands of lookups).
  thread_local EpochTable disc_label, with_m_slot;
  disc_label.begin(c.num_vertices);
  for (std::uint32_t l = 0; l < nd; ++l) disc_label.set(plan.disc[l], l);
  const auto in_disc = [&](std::uint32_t v) { return disc_label.get(v); };
  const auto gram_of = [](const FaceGrams& grams, std::uint32_t f) -> const FaceGramCache::FaceGram& {
    return grams.gram[grams.slot[f]];
  };

  // Left side: <phi_i^j, phi_l^j> over the level-j faces that touch D's supports.
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(nd, nd);
  thread_local std::vector<std::pair<int, std::uint32_t>> in;  // (place in the face's N(f), label in D)
  for (std::uint32_t f : plan.coarse_faces) {
    const auto& fg = gram_of(lv.coarse_faces, f);
    in.clear();
    for (std::size_t p = 0; p < fg.verts.size(); ++p)
      if (const std::uint32_t l = in_disc(fg.verts[p]); l != UINT32_MAX) in.emplace_back(static_cast<int>(p), l);
    // Column by column: the Grams are column-major and mostly out of cache. The lower triangle
    // only: each face's Gram is exactly symmetric, so the upper one would get the same sums.
    for (const auto& [q, lq] : in)
      for (const auto& [p, lp] : in)
        if (lp >= lq) G(lp, lq) += (*fg.G)(p, q);
  }
  for (Eigen::Index c = 1; c < G.cols(); ++c)
    for (Eigen::Index r = 0; r < c; ++r) G(r, c) = G(c, r);

  // Right side: <phi_c^{j+1}, phi_m^{j+1}> over the level-(j+1) faces around m, pulled back.
  const std::uint32_t nv = c.num_vertices;
  const std::uint32_t m = nv + plan.edge;
  // Fine vertex c -> <phi_c, phi_m>, summed in the order the faces are met (a short list).
  thread_local std::vector<std::pair<std::uint32_t, double>> with_m;
  with_m.clear();
  with_m_slot.begin(fine.num_vertices);
  for (std::uint32_t f : plan.fine_faces) {
    const auto& fg = gram_of(lv.fine_faces, f);
    int im = -1;
    for (std::size_t p = 0; p < fg.verts.size(); ++p)
      if (fg.verts[p] == m) im = static_cast<int>(p);
    if (im < 0) continue;
    for (std::size_t p = 0; p < fg.verts.size(); ++p) {
      const double add = 0.25 * (*fg.G)(static_cast<int>(p), im);
      const std::uint32_t at = with_m_slot.get(fg.verts[p]);
      if (at != UINT32_MAX) {
        with_m[at].second += add;
      } else {
        with_m_slot.set(fg.verts[p], static_cast<std::uint32_t>(with_m.size()));
        with_m.emplace_back(fg.verts[p], add);
      }
    }
  }
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(nd);
  double self = 0;
  // Not a structured binding: clang 14 (the fuzz build's compiler) cannot capture one in a lambda.
  for (const auto& entry : with_m) {
    const double value = entry.second;
    if (entry.first == m) self = value;
    for_each_stencil_weight(st, nv, entry.first, [&](std::uint32_t i, double w) {
      if (const std::uint32_t l = in_disc(i); l != UINT32_MAX) rhs(l) += w * value;
    });
  }

  EdgeWavelet out;
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(G);
  const Eigen::VectorXd alpha = ldlt.solve(rhs);
  out.alpha.assign(alpha.data(), alpha.data() + nd);
  out.self = self;
  out.norm2 = out.self - alpha.dot(rhs);
  out.residual = (G * alpha - rhs).cwiseAbs().maxCoeff();
  return out;
}

std::vector<const EdgeWavelet*> TriWaveletBuilder::solve(TriLevel& lv, std::span<const std::uint32_t> edges,
                                                         std::span<std::string> signatures) {
  if (edges.size() != signatures.size()) throw std::logic_error("tri_wavelets: one signature per edge");
  std::vector<const EdgeWavelet*> out(edges.size(), nullptr);
  if (edges.empty()) return out;
  if (lv.fine->vertex_faces.rows() != lv.fine->num_vertices) {
    lv.fine_built = std::make_unique<Complex>(*lv.fine);
    build_adjacency(*lv.fine_built);
    lv.fine = lv.fine_built.get();
  }
  if (!lv.fine_rings) {
    lv.fine_rings_built = std::make_unique<TriRings>(refine_tri_rings(*lv.coarse, *lv.coarse_rings));
    lv.fine_rings = lv.fine_rings_built.get();
  }
  const auto n = static_cast<std::uint32_t>(edges.size());
  std::vector<EdgePlan> plans(n);
  std::atomic<bool> failed{false};
  parallel_for(n, 16, [&](std::uint32_t begin, std::uint32_t end) {
    try {
      for (std::uint32_t i = begin; i < end; ++i) plan(lv, edges[i], plans[i]);
    } catch (...) {
      failed = true;
    }
  });
  if (failed) {  // the rings were checked, so this is a defect; the serial call names it
    for (std::uint32_t i = 0; i < n; ++i) plan(lv, edges[i], plans[i]);
    throw std::logic_error("tri_wavelets: an edge's neighbourhood could not be ordered");
  }

  // The faces not asked yet on this level, looked up in parallel where their type is known;
  // the others' types are made together (add_types), then those faces are looked up again.
  std::vector<FaceGramCache::FaceRef> missing;
  std::vector<FaceGramCache::FaceGram*> fill;  // aligned with `missing`
  // A face whose type is known takes it without a signature: a coarse face from `known` (handed
  // on from the coarser level), a fine face from its parent's (`parents`: the coarse faces;
  // refine_tri's face 4 g + k is child k of g). The fine faces are three quarters of those asked.
  const auto look_up = [&](const Complex& mesh, const TriRings& rings, FaceGrams& grams,
                           std::vector<std::uint32_t> EdgePlan::*faces, const std::vector<std::int32_t>* known,
                           const FaceGrams* parents) {
    if (grams.slot.size() != mesh.num_faces()) grams.slot.assign(mesh.num_faces(), UINT32_MAX);
    const auto first = static_cast<std::uint32_t>(grams.gram.size());
    std::vector<std::uint32_t> asked;
    for (const EdgePlan& p : plans)
      for (std::uint32_t f : p.*faces)
        if (grams.slot[f] == UINT32_MAX) {
          grams.slot[f] = static_cast<std::uint32_t>(grams.gram.size());
          grams.gram.emplace_back();
          asked.push_back(f);
        }
    parallel_for(static_cast<std::uint32_t>(asked.size()), 64, [&](std::uint32_t begin, std::uint32_t end) {
      try {
        for (std::uint32_t k = begin; k < end; ++k) {
          const std::uint32_t f = asked[k];
          FaceGramCache::FaceGram& out = grams.gram[first + k];
          if (known && (*known)[f] >= 0 && gram_.from_type(mesh, rings, f, (*known)[f], out)) continue;
          if (parents && parents->slot[f / 4] != UINT32_MAX) {
            const int parent = parents->gram[parents->slot[f / 4]].type;
            if (parent >= 0 && gram_.from_type(mesh, rings, f, gram_.child_type(parent, static_cast<int>(f % 4)), out))
              continue;
          }
          gram_.find(mesh, rings, f, out);
        }
      } catch (...) {
        // The chunk's rest is left unfound: add_types meets those faces again and names the fault.
      }
    });
    for (std::uint32_t k = 0; k < asked.size(); ++k)
      if (!grams.gram[first + k].G) {
        missing.push_back({&mesh, &rings, asked[k]});
        fill.push_back(&grams.gram[first + k]);
      }
  };
  const std::vector<std::int32_t>* known =
      lv.coarse_types && lv.coarse_types->size() == lv.coarse->num_faces() ? lv.coarse_types : nullptr;
  look_up(*lv.coarse, *lv.coarse_rings, lv.coarse_faces, &EdgePlan::coarse_faces, known, nullptr);
  look_up(*lv.fine, *lv.fine_rings, lv.fine_faces, &EdgePlan::fine_faces, nullptr, &lv.coarse_faces);
  if (!missing.empty()) {
    gram_.add_types(missing);
    std::atomic<bool> lost{false};
    parallel_for(static_cast<std::uint32_t>(missing.size()), 64, [&](std::uint32_t begin, std::uint32_t end) {
      try {
        for (std::uint32_t k = begin; k < end; ++k)
          if (!gram_.find(*missing[k].mesh, *missing[k].rings, missing[k].face, *fill[k])) lost = true;
      } catch (...) {
        lost = true;
      }
    });
    if (lost) throw std::logic_error("tri_wavelets: a face's new type was not made");
  }

  std::vector<std::unique_ptr<EdgeWavelet>> solved(n);
  parallel_for(n, 16, [&](std::uint32_t begin, std::uint32_t end) {
    try {
      for (std::uint32_t i = begin; i < end; ++i) solved[i] = std::make_unique<EdgeWavelet>(compute(lv, plans[i]));
    } catch (...) {
      failed = true;  // out of memory: nothing is cached
    }
  });
  if (failed) throw std::bad_alloc();
  for (std::uint32_t i = 0; i < n; ++i) {
    const auto [it, inserted] = edges_.try_emplace(std::move(signatures[i]), std::move(solved[i]));
    if (!inserted) throw std::logic_error("tri_wavelets: an edge's signature was cached already, or asked twice");
    out[i] = it->second.get();
  }
  return out;
}

std::vector<std::int32_t> TriWaveletBuilder::fine_face_types(const TriLevel& lv) const {
  const std::uint32_t nf = lv.coarse->num_faces();
  const bool known = lv.coarse_types && lv.coarse_types->size() == nf;
  std::vector<std::int32_t> out(std::size_t(nf) * 4, -1);
  const auto type_in = [](const FaceGrams& grams, std::uint32_t f) {
    return f < grams.slot.size() && grams.slot[f] != UINT32_MAX ? grams.gram[grams.slot[f]].type : -1;
  };
  parallel_for(nf, 4096, [&](std::uint32_t begin, std::uint32_t end) {
    for (std::uint32_t f = begin; f < end; ++f) {
      const std::int32_t t = known && (*lv.coarse_types)[f] >= 0 ? (*lv.coarse_types)[f] : type_in(lv.coarse_faces, f);
      for (std::uint32_t k = 0; k < 4; ++k)
        out[4 * f + k] = t >= 0 ? gram_.child_type(t, static_cast<int>(k)) : type_in(lv.fine_faces, 4 * f + k);
    }
  });
  return out;
}

TriWaveletBuilder::EdgeKey TriWaveletBuilder::edge_key(const TriLevel& lv, std::uint32_t e) const {
  EdgeKey key;
  edge_key(lv, e, key.disc, key.signature);
  return key;
}

void TriWaveletBuilder::edge_key(const TriLevel& lv, std::uint32_t e, std::vector<std::uint32_t>& disc,
                                 std::string& signature) const {
  const Complex& c = *lv.coarse;
  const std::uint32_t a = c.edge_verts[2 * e], b = c.edge_verts[2 * e + 1];
  const std::uint32_t seeds[2] = {a, b}, starts[2] = {b, a};
  thread_local LocalOrder order;
  local_order_and_key(c, *lv.coarse_rings, seeds, starts, signature_radius(), order, signature);
  const std::uint32_t nd = labels_within(order, disc_);
  disc.assign(order.vertex.begin(), order.vertex.begin() + nd);
}

const EdgeWavelet* TriWaveletBuilder::find(const std::string& signature) const {
  const auto it = edges_.find(signature);
  return it == edges_.end() ? nullptr : it->second.get();
}

const EdgeWavelet& TriWaveletBuilder::edge_wavelet(TriLevel& lv, std::uint32_t e, EdgeKey&& key) {
  if (const EdgeWavelet* w = find(key.signature)) return *w;
  return *solve(lv, std::span<const std::uint32_t>(&e, 1), std::span<std::string>(&key.signature, 1))[0];
}

const EdgeWavelet& TriWaveletBuilder::edge_wavelet(TriLevel& lv, std::uint32_t e, std::vector<std::uint32_t>* disc_out,
                                                   bool regular_hint) {
  const Complex& c = *lv.coarse;
  if (regular_hint && regular_) {
    if (disc_out) {
      const std::uint32_t seeds[2] = {c.edge_verts[2 * e], c.edge_verts[2 * e + 1]}, starts[2] = {seeds[1], seeds[0]};
      *disc_out = local_order(*lv.coarse_rings, seeds, starts, disc_).vertex;
    }
    return *regular_;
  }
  EdgeKey key = edge_key(lv, e);
  if (disc_out) *disc_out = key.disc;
  const EdgeWavelet& w = edge_wavelet(lv, e, std::move(key));
  if (regular_hint) regular_ = std::make_unique<EdgeWavelet>(w);
  return w;
}

const EdgeWavelet& TriWaveletBuilder::edge_wavelet(const Complex& c, const TriRings& r, std::uint32_t e,
                                                   std::vector<std::uint32_t>* disc_out) {
  const Complex fine = refine_tri(c);
  const TriRings fr = refine_tri_rings(c, r);
  const TriStencils st = build_tri_stencils(c, gram_.scheme());
  TriLevel lv;
  lv.coarse = &c;
  lv.coarse_rings = &r;
  lv.fine = &fine;
  lv.fine_rings = &fr;
  lv.stencils = &st;
  return edge_wavelet(lv, e, disc_out);
}

std::uint32_t TriWaveletBuilder::anchor_type(const std::string& signature) {
  return anchor_types_.try_emplace(signature, static_cast<std::uint32_t>(anchor_types_.size())).first->second;
}

const EdgeWavelet* TriWaveletBuilder::find_anchored(std::uint64_t key) const {
  const auto it = anchored_.find(key);
  return it == anchored_.end() ? nullptr : it->second;
}

std::vector<std::uint8_t> distance_to_irregular(const Complex& c, const TriRings& r, int cap,
                                                std::vector<std::uint32_t>* nearest) {
  const std::uint32_t nv = c.num_vertices;
  std::vector<std::uint8_t> d(nv, static_cast<std::uint8_t>(cap));
  if (nearest) nearest->assign(nv, UINT32_MAX);
  std::vector<std::uint32_t> frontier, next;
  for (std::uint32_t v = 0; v < nv; ++v) {
    bool irregular = r.ring.size(v) != 6 || !r.closed[v] || (!c.vertex_dim.empty() && c.vertex_dim[v] < 2);
    if (!irregular && !c.edge_dim.empty())
      for (std::uint32_t e : r.ring_edge.row(v)) irregular |= c.edge_dim[e] < 2;
    if (irregular) {
      d[v] = 0;
      frontier.push_back(v);
      if (nearest) (*nearest)[v] = v;
    }
  }
  for (int k = 1; k < cap && !frontier.empty(); ++k) {
    next.clear();
    for (std::uint32_t v : frontier)
      for (std::uint32_t w : r.ring.row(v))
        if (d[w] > k) {
          d[w] = static_cast<std::uint8_t>(k);
          next.push_back(w);
          if (nearest) (*nearest)[w] = (*nearest)[v];
        }
    frontier.swap(next);
  }
  return d;
}

Complex extraordinary_disc(int valence, int radius, std::vector<double>* xy) {
  if (valence < 3 || radius < 1) throw std::invalid_argument("extraordinary_disc: valence >= 3, radius >= 1");
  // Vertex (s, p, q) = p e_s + q e_{s+1} in wedge s, p >= 1, q >= 0, p + q <= radius; (s, 0, q)
  // is spoke s+1's (s+1, q, 0).
  const int n = valence;
  std::vector<std::vector<std::uint32_t>> id(static_cast<std::size_t>(n));
  std::uint32_t next = 1;
  const auto slot = [&](int p, int q) { return static_cast<std::size_t>(p * (radius + 1) + q); };
  if (xy) xy->assign(2, 0.0);
  for (int s = 0; s < n; ++s) {
    id[static_cast<std::size_t>(s)].assign(static_cast<std::size_t>((radius + 1) * (radius + 1)), UINT32_MAX);
    const double a0 = 2 * M_PI * s / n, a1 = 2 * M_PI * (s + 1) / n;
    for (int p = 1; p <= radius; ++p)
      for (int q = 0; p + q <= radius; ++q) {
        id[static_cast<std::size_t>(s)][slot(p, q)] = next++;
        if (xy) xy->insert(xy->end(), {p * std::cos(a0) + q * std::cos(a1), p * std::sin(a0) + q * std::sin(a1)});
      }
  }
  const auto vid = [&](int s, int p, int q) -> std::uint32_t {
    if (p == 0 && q == 0) return 0;
    if (p == 0) return id[static_cast<std::size_t>((s + 1) % n)][slot(q, 0)];
    return id[static_cast<std::size_t>(s)][slot(p, q)];
  };
  Csr faces;
  const auto tri = [&](std::uint32_t x, std::uint32_t y, std::uint32_t z) {
    faces.items.insert(faces.items.end(), {x, y, z});
    faces.offsets.push_back(static_cast<std::uint32_t>(faces.items.size()));
  };
  for (int s = 0; s < n; ++s)
    for (int p = 0; p < radius; ++p)
      for (int q = 0; p + q < radius; ++q) {
        tri(vid(s, p, q), vid(s, p + 1, q), vid(s, p, q + 1));
        if (p + q + 2 <= radius) tri(vid(s, p + 1, q), vid(s, p + 1, q + 1), vid(s, p, q + 1));
      }
  return complex_from_polygons(next, faces);
}

}  // namespace sublift
