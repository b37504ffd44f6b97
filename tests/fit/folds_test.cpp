// Folded faces of a fitted net (core/fit/folds.h): the guard never folds a face, and untangling
// brings folded faces back, in the net and in a Loop limit surface, on a flat grid whose input
// faces +z everywhere.
#include "core/fit/folds.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/complex/complex_build.h"
#include "core/multires/hierarchy.h"
#include "tests/mesh_fixtures.h"

namespace sublift {
namespace {

// An n x n grid of unit squares in the plane z = 0, each cut into two triangles.
Complex grid(std::uint32_t n, std::vector<double>& x) {
  Csr faces;
  x.clear();
  for (std::uint32_t j = 0; j <= n; ++j)
    for (std::uint32_t i = 0; i <= n; ++i) x.insert(x.end(), {double(i), double(j), 0.0});
  for (std::uint32_t j = 0; j < n; ++j)
    for (std::uint32_t i = 0; i < n; ++i) {
      const std::uint32_t a = j * (n + 1) + i;
      fixtures::push_row(faces, {a, a + 1, a + n + 2});
      fixtures::push_row(faces, {a, a + n + 2, a + n + 1});
    }
  Complex c = complex_from_polygons((n + 1) * (n + 1), faces);
  build_adjacency(c);
  return c;
}

const FacingFn up = [](std::span<const double> x) { return std::vector<glm::dvec3>(x.size(), glm::dvec3(0, 0, 1)); };
const ProjectFn onto_plane = [](const glm::dvec3& p, const glm::dvec3&, double) { return glm::dvec3(p.x, p.y, 0.0); };

std::size_t folds(const Csr& faces, std::span<const double> x) {
  std::size_t n = 0;
  for (std::size_t f = 0; f < faces.rows(); ++f) n += turned(faces, f, x, {0, 0, 1});
  return n;
}

TEST(Folds, GuardTakesBackMovesThatFold) {
  std::vector<double> x;
  const Complex c = grid(4, x);
  std::vector<double> after = x;
  after[3 * 12] += 1.6;  // the centre (2, 2) past its neighbour (3, 2): its faces turn over
  ASSERT_GT(folds(c.faces, after), 0u);
  keep_unfolded(c.faces, up(x), x, after);
  EXPECT_EQ(folds(c.faces, after), 0u);
  EXPECT_GT(after[3 * 12], 2.0);  // part of the move stays
}

// The parallel per-face verdicts (chunks on both threads: more faces than a chunk) are the
// serial ones, face for face, and their count.
TEST(Folds, TurnedFacesInParallelAreEachFacesVerdict) {
  std::vector<double> x;
  const Complex c = grid(60, x);
  for (std::uint32_t v = 0; v < c.num_vertices; v += 97) x[3 * v] += 1.5;  // scattered folds
  const std::vector<glm::dvec3> facing = up(x);
  const std::vector<std::uint8_t> t = turned_faces(c.faces, x, facing);
  ASSERT_EQ(t.size(), c.faces.rows());
  std::size_t n = 0;
  for (std::size_t f = 0; f < c.faces.rows(); ++f) {
    EXPECT_EQ(t[f] != 0, turned(c.faces, f, x, facing[f])) << f;
    n += t[f];
  }
  EXPECT_GT(n, 50u);
  EXPECT_EQ(count_turned(c.faces, x, facing), n);
  EXPECT_EQ(folds(c.faces, x), n);
}

TEST(Folds, UntangleUnfoldsTheNet) {
  std::vector<double> x;
  const Complex c = grid(6, x);
  const std::vector<double> flat = x;
  x[3 * 24] += 1.7, x[3 * 24 + 1] += 0.4;  // vertex (3, 3) over (4, 3)
  x[3 * 16] -= 1.3;                         // and (2, 2) over (1, 2)
  ASSERT_GT(folds(c.faces, x), 3u);
  untangle(c, onto_plane, FeatureLines({}, {}), up(x), x);
  EXPECT_EQ(folds(c.faces, x), 0u);
  // Only the points of folded faces moved: the grid's rim is where it was.
  for (std::uint32_t v = 0; v < c.num_vertices; ++v)
    if (c.vertex_dim[v] < 2) {
      for (int k = 0; k < 3; ++k) EXPECT_EQ(x[3 * v + k], flat[3 * v + k]) << v;
    }
}

TEST(Folds, UntangleLimitUnfoldsTheLoopLimitSurface) {
  std::vector<double> x0;
  const Complex base = grid(3, x0);
  Hierarchy h = make_hierarchy(base, 1, Scheme::Loop, 3);
  set_base(h, x0);
  std::vector<double> x = synthesize(h, 1);
  Complex c = h.levels.back();
  build_adjacency(c);
  const LimitStencils ls = build_limit_stencils(h);
  // An inner control point dragged over two of its neighbours: the limit surface folds.
  std::uint32_t v = 0;  // the level-1 point nearest (1.5, 1.5): the middle square's diagonal's midpoint
  for (std::uint32_t w = 0; w < c.num_vertices; ++w)
    if (std::hypot(x[3 * w] - 1.5, x[3 * w + 1] - 1.5) < std::hypot(x[3 * v] - 1.5, x[3 * v + 1] - 1.5)) v = w;
  ASSERT_EQ(c.vertex_dim[v], 2);
  x[3 * std::size_t(v)] += 1.4;
  std::vector<double> y(x.size());
  const auto limit_folds = [&](const std::vector<double>& net) {
    eval_limit(ls, net.data(), y.data());
    return folds(c.faces, y);
  };
  const std::size_t before = limit_folds(x);
  ASSERT_GT(before, 0u);
  const std::size_t net_before = folds(c.faces, x);
  untangle_limit(c, ls, onto_plane, FeatureLines({}, {}), up, x);
  std::printf("limit folds %zu -> %zu, net folds %zu -> %zu\n", before, limit_folds(x), net_before, folds(c.faces, x));
  EXPECT_EQ(limit_folds(x), 0u);
}

}  // namespace
}  // namespace sublift
