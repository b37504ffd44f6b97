// The fitting base (core/fit/base_mesh.h, issue 17): OpenMesh's decimater keeps genus, boundary
// loops and sharp features, folds nothing, and refuses what it cannot hold.
#include "core/fit/base_mesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <filesystem>
#include <map>

#include "core/base/errors.h"
#include "core/io/mesh/mesh_import.h"
#include "tests/mesh_fixtures.h"

namespace sublift {
namespace {

fixtures::Polygons triangulated(const fixtures::Polygons& m) {
  fixtures::Polygons t{m.num_vertices, {}, m.positions};
  for (std::size_t f = 0; f < m.faces.rows(); ++f) {
    const auto q = m.faces.row(f);
    for (std::size_t k = 1; k + 1 < q.size(); ++k) fixtures::push_row(t.faces, {q[0], q[k], q[k + 1]});
  }
  return t;
}

// Smallest cosine between the normals of two faces sharing an edge, and the smallest face area.
void shape_of(const BaseMesh& b, double& min_cos, double& min_area) {
  auto normal = [&](std::size_t f, double n[3]) {
    const auto q = b.faces.row(f);
    const double* p0 = &b.positions[3 * q[0]];
    const double* p1 = &b.positions[3 * q[1]];
    const double* p2 = &b.positions[3 * q[2]];
    const double u[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]}, v[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
    n[0] = u[1] * v[2] - u[2] * v[1], n[1] = u[2] * v[0] - u[0] * v[2], n[2] = u[0] * v[1] - u[1] * v[0];
    const double l = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; ++k) n[k] /= l > 0 ? l : 1;
    return 0.5 * l;
  };
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> first;
  min_cos = 1, min_area = HUGE_VAL;
  for (std::size_t f = 0; f < b.faces.rows(); ++f) {
    double n[3];
    min_area = std::min(min_area, normal(f, n));
    const auto q = b.faces.row(f);
    for (int k = 0; k < 3; ++k) {
      const std::pair<std::uint32_t, std::uint32_t> e{std::min(q[k], q[(k + 1) % 3]), std::max(q[k], q[(k + 1) % 3])};
      auto [it, fresh] = first.emplace(e, f);
      if (fresh) continue;
      double o[3];
      normal(it->second, o);
      min_cos = std::min(min_cos, n[0] * o[0] + n[1] * o[1] + n[2] * o[2]);
    }
  }
}

TEST(BaseMesh, TorusKeepsItsGenusAndFoldsNothing) {
  const fixtures::Polygons t = triangulated(fixtures::torus(64, 32));
  const BaseMesh b = decimate_to_base(t.num_vertices, t.faces, t.positions, {128});
  EXPECT_EQ(b.num_vertices, 128u);
  EXPECT_EQ(b.euler_before, 0);
  EXPECT_EQ(b.euler_after, 0);  // genus 1
  EXPECT_EQ(b.boundary_loops_after, 0u);
  double min_cos, min_area;
  shape_of(b, min_cos, min_area);
  EXPECT_GT(min_cos, 0.0) << "adjacent base faces turn by more than 90 degrees";
  EXPECT_GT(min_area, 0.0);
  for (std::size_t i = 0; i < b.input_vertex.size(); ++i)
    for (int k = 0; k < 3; ++k) EXPECT_NE(b.positions[3 * i + k], HUGE_VAL);
}

// With quads a face target still bounds the polygons: the pairing leaves some triangles, and
// the decimation goes on until they fit.
TEST(BaseMesh, QuadBasesKeepToTheirFaceTarget) {
  const fixtures::Polygons t = triangulated(fixtures::torus(64, 32));
  for (const std::uint32_t faces : {57u, 100u, 150u, 301u}) {
    BaseMeshOptions o;
    o.target_faces = faces;
    o.quads = true;
    const BaseMesh b = decimate_to_base(t.num_vertices, t.faces, t.positions, o);
    EXPECT_LE(b.faces.rows(), faces);
    EXPECT_GE(b.faces.rows(), faces * 3 / 4) << "far below the target";
    EXPECT_EQ(b.euler_after, 0);
  }
}

TEST(BaseMesh, OpenSheetKeepsItsBoundary) {
  fixtures::Polygons g;
  const std::uint32_t n = 40;
  g.num_vertices = (n + 1) * (n + 1);
  for (std::uint32_t y = 0; y <= n; ++y)
    for (std::uint32_t x = 0; x <= n; ++x) g.positions.insert(g.positions.end(), {double(x), double(y), 0.1 * std::sin(0.3 * x + 0.2 * y)});
  for (std::uint32_t y = 0; y < n; ++y)
    for (std::uint32_t x = 0; x < n; ++x) {
      const std::uint32_t a = y * (n + 1) + x;
      fixtures::push_row(g.faces, {a, a + 1, a + n + 2, a + n + 1});
    }
  const fixtures::Polygons t = triangulated(g);
  const BaseMesh b = decimate_to_base(t.num_vertices, t.faces, t.positions, {60});
  EXPECT_EQ(b.boundary_loops_before, 1u);
  EXPECT_EQ(b.boundary_loops_after, 1u);
  EXPECT_EQ(b.euler_after, 1);
  EXPECT_LE(b.num_vertices, 60u + 4u);  // corners and boundary vertices only move along the boundary
}

// The decimation reports its progress (rising, within 0-1, close to 1 at the end) and stops when
// the callback says so: Cancelled, and nothing returned.
TEST(BaseMesh, ReportsProgressAndCancels) {
  const fixtures::Polygons t = triangulated(fixtures::torus(64, 32));
  for (const bool quads : {false, true}) {
    SCOPED_TRACE(quads);
    std::vector<double> seen;
    BaseMeshOptions o;
    o.target_vertices = quads ? 0 : 128;
    o.target_faces = quads ? 100 : 0;
    o.quads = quads;
    o.progress = [&](double f) {
      seen.push_back(f);
      return true;
    };
    const BaseMesh b = decimate_to_base(t.num_vertices, t.faces, t.positions, o);
    ASSERT_GE(seen.size(), 50u) << "about one report per 1 % of the collapses";
    for (std::size_t k = 1; k < seen.size(); ++k) EXPECT_GT(seen[k], seen[k - 1]);
    EXPECT_GT(seen.front(), 0.0);
    EXPECT_LE(seen.back(), 1.0);
    EXPECT_GT(seen.back(), 0.9);
    EXPECT_EQ(b.euler_after, 0);
    int calls = 0;
    o.progress = [&](double f) { return ++calls < 10 && f < 0.5; };
    EXPECT_THROW(decimate_to_base(t.num_vertices, t.faces, t.positions, o), Cancelled);
    EXPECT_EQ(calls, 10) << "the decimation went on after the callback said stop";
  }
}

TEST(BaseMesh, BadInputIsRefused) {
  fixtures::Polygons fin;  // three triangles on one edge
  fin.num_vertices = 5;
  fin.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1};
  fixtures::push_row(fin.faces, {0, 1, 2});
  fixtures::push_row(fin.faces, {1, 0, 3});
  fixtures::push_row(fin.faces, {0, 1, 4});
  EXPECT_THROW(decimate_to_base(fin.num_vertices, fin.faces, fin.positions, {3}), TopologyError);
  EXPECT_THROW(decimate_to_base(0, Csr{}, {}, {}), TopologyError);
  const fixtures::Polygons t = triangulated(fixtures::torus(8, 6));
  EXPECT_THROW(decimate_to_base(t.num_vertices, t.faces, t.positions, {1000}), TopologyError);
}

