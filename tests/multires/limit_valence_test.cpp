// Limit stencils at high valence (issue 18): the structured solve (power iteration, the
// rotational symmetry's frequency blocks) against the dense eigen-analysis where both can run,
// and the limit points of a 1000-gon and of a valence-1000 vertex against repeated subdivision.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <vector>

#include "core/complex/complex_build.h"
#include "core/multires/hierarchy.h"
#include "core/multires/limit.h"
#include "tests/limit_convergence.h"
#include "tests/mesh_fixtures.h"

namespace sublift {
namespace {

using fixtures::Polygons;

Complex complex_of(const Polygons& m) {
  Complex c = complex_from_polygons(m.num_vertices, m.faces);
  build_adjacency(c);
  return c;
}

Hierarchy surface(const Polygons& m, int levels) {
  Hierarchy h = make_hierarchy(complex_from_polygons(m.num_vertices, m.faces), levels, Scheme::Cubic, 3);
  set_base(h, m.positions);
  return h;
}

// Distance of each column of `b` from the span of the columns of `a` (least squares), relative.
double span_residual(const std::vector<double>& a1, const std::vector<double>& a2, const std::vector<double>& b) {
  const Eigen::Index n = Eigen::Index(b.size());
  Eigen::MatrixXd A(n, 2);
  for (Eigen::Index i = 0; i < n; ++i) A(i, 0) = a1[std::size_t(i)], A(i, 1) = a2[std::size_t(i)];
  const Eigen::VectorXd y = Eigen::Map<const Eigen::VectorXd>(b.data(), n);
  const Eigen::VectorXd x = A.colPivHouseholderQr().solve(y);
  return (A * x - y).norm() / y.norm();
}

void expect_structured_equals_dense(const Polygons& m, double spectrum_tol) {
  const Complex c = complex_of(m);
  const ProbedStencil d = probe_limit_stencil(c, 0, LimitSolver::Dense);
  const ProbedStencil s = probe_limit_stencil(c, 0, LimitSolver::Structured);
  ASSERT_TRUE(d.ok);
  ASSERT_TRUE(s.ok);
  ASSERT_EQ(d.vertices, s.vertices);
  double worst = 0, sum = 0;
  for (std::size_t i = 0; i < d.weights.size(); ++i) worst = std::max(worst, std::abs(d.weights[i] - s.weights[i])), sum += s.weights[i];
  EXPECT_LT(worst, 1e-13);
  EXPECT_NEAR(sum, 1.0, 1e-13);
  ASSERT_EQ(s.spectrum.size(), d.spectrum.size());
  for (std::size_t i = 0; i < d.spectrum.size(); ++i) EXPECT_NEAR(s.spectrum[i], d.spectrum[i], spectrum_tol) << "eigenvalue " << i;
  ASSERT_FALSE(d.du.empty());
  ASSERT_FALSE(s.du.empty());
  // The same tangent plane stencils: each pair spans the other.
  EXPECT_LT(span_residual(s.du, s.dv, d.du), 1e-10);
  EXPECT_LT(span_residual(s.du, s.dv, d.dv), 1e-10);
  EXPECT_LT(span_residual(d.du, d.dv, s.du), 1e-10);
  EXPECT_LT(span_residual(d.du, d.dv, s.dv), 1e-10);
}

TEST(LimitValence, StructuredSolveEqualsDenseOnQuadFans) {
  for (std::uint32_t n : {3u, 5u, 8u, 20u, 40u}) {
    SCOPED_TRACE("valence " + std::to_string(n));
    expect_structured_equals_dense(fixtures::quad_fan(n), 1e-11);
  }
}

TEST(LimitValence, StructuredSolveEqualsDenseOnTriangleFans) {
  // The finest level is the base: triangles in the star (face points of valence 3 one level on).
  for (std::uint32_t n : {5u, 12u, 30u}) {
    SCOPED_TRACE("valence " + std::to_string(n));
    expect_structured_equals_dense(fixtures::triangle_cone(n), 1e-11);
  }
}

TEST(LimitValence, LargeFanOfMixedFacesIsSymmetricOneLevelOn) {
  // Triangles among the quads: the patch has no symmetry, but the star's own matrix (level 1 to
  // 2, all quads) has, so the structured solve still finds the tangents.
  expect_structured_equals_dense(fixtures::quad_fan(80, /*mixed=*/true), 1e-11);
}

TEST(LimitValence, LargeDartGetsItsPositionAndFaceNormals) {
  // One crease edge at a valence-80 surface vertex: the star's matrix has no rotational symmetry.
  const Polygons m = fixtures::quad_fan(80);
  FeatureTags tags;
  tags.crease_edges = {{0, 1}};
  Complex c = complex_from_polygons(m.num_vertices, m.faces, tags);
  build_adjacency(c);
  ASSERT_EQ(c.vertex_dim[0], 2);
  const ProbedStencil a = probe_limit_stencil(c, 0);
  const ProbedStencil d = probe_limit_stencil(c, 0, LimitSolver::Dense);
  ASSERT_TRUE(a.ok);
  ASSERT_TRUE(d.ok);
  EXPECT_TRUE(a.du.empty()) << "no exact tangents without the symmetry: the faces give the normal";
  EXPECT_TRUE(a.spectrum.empty());
  ASSERT_EQ(a.vertices, d.vertices);
  double worst = 0;
  for (std::size_t i = 0; i < d.weights.size(); ++i) worst = std::max(worst, std::abs(d.weights[i] - a.weights[i]));
  EXPECT_LT(worst, 1e-13);
}

// |lambda_2| is about 0.6545 at high valence: at least 20 % a level, and a quarter (or a third)
// of the first error after four (three) levels (tests/limit_convergence.h).
void expect_converges(const Polygons& m, int base_levels, std::uint32_t vertex, int more, double last) {
  testing::expect_converges(m, base_levels, vertex, more, {.min_first = 1e-3, .rate = 0.8, .last_ratio = last});
}

TEST(LimitValence, ThousandGonFacePointConvergesToItsStencil) {
  const Polygons m = fixtures::ngon_prism(1000);
  const Hierarchy h = surface(m, 1);
  const std::uint32_t centre = h.num_vertices(0) + h.levels[0].num_edges();  // the face point
  const Complex c = [&] { Complex x = h.levels[1]; build_adjacency(x); return x; }();
  ASSERT_EQ(c.vertex_edges.size(centre), 1000u);
  const ProbedStencil p = probe_limit_stencil(c, centre);
  ASSERT_TRUE(p.ok);
  EXPECT_FALSE(p.du.empty()) << "a uniform fan: exact tangents from the frequency-1 block";
  ASSERT_EQ(p.spectrum.size(), 2001u);
  EXPECT_NEAR(p.spectrum[0], 1.0, 1e-12);
  EXPECT_NEAR(p.spectrum[1], p.spectrum[2], 1e-12);
  // The subdominant eigenvalue at valence 1000 (docs/limit_stencils.md: it tends to ~0.6545).
  EXPECT_GT(p.spectrum[1], 0.65);
  EXPECT_LT(p.spectrum[1], 0.66);
  // 0.6545 per level asymptotically: three levels take the error below a third.
  expect_converges(m, 1, centre, 3, 0.35);
  expect_converges(m, 1, centre + 1, 3, 0.35);  // the other cap
}

TEST(LimitValence, ValenceThousandVertexConvergesToItsStencil) {
  const Polygons m = fixtures::triangle_cone(1000);
  expect_converges(m, 1, 0, 4, 0.25);  // a valence-1000 vertex among quads
  expect_converges(m, 0, 0, 4, 0.25);  // the base itself: its triangles in the star
}

}  // namespace
}  // namespace sublift
