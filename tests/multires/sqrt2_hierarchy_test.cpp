// The sqrt(2) scheme (paper 001) in the engine: Scheme::Sqrt2 hierarchies (level counts, perfect
// reconstruction, interpolation, analysis of a pure refinement, L2 ranking), project files, and
// the basis functions (interpolating scaling functions, dual functions = analysis rows). Also the
// 001 sec. 4 index-set rule next to a crease that ends inside the surface.
#include <gtest/gtest.h>

#include "tests/test_shapes.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "core/analysis/compress.h"
#include "core/multires/basis.h"
#include "core/complex/complex_build.h"
#include "core/base/errors.h"
#include "core/multires/hierarchy.h"
#include "core/io/project/project_io.h"
#include "core/complex/refine_sqrt2.h"
#include "core/io/lattice/shape_io.h"
#include "core/complex/shapes.h"
#include "core/schemes/sqrt2/sqrt2_transform.h"
#include "tests/io_test_util.h"

using namespace sublift;

namespace {

using sublift::testing::max_abs_diff;
using sublift::testing::random_coefficients;

struct Base {
  Complex c;
  std::vector<double> xyz;
};

Base asset(const std::string& name) {
  Shape s = read_shape(std::string(SUBLIFT_ASSETS_DIR) + "/" + name);
  return {std::move(s.base), std::move(s.positions)};
}

Base torus(int n, int m) {
  const SurfaceMesh t = make_quad_torus(n, m);
  return {complex_from_surface_mesh(t), flatten_positions(t)};
}

// Bases with a boundary, a crease loop, a crease ending inside (dart), polygons, a closed cube.
const char* const kAssets[] = {"cube.obj", "quad_grid_boundary.obj", "crease_loop.obj", "crease_dart_flat.obj",
                               "mixed_polygons.obj"};

}  // namespace

// Even levels have the Catmull-Clark (1-to-4) topology; odd ones add one point per face; the
// predicted counts (used to refuse big requests) are exact from level 0.
TEST(Sqrt2Hierarchy, LevelCountsMatchPredictionAndCatmullClark) {
  for (const char* name : kAssets) {
    SCOPED_TRACE(name);
    const Base b = asset(name);
    const Hierarchy h = make_hierarchy(b.c, 5, Scheme::Sqrt2, 3);
    const Hierarchy cc = make_hierarchy(b.c, 2, Scheme::Cubic, 3);
    const std::vector<double> predicted = predicted_level_counts(b.c, 5, Scheme::Sqrt2);
    ASSERT_EQ(predicted.size(), 6u);
    for (int l = 0; l <= 5; ++l) {
      EXPECT_EQ(predicted[std::size_t(l)], double(h.num_vertices(l))) << "level " << l;
      if (l % 2 == 0 && l / 2 <= 2) {
        EXPECT_EQ(h.num_vertices(l), cc.num_vertices(l / 2)) << "level " << l;
        EXPECT_EQ(h.levels[std::size_t(l)].num_faces(), cc.levels[std::size_t(l / 2)].num_faces()) << "level " << l;
      }
      if (l % 2 == 1) {
        EXPECT_EQ(h.num_vertices(l), h.num_vertices(l - 1) + h.levels[std::size_t(l - 1)].num_faces()) << "level " << l;
      }
    }
    // From an odd level the next count is exact too (one point per curve edge and per quad).
    EXPECT_EQ(predicted_level_counts(h.levels[1], 1, Scheme::Sqrt2, 1)[1], double(h.num_vertices(2)));
    EXPECT_EQ(predicted_level_counts(h.levels[3], 1, Scheme::Sqrt2, 3)[1], double(h.num_vertices(4)));
  }
}

