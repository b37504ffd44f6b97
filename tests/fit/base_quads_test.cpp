// Quad-dominant fitting bases (core/fit/base_quads.h, issue 17): triangles pair into convex,
// near-square quads; crease and boundary edges stay; the topology does not change.
#include "core/fit/base_quads.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>

#include <glm/geometric.hpp>

#include "core/complex/complex_build.h"
#include "core/io/mesh/mesh_import.h"
#include "tests/mesh_fixtures.h"

namespace sublift {
namespace {

// An n x n grid of unit squares, each cut along its diagonal (a, a + n + 2).
BaseMesh cut_grid(std::uint32_t n) {
  BaseMesh b;
  b.num_vertices = (n + 1) * (n + 1);
  for (std::uint32_t j = 0; j <= n; ++j)
    for (std::uint32_t i = 0; i <= n; ++i) b.positions.insert(b.positions.end(), {double(i), double(j), 0.0});
  for (std::uint32_t j = 0; j < n; ++j)
    for (std::uint32_t i = 0; i < n; ++i) {
      const std::uint32_t a = j * (n + 1) + i;
      fixtures::push_row(b.faces, {a, a + 1, a + n + 2});
      fixtures::push_row(b.faces, {a, a + n + 2, a + n + 1});
    }
  return b;
}

std::map<std::pair<std::uint32_t, std::uint32_t>, int> edge_uses(const Csr& faces) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
  for (std::size_t f = 0; f < faces.rows(); ++f) {
    const auto r = faces.row(f);
    for (std::size_t k = 0; k < r.size(); ++k) ++uses[std::minmax(r[k], r[(k + 1) % r.size()])];
  }
  return uses;
}

long long euler(const BaseMesh& b) {
  return static_cast<long long>(b.num_vertices) - static_cast<long long>(edge_uses(b.faces).size()) + static_cast<long long>(b.faces.rows());
}

glm::dvec3 at(const BaseMesh& b, std::uint32_t v) { return {b.positions[3 * v], b.positions[3 * v + 1], b.positions[3 * v + 2]}; }

// Whether every quad is convex: both of its diagonals split it into triangles facing alike.
bool quads_convex(const BaseMesh& b) {
  for (std::size_t f = 0; f < b.faces.rows(); ++f) {
    const auto r = b.faces.row(f);
    if (r.size() != 4) continue;
    const glm::dvec3 p[4] = {at(b, r[0]), at(b, r[1]), at(b, r[2]), at(b, r[3])};
    const glm::dvec3 n1 = glm::cross(p[1] - p[0], p[2] - p[0]), n2 = glm::cross(p[2] - p[0], p[3] - p[0]);
    const glm::dvec3 n3 = glm::cross(p[2] - p[1], p[3] - p[1]), n4 = glm::cross(p[3] - p[1], p[0] - p[1]);
    if (glm::dot(n1, n2) <= 0 || glm::dot(n3, n4) <= 0) return false;
  }
  return true;
}

TEST(BaseQuads, CutGridPairsBackIntoItsSquares) {
  BaseMesh b = cut_grid(6);
  EXPECT_EQ(pair_into_quads(b), 36u);
  ASSERT_EQ(b.faces.rows(), 36u);
  for (std::size_t f = 0; f < b.faces.rows(); ++f) {
    const auto r = b.faces.row(f);
    ASSERT_EQ(r.size(), 4u);
    // The unit square's corners, in the triangles' (counterclockwise) order.
    const glm::dvec3 n = glm::cross(at(b, r[1]) - at(b, r[0]), at(b, r[2]) - at(b, r[0]));
    EXPECT_GT(n.z, 0.0);
    for (std::size_t k = 0; k < 4; ++k) EXPECT_DOUBLE_EQ(glm::distance(at(b, r[k]), at(b, r[(k + 1) % 4])), 1.0);
  }
  EXPECT_EQ(euler(b), 1);
}

TEST(BaseQuads, CreasesStay) {
  BaseMesh b = cut_grid(3);
  // The diagonal of the middle square (vertices 5 and 10) is a crease: its two triangles stay apart.
  b.tags.crease_edges.emplace_back(5u, 10u);
  pair_into_quads(b);
  EXPECT_EQ((edge_uses(b.faces)[{5u, 10u}]), 2);
  EXPECT_NO_THROW(complex_from_polygons(b.num_vertices, b.faces, b.tags));
  EXPECT_EQ(euler(b), 1);
}

TEST(BaseQuads, BadShapesStayTriangles) {
  // Two triangles whose union is not convex (a dart) and a pair that would be a long sliver.
  BaseMesh dart;
  dart.num_vertices = 4;
  dart.positions = {0, 0, 0, 2, 0, 0, 1, 0.3, 0, 1, 2, 0};
  fixtures::push_row(dart.faces, {0, 2, 3});
  fixtures::push_row(dart.faces, {2, 1, 3});
  EXPECT_EQ(pair_into_quads(dart), 0u);
  EXPECT_EQ(dart.faces.rows(), 2u);
  BaseMesh sliver;
  sliver.num_vertices = 4;
  sliver.positions = {0, 0, 0, 4, 0, 0, 6, 1, 0, 2, 1, 0};  // corners 27 and 153 degrees
  fixtures::push_row(sliver.faces, {0, 1, 2});
  fixtures::push_row(sliver.faces, {0, 2, 3});
  EXPECT_EQ(pair_into_quads(sliver), 0u);  // 63 degrees off 90: more than kMaxQuadCornerDeviationDeg
}

TEST(BaseQuads, AugmentingPathsPairWhatGreedyLeaves) {
  // A unit square cut along A-C (triangles t1, t2, the best quad) with a triangle below A-B (t0)
  // and one above C-D (t3). Greedy takes the square and strands t0 and t3; the augmenting path
  // t0-t1, t2-t3 pairs all four (each quad's worst corner is 58 degrees off).
  BaseMesh b;
  b.num_vertices = 6;
  b.positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0.5, -0.8, 0, 0.5, 1.8, 0};  // A B C D E F
  fixtures::push_row(b.faces, {0, 4, 1});  // t0
  fixtures::push_row(b.faces, {0, 1, 2});  // t1
  fixtures::push_row(b.faces, {0, 2, 3});  // t2
  fixtures::push_row(b.faces, {2, 5, 3});  // t3
  EXPECT_EQ(pair_into_quads(b), 2u);
  ASSERT_EQ(b.faces.rows(), 2u);
  EXPECT_TRUE(quads_convex(b));
  EXPECT_EQ(euler(b), 1);
}

