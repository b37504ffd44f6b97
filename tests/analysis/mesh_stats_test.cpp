
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
