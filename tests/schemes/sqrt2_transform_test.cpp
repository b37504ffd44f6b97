// sqrt(2) wavelet transform (core/schemes/sqrt2/sqrt2_transform.h): interpolation and the eq. 1 / eq. 11 rules
// recomputed here from the fine complex's adjacency, perfect reconstruction (float and integer)
// on closed, open, creased and polygon bases over levels 1..4, analysis of a pure refinement,
// and near-orthogonality of the lifted wavelet to its 12 scaling functions (001 eq. 5-9).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "core/base/parallel.h"
#include "core/complex/complex_build.h"
#include "tests/test_shapes.h"
#include "core/engine/executor.h"
#include "core/complex/refine_sqrt2.h"
#include "core/io/lattice/shape_io.h"
#include "core/complex/shapes.h"
#include "core/schemes/sqrt2/sqrt2_transform.h"

using namespace sublift;

namespace {

// The one executor on a standalone sqrt(2) transition (Weighted steps read no complex).
const Complex kNoParent;
void sqrt2_synthesize(const Sqrt2Transition& t, double* x, int channels, bool integer = false) {
  run_synthesis(t.transition, kNoParent, x, channels, integer);
}
void sqrt2_analyze(const Sqrt2Transition& t, double* x, int channels, bool integer = false) {
  run_analysis(t.transition, kNoParent, x, channels, integer);
}

Complex asset(const std::string& name) {
  Complex c = read_shape(std::string(SUBLIFT_ASSETS_DIR) + "/" + name).base;
  build_adjacency(c);
  return c;
}

Complex torus(int n, int m) {
  Complex c = complex_from_surface_mesh(make_quad_torus(n, m));
  build_adjacency(c);
  return c;
}

struct Chain {
  std::vector<Complex> levels;
  std::vector<Sqrt2Children> children;
  std::vector<Sqrt2Transition> transitions;
};

Chain chain(const Complex& base, int J) {
  Chain ch;
  ch.levels.push_back(base);
  for (int j = 0; j < J; ++j) {
    Sqrt2Step s = refine_sqrt2(ch.levels.back(), j);
    ch.transitions.push_back(build_sqrt2_transition(ch.levels.back(), s.fine, s.children));
    ch.children.push_back(std::move(s.children));
    ch.levels.push_back(std::move(s.fine));
  }
  return ch;
}

// Levels 0..4 of an asset, built once per test binary (the refinement dominates under ASan).
const Chain& asset_chain(const std::string& name) {
  static std::map<std::string, Chain> cache;
  auto it = cache.find(name);
  if (it == cache.end()) it = cache.emplace(name, chain(asset(name), 4)).first;
  return it->second;
}


bool is_curve(const Complex& c, std::uint32_t e) { return c.edge_dim[e] <= 1 || c.edge_faces.size(e) != 2; }

std::uint32_t other_end(const Complex& c, std::uint32_t e, std::uint32_t v) {
  return c.edge_verts[2 * e] == v ? c.edge_verts[2 * e + 1] : c.edge_verts[2 * e];
}

std::vector<std::uint32_t> neighbours(const Complex& c, std::uint32_t v) {
  std::vector<std::uint32_t> out;
  for (std::uint32_t e : c.vertex_edges.row(v)) out.push_back(other_end(c, e, v));
  return out;
}

// Coarse edge neighbours of old vertex v, read off the fine level: on a closed quad mesh every
// fine face is (a, f_B, b, f_A), so they are the corners opposite v.
std::set<std::uint32_t> coarse_neighbours(const Complex& fine, std::uint32_t v) {
  std::set<std::uint32_t> out;
  for (std::uint32_t f : fine.vertex_faces.row(v)) {
    const auto vs = fine.faces.row(f);
    for (std::size_t i = 0; i < vs.size(); ++i)
      if (vs[i] == v) out.insert(vs[(i + 2) % 4]);
  }
  return out;
}

// 12 scaling-function vertices of face point fp: its corners and their outer neighbours.
std::set<std::uint32_t> phi_set(const Complex& fine, std::uint32_t fp) {
  const auto corners = neighbours(fine, fp);
  std::set<std::uint32_t> out(corners.begin(), corners.end());
  for (std::uint32_t c : corners) out.merge(coarse_neighbours(fine, c));
  return out;
}


// Zero wavelets on a regular torus: old vertices kept exactly, face points = 5/16 corners -
// 1/32 outer neighbours (eq. 1 with n = 4), at a keep step (0 -> 1) and a curve step (1 -> 2).
TEST(Sqrt2Transform, RegularFacePointsFollowEq1) {
  const Chain ch = chain(torus(8, 10), 2);
  for (int j = 0; j < 2; ++j) {
    const Sqrt2Transition& t = ch.transitions[j];
    const Complex& fine = ch.levels[j + 1];
    const int channels = 2;
    std::vector<double> x(std::size_t(fine.num_vertices) * channels, 0.0);
    const auto coarse = sublift::testing::random_coefficients(std::size_t(t.transition.num_coarse) * channels, 7 + j, false);
    std::copy(coarse.begin(), coarse.end(), x.begin());
    sqrt2_synthesize(t, x.data(), channels);
    for (std::size_t i = 0; i < coarse.size(); ++i) ASSERT_EQ(x[i], coarse[i]);
    EXPECT_EQ(t.lifted_face_points, fine.num_vertices - t.transition.num_coarse);
    for (std::uint32_t fp = t.transition.num_coarse; fp < fine.num_vertices; ++fp) {
      const auto corners = neighbours(fine, fp);
      ASSERT_EQ(corners.size(), 4u);
      std::vector<std::uint32_t> outer;
      for (std::uint32_t c : corners)
        for (std::uint32_t o : coarse_neighbours(fine, c))
          if (std::find(corners.begin(), corners.end(), o) == corners.end()) outer.push_back(o);
      ASSERT_EQ(outer.size(), 8u);
      for (int k = 0; k < channels; ++k) {
        double want = 0;
        for (std::uint32_t c : corners) want += 5.0 / 16 * x[c * channels + k];
        for (std::uint32_t o : outer) want -= 1.0 / 32 * x[o * channels + k];
        EXPECT_NEAR(x[fp * channels + k], want, 1e-14) << "level " << j << " point " << fp;
      }
    }
  }
}

// Curve points on an open grid, a crease loop and a crease ending on the boundary follow eq. 11:
// (a) inside a curve, (b) next to a curve end; the curve neighbours are found here from the
// coarse curve edges.
TEST(Sqrt2Transform, CurvePointsFollowEq11) {
  for (const char* name : {"quad_grid_boundary.obj", "crease_loop.obj", "crease_grid_flat.obj"}) {
    const Chain& ch = asset_chain(name);
    int inner_rules = 0, corner_rules = 0;
    for (int j : {1, 3}) {
      const Complex& coarse = ch.levels[j];
      const Complex& fine = ch.levels[j + 1];
      const Sqrt2Transition& t = ch.transitions[j];
      std::vector<double> x(fine.num_vertices, 0.0);
      const auto c = sublift::testing::random_coefficients(t.transition.num_coarse, 11 + j, false);
      std::copy(c.begin(), c.end(), x.begin());
      sqrt2_synthesize(t, x.data(), 1);
      const std::uint32_t first_face_point = ch.children[j].first_face_point;
      ASSERT_GT(first_face_point, t.transition.num_coarse) << name;
      for (std::uint32_t b = t.transition.num_coarse; b < first_face_point; ++b) {
        std::vector<std::uint32_t> ends;  // p, q: the curve point's neighbours along fine curves
        for (std::uint32_t e : fine.vertex_edges.row(b))
          if (is_curve(fine, e)) ends.push_back(other_end(fine, e, b));
        ASSERT_EQ(ends.size(), 2u);
        // The other curve neighbour of p (not q), or none where the curve ends at p.
        auto beyond = [&](std::uint32_t p, std::uint32_t q) -> long {
          std::vector<std::uint32_t> others;
          int curve_edges = 0;
          for (std::uint32_t e : coarse.vertex_edges.row(p))
            if (is_curve(coarse, e)) {
              ++curve_edges;
              const std::uint32_t o = other_end(coarse, e, p);
              if (o != q) others.push_back(o);
            }
          if (coarse.vertex_dim[p] != 1 || curve_edges != 2 || others.size() != 1) return -1;
          return others[0];
        };
        const std::uint32_t p = ends[0], q = ends[1];
        const long a = beyond(p, q), d = beyond(q, p);
        double want;
        if (a >= 0 && d >= 0) {
          want = (-x[a] + 9 * x[p] + 9 * x[q] - x[d]) / 16, ++inner_rules;
        } else if (a >= 0) {
          want = (-x[a] + 6 * x[p] + 3 * x[q]) / 8, ++corner_rules;
        } else if (d >= 0) {
          want = (-x[d] + 6 * x[q] + 3 * x[p]) / 8, ++corner_rules;
        } else {
          want = (x[p] + x[q]) / 2;
        }
        EXPECT_NEAR(x[b], want, 1e-14) << name << " level " << j << " point " << b;
      }
    }
    EXPECT_GT(inner_rules, 0) << name;
    if (std::string(name) == "crease_grid_flat.obj") {  // the crease ends at branches on the boundary
      EXPECT_GT(corner_rules, 0);
    }
  }
}

// Next to a boundary (keep step 0 -> 1 on the open 4 x 4 grid, inner vertices regular): a face
// point is the mean of its inner corners' eq. 1 estimates (001 sec. 4, the 4/l rule): 1/2 the
// corner, 3/8 its two neighbours in the face, -1/8 its two others.
TEST(Sqrt2Transform, BoundaryFacePointsAverageInnerCorners) {
  const Chain ch = chain(asset("quad_grid_boundary.obj"), 1);
  const Complex& coarse = ch.levels[0];
  const Complex& fine = ch.levels[1];
  const Sqrt2Transition& t = ch.transitions[0];
  std::vector<bool> on_curve(coarse.num_vertices, false);
  for (std::uint32_t e = 0; e < coarse.num_edges(); ++e)
    if (is_curve(coarse, e)) on_curve[coarse.edge_verts[2 * e]] = on_curve[coarse.edge_verts[2 * e + 1]] = true;
  std::vector<double> x(fine.num_vertices, 0.0);
  const auto c = sublift::testing::random_coefficients(t.transition.num_coarse, 3, false);
  std::copy(c.begin(), c.end(), x.begin());
  sqrt2_synthesize(t, x.data(), 1);
  int partial = 0;
  for (std::uint32_t fp = t.transition.num_coarse; fp < fine.num_vertices; ++fp) {
    const auto corners = neighbours(fine, fp);
    double sum = 0;
    int l = 0;
    for (std::uint32_t k : corners) {
      if (on_curve[k]) continue;
      ++l;
      const auto ring = neighbours(coarse, k);
      ASSERT_EQ(ring.size(), 4u);
      sum += 0.5 * x[k];
      for (std::uint32_t r : ring)
        sum += (std::find(corners.begin(), corners.end(), r) != corners.end() ? 3.0 / 8 : -1.0 / 8) * x[r];
    }
    ASSERT_GT(l, 0);
    if (l < 4) ++partial;
    EXPECT_NEAR(x[fp], sum / l, 1e-14) << "point " << fp << " with " << l << " inner corners";
  }
  EXPECT_EQ(partial, 12);  // the 12 faces along the boundary
}

// Curves are self-governed (001 sec. 4): inner wavelets change no curve vertex and no curve
// point, so curve values depend on curve data only.
TEST(Sqrt2Transform, InnerWaveletsLeaveCurvesAlone) {
  for (const char* name : {"quad_grid_boundary.obj", "crease_loop.obj", "crease_grid_flat.obj"}) {
    const Chain& ch = asset_chain(name);
    for (int j = 0; j < 4; ++j) {
      const Complex& coarse = ch.levels[j];
      const Sqrt2Transition& t = ch.transitions[j];
      const std::uint32_t first_face_point = ch.children[j].first_face_point;
      std::vector<double> x = sublift::testing::random_coefficients(t.transition.num_fine, 40 + j, false);
      std::fill(x.begin(), x.begin() + first_face_point, 0.0);  // face-point wavelets only
      sqrt2_synthesize(t, x.data(), 1);
      for (std::uint32_t e = 0; e < coarse.num_edges(); ++e)
        if (is_curve(coarse, e)) {
          EXPECT_EQ(x[coarse.edge_verts[2 * e]], 0.0) << name << " level " << j;
          EXPECT_EQ(x[coarse.edge_verts[2 * e + 1]], 0.0) << name << " level " << j;
        }
      for (std::uint32_t b = t.transition.num_coarse; b < first_face_point; ++b) EXPECT_EQ(x[b], 0.0) << name;
    }
  }
}

// Constants are reproduced: every predict row sums to 1 (eq. 1, the 4/l rule, eq. 11).
TEST(Sqrt2Transform, ConstantsReproduced) {
  for (const char* name : {"quad_grid_boundary.obj", "crease_loop.obj", "mixed_polygons.obj"}) {
    const Chain& ch = asset_chain(name);
    for (const Sqrt2Transition& t : ch.transitions) {
      std::vector<double> x(t.transition.num_fine, 0.0);
      std::fill(x.begin(), x.begin() + t.transition.num_coarse, 2.5);
      sqrt2_synthesize(t, x.data(), 1);
      for (double v : x) EXPECT_NEAR(v, 2.5, 1e-13) << name;
    }
  }
}

struct Case {
  const char* name;
  const Chain& ch;
};

std::vector<Case> cases() {
  static const Chain small_torus = chain(torus(6, 5), 4);
  return {{"torus", small_torus},
          {"grid", asset_chain("quad_grid_boundary.obj")},
          {"crease", asset_chain("crease_loop.obj")},
          {"crease_branch", asset_chain("crease_grid_flat.obj")},
          {"mixed", asset_chain("mixed_polygons.obj")}};
}

// Full analysis J -> 0 then synthesis 0 -> J, and the other way round, on random data.
TEST(Sqrt2Transform, PerfectReconstruction) {
  for (const Case& c : cases()) {
    const Chain& ch = c.ch;
    for (int J = 1; J <= 4; ++J)
      for (bool integer : {false, true}) {
        const int channels = 3;
        const std::size_t n = std::size_t(ch.levels[J].num_vertices) * channels;
        const auto data = sublift::testing::random_coefficients(n, 100 * J + integer, integer);
        std::vector<double> x = data;
        for (int j = J - 1; j >= 0; --j) sqrt2_analyze(ch.transitions[j], x.data(), channels, integer);
        const std::vector<double> coefficients = x;
        for (int j = 0; j < J; ++j) sqrt2_synthesize(ch.transitions[j], x.data(), channels, integer);
        if (integer) {
          EXPECT_EQ(x, data) << c.name << " J=" << J;
          for (double v : coefficients) ASSERT_EQ(v, std::round(v)) << c.name;
        } else {
          EXPECT_LT(sublift::testing::max_abs_diff(x, data), 1e-12) << c.name << " J=" << J;
        }
        for (int j = J - 1; j >= 0; --j) sqrt2_analyze(ch.transitions[j], x.data(), channels, integer);
        if (integer) EXPECT_EQ(x, coefficients) << c.name << " J=" << J;
        else EXPECT_LT(sublift::testing::max_abs_diff(x, coefficients), 1e-12) << c.name << " J=" << J;
      }
  }
}

// Analysing a pure refinement gives the coarse data back and zero wavelets.
TEST(Sqrt2Transform, PureRefinementHasZeroWavelets) {
  for (const Case& c : cases()) {
    const Chain& ch = c.ch;
    const std::size_t n0 = ch.levels[0].num_vertices;
    std::vector<double> x(ch.levels[4].num_vertices, 0.0);
    const auto coarse = sublift::testing::random_coefficients(n0, 5, false);
    std::copy(coarse.begin(), coarse.end(), x.begin());
    for (int j = 0; j < 4; ++j) sqrt2_synthesize(ch.transitions[j], x.data(), 1);
    for (int j = 3; j >= 0; --j) sqrt2_analyze(ch.transitions[j], x.data(), 1);
    for (std::size_t i = 0; i < x.size(); ++i) EXPECT_NEAR(x[i], i < n0 ? coarse[i] : 0.0, 1e-12) << c.name << " " << i;
  }
}

// On a regular torus the synthesised lifted wavelet of a face point is orthogonal (discrete
// inner product over the fine level, as docs/sqrt2.md) to the 12 scaling functions of its face;
// the primitive wavelet (the unit vector) is not.
TEST(Sqrt2Transform, LiftedWaveletOrthogonalToItsScalingFunctions) {
  const Chain ch = chain(torus(12, 12), 2);
  for (int j = 0; j < 2; ++j) {
    const Sqrt2Transition& t = ch.transitions[j];
    const Complex& fine = ch.levels[j + 1];
    auto synth = [&](std::uint32_t unit) {
      std::vector<double> x(fine.num_vertices, 0.0);
      x[unit] = 1.0;
      sqrt2_synthesize(t, x.data(), 1);
      return x;
    };
    for (std::uint32_t fp : {t.transition.num_coarse, t.transition.num_coarse + 17}) {
      const std::set<std::uint32_t> phis = phi_set(fine, fp);
      ASSERT_EQ(phis.size(), 12u);
      const std::vector<double> psi = synth(fp);
      for (std::uint32_t v : phis) {
        const std::vector<double> phi = synth(v);
        double lifted = 0;
        for (std::size_t i = 0; i < psi.size(); ++i) lifted += psi[i] * phi[i];
        EXPECT_NEAR(lifted, 0.0, 1e-12) << "level " << j << " point " << fp << " phi at " << v;
        EXPECT_GT(std::abs(phi[fp]), 0.03) << "primitive <psi, phi> = phi at the face point";
      }
    }
  }
}

// Face points with a corner on a curve (001 sec. 4) are lifted with inner scaling functions
// only, their omega solved from the actual masks: the lifted wavelet is orthogonal to each
// scaling function it lifts (discrete inner product over the whole fine level), and does lift.
TEST(Sqrt2Transform, NearCurveWaveletsOrthogonalToTheirScalingFunctions) {
  for (const char* name : {"quad_grid_boundary.obj", "crease_grid_flat.obj"}) {
    const Chain& ch = asset_chain(name);
    int checked = 0;
    for (int j : {0, 1, 2}) {
      const Complex& coarse = ch.levels[j];
      const Complex& fine = ch.levels[j + 1];
      const Sqrt2Transition& t = ch.transitions[j];
      EXPECT_GT(t.near_curve_face_points, 0u) << name;
      std::vector<bool> on_curve(coarse.num_vertices, false);
      for (std::uint32_t e = 0; e < coarse.num_edges(); ++e)
        if (is_curve(coarse, e)) on_curve[coarse.edge_verts[2 * e]] = on_curve[coarse.edge_verts[2 * e + 1]] = true;
      auto synth = [&](std::uint32_t unit) {
        std::vector<double> x(fine.num_vertices, 0.0);
        x[unit] = 1.0;
        sqrt2_synthesize(t, x.data(), 1);
        return x;
      };
      for (std::uint32_t fp = ch.children[j].first_face_point; fp < fine.num_vertices; fp += 3) {
        const auto corners = neighbours(fine, fp);
        const auto curve_corner = [&](std::uint32_t v) { return bool(on_curve[v]); };
        if (corners.size() != 4 || std::none_of(corners.begin(), corners.end(), curve_corner)) continue;
        const std::vector<double> psi = synth(fp);
        int lifted = 0;
        for (std::uint32_t v = 0; v < t.transition.num_coarse; ++v) {
          if (psi[v] == 0.0) continue;  // old vertices hold omega after synthesis of a unit wavelet
          ++lifted;
          EXPECT_FALSE(on_curve[v]) << name;
          const std::vector<double> phi = synth(v);
          double dot = 0;
          for (std::size_t i = 0; i < psi.size(); ++i) dot += psi[i] * phi[i];
          EXPECT_NEAR(dot, 0.0, 1e-12) << name << " level " << j << " point " << fp << " phi at " << v;
        }
        EXPECT_GT(lifted, 0) << name << " level " << j << " point " << fp;
        ++checked;
      }
    }
    EXPECT_GT(checked, 5) << name;
  }
}

// The eta lifting (eq. 12-14): with the 1-D inner product (sum over the fine curves' vertices,
// the masks of Figure 5) a lifted curve wavelet is orthogonal to the scaling functions it is
// lifted with: case (a) on a closed crease loop, case (b) next to the ends of a crease that
// meets the boundary. The primitive one (the unit vector) is not.
TEST(Sqrt2Transform, LiftedCurveWaveletOrthogonalAlongTheCurve) {
  for (const char* name : {"crease_loop.obj", "crease_grid_flat.obj"}) {
    const bool closed = std::string(name) == "crease_loop.obj";
    const Chain& ch = asset_chain(name);
    const int j = 3;
    const Complex& fine = ch.levels[j + 1];
    const Sqrt2Transition& t = ch.transitions[j];
    const Sqrt2Children& kids = ch.children[j];
    std::vector<bool> on_curve(fine.num_vertices, false);
    for (std::uint32_t e = 0; e < fine.num_edges(); ++e)
      if (is_curve(fine, e)) on_curve[fine.edge_verts[2 * e]] = on_curve[fine.edge_verts[2 * e + 1]] = true;
    auto synth = [&](std::uint32_t unit) {
      std::vector<double> x(fine.num_vertices, 0.0);
      x[unit] = 1.0;
      sqrt2_synthesize(t, x.data(), 1);
      return x;
    };
    int checked = 0;
    for (std::uint32_t k = 0; k < kids.curve_edges.size(); ++k) {
      const std::uint32_t* st = kids.curve_stencils.data() + 4 * k;
      std::vector<std::uint32_t> targets;
      const bool has_a = st[0] != Sqrt2Children::kNone, has_b = st[3] != Sqrt2Children::kNone;
      if (closed && has_a && has_b) targets = {st[0], st[1], st[2], st[3]};
      if (!closed && has_a && !has_b) targets = {st[0], st[1]};
      if (!closed && !has_a && has_b) targets = {st[3], st[2]};
      if (targets.empty()) continue;
      const std::uint32_t x = t.transition.num_coarse + k;
      const std::vector<double> psi = synth(x);
      for (std::uint32_t v : targets) {
        const std::vector<double> phi = synth(v);
        double dot = 0;
        for (std::uint32_t i = 0; i < fine.num_vertices; ++i)
          if (on_curve[i]) dot += psi[i] * phi[i];
        EXPECT_NEAR(dot, 0.0, 1e-12) << name << " curve point " << x << " phi at " << v;
        EXPECT_GT(std::abs(phi[x]), 0.05) << name;
        ++checked;
      }
    }
    EXPECT_GT(checked, 0) << name;
  }
}

// The face points are built in chunks on the pool and joined in order: one thread and two
// give the same rows bit for bit, rows in target order, each row's sources increasing and
// merged (no source twice). A 128 x 72 torus with a crease ring (near-curve face points too)
// has more face points than one chunk at both steps.
TEST(Sqrt2Transform, RowsAreTheSameWhateverTheThreadCount) {
  Complex c = torus(128, 72);
  for (std::uint32_t e = 0; e < c.num_edges(); ++e)  // vertex (i, j) is i * 72 + j: the ring j = 0
    if (c.edge_verts[2 * e] % 72 == 0 && c.edge_verts[2 * e + 1] % 72 == 0) c.edge_dim[e] = 1;
  const int threads = parallel_threads();
  for (int j = 0; j < 2; ++j) {
    Sqrt2Step s = refine_sqrt2(c, j);
    set_parallel_threads(1);
    const Sqrt2Transition one = build_sqrt2_transition(c, s.fine, s.children);
    set_parallel_threads(2);
    const Sqrt2Transition two = build_sqrt2_transition(c, s.fine, s.children);
    set_parallel_threads(threads);
    EXPECT_GT(s.children.point_faces.size(), 8192u) << "step " << j;
    EXPECT_GT(one.near_curve_face_points, 0u) << "step " << j;
    EXPECT_EQ(one.lifted_face_points, two.lifted_face_points);
    ASSERT_EQ(one.transition.steps.size(), two.transition.steps.size());
    for (std::size_t k = 0; k < one.transition.steps.size(); ++k) {
      const auto* a = std::get_if<WeightedStep>(&one.transition.steps[k].op);
      const auto* b = std::get_if<WeightedStep>(&two.transition.steps[k].op);
      ASSERT_TRUE(a && b) << "step " << j << " sub-step " << k;
      EXPECT_EQ(a->target, b->target);
      EXPECT_EQ(a->sources.offsets, b->sources.offsets);
      EXPECT_EQ(a->sources.items, b->sources.items);
      ASSERT_EQ(a->weights.size(), b->weights.size());
      EXPECT_EQ(0, std::memcmp(a->weights.data(), b->weights.data(), a->weights.size() * sizeof(double)));
      for (std::size_t r = 0; r + 1 < a->target.size(); ++r) ASSERT_LT(a->target[r], a->target[r + 1]);
      for (std::size_t r = 0; r < a->target.size(); ++r)
        for (std::uint32_t i = a->sources.offsets[r] + 1; i < a->sources.offsets[r + 1]; ++i)
          ASSERT_LT(a->sources.items[i - 1], a->sources.items[i]) << "row of " << a->target[r];
    }
    c = std::move(s.fine);
    build_adjacency(c);
  }
}

TEST(Sqrt2Transform, RejectsMismatchedLevels) {
  const Chain ch = chain(torus(4, 4), 2);
  EXPECT_ANY_THROW(build_sqrt2_transition(ch.levels[0], ch.levels[2], ch.children[0]));
}

}  // namespace
