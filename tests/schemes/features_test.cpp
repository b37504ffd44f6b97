// Features (paper 000 sec. 3.3): creases and boundaries subdivide as 1-D cubic curves of their
// own vertices, cusps never move, and the boundary surface of a lattice subdivides exactly like
// the surface scheme applied to that boundary mesh.
#include <gtest/gtest.h>

#include "core/complex/complex_build.h"
#include "core/multires/hierarchy.h"
#include "core/io/mesh/mesh_import.h"
#include "core/complex/refine.h"
#include "core/complex/shapes.h"
#include "tests/test_lattices.h"
#include "tests/test_shapes.h"

using namespace sublift;
using namespace sublift::testing;

namespace {

std::string assets(const char* f) { return std::string(SUBLIFT_ASSETS_DIR) + "/" + f; }

// The next level's vertex loop: each vertex followed by the e-vertex of the edge to its successor.
std::vector<std::uint32_t> refine_loop(const Complex& c, const std::vector<std::uint32_t>& loop) {
  const auto em = edge_map(c);
  std::vector<std::uint32_t> out;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    out.push_back(loop[i]);
    out.push_back(c.num_vertices + edge_of(em, loop[i], loop[(i + 1) % loop.size()]));
  }
  return out;
}

std::vector<double> bspline_closed(const std::vector<double>& p) {
  const std::size_t n = p.size() / 3;
  std::vector<double> out(2 * n * 3);
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) {
      const double prev = p[((i + n - 1) % n) * 3 + c], cur = p[i * 3 + c], next = p[((i + 1) % n) * 3 + c];
      out[(2 * i) * 3 + c] = (prev + 6 * cur + next) / 8;
      out[(2 * i + 1) * 3 + c] = (cur + next) / 2;
    }
  return out;
}

// Checks that the closed feature loop `loop0` (level-0 vertices in order) subdivides as a closed
// uniform cubic B-spline curve of its own control points, for levels 1..3.
void expect_loop_is_bspline(const Complex& base, const std::vector<double>& pos, std::vector<std::uint32_t> loop) {
  Hierarchy h = make_hierarchy(base, 3, Scheme::Cubic, 3);
  set_base(h, pos);
  std::vector<double> want;
  for (std::uint32_t v : loop) want.insert(want.end(), {pos[v * 3], pos[v * 3 + 1], pos[v * 3 + 2]});
  for (int level = 1; level <= 3; ++level) {
    loop = refine_loop(h.levels[level - 1], loop);
    want = bspline_closed(want);
    const std::vector<double> got = synthesize(h, level);
    for (std::size_t i = 0; i < loop.size(); ++i)
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(got[loop[i] * 3 + c], want[i * 3 + c], 1e-13) << "level " << level;
  }
}

}  // namespace

TEST(Features, BoundaryCurveIsCubicCurveOfItsOwnVertices) {
  const LoadedMesh m = import_surface_mesh(assets("quad_grid_boundary.obj"));
  const Complex c = complex_from_surface_mesh(m.mesh);
  std::vector<std::uint32_t> loop;  // the 5 x 5 grid's boundary, in order
  for (std::uint32_t x = 0; x < 4; ++x) loop.push_back(x);
  for (std::uint32_t y = 0; y < 4; ++y) loop.push_back(y * 5 + 4);
  for (std::uint32_t x = 4; x > 0; --x) loop.push_back(20 + x);
  for (std::uint32_t y = 4; y > 0; --y) loop.push_back(y * 5);
  for (std::uint32_t v : loop) EXPECT_EQ(c.vertex_dim[v], 1) << v;
  expect_loop_is_bspline(c, random_values(m.mesh.positions.size() * 3, 11), loop);
}

TEST(Features, TaggedCreaseLoopIsCubicCurveOfItsOwnVertices) {
  const LoadedMesh m = import_surface_mesh(assets("crease_loop.obj"));
  ImportReport report;
  const Complex c = complex_from_surface_mesh(m.mesh, &report);
  EXPECT_TRUE(report.empty()) << report.format("crease_loop.obj");
  for (std::uint32_t v : {4u, 5u, 6u, 7u}) EXPECT_EQ(c.vertex_dim[v], 1);
  for (std::uint32_t v : {0u, 8u, 12u}) EXPECT_EQ(c.vertex_dim[v], 2);
  expect_loop_is_bspline(c, random_values(m.mesh.positions.size() * 3, 12), {4, 5, 6, 7});
}