// A hierarchy started at an odd level (as the basis explorer builds one from level j) refines as
// the tail of the full hierarchy: same complexes, same synthesis.
TEST(Sqrt2Hierarchy, StartingAtAnOddLevelContinuesTheHierarchy) {
  const Base b = asset("crease_dart_flat.obj");
  Hierarchy full = make_hierarchy(b.c, 4, Scheme::Sqrt2, 1);
  Hierarchy tail = make_hierarchy(full.levels[1], 3, Scheme::Sqrt2, 1, false, 1);
  for (int l = 0; l <= 3; ++l) {
    const Complex& a = full.levels[std::size_t(l + 1)];
    const Complex& t = tail.levels[std::size_t(l)];
    EXPECT_EQ(a.edge_verts, t.edge_verts) << "level " << l;
    EXPECT_EQ(a.faces.items, t.faces.items) << "level " << l;
  }
  full.coeffs = random_coefficients(full.coeffs.size(), 3, false);
  std::copy(full.coeffs.begin(), full.coeffs.end(), tail.coeffs.begin());  // same layout from level 1 on
  std::vector<double> x1 = synthesize(full, 1);
  std::copy(x1.begin(), x1.end(), tail.coeffs.begin());
  EXPECT_EQ(max_abs_diff(synthesize(full, 4), synthesize(tail, 3)), 0.0);
  // Started as an even level instead, the crease would be refined one step too early.
  const Hierarchy wrong = make_hierarchy(full.levels[1], 1, Scheme::Sqrt2, 1, false, 0);
  EXPECT_NE(wrong.num_vertices(1), full.num_vertices(2));
}

TEST(Sqrt2Hierarchy, PerfectReconstruction) {
  for (const char* name : kAssets)
    for (const int J : {1, 4, 5}) {
      SCOPED_TRACE(std::string(name) + " J " + std::to_string(J));
      const Base b = asset(name);
      Hierarchy h = make_hierarchy(b.c, J, Scheme::Sqrt2, 3);
      const std::vector<double> coeffs = random_coefficients(h.coeffs.size(), 11 + J, false);
      h.coeffs = coeffs;
      const std::vector<double> fine = synthesize(h, J);
      analyze(h, fine);
      EXPECT_LT(max_abs_diff(h.coeffs, coeffs), 1e-12);
      // Integer mode: bit-exact.
      Hierarchy hi = make_hierarchy(b.c, J, Scheme::Sqrt2, 3, true);
      const std::vector<double> ic = random_coefficients(hi.coeffs.size(), 5 + J, true);
      hi.coeffs = ic;
      const std::vector<double> ifine = synthesize(hi, J);
      for (const double v : ifine) ASSERT_EQ(v, std::round(v));
      analyze(hi, ifine);
      EXPECT_EQ(std::memcmp(hi.coeffs.data(), ic.data(), ic.size() * sizeof(double)), 0);
    }
}

// Interpolation: with zero details every level keeps the previous level's points bit for bit,
// and analysing that pure refinement gives zero wavelets.
TEST(Sqrt2Hierarchy, InterpolatesAndPureRefinementHasZeroWavelets) {
  for (const char* name : kAssets) {
    SCOPED_TRACE(name);
    const Base b = asset(name);
    Hierarchy h = make_hierarchy(b.c, 5, Scheme::Sqrt2, 3);
    set_base(h, b.xyz);
    for (int l = 0; l < 5; ++l) {
      const std::vector<double> lo = synthesize(h, l), hi = synthesize(h, l + 1);
      EXPECT_EQ(std::memcmp(lo.data(), hi.data(), lo.size() * sizeof(double)), 0) << "level " << l;
    }
    Hierarchy a = make_hierarchy(b.c, 5, Scheme::Sqrt2, 3);
    analyze(a, synthesize(h, 5));
    for (std::size_t i = b.xyz.size(); i < a.coeffs.size(); ++i) ASSERT_LT(std::abs(a.coeffs[i]), 1e-12) << i;
    EXPECT_LT(max_abs_diff(std::vector<double>(a.coeffs.begin(), a.coeffs.begin() + std::ptrdiff_t(b.xyz.size())), b.xyz),
              1e-12);
  }
}