// Decimated real and generated surfaces: mostly in quads, convex, the same topology, every crease
// tag still an edge (complex_from_polygons refuses a tag that names no edge).
TEST(BaseQuads, DecimatedBasesAreQuadDominant) {
  struct Case {
    std::string name;
    std::uint32_t n;
    Csr faces;
    std::vector<double> xyz;
  };
  std::vector<Case> cases;
  {
    const fixtures::Polygons t = fixtures::torus(64, 32);
    Case c{"torus", t.num_vertices, {}, t.positions};
    for (std::size_t f = 0; f < t.faces.rows(); ++f) {
      const auto q = t.faces.row(f);
      fixtures::push_row(c.faces, {q[0], q[1], q[2]});
      fixtures::push_row(c.faces, {q[0], q[2], q[3]});
    }
    cases.push_back(std::move(c));
  }
  const std::filesystem::path dir = std::filesystem::path(SUBLIFT_SHARED_DATA) / "scans";
  for (const char* scan : {"fandisk.off", "rocker-arm.obj"}) {
    if (!std::filesystem::exists(dir / scan)) {
      std::printf("skipping %s: no third-party data at %s (SUBLIFT_SHARED_DATA)\n", scan, dir.string().c_str());
      continue;
    }
    const LoadedMesh lm = import_surface_mesh((dir / scan).string());
    Case c{scan, static_cast<std::uint32_t>(lm.mesh.num_vertices()), {}, {}};
    c.faces.offsets = lm.mesh.face_offsets;
    c.faces.items = lm.mesh.face_indices;
    for (const auto& p : lm.mesh.positions) c.xyz.insert(c.xyz.end(), {p.x, p.y, p.z});
    cases.push_back(std::move(c));
  }
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    BaseMeshOptions o;
    o.quads = true;
    const BaseMesh b = decimate_to_base(c.n, c.faces, c.xyz, o);
    std::size_t quads = 0;
    for (std::size_t f = 0; f < b.faces.rows(); ++f) quads += b.faces.size(f) == 4;
    std::printf("%s: %u vertices, %zu faces, %zu quads\n", c.name.c_str(), b.num_vertices, b.faces.rows(), quads);
    // Most of the surface in quads: of the decimated triangles, 64 % on fandisk (its creases keep
    // many apart), 69 % on the torus, 72 % on the rocker arm.
    const std::size_t triangles = b.faces.rows() + quads;
    EXPECT_GE(10 * 2 * quads, 6 * triangles) << "fewer than 60 % of the triangles paired";
    EXPECT_EQ(euler(b), b.euler_after);
    EXPECT_EQ(b.euler_after, b.euler_before);
    EXPECT_TRUE(quads_convex(b));
    for (const auto& [e, uses] : edge_uses(b.faces)) EXPECT_LE(uses, 2);
    EXPECT_NO_THROW(complex_from_polygons(b.num_vertices, b.faces, b.tags));
  }
}

}  // namespace
}  // namespace sublift