TEST(Features, CuspsNeverMove) {
  SurfaceMesh m = import_surface_mesh(assets("mixed_polygons.obj")).mesh;
  m.tags.push_back({"corner", {10, 0}, {10.0}, {}, 0});  // the apex and one base corner
  const Complex c = complex_from_surface_mesh(m);
  EXPECT_EQ(c.vertex_dim[10], 0);
  EXPECT_EQ(c.vertex_dim[0], 0);
  const std::vector<double> pos = random_values(m.positions.size() * 3, 13);
  for (Scheme s : {Scheme::Linear, Scheme::Cubic}) {
    Hierarchy h = make_hierarchy(c, 3, s, 3);
    set_base(h, pos);
    for (int level = 1; level <= 3; ++level) {
      const std::vector<double> got = synthesize(h, level);
      for (std::uint32_t v : {0u, 10u})
        for (int k = 0; k < 3; ++k) EXPECT_EQ(got[v * 3 + k], pos[v * 3 + k]);
    }
  }
}

TEST(Features, OpenCurveEndsAreCuspsAndThreeCreasesMakeACusp) {
  Csr lines;  // an open polyline 0-1-2-3
  lines.items = {0, 1, 2, 3};
  lines.offsets.push_back(4);
  const Complex curve = complex_from_polylines(4, lines);
  EXPECT_EQ(curve.vertex_dim, (std::vector<std::uint8_t>{0, 1, 1, 0}));
  const std::vector<double> pos = random_values(12, 14);
  Hierarchy h = make_hierarchy(curve, 2, Scheme::Cubic, 3);
  set_base(h, pos);
  const std::vector<double> got = synthesize(h, 2);
  for (std::uint32_t v : {0u, 3u})
    for (int k = 0; k < 3; ++k) EXPECT_EQ(got[v * 3 + k], pos[v * 3 + k]);
  // An interior vertex of the open curve follows the cubic rule with the fixed ends.
  const std::vector<double> one = synthesize(h, 1);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(one[1 * 3 + k], (pos[k] + 6 * pos[3 + k] + pos[6 + k]) / 8, 1e-15);

  // Three tagged crease edges at vertex 12 of the crease box make it a cusp.
  SurfaceMesh box = import_surface_mesh(assets("crease_loop.obj")).mesh;
  box.tags.push_back({"crease", {12, 13}, {1.0}, {}, 0});
  box.tags.push_back({"crease", {12, 15}, {1.0}, {}, 0});
  box.tags.push_back({"crease", {12, 8}, {1.0}, {}, 0});
  EXPECT_EQ(complex_from_surface_mesh(box).vertex_dim[12], 0);
}

TEST(Features, DartVertexStaysSmooth) {
  // One crease edge ending inside the torus: the inner end is a dart (dim 2), the edge dim 1.
  SurfaceMesh t = make_quad_torus(6, 6);
  t.tags.push_back({"crease", {0, 1}, {2.0}, {}, 0});
  const Complex c = complex_from_surface_mesh(t);
  EXPECT_EQ(c.vertex_dim[0], 2);
  EXPECT_EQ(c.vertex_dim[1], 2);
  EXPECT_EQ(c.edge_dim[edge_of(edge_map(c), 0, 1)], 1);
}

TEST(Features, ZeroSharpnessAndUnknownTagsAreReportedNotUsed) {
  SurfaceMesh t = make_quad_torus(4, 4);
  t.tags.push_back({"crease", {0, 1}, {0.0}, {}, 7});
  t.tags.push_back({"interpolateboundary", {1}, {}, {}, 8});
  ImportReport r;
  const Complex c = complex_from_surface_mesh(t, &r);
  EXPECT_EQ(r.warnings.size(), 2u) << r.format("t");
  for (std::uint8_t d : c.edge_dim) EXPECT_EQ(d, 2);
}