// keep_largest ranks a level-j wavelet by |w| 2^(-j/2) for sqrt2 (each level halves the area), not
// by the 1-to-4 schemes' 2^(-j): a level-2 wavelet of size 3 outranks a level-0 one of size 1.
TEST(Sqrt2Hierarchy, KeepLargestUsesTheHalvingArea) {
  const Base b = torus(4, 4);
  for (const Scheme s : {Scheme::Sqrt2, Scheme::Cubic}) {
    Hierarchy h = make_hierarchy(b.c, 3, s, 3);
    const std::uint32_t w0 = h.num_vertices(0), w2 = h.num_vertices(2);
    h.coeffs[3 * std::size_t(w0)] = 1.0;
    h.coeffs[3 * std::size_t(w2)] = 3.0;
    EXPECT_EQ(keep_largest(h, 1.0 / double(h.num_vertices(3) - h.num_vertices(0))), 1u);
    const bool level2_kept = h.coeffs[3 * std::size_t(w2)] != 0.0;
    EXPECT_EQ(level2_kept, s == Scheme::Sqrt2) << scheme_name(s);  // 3/2 > 1 but 3/4 < 1
  }
}

TEST(Sqrt2Hierarchy, SurfacesOnly) {
  const Base curve = asset("curves/curve.obj");
  const Base lattice = asset("cube_cell.lattice");
  EXPECT_THROW(make_hierarchy(curve.c, 1, Scheme::Sqrt2, 3), Error);
  EXPECT_THROW(make_hierarchy(lattice.c, 1, Scheme::Sqrt2, 3), Error);
  EXPECT_EQ(parse_scheme("sqrt2"), Scheme::Sqrt2);
  EXPECT_EQ(scheme_name(Scheme::Sqrt2), "sqrt2");
  EXPECT_THROW(parse_scheme("sqrt3"), std::invalid_argument);
}

TEST(Sqrt2Hierarchy, ProjectRoundTrip) {
  const sublift::testing::TempDir dir("sublift_sqrt2_project");
  const Base b = asset("crease_dart_flat.obj");
  Hierarchy h = make_hierarchy(b.c, 5, Scheme::Sqrt2, 3);
  h.coeffs = random_coefficients(h.coeffs.size(), 9, false);
  write_project(dir.file("p.sublift"), h);
  const Hierarchy r = read_project(dir.file("p.sublift"));
  EXPECT_EQ(r.scheme, Scheme::Sqrt2);
  EXPECT_EQ(r.finest_level(), 5);
  EXPECT_EQ(std::memcmp(r.coeffs.data(), h.coeffs.data(), h.coeffs.size() * sizeof(double)), 0);
  EXPECT_EQ(max_abs_diff(synthesize(r, 5), synthesize(h, 5)), 0.0);
}

// Interpolating scaling functions (001): one at their own vertex, zero at every other vertex of
// their level, exactly; on a regular torus every level-j function has integral 2^-j (they sum to
// one, and all vertices of a level are alike: odd levels are the diagonal grid).
TEST(Sqrt2Basis, ScalingFunctionsInterpolate) {
  const Base b = torus(6, 4);
  for (int j = 0; j <= 3; ++j) {
    Hierarchy h = make_hierarchy(b.c, j, Scheme::Sqrt2, 3);
    set_base(h, b.xyz);
    const std::vector<double> pos = synthesize(h, j);
    const std::uint32_t nv = h.num_vertices(j);
    for (const std::uint32_t i : {0u, nv / 2, nv - 1}) {
      BasisRequest r;
      r.level = j;
      r.index = i;
      r.extra_levels = 4;
      const BasisFunction f = basis_function(h.levels.back(), Scheme::Sqrt2, r, pos);
      SCOPED_TRACE("level " + std::to_string(j) + " vertex " + std::to_string(i));
      EXPECT_TRUE(f.limit);
      for (std::uint32_t v = 0; v < nv; ++v) ASSERT_EQ(f.values[v], v == i ? 1.0 : 0.0) << v;
      EXPECT_NEAR(f.integral, std::ldexp(1.0, -j), 1e-12);
      EXPECT_EQ(f.max, 1.0);
      EXPECT_LT(f.min, 0.0);  // interpolatory: negative lobes
    }
  }
}

