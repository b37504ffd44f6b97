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

#include <glm/geometric.hpp>

#include "core/complex/complex_build.h"
#include "core/complex/polygon_normal.h"
#include "core/fit/feature_lines.h"
#include "core/fit/sparse_product.h"
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
// triangle of its face's fan, and the couplings across the diagonal are kept.
TEST(NetSolve, AQuadNetSolvesAsItsFanTriangulation) {
  const fixtures::Polygons cube = fixtures::cube();
  Hierarchy h = make_hierarchy(complex_from_polygons(cube.num_vertices, cube.faces), 2, Scheme::Cubic, 3);
  set_base(h, cube.positions);
  const Complex quads = finest_with_adjacency(h);
  const std::vector<double> x = synthesize(h, 2);
  Csr fan;
  for (std::size_t f = 0; f < quads.faces.rows(); ++f) {
    const auto r = quads.faces.row(f);
    for (std::size_t t = 1; t + 1 < r.size(); ++t) fixtures::push_row(fan, {r[0], r[t], r[t + 1]});
  }
  Complex tris = complex_from_polygons(quads.num_vertices, fan);
  build_adjacency(tris);
  // The input: the net's points pushed out by 10 % and turned a little; targets 5 % out.
  std::vector<double> input(x.size()), targets(x.size());
  for (std::size_t v = 0; v < x.size() / 3; ++v)
    for (int k = 0; k < 3; ++k) {
      const double* p = &x[3 * v];
      input[3 * v + k] = 1.1 * p[k] + 0.02 * p[(k + 1) % 3];
      targets[3 * v + k] = 1.05 * p[k];
    }
  const std::vector<double> n = area_weighted_normals(fan, input);
  NetSolveWeights w;
  w.kappa = 0;
  const std::vector<double> a = solve_net(quads, {x, x, targets}, input, n, {}, w);
  const std::vector<double> b = solve_net(tris, {x, x, targets}, input, n, {}, w);
  EXPECT_LE(testing::max_abs_diff(a, b), 1e-9);
  EXPECT_GT(testing::max_abs_diff(a, x), 0.01);  // and the input did pull the net
}

// The solve's own sparse product against Eigen's, bit for bit: random matrices wider than one
// chunk of columns, with empty columns and rows, entries that cancel to zero, and the shapes
// L^T M L takes (square, and a product of products).
TEST(SparseProduct, BitForBitEigens) {
  using Sparse = Eigen::SparseMatrix<double>;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  const auto random_matrix = [&](int rows, int cols, int per_column) {
    std::vector<Eigen::Triplet<double>> t;
    for (int j = 0; j < cols; ++j) {
      if (j % 97 == 5) continue;  // an empty column
      for (int k = 0; k < per_column; ++k) {
        const int i = static_cast<int>(rng() % static_cast<unsigned>(rows));
        if (i % 89 == 3) continue;  // rows left empty
        const double x = k == 0 ? 0.5 : value(rng);
        t.emplace_back(i, j, x);
        if (k == 1) t.emplace_back(i, j, -x);  // a duplicate that cancels: an explicit zero
      }
    }
    Sparse m(rows, cols);
    m.setFromTriplets(t.begin(), t.end());
    return m;
  };
  const auto expect_same_bits = [](const Sparse& ours, const Sparse& eigens, const char* what) {
    ASSERT_EQ(ours.rows(), eigens.rows()) << what;
    ASSERT_EQ(ours.cols(), eigens.cols()) << what;
    ASSERT_EQ(ours.nonZeros(), eigens.nonZeros()) << what;
    ASSERT_TRUE(ours.isCompressed()) << what;
    for (int j = 0; j < eigens.outerSize(); ++j) {
      ASSERT_EQ(ours.outerIndexPtr()[j + 1], eigens.outerIndexPtr()[j + 1]) << what << ", column " << j;
      for (Sparse::InnerIterator x(ours, j), y(eigens, j); y; ++x, ++y) {
        EXPECT_EQ(x.index(), y.index()) << what << ", column " << j;
        const double a = x.value(), b = y.value();
        EXPECT_EQ(std::memcmp(&a, &b, sizeof a), 0) << what << ", entry (" << y.index() << ", " << j << "): " << a << " vs " << b;
      }
    }
  };
  const Sparse l = random_matrix(5000, 5000, 12), m = random_matrix(5000, 5000, 7);
  const Sparse lt = l.transpose();
  const Sparse lm = fit_detail::sparse_product(lt, m);
  expect_same_bits(lm, Sparse(lt * m), "L^T M");
  expect_same_bits(fit_detail::sparse_product(lm, l), Sparse(lt * m * l), "L^T M L");
  const Sparse wide = random_matrix(300, 7000, 4), tall = random_matrix(7000, 40, 30);
  expect_same_bits(fit_detail::sparse_product(wide, tall), Sparse(wide * tall), "300 x 7000 times 7000 x 40");
  expect_same_bits(fit_detail::sparse_product(Sparse(0, 0), Sparse(0, 0)), Sparse(0, 0), "empty");
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
