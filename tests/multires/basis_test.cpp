// Basis functions (issue 5): primal scaling functions are B-splines (1-D, tensor products in 2-D
// and 3-D), partition of unity, vanishing moments of the wavelets, biorthogonality of the dual
// (analysis rows) and primal functions, and the adjoint against brute-force analysis.
#include <cmath>

#include <gtest/gtest.h>

#include "core/multires/basis.h"
#include "core/complex/complex_build.h"
#include "core/base/errors.h"
#include "core/multires/hierarchy.h"
#include "core/complex/shapes.h"
#include "tests/mesh_fixtures.h"
#include "tests/test_lattices.h"

namespace sublift {
namespace {

// Uniform cubic B-spline centred at 0, support [-2, 2] (knot spacing 1).
double bspline3(double x) {
  x = std::abs(x);
  if (x >= 2) return 0.0;
  if (x >= 1) return (2 - x) * (2 - x) * (2 - x) / 6;
  return (4 - 6 * x * x + 3 * x * x * x) / 6;
}

double hat(double x) { return std::max(0.0, 1 - std::abs(x)); }

// Parameters of every vertex of the finest level of h from the level-0 parameters `base`
// (`dims` coordinates per vertex; period[c] > 0 wraps coordinate c): each child is the centroid
// of its parent primitive's corners, unwrapped next to the first corner.
std::vector<double> finest_params(const Hierarchy& h, std::vector<double> t, int dims, const std::vector<double>& period) {
  auto centroid = [&](const std::vector<double>& x, auto corners, std::vector<double>& out) {
    const std::uint32_t first = *corners.begin();
    std::size_t n = 0;
    for (int c = 0; c < dims; ++c) out[std::size_t(c)] = 0;
    for (std::uint32_t v : corners) {
      ++n;
      for (int c = 0; c < dims; ++c) {
        double d = x[std::size_t(v) * dims + c] - x[std::size_t(first) * dims + c];
        if (period[std::size_t(c)] > 0) d -= period[std::size_t(c)] * std::round(d / period[std::size_t(c)]);
        out[std::size_t(c)] += x[std::size_t(first) * dims + c] + d;
      }
    }
    for (int c = 0; c < dims; ++c) out[std::size_t(c)] /= double(n);
  };
  std::vector<double> tmp(std::size_t(dims), 0.0);
  for (int l = 0; l < h.finest_level(); ++l) {
    const Complex& p = h.levels[std::size_t(l)];
    std::vector<double> child(std::size_t(p.num_child_vertices()) * dims);
    std::copy(t.begin(), t.end(), child.begin());
    std::size_t at = std::size_t(p.num_vertices) * dims;
    auto put = [&] {
      for (int c = 0; c < dims; ++c) child[at++] = tmp[std::size_t(c)];
    };
    for (std::uint32_t e = 0; e < p.num_edges(); ++e) {
      centroid(t, std::vector<std::uint32_t>{p.edge_verts[2 * e], p.edge_verts[2 * e + 1]}, tmp);
      put();
    }
    for (std::size_t f = 0; f < p.faces.rows(); ++f) {
      centroid(t, p.faces.row(f), tmp);
      put();
    }
    for (std::size_t k = 0; k < p.cell_verts.rows(); ++k) {
      centroid(t, p.cell_verts.row(k), tmp);
      put();
    }
    t = std::move(child);
  }
  return t;
}

double wrap(double d, double period) { return period > 0 ? d - period * std::round(d / period) : d; }

Complex open_polyline(std::uint32_t n) {
  Csr lines;
  for (std::uint32_t i = 0; i < n; ++i) lines.items.push_back(i);
  lines.offsets.push_back(n);
  return complex_from_polylines(n, lines);
}

std::vector<double> line_positions(std::uint32_t n) {
  std::vector<double> p;
  for (std::uint32_t i = 0; i < n; ++i) p.insert(p.end(), {double(i), 0.0, 0.0});
  return p;
}

BasisFunction basis(const Complex& c, Scheme s, BasisKind kind, std::uint32_t index, int K, std::span<const double> pos,
                    bool dual = false) {
  BasisRequest r;
  r.kind = kind;
  r.index = index;
  r.extra_levels = K;
  r.dual = dual;
  return basis_function(c, s, r, pos);
}

TEST(Basis, CubicCurveScalingFunctionIsTheBSpline) {
  std::vector<double> pos;
  const Complex loop = make_curve_loop(32, pos);
  const std::uint32_t i = 10;
  double control_error[3];
  for (int K = 4; K <= 6; ++K) {
    const BasisFunction b = basis(loop, Scheme::Cubic, BasisKind::Scaling, i, K, pos);
    const Hierarchy h = make_hierarchy(loop, K, Scheme::Cubic, 1);
    std::vector<double> t0(32);
    for (std::uint32_t v = 0; v < 32; ++v) t0[v] = v;
    const std::vector<double> t = finest_params(h, t0, 1, {32.0});
    ASSERT_EQ(b.values.size(), t.size());
    EXPECT_TRUE(b.limit);
    double limit_error = 0, ce = 0;
    for (std::size_t v = 0; v < t.size(); ++v) {
      const double exact = bspline3(wrap(t[v] - i, 32));
      limit_error = std::max(limit_error, std::abs(b.values[v] - exact));
      ce = std::max(ce, std::abs(b.control[v] - exact));
    }
    EXPECT_LT(limit_error, 1e-13) << "K = " << K;
    control_error[K - 4] = ce;
    EXPECT_GT(ce, 1e-4 * std::pow(4.0, -K));  // control points are not samples of the B-spline
    // Integral 1 (level-0 units), support (-2, 2) around the vertex.
    EXPECT_NEAR(b.integral, 1.0, 1e-13);
    EXPECT_NEAR(b.max, 2.0 / 3.0, 1e-13);
    EXPECT_EQ(b.support_per_level.front(), 1u);
    EXPECT_EQ(b.support_per_level.size(), std::size_t(K) + 1);
  }
  EXPECT_NEAR(control_error[0] / control_error[1], 4.0, 0.3);
  EXPECT_NEAR(control_error[1] / control_error[2], 4.0, 0.3);
}

TEST(Basis, LinearCurveScalingFunctionIsTheHat) {
  std::vector<double> pos;
  const Complex loop = make_curve_loop(16, pos);
  const BasisFunction b = basis(loop, Scheme::Linear, BasisKind::Scaling, 5, 4, pos);
  const Hierarchy h = make_hierarchy(loop, 4, Scheme::Linear, 1);
  std::vector<double> t0(16);
  for (std::uint32_t v = 0; v < 16; ++v) t0[v] = v;
  const std::vector<double> t = finest_params(h, t0, 1, {16.0});
  for (std::size_t v = 0; v < t.size(); ++v) {
    EXPECT_EQ(b.control[v], hat(wrap(t[v] - 5, 16))) << v;
    EXPECT_EQ(b.values[v], b.control[v]);
  }
  EXPECT_NEAR(b.integral, 1.0, 1e-14);
  EXPECT_EQ(b.support.size(), 2u * 16 - 1);  // open interval (-1, 1) at spacing 1/16
}

TEST(Basis, WaveletsIntegrateToZeroAndCubicHasZeroFirstMoment) {
  const std::uint32_t n = 40;
  const Complex line = open_polyline(n);
  const std::vector<double> pos = line_positions(n);
  const std::uint32_t edge = 20;  // joins vertices 20 and 21, far from both ends
  for (const Scheme s : {Scheme::Linear, Scheme::Cubic}) {
    const BasisFunction w = basis(line, s, BasisKind::Wavelet, n + edge, 6, pos);
    EXPECT_NEAR(w.integral, 0.0, 1e-14) << scheme_name(s);
    EXPECT_GT(w.max, 0.1);
    if (s == Scheme::Cubic) {
      EXPECT_NEAR(w.moment[0], 0.0, 1e-13);
    }
    // For reference, the scaling function has integral 1 and its moment is its centre.
    const BasisFunction phi = basis(line, s, BasisKind::Scaling, edge, 6, pos);
    EXPECT_NEAR(phi.integral, 1.0, 1e-13);
    EXPECT_NEAR(phi.moment[0], double(edge), 1e-12);
  }
  // The same on a closed loop (integral only: the positions are a circle).
  std::vector<double> lp;
  const Complex loop = make_curve_loop(24, lp);
  for (const Scheme s : {Scheme::Linear, Scheme::Cubic})
    EXPECT_NEAR(basis(loop, s, BasisKind::Wavelet, 24 + 3, 5, lp).integral, 0.0, 1e-14);
}

TEST(Basis, TorusScalingFunctionIsTensorProduct) {
  const int n = 12, m = 10;
  const SurfaceMesh mesh = make_quad_torus(n, m);
  const Complex c = complex_from_surface_mesh(mesh);
  const std::vector<double> pos = flatten_positions(mesh);
  const int i = 6, j = 5;
  std::vector<double> t0;
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < m; ++b) t0.insert(t0.end(), {double(a), double(b)});
  for (const Scheme s : {Scheme::Linear, Scheme::Cubic}) {
    const BasisFunction b = basis(c, s, BasisKind::Scaling, std::uint32_t(i * m + j), -1, pos);
    EXPECT_EQ(b.extra_levels, 4);
    const Hierarchy h = make_hierarchy(c, b.extra_levels, s, 1);
    const std::vector<double> t = finest_params(h, t0, 2, {double(n), double(m)});
    ASSERT_EQ(t.size(), 2 * b.values.size());
    double err = 0;
    for (std::size_t v = 0; v < b.values.size(); ++v) {
      const double du = wrap(t[2 * v] - i, n), dv = wrap(t[2 * v + 1] - j, m);
      const double exact = s == Scheme::Cubic ? bspline3(du) * bspline3(dv) : hat(du) * hat(dv);
      err = std::max(err, std::abs(b.values[v] - exact));
    }
    EXPECT_LT(err, 1e-13) << scheme_name(s);
    EXPECT_NEAR(b.integral, 1.0, 1e-12);
  }
}

TEST(Basis, HexBlockScalingFunctionIsTensorProduct) {
  std::vector<double> pos;
  const int n = 6;
  const Complex c = make_hex_block(n, pos);
  const std::uint32_t centre = (3 * (n + 1) + 3) * (n + 1) + 3;
  for (const Scheme s : {Scheme::Linear, Scheme::Cubic}) {
    const BasisFunction b = basis(c, s, BasisKind::Scaling, centre, -1, pos);
    EXPECT_EQ(b.extra_levels, 3);
    const Hierarchy h = make_hierarchy(c, b.extra_levels, s, 1);
    const std::vector<double> t = finest_params(h, pos, 3, {0.0, 0.0, 0.0});
    double err = 0;
    for (std::size_t v = 0; v < b.values.size(); ++v) {
      double exact = 1;
      for (int k = 0; k < 3; ++k) {
        const double d = t[3 * v + std::size_t(k)] - 3;
        exact *= s == Scheme::Cubic ? bspline3(d) : hat(d);
      }
      err = std::max(err, std::abs(b.values[v] - exact));
    }
    EXPECT_LT(err, 1e-13) << scheme_name(s);
    EXPECT_NEAR(b.integral, 1.0, 1e-12);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(b.moment[k], 3.0, 1e-12);
  }
}

struct Case {
  const char* name;
  Complex c;
  std::vector<double> pos;
};

std::vector<Case> irregular_cases() {
  std::vector<Case> out;
  const fixtures::Polygons cube = fixtures::cube();
  out.push_back({"cube", complex_from_polygons(cube.num_vertices, cube.faces), cube.positions});
  FeatureTags creased;
  creased.crease_edges = {{0, 1}, {1, 3}, {3, 2}};
  creased.corner_vertices = {0};
  out.push_back({"creased cube", complex_from_polygons(cube.num_vertices, cube.faces, creased), cube.positions});
  out.push_back({"open polyline", open_polyline(7), line_positions(7)});
  std::vector<double> hp;
  Complex block = make_hex_block(2, hp);
  out.push_back({"hex block", std::move(block), hp});
  Complex prism = testing::prism_cell();
  out.push_back({"prism", std::move(prism), std::vector<double>(18, 0.0)});
  return out;
}

TEST(Basis, PartitionOfUnity) {
  for (const Case& k : irregular_cases())
    for (const Scheme s : {Scheme::Linear, Scheme::Cubic}) {
      std::vector<double> sum_control, sum_values;
      for (std::uint32_t v = 0; v < k.c.num_vertices; ++v) {
        const BasisFunction b = basis(k.c, s, BasisKind::Scaling, v, 2, k.pos);
        sum_control.resize(b.control.size(), 0.0);
        sum_values.resize(b.values.size(), 0.0);
        for (std::size_t i = 0; i < b.control.size(); ++i) {
          sum_control[i] += b.control[i];
          sum_values[i] += b.values[i];
        }
      }
      for (std::size_t i = 0; i < sum_control.size(); ++i) {
        ASSERT_NEAR(sum_control[i], 1.0, 1e-13) << k.name << " " << scheme_name(s) << " vertex " << i;
        ASSERT_NEAR(sum_values[i], 1.0, 1e-13) << k.name << " " << scheme_name(s) << " vertex " << i;
      }
    }
}

// A few coefficients of each case: two scaling ones, the first e-, f- and c-wavelets present.
std::vector<std::pair<BasisKind, std::uint32_t>> some_coefficients(const Complex& c) {
  std::vector<std::pair<BasisKind, std::uint32_t>> out = {{BasisKind::Scaling, 0},
                                                          {BasisKind::Scaling, c.num_vertices - 1},
                                                          {BasisKind::Wavelet, c.num_vertices}};
  if (c.num_faces()) out.push_back({BasisKind::Wavelet, c.num_vertices + c.num_edges() + 1});
  if (c.num_cells()) out.push_back({BasisKind::Wavelet, c.num_vertices + c.num_edges() + c.num_faces()});
  return out;
}

TEST(Basis, AnalysisOfSynthesisedUnitIsThatUnit) {
  const int K = 2;
  for (const Case& k : irregular_cases())
    for (const Scheme s : {Scheme::Linear, Scheme::Cubic}) {
      const auto coeffs = some_coefficients(k.c);
      std::vector<BasisFunction> primal, dual;
      for (const auto& [kind, index] : coeffs) {
        primal.push_back(basis(k.c, s, kind, index, K, k.pos));
        dual.push_back(basis(k.c, s, kind, index, K, k.pos, true));
      }
      Hierarchy h = make_hierarchy(k.c, K, s, 1);
      for (std::size_t a = 0; a < coeffs.size(); ++a) {
        analyze(h, primal[a].control);
        for (std::size_t i = 0; i < h.coeffs.size(); ++i)
          ASSERT_NEAR(h.coeffs[i], i == coeffs[a].second ? 1.0 : 0.0, 1e-13) << k.name << " " << scheme_name(s);
        for (std::size_t b = 0; b < coeffs.size(); ++b) {
          double ip = 0;
          for (std::size_t i = 0; i < primal[b].control.size(); ++i) ip += dual[a].control[i] * primal[b].control[i];
          EXPECT_NEAR(ip, a == b ? 1.0 : 0.0, 1e-13) << k.name << " " << scheme_name(s) << " " << a << " " << b;
        }
        // The dual functional of a scaling coefficient reads 1 from the constant and the
        // coefficient's own position from the synthesised geometry; a dual wavelet reads 0.
        const bool scaling = coeffs[a].first == BasisKind::Scaling;
        EXPECT_NEAR(dual[a].integral, scaling ? 1.0 : 0.0, 1e-13) << k.name;
        for (int c = 0; c < 3; ++c)
          EXPECT_NEAR(dual[a].moment[c], scaling ? k.pos[3 * coeffs[a].second + std::size_t(c)] : 0.0, 1e-12) << k.name;
      }
    }
}

TEST(Basis, DualAdjointEqualsBruteForceAnalysis) {
  const int K = 2;
  for (const Case& k : irregular_cases())
    for (const Scheme s : {Scheme::Linear, Scheme::Cubic}) {
      Hierarchy h = make_hierarchy(k.c, K, s, 1);
      const std::uint32_t n = h.num_vertices(K);
      for (const auto& [kind, index] : some_coefficients(k.c)) {
        const BasisFunction d = basis(k.c, s, kind, index, K, k.pos, true);
        ASSERT_EQ(d.control.size(), n);
        EXPECT_FALSE(d.limit);
        std::vector<double> e(n, 0.0);
        double err = 0;
        for (std::uint32_t v = 0; v < n; ++v) {
          e[v] = 1.0;
          analyze(h, e);
          e[v] = 0.0;
          err = std::max(err, std::abs(h.coeffs[index] - d.control[v]));
        }
        EXPECT_LT(err, 1e-13) << k.name << " " << scheme_name(s) << " index " << index;
      }
    }
}

TEST(Basis, SupportAndErrors) {
  std::vector<double> pos;
  const Complex loop = make_curve_loop(32, pos);
  // Linear scaling function of a curve: 1, 3, 7, ... non-zero control values per level.
  const BasisFunction b = basis(loop, Scheme::Linear, BasisKind::Scaling, 3, 3, pos);
  ASSERT_EQ(b.support_per_level.size(), 4u);
  EXPECT_EQ(b.support_per_level[0], 1u);
  EXPECT_EQ(b.support_per_level[1], 3u);
  EXPECT_EQ(b.support_per_level[2], 7u);
  EXPECT_EQ(b.support_per_level[3], 15u);
  EXPECT_EQ(b.support.size(), 15u);
  EXPECT_EQ(b.finest.num_vertices, 32u * 8);
  // A wavelet has no level-j control values.
  EXPECT_EQ(basis(loop, Scheme::Cubic, BasisKind::Wavelet, 40, 2, pos).support_per_level[0], 0u);
  EXPECT_THROW(basis(loop, Scheme::Cubic, BasisKind::Wavelet, 3, 2, pos), Error);   // a v vertex
  EXPECT_THROW(basis(loop, Scheme::Cubic, BasisKind::Wavelet, 64, 2, pos), Error);  // beyond level 1
  EXPECT_THROW(basis(loop, Scheme::Cubic, BasisKind::Scaling, 32, 2, pos), Error);
  EXPECT_THROW(basis(loop, Scheme::Cubic, BasisKind::Wavelet, 40, 0, pos), Error);  // K = 0
  BasisRequest big;
  big.extra_levels = 12;
  big.max_vertices = 1e5;
  EXPECT_THROW(basis_function(loop, Scheme::Cubic, big, pos), Error);
  EXPECT_EQ(default_extra_levels(loop, 1000), 4);  // 32 * 2^4 = 512 <= 1000 < 1024
}

}  // namespace
}  // namespace sublift