TEST(BaseMesh, SharedScansKeepTopologyAndFeatures) {
  const std::filesystem::path dir = std::filesystem::path(SUBLIFT_SHARED_DATA) / "scans";
  if (!std::filesystem::exists(dir)) GTEST_SKIP() << "no third-party data at " << dir << " (SUBLIFT_SHARED_DATA)";
  struct Case {
    const char* file;
    long long euler;
    bool features;
  };
  for (const Case& c : {Case{"bunny_npm_lowres.obj", 2, false}, Case{"rocker-arm.obj", 0, false}, Case{"fandisk.off", 2, true}}) {
    SCOPED_TRACE(c.file);
    const LoadedMesh lm = import_surface_mesh((dir / c.file).string());
    std::vector<double> xyz;
    for (const auto& p : lm.mesh.positions) xyz.insert(xyz.end(), {p.x, p.y, p.z});
    Csr faces;
    faces.offsets = lm.mesh.face_offsets;
    faces.items = lm.mesh.face_indices;
    const BaseMesh b = decimate_to_base(static_cast<std::uint32_t>(lm.mesh.num_vertices()), faces, xyz, {});
    EXPECT_EQ(b.euler_before, c.euler);
    EXPECT_EQ(b.euler_after, b.euler_before);
    EXPECT_EQ(b.boundary_loops_after, b.boundary_loops_before);
    EXPECT_GE(b.faces.rows(), 24u);
    double min_cos, min_area;
    shape_of(b, min_cos, min_area);
    EXPECT_GT(min_area, 0.0);
    if (c.features) {
      EXPECT_GT(b.tags.crease_edges.size(), 10u);
      EXPECT_GT(b.tags.corner_vertices.size(), 0u);  // where fandisk's lines meet or turn
    }
    std::printf("%s: %u -> %u vertices, %zu creases, min adjacent-normal cosine %.3f\n", c.file,
                static_cast<unsigned>(lm.mesh.num_vertices()), b.num_vertices, b.tags.crease_edges.size(), min_cos);
  }
}

// A fan wider than kMaxFitValence (the corpus has one of 70,000 faces, which made the
// decimation quadratic) is refused at once, naming the vertex; a UV sphere's pole of 64 is taken.
TEST(BaseMesh, FansWiderThanTheValenceLimitAreRefused) {
  for (const std::uint32_t n : {64u, kMaxFitValence + 1}) {
    std::vector<double> xyz = {0, 0, 0};
    Csr faces;
    for (std::uint32_t k = 0; k <= n; ++k) {
      const double a = 2.0 * std::numbers::pi * k / n;
      xyz.insert(xyz.end(), {std::cos(a), std::sin(a), 0.0});
    }
    for (std::uint32_t k = 0; k < n; ++k) {
      faces.items.insert(faces.items.end(), {0u, 1 + k, 1 + (k + 1) % n});
      faces.offsets.push_back(static_cast<std::uint32_t>(faces.items.size()));
    }
    const std::uint32_t nv = n + 2;  // the last rim point repeats the first, unused
    if (n > kMaxFitValence) {
      try {
        decimate_to_base(nv, faces, xyz, {24});
        FAIL() << "a fan of " << n << " faces was taken";
      } catch (const TopologyError& e) {
        EXPECT_NE(std::string(e.what()).find("vertex 0 has more than"), std::string::npos) << e.what();
      }
    } else {
      EXPECT_LE(decimate_to_base(nv, faces, xyz, {24}).num_vertices, 30u);
    }
  }
}

}  // namespace
}  // namespace sublift