namespace {

// Compares one refinement step of a lattice's boundary with the surface scheme applied to the
// boundary mesh (same vertex ids), at every level of a 3-level hierarchy.
void expect_boundary_is_surface_scheme(const Complex& lattice, std::uint64_t seed) {
  Hierarchy h = make_hierarchy(lattice, 3, Scheme::Cubic, 3);
  std::vector<double> pos = random_values(std::size_t(lattice.num_vertices) * 3, seed);
  set_base(h, pos);
  for (int level = 0; level < 3; ++level) {
    const Complex& L = h.levels[level];
    const std::vector<double> here = synthesize(h, level), next = synthesize(h, level + 1);
    Csr boundary;
    std::vector<std::uint32_t> lattice_face;
    for (std::uint32_t f = 0; f < L.num_faces(); ++f) {
      if (L.face_cells.size(f) != 1) continue;
      ASSERT_EQ(L.face_dim[f], 2);
      const auto r = L.faces.row(f);
      boundary.items.insert(boundary.items.end(), r.begin(), r.end());
      boundary.offsets.push_back(static_cast<std::uint32_t>(boundary.items.size()));
      lattice_face.push_back(f);
    }
    const Complex surface = complex_from_polygons(L.num_vertices, boundary);
    Hierarchy s = make_hierarchy(surface, 1, Scheme::Cubic, 3);
    set_base(s, here);
    const std::vector<double> want = synthesize(s, 1);
    const auto lattice_edges = edge_map(L);
    auto same = [&](std::uint32_t lv, std::uint32_t sv) {
      for (int k = 0; k < 3; ++k) ASSERT_NEAR(next[lv * 3 + k], want[sv * 3 + k], 1e-12) << "level " << level + 1;
    };
    for (std::uint32_t f = 0; f < surface.num_faces(); ++f) {
      for (std::uint32_t v : surface.faces.row(f)) same(v, v);
      same(L.num_vertices + L.num_edges() + lattice_face[f], surface.num_vertices + surface.num_edges() + f);
    }
    for (std::uint32_t e = 0; e < surface.num_edges(); ++e) {
      const std::uint32_t le = edge_of(lattice_edges, surface.edge_verts[2 * e], surface.edge_verts[2 * e + 1]);
      same(L.num_vertices + le, surface.num_vertices + e);
    }
  }
}

}  // namespace

TEST(Features, LatticeBoundarySubdividesLikeTheSurfaceScheme) {
  std::vector<double> pos;
  expect_boundary_is_surface_scheme(make_hex_block(2, pos), 21);
  expect_boundary_is_surface_scheme(pyramid_cell(), 22);
  expect_boundary_is_surface_scheme(prism_cell(), 23);
  expect_boundary_is_surface_scheme(tetra_cell(), 24);
}

TEST(Features, InnerFeatureSurfaceIsASurfaceFeature) {
  // A 2 x 1 x 1 block whose middle face is tagged: it becomes dim 2 and its vertices too.
  std::vector<double> pos;
  Complex block = make_hex_block(2, pos);
  FeatureTags tags;
  // The plane x = 1 inside the 2 x 2 x 2 block: vertices (1, j, k).
  auto id = [](int i, int j, int k) { return static_cast<std::uint32_t>((k * 3 + j) * 3 + i); };
  for (int j = 0; j < 2; ++j)
    for (int k = 0; k < 2; ++k) tags.feature_faces.push_back({id(1, j, k), id(1, j + 1, k), id(1, j + 1, k + 1), id(1, j, k + 1)});
  assign_feature_dims(block, tags);
  EXPECT_EQ(block.vertex_dim[id(1, 1, 1)], 2);  // centre of the block, on the inner surface
  EXPECT_EQ(block.vertex_dim[id(0, 1, 1)], 2);  // face centre on the boundary
  int inner_feature_faces = 0;
  for (std::uint32_t f = 0; f < block.num_faces(); ++f) inner_feature_faces += block.face_cells.size(f) == 2 && block.face_dim[f] == 2;
  EXPECT_EQ(inner_feature_faces, 4);
}