// A dual function is the analysis row: coefficient = sum_k w_k x_k for level j+K values x, for
// scaling functions and wavelets, from even and odd levels of a mesh with boundary and crease.
TEST(Sqrt2Basis, DualFunctionsAreAnalysisRows) {
  for (const char* name : {"quad_grid_boundary.obj", "crease_dart_flat.obj"})
    for (const int j : {0, 1, 2}) {
      const Base b = asset(name);
      Hierarchy h = make_hierarchy(b.c, j, Scheme::Sqrt2, 3);
      set_base(h, b.xyz);
      const std::vector<double> pos = synthesize(h, j);
      const Complex& cj = h.levels.back();
      const int K = 3;
      Hierarchy a = make_hierarchy(cj, K, Scheme::Sqrt2, 1, false, j);
      const std::vector<double> x = random_coefficients(a.coeffs.size(), 21 + j, false);
      analyze(a, x);
      for (const BasisKind kind : {BasisKind::Scaling, BasisKind::Wavelet}) {
        BasisRequest r;
        r.level = j;
        r.kind = kind;
        r.dual = true;
        r.extra_levels = K;
        r.index = kind == BasisKind::Scaling ? cj.num_vertices / 2 : a.num_vertices(1) - 1;
        const BasisFunction f = basis_function(cj, Scheme::Sqrt2, r, pos);
        double dot = 0;
        for (std::size_t k = 0; k < x.size(); ++k) dot += f.values[k] * x[k];
        EXPECT_NEAR(dot, a.coeffs[r.index], 1e-12) << name << " level " << j << (kind == BasisKind::Scaling ? " scaling" : " wavelet");
      }
    }
}

// 001 sec. 4: a face point next to a curve lifts only inner scaling functions, and for a corner
// p_k on a curve its whole set S_k (p_k and its two neighbours outside the face) is dropped.
// Where a crease ends inside the surface, the end vertex is on a curve while one of those
// neighbours is inner: only the S_k rule keeps it out of the lifting.
TEST(Sqrt2Transition, CurveCornerDropsItsIndexSetAtACreaseEnd) {
  Complex c = asset("crease_dart_flat.obj").c;
  build_adjacency(c);
  const Sqrt2Step step = refine_sqrt2(c, 0);
  const Sqrt2Transition t = build_sqrt2_transition(c, step.fine, step.children);
  std::vector<bool> on_curve(c.num_vertices, false);
  for (std::uint32_t e = 0; e < c.num_edges(); ++e)
    if (sqrt2_is_curve_edge(c, e)) on_curve[c.edge_verts[2 * e]] = on_curve[c.edge_verts[2 * e + 1]] = true;
  constexpr std::uint32_t kEnd = 24;  // the centre, where the crease from the boundary stops
  ASSERT_TRUE(on_curve[kEnd]);
  const WeightedStep& update = std::get<WeightedStep>(t.transition.steps.at(0).op);
  int checked_inner_neighbours = 0;
  for (std::uint32_t k = 0; k < step.children.point_faces.size(); ++k) {
    const std::uint32_t f = step.children.point_faces[k], fp = step.children.first_face_point + k;
    const auto corners = c.faces.row(f);
    if (std::find(corners.begin(), corners.end(), kEnd) == corners.end()) continue;
    std::set<std::uint32_t> lifted;  // old vertices receiving this face point's wavelet
    for (std::uint32_t r = 0; r < update.target.size(); ++r)
      for (std::uint32_t s = update.sources.offsets[r]; s < update.sources.offsets[r + 1]; ++s)
        if (update.sources.items[s] == fp && update.weights[s] != 0.0) lifted.insert(update.target[r]);
    EXPECT_FALSE(lifted.empty()) << "face " << f;
    for (const std::uint32_t p : corners) {
      if (!on_curve[p]) continue;
      EXPECT_EQ(lifted.count(p), 0u) << "face " << f << " corner " << p;
      for (const std::uint32_t e : c.vertex_edges.row(p)) {
        const std::uint32_t q = c.edge_verts[2 * e] == p ? c.edge_verts[2 * e + 1] : c.edge_verts[2 * e];
        if (std::find(corners.begin(), corners.end(), q) != corners.end()) continue;
        EXPECT_EQ(lifted.count(q), 0u) << "face " << f << ": S_k of corner " << p << " holds " << q;
        if (!on_curve[q]) ++checked_inner_neighbours;
      }
    }
  }
  EXPECT_GE(checked_inner_neighbours, 2);  // the case only S_k excludes did occur
}
