// The two-way solve (core/fit/net_solve.h) and the feature lines' query (core/fit/
// feature_lines.h). A net that already lies on the input, its points on their projections and
// every input vertex on it, is where the energy is zero: the solve must return it, with the net
// as the surface and with its limit surface. A net pulled by input vertices beyond it moves
// towards them. The lines' closest point equals brute force over the segments.
#include "core/fit/net_solve.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <glm/geometric.hpp>

#include "core/complex/complex_build.h"
#include "core/complex/polygon_normal.h"
#include "core/base/parallel.h"
#include "core/fit/feature_lines.h"
#include "core/fit/net_system.h"
#include "core/multires/hierarchy.h"
#include "tests/mesh_fixtures.h"
#include "tests/test_shapes.h"

namespace sublift {
namespace {

// An octahedron subdivided `levels` times by Loop, its finest level with adjacency.
Hierarchy octahedron(int levels) {
  Csr f;
  const std::uint32_t tris[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (const auto& t : tris) {
    f.items.insert(f.items.end(), {t[0], t[1], t[2]});
    f.offsets.push_back(static_cast<std::uint32_t>(f.items.size()));
  }
  Hierarchy h = make_hierarchy(complex_from_polygons(6, f), levels, Scheme::Loop, 3);
  set_base(h, std::vector<double>{1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1});
  return h;
}

Complex finest_with_adjacency(const Hierarchy& h) {
  Complex c = h.levels.back();
  if (c.vertex_edges.rows() != c.num_vertices) build_adjacency(c);
  return c;
}

TEST(NetSolve, ANetOnTheInputStaysPut) {
  const Hierarchy h = octahedron(3);
  const Complex c = finest_with_adjacency(h);
  const std::vector<double> x = synthesize(h, 3);
  const std::vector<double> n = area_weighted_normals(c.faces, x);
  EXPECT_LE(testing::max_abs_diff(solve_net(c, {x, x, x}, x, n, {}), x), 1e-9);
  // The limit surface as the surface: the input is the limit's own points.
  const LimitStencils ls = build_limit_stencils(h);
  std::vector<double> y(x.size());
  eval_limit(ls, x.data(), y.data());
  EXPECT_LE(testing::max_abs_diff(solve_net(c, {x, y, y, &ls}, y, area_weighted_normals(c.faces, y), {}), x), 1e-8);
}

TEST(NetSolve, InputBeyondTheNetPullsItOut) {
  const Hierarchy h = octahedron(2);
  const Complex c = finest_with_adjacency(h);
  const std::vector<double> x = synthesize(h, 2);
  // The input: the same net scaled by 1.1 about the centre; the targets stay on the net.
  std::vector<double> input = x;
  for (double& v : input) v *= 1.1;
  const std::vector<double> solved = solve_net(c, {x, x, x}, input, area_weighted_normals(c.faces, input), {});
  double before = 0, after = 0;
  for (std::uint32_t v = 0; v < c.num_vertices; ++v) {
    const glm::dvec3 a(x[3 * v], x[3 * v + 1], x[3 * v + 2]), b(solved[3 * v], solved[3 * v + 1], solved[3 * v + 2]);
    before += glm::length(a), after += glm::length(b);
  }
  // Pulled half way between net (alpha = 1) and input (the same weight per point): 1.05.
  EXPECT_GT(after / before, 1.03);
  EXPECT_LT(after / before, 1.07);
  // Held firmly (hold 1e6), the net does not move.
  const std::vector<double> hold(c.num_vertices, 1e6);
  EXPECT_LE(testing::max_abs_diff(solve_net(c, {x, x, x}, input, area_weighted_normals(c.faces, input), hold), x), 1e-6);
}

// A polygon net solves as its fan triangulation would (springs off: the springs live on the
// edges, and the triangulation has the diagonals as edges too): an input point's foot is on one
// triangle of its face's fan, and the couplings across the diagonals are kept. Quads (a cube's
// level 2) and pentagons (a pentagonal prism, two diagonals each).
TEST(NetSolve, APolygonNetSolvesAsItsFanTriangulation) {
  const auto check = [](const Complex& polygons, const std::vector<double>& x, const char* name) {
    Csr fan;
    for (std::size_t f = 0; f < polygons.faces.rows(); ++f) {
      const auto r = polygons.faces.row(f);
      for (std::size_t t = 1; t + 1 < r.size(); ++t) fixtures::push_row(fan, {r[0], r[t], r[t + 1]});
    }
    Complex tris = complex_from_polygons(polygons.num_vertices, fan);
    build_adjacency(tris);
    // The input: the net's points and its faces' centres (whose feet lie inside the faces, so
    // the diagonals couple), pushed out by 10 % and turned a little; targets 5 % out.
    std::vector<double> centred = x, targets(x.size());
    for (std::size_t f = 0; f < polygons.faces.rows(); ++f) {
      glm::dvec3 m(0.0);
      for (const std::uint32_t v : polygons.faces.row(f)) m += glm::dvec3(x[3 * v], x[3 * v + 1], x[3 * v + 2]);
      m /= double(polygons.faces.size(f));
      centred.insert(centred.end(), {m.x, m.y, m.z});
    }
    std::vector<double> input(centred.size());
    for (std::size_t v = 0; v < centred.size() / 3; ++v)
      for (int k = 0; k < 3; ++k) {
        const double* p = &centred[3 * v];
        input[3 * v + k] = 1.1 * p[k] + 0.02 * p[(k + 1) % 3];
        if (3 * v < x.size()) targets[3 * v + k] = 1.05 * p[k];
      }
    std::vector<double> n = area_weighted_normals(fan, std::span<const double>(input).first(x.size()));
    n.resize(input.size(), 0.0);  // the centres: pull the nearest face
    NetSolveWeights w;
    w.kappa = 0;
    const std::vector<double> a = solve_net(polygons, {x, x, targets}, input, n, {}, w);
    const std::vector<double> b = solve_net(tris, {x, x, targets}, input, n, {}, w);
    EXPECT_LE(testing::max_abs_diff(a, b), 1e-9) << name;
    EXPECT_GT(testing::max_abs_diff(a, x), 0.01) << name;  // and the input did pull the net
  };
  const fixtures::Polygons cube = fixtures::cube();
  Hierarchy h = make_hierarchy(complex_from_polygons(cube.num_vertices, cube.faces), 2, Scheme::Cubic, 3);
  set_base(h, cube.positions);
  check(finest_with_adjacency(h), synthesize(h, 2), "cube, level 2");
  fixtures::Polygons prism;  // pentagons 0-4 (z = -1) and 5-9 (z = 1), quads between
  prism.num_vertices = 10;
  for (std::uint32_t i = 0; i < 5; ++i) {
    const double a = 2 * 3.14159265358979 * i / 5;
    prism.positions.insert(prism.positions.end(), {std::cos(a), std::sin(a), -1.0});
  }
  for (std::uint32_t i = 0; i < 5; ++i) prism.positions.insert(prism.positions.end(), {prism.positions[3 * i], prism.positions[3 * i + 1], 1.0});
  fixtures::push_row(prism.faces, {4, 3, 2, 1, 0});
  fixtures::push_row(prism.faces, {5, 6, 7, 8, 9});
  for (std::uint32_t i = 0; i < 5; ++i) fixtures::push_row(prism.faces, {i, (i + 1) % 5, 5 + (i + 1) % 5, 5 + i});
  Complex c = complex_from_polygons(prism.num_vertices, prism.faces);
  build_adjacency(c);
  check(c, prism.positions, "pentagonal prism");
}

// The system applied without forming it (core/fit/net_system.h) against Eigen's formed
// A = L^T M L + K: the products, the diagonal (Jacobi's), and conjugate gradients against a
// direct factorisation; with L (the cubic scheme's limit stencils on a cube's finest level, quads
// with fan couplings) and without. The bits of a solve are the same on one thread and on two
// (6,146 vertices: sums over two blocks).
TEST(NetSystem, AppliesAndSolvesTheFormedSystem) {
  using Sparse = Eigen::SparseMatrix<double>;
  const fixtures::Polygons cube = fixtures::cube();
  Hierarchy h = make_hierarchy(complex_from_polygons(cube.num_vertices, cube.faces), 5, Scheme::Cubic, 3);
  set_base(h, cube.positions);
  const Complex c = finest_with_adjacency(h);
  const LimitStencils ls = build_limit_stencils(h);
  const std::uint32_t n = c.num_vertices;
  const std::vector<double> noise = testing::random_values(n + c.num_edges() + c.faces.rows(), 3, 0.0, 1.0);
  std::vector<double> diag(n), off(c.num_edges());
  for (std::uint32_t v = 0; v < n; ++v) diag[v] = 8.0 + noise[v];
  for (std::uint32_t e = 0; e < off.size(); ++e) off[e] = 0.5 * noise[n + e] - 0.25;
  std::vector<fit_detail::Coupling> couplings;  // each face's diagonal (0, 2), some twice
  for (std::uint32_t f = 0; f < c.faces.rows(); ++f)
    for (int twice = 0; twice < 1 + int(f % 3 == 0); ++twice)
      couplings.push_back({c.faces.row(f)[0], c.faces.row(f)[2], 0.3 * noise[n + off.size() + f]});
  const double kappa = 0.7;
  std::vector<Eigen::Triplet<double>> tm, tk, tl;
  for (std::uint32_t v = 0; v < n; ++v) tm.emplace_back(v, v, diag[v]);
  for (std::uint32_t e = 0; e < off.size(); ++e) {
    const std::uint32_t a = c.edge_verts[2 * e], b = c.edge_verts[2 * e + 1];
    tm.emplace_back(a, b, off[e]), tm.emplace_back(b, a, off[e]);
    tk.emplace_back(a, a, kappa), tk.emplace_back(b, b, kappa), tk.emplace_back(a, b, -kappa), tk.emplace_back(b, a, -kappa);
  }
  for (const fit_detail::Coupling& k : couplings) tm.emplace_back(k.a, k.b, k.w), tm.emplace_back(k.b, k.a, k.w);
  for (std::uint32_t v = 0; v < n; ++v)
    for (std::uint32_t k = ls.rows.offsets[v]; k < ls.rows.offsets[v + 1]; ++k) tl.emplace_back(v, ls.rows.items[k], ls.weights[k]);
  Sparse m(n, n), springs(n, n), l(n, n);
  m.setFromTriplets(tm.begin(), tm.end());
  springs.setFromTriplets(tk.begin(), tk.end());
  l.setFromTriplets(tl.begin(), tl.end());

  fit_detail::NetSystem with_limit;
  with_limit.net = &c;
  with_limit.limit = {ls.rows.offsets, ls.rows.items, ls.weights};
  with_limit.limit_t = fit_detail::transposed(with_limit.limit, n);
  with_limit.data = fit_detail::net_rows(c, diag, off, couplings);
  with_limit.kappa = kappa;
  std::vector<double> diag_k(diag), off_k(off);
  for (std::uint32_t v = 0; v < n; ++v) diag_k[v] += kappa * c.vertex_edges.size(v);
  for (double& o : off_k) o -= kappa;
  fit_detail::NetSystem net_only;
  net_only.net = &c;
  net_only.data = fit_detail::net_rows(c, diag_k, off_k, couplings);

  const std::vector<double> x = testing::random_values(3 * std::size_t(n), 11), b = testing::random_values(3 * std::size_t(n), 12);
  const auto as_matrix = [n](const std::vector<double>& v) { return Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(v.data(), n, 3); };
  const struct {
    const char* name;
    const fit_detail::NetSystem& ours;
    Sparse formed;
  } cases[] = {{"L^T M L + K", with_limit, Sparse(l.transpose() * m * l + springs)}, {"M + K", net_only, Sparse(m + springs)}};
  const int threads_before = parallel_threads();
  for (const auto& cs : cases) {
    const double scale = cs.formed.coeffs().cwiseAbs().maxCoeff();
    std::vector<double> y(x.size());
    cs.ours.apply(x, y);
    EXPECT_LE((as_matrix(y) - cs.formed * as_matrix(x)).cwiseAbs().maxCoeff(), 1e-12 * scale) << cs.name;
    const std::vector<double> d = cs.ours.diagonal();
    for (std::uint32_t v = 0; v < n; ++v) EXPECT_NEAR(d[v], cs.formed.coeff(v, v), 1e-13 * scale) << cs.name << ", vertex " << v;
    Eigen::SimplicialLDLT<Sparse> direct(cs.formed);
    ASSERT_EQ(direct.info(), Eigen::Success) << cs.name;
    const Eigen::MatrixXd exact = direct.solve(Eigen::MatrixXd(as_matrix(b)));
    std::vector<double> first;
    for (const int threads : {1, 2}) {
      set_parallel_threads(threads);
      std::vector<double> solved(x);  // from x as the first guess
      EXPECT_GT(fit_detail::solve_cg3(cs.ours, b, solved, 1e-12, 1000), 0) << cs.name;
      EXPECT_LE((as_matrix(solved) - exact).cwiseAbs().maxCoeff(), 1e-9 * exact.cwiseAbs().maxCoeff()) << cs.name << ", " << threads << " threads";
      if (threads == 1) first = solved;
      else EXPECT_EQ(std::memcmp(first.data(), solved.data(), solved.size() * sizeof(double)), 0) << cs.name << ": bits differ with threads";
    }
    set_parallel_threads(threads_before);
  }
}

TEST(FeatureLines, ClosestPointIsTheBruteForceOne) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0), d(-0.05, 0.05);
  std::vector<double> xyz;
  std::vector<std::uint32_t> edges;
  for (std::uint32_t s = 0; s < 200; ++s) {  // short segments, as a mesh's edges are
    const double cx = u(rng), cy = u(rng), cz = u(rng);
    xyz.insert(xyz.end(), {cx, cy, cz, cx + d(rng), cy + d(rng), cz + d(rng)});
    edges.insert(edges.end(), {2 * s, 2 * s + 1});
  }
  const FeatureLines lines(xyz, edges);
  ASSERT_EQ(lines.size(), 200u);
  std::uniform_real_distribution<double> q(-0.5, 1.5);
  for (int k = 0; k < 300; ++k) {
    const glm::dvec3 p(q(rng), q(rng), q(rng));
    double best = std::numeric_limits<double>::infinity();
    for (std::uint32_t s = 0; s < 200; ++s) {
      const glm::dvec3 a(xyz[6 * s], xyz[6 * s + 1], xyz[6 * s + 2]), b(xyz[6 * s + 3], xyz[6 * s + 4], xyz[6 * s + 5]);
      const double t = std::clamp(glm::dot(p - a, b - a) / glm::dot(b - a, b - a), 0.0, 1.0);
      best = std::min(best, glm::distance(p, a + t * (b - a)));
    }
    EXPECT_NEAR(glm::distance(lines.closest(p), p), best, 1e-12) << k;
  }
  EXPECT_TRUE(FeatureLines(xyz, {}).empty());
}

}  // namespace
}  // namespace sublift
