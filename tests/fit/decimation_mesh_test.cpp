// The fitting base's own collapse check (core/fit/decimation_mesh.h) against the packaged
// OpenMesh's TriConnectivity::is_collapse_ok, the oracle, on every halfedge of meshes with
// boundaries, tight handles and small closed shapes, before and between rounds of a quadric
// decimation (so deleted elements and collapsed neighbourhoods are met too).
#include "core/fit/decimation_mesh.h"

#include <gtest/gtest.h>

#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>

#include <cmath>
#include <filesystem>
#include <string>

#include "core/io/mesh/mesh_import.h"
#include "tests/mesh_fixtures.h"

namespace sublift {
namespace {

using fit_detail::Mesh;

Mesh om_mesh(const fixtures::Polygons& p) {
  Mesh m;
  std::vector<Mesh::VertexHandle> vh;
  for (std::uint32_t v = 0; v < p.num_vertices; ++v) {
    // Topology-only fixtures get distinct, non-planar positions so the quadrics differ.
    const double x = p.positions.empty() ? std::cos(1.7 * v) : p.positions[3 * v];
    const double y = p.positions.empty() ? std::sin(2.3 * v) : p.positions[3 * v + 1];
    const double z = p.positions.empty() ? 0.1 * v : p.positions[3 * v + 2];
    vh.push_back(m.add_vertex({x, y, z}));
  }
  for (std::size_t f = 0; f < p.faces.rows(); ++f) {
    const auto r = p.faces.row(f);
    for (std::size_t k = 1; k + 1 < r.size(); ++k)
      EXPECT_TRUE(m.add_face(vh[r[0]], vh[r[k]], vh[r[k + 1]]).is_valid()) << "face " << f;
  }
  m.request_vertex_status();
  m.request_edge_status();
  m.request_face_status();
  return m;
}

// Every halfedge, ours against OpenMesh's (the collapse check, and finding the halfedge from
// its ends and from its tip to a vertex two steps on, usually no edge); returns how many
// collapses were legal.
std::size_t compare_all(Mesh& m, const std::string& what) {
  std::size_t legal = 0;
  for (auto h : m.halfedges()) {
    if (m.status(m.edge_handle(h)).deleted()) continue;
    const auto a = m.from_vertex_handle(h), b = m.to_vertex_handle(h);
    EXPECT_EQ(m.find_halfedge(a, b), m.PolyConnectivity::find_halfedge(a, b)) << what;
    const auto c = m.to_vertex_handle(m.next_halfedge_handle(m.opposite_halfedge_handle(m.next_halfedge_handle(h))));
    EXPECT_EQ(m.find_halfedge(a, c), m.PolyConnectivity::find_halfedge(a, c)) << what;
  }
  for (auto h : m.halfedges()) {
    const bool ours = m.is_collapse_ok(h);
    const bool theirs = m.TriConnectivity::is_collapse_ok(h);
    EXPECT_EQ(ours, theirs) << what << ", halfedge " << h.idx();
    legal += ours;
  }
  return legal;
}

void check(const fixtures::Polygons& p, const std::string& name) {
  Mesh m = om_mesh(p);
  std::size_t legal = compare_all(m, name + " before");
  EXPECT_GT(legal, 0u) << name;
  OpenMesh::Decimater::DecimaterT<Mesh> dec(m);
  OpenMesh::Decimater::ModQuadricT<Mesh>::Handle q;
  dec.add(q);
  ASSERT_TRUE(dec.initialize());
  const std::size_t step = std::max<std::size_t>(1, m.n_vertices() / 8);
  for (int round = 0; round < 12; ++round) {
    const std::size_t done = dec.decimate(step);
    compare_all(m, name + " after round " + std::to_string(round));
    if (done == 0) break;  // nothing more gives way: the last comparisons were at the end
  }
}

TEST(DecimationMesh, CollapseCheckEqualsOpenMeshs) {
  fixtures::Polygons sheet;  // an open grid: boundary vertices and edges, corners of valence 2-3
  const std::uint32_t n = 9;
  sheet.num_vertices = (n + 1) * (n + 1);
  for (std::uint32_t y = 0; y <= n; ++y)
    for (std::uint32_t x = 0; x <= n; ++x) sheet.positions.insert(sheet.positions.end(), {double(x), double(y), 0.2 * std::sin(0.7 * x * y)});
  for (std::uint32_t y = 0; y < n; ++y)
    for (std::uint32_t x = 0; x < n; ++x) {
      const std::uint32_t a = y * (n + 1) + x;
      fixtures::push_row(sheet.faces, {a, a + 1, a + n + 2});
      fixtures::push_row(sheet.faces, {a, a + n + 2, a + n + 1});
    }
  fixtures::Polygons strip;  // one quad wide: every vertex on the boundary, diagonals inside
  strip.num_vertices = 2 * (n + 1);
  for (std::uint32_t x = 0; x <= n; ++x)
    for (std::uint32_t y = 0; y < 2; ++y) strip.positions.insert(strip.positions.end(), {double(x), double(y), 0.3 * std::sin(1.3 * x + y)});
  for (std::uint32_t x = 0; x < n; ++x) {
    fixtures::push_row(strip.faces, {2 * x, 2 * x + 2, 2 * x + 3});
    fixtures::push_row(strip.faces, {2 * x, 2 * x + 3, 2 * x + 1});
  }
  fixtures::Polygons tetra;  // the smallest closed surface: each ring is the other three vertices
  tetra.num_vertices = 4;
  for (const auto& f : {std::array<std::uint32_t, 3>{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}}) fixtures::push_row(tetra.faces, {f[0], f[1], f[2]});
  check(tetra, "tetrahedron");

  check(fixtures::torus(6, 4), "thin torus 6 x 4 (handles close within a ring)");
  check(fixtures::torus(16, 8), "torus 16 x 8");
  check(fixtures::octahedron(), "octahedron");
  check(fixtures::triangle_cone(9), "open cone");
  check(fixtures::triangle_cone(40), "open cone of 40 (a ring longer than the 32 the check keeps)");
  check(sheet, "sheet");
  check(strip, "strip");
  const std::filesystem::path fandisk = std::filesystem::path(SUBLIFT_SHARED_DATA) / "scans" / "fandisk.off";
  if (!std::filesystem::exists(fandisk)) {
    std::printf("fandisk skipped: no third-party data at %s (SUBLIFT_SHARED_DATA)\n", fandisk.string().c_str());
    return;
  }
  const LoadedMesh lm = import_surface_mesh(fandisk.string());
  fixtures::Polygons f{static_cast<std::uint32_t>(lm.mesh.num_vertices()), {}, {}};
  for (const auto& p : lm.mesh.positions) f.positions.insert(f.positions.end(), {p.x, p.y, p.z});
  f.faces.offsets = lm.mesh.face_offsets;
  f.faces.items = lm.mesh.face_indices;
  check(f, "fandisk");
}

}  // namespace
}  // namespace sublift
