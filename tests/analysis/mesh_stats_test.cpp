
#include <gtest/gtest.h>

#include "core/analysis/mesh_stats.h"
#include "core/complex/shapes.h"
#include "tests/test_util.h"

using namespace sublift;
using sublift::testing::load;


TEST(MeshStats, ClosedQuadTorus) {
  const MeshStats s = compute_mesh_stats(make_quad_torus(8, 8, 2.0, 1.0));  // V = E/2 = F = 64
  EXPECT_EQ(s.vertices, 64u);
  EXPECT_EQ(s.edges, 128u);
  EXPECT_EQ(s.faces, 64u);
  EXPECT_EQ(s.euler_characteristic, 0);
  EXPECT_EQ(s.boundary_loops, 0u);
  EXPECT_EQ(s.components, 1u);
  EXPECT_EQ(s.valences, (std::map<std::size_t, std::size_t>{{4, 64}}));
  EXPECT_EQ(s.face_sizes, (std::map<std::size_t, std::size_t>{{4, 64}}));
  EXPECT_EQ(s.non_manifold_edges + s.non_manifold_vertices + s.misoriented_edges, 0u);
  EXPECT_NEAR(s.bbox_max.z, 1.0, 1e-12);
}

TEST(MeshStats, OpenCubeHasOneBoundaryLoop) {
  const MeshStats s = compute_mesh_stats(load("c.obj",
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
      "f 1 4 3 2\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n").mesh);
  EXPECT_EQ(s.edges, 12u);
  EXPECT_EQ(s.boundary_edges, 4u);
  EXPECT_EQ(s.boundary_loops, 1u);
  EXPECT_EQ(s.euler_characteristic, 1);
  EXPECT_EQ(s.misoriented_edges, 0u);
  EXPECT_EQ(s.valences, (std::map<std::size_t, std::size_t>{{3, 8}}));
}

TEST(MeshStats, NonManifoldEdgeBowtieAndMisorientation) {
  const MeshStats e = compute_mesh_stats(load("e.obj",
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 0 0 -1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n").mesh);
  EXPECT_EQ(e.non_manifold_edges, 1u);
  EXPECT_EQ(e.non_manifold_vertices, 2u);
  const MeshStats b = compute_mesh_stats(load("b.obj",
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv -1 0 0\nv -1 -1 0\nf 1 2 3\nf 1 4 5\n").mesh);
  EXPECT_EQ(b.non_manifold_edges, 0u);
  EXPECT_EQ(b.non_manifold_vertices, 1u);
  EXPECT_EQ(b.boundary_loops, 1u);  // the boundary-edge graph is connected through the bowtie vertex
  const MeshStats o = compute_mesh_stats(load("o.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 3 4\n").mesh);
  EXPECT_EQ(o.misoriented_edges, 1u);
  EXPECT_EQ(o.non_manifold_vertices, 0u);
}

TEST(MeshStats, ComponentsAndIsolatedVertices) {
  const MeshStats s = compute_mesh_stats(load("two.obj",
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 5 5\nv 3 0 0\nv 4 0 0\nv 3 1 0\nf 1 2 3\nf 5 6 7\n").mesh);
  EXPECT_EQ(s.components, 2u);
  EXPECT_EQ(s.isolated_vertices, 1u);
  EXPECT_EQ(s.used_vertices, 6u);
  EXPECT_EQ(s.bbox_max, glm::dvec3(4, 1, 0));  // the isolated (5,5,5) is not in the box
}

// Issue 18: the one text of the topology warnings, with counts and the first five elements.
TEST(MeshStats, TopologyWarningsNameTheFirstFiveElements) {
  EXPECT_TRUE(topology_warnings(compute_mesh_stats(make_quad_torus(4, 3))).empty());
  // Seven triangles on the edge 0-1: a non-manifold edge, run the same way by all, whose ends
  // are non-manifold vertices.
  SurfaceMesh fan;
  fan.positions.assign(9, glm::dvec3(0.0));
  for (std::uint32_t k = 2; k < 9; ++k) {
    const std::uint32_t f[3] = {0, 1, k};
    fan.add_face(f);
  }
  const std::vector<ImportWarning> w = topology_warnings(compute_mesh_stats(fan));
  ASSERT_EQ(w.size(), 3u);
  EXPECT_EQ(w[0].what, "non-manifold vertex: its faces do not form one fan (vertices 0, 1; 0-based)");
  EXPECT_EQ(w[0].count, 2u);
  EXPECT_EQ(w[1].what, "non-manifold edge: in more than two faces (edge 0-1; 0-based)");
  EXPECT_EQ(w[2].what, "misoriented edge: two faces run it the same way, so the faces are not consistently oriented (edge 0-1; 0-based)");
  // Seven bowties sharing nothing but their apexes: more than five are cut with "...".
  SurfaceMesh bows;
  bows.positions.assign(7 * 5, glm::dvec3(0.0));
  for (std::uint32_t b = 0; b < 7; ++b) {
    const std::uint32_t o = 5 * b, t1[3] = {o, o + 1, o + 2}, t2[3] = {o, o + 3, o + 4};
    bows.add_face(t1);
    bows.add_face(t2);
  }
  const std::vector<ImportWarning> v = topology_warnings(compute_mesh_stats(bows));
  ASSERT_EQ(v.size(), 1u);
  EXPECT_EQ(v[0].count, 7u);
  EXPECT_EQ(v[0].what, "non-manifold vertex: its faces do not form one fan (vertices 0, 5, 10, 15, 20, ...; 0-based)");
  ImportReport r;
  add_topology_warnings(r, bows);
  EXPECT_EQ(r.format("b.obj"), "b.obj: warning: 7 x non-manifold vertex: its faces do not form one fan (vertices 0, 5, 10, 15, 20, ...; 0-based)\n");
}
