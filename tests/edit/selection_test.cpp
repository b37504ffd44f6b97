// core/edit/selection (issue 19): edge loops and rings, linked, grow, shrink, invert and edge
// picking, on hand-made nets whose answers are counted here.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "core/complex/complex_build.h"
#include "core/complex/shapes.h"
#include "core/edit/selection.h"
#include "core/edit/symmetry.h"
#include "core/io/lattice/shape_io.h"
#include "tests/edit_grid.h"

namespace sublift {
namespace {

using V = std::vector<unsigned>;

// An nx x ny grid of unit quads in z = 0; vertex (i, j) is j * (nx + 1) + i at (i, j, 0).
Complex grid(int nx, int ny, std::vector<double>* positions = nullptr) {
  std::vector<double> p;
  Complex c = testing::quad_grid(nx, ny, p);
  if (positions) *positions = std::move(p);
  return c;
}

std::uint32_t edge(const Complex& c, std::uint32_t a, std::uint32_t b) {
  const std::int64_t e = find_edge(c, a, b);
  EXPECT_GE(e, 0) << a << "-" << b;
  return static_cast<std::uint32_t>(e);
}

TEST(Selection, LoopsAndRingsOnAGridWithBoundary) {
  const Complex c = grid(4, 3);
  // An interior row runs from boundary to boundary (it stops at the valence-3 ends).
  EXPECT_EQ(edge_vertices(c, edge_loop(c, edge(c, 6, 7))), (V{5, 6, 7, 8, 9}));
  // A boundary edge follows the boundary up to the corner (valence 2).
  EXPECT_EQ(edge_vertices(c, edge_loop(c, edge(c, 1, 2))), (V{0, 1, 2, 3, 4}));
  // A column through the middle.
  EXPECT_EQ(edge_vertices(c, edge_loop(c, edge(c, 7, 12))), (V{2, 7, 12, 17}));
  // The ring of a horizontal edge: the edges above and below it, boundary to boundary.
  const std::vector<std::uint32_t> ring = edge_ring(c, edge(c, 6, 7));
  EXPECT_EQ(ring.size(), 4u);
  EXPECT_EQ(ring.front(), edge(c, 6, 7));
  EXPECT_EQ(edge_vertices(c, ring), (V{1, 2, 6, 7, 11, 12, 16, 17}));
  EXPECT_EQ(find_edge(c, 0, 6), -1);  // a diagonal is no edge
}

TEST(Selection, ClosedLoopsAndRingsOnATorus) {
  // 10 x 7 torus: every loop closes after 10 or 7 edges and the ring of an edge runs the other way.
  const SurfaceMesh m = make_quad_torus(10, 7);
  const Complex c = complex_from_surface_mesh(m);
  for (std::uint32_t e = 0; e < c.num_edges(); ++e) {
    const std::size_t loop = edge_loop(c, e).size(), ring = edge_ring(c, e).size();
    ASSERT_TRUE(loop == 10 || loop == 7) << e << ": " << loop;
    EXPECT_EQ(loop + ring, 17u) << e;
  }
}

TEST(Selection, IrregularVerticesCurvesLatticesAndTriangles) {
  const Shape cube = read_shape(std::string(SUBLIFT_ASSETS_DIR) + "/cube.obj");
  EXPECT_EQ(edge_loop(cube.base, 0).size(), 1u);  // valence 3 everywhere: a loop stops at once
  EXPECT_EQ(edge_ring(cube.base, 0).size(), 4u);  // a ring goes round the cube
  const Shape octa = read_shape(std::string(SUBLIFT_ASSETS_DIR) + "/octahedron.obj");
  EXPECT_EQ(edge_loop(octa.base, 0).size(), 4u);  // valence 4: the equator through the edge
  EXPECT_EQ(edge_ring(octa.base, 0).size(), 1u);  // triangles have no opposite edge
  std::vector<double> p;
  const Complex curve = make_curve_loop(9, p);
  EXPECT_EQ(edge_loop(curve, 3).size(), 9u);
  // A 4 x 4 x 4 hexahedral block: a loop is a straight line of 4 edges through the block.
  const Complex block = make_hex_block(4, p);
  auto vid = [](int i, int j, int k) { return static_cast<std::uint32_t>((k * 5 + j) * 5 + i); };
  EXPECT_EQ(edge_vertices(block, edge_loop(block, edge(block, vid(1, 2, 2), vid(2, 2, 2)))),
            (V{vid(0, 2, 2), vid(1, 2, 2), vid(2, 2, 2), vid(3, 2, 2), vid(4, 2, 2)}));
  EXPECT_TRUE(edge_loop(block, block.num_edges()).empty());
}

TEST(Selection, LinkedGrowShrinkInvert) {
  // Two separate quads: 0-3 and 4-7.
  Csr faces;
  faces.items = {0, 1, 2, 3, 4, 5, 6, 7};
  faces.offsets = {0, 4, 8};
  const Complex two = complex_from_polygons(8, faces);
  EXPECT_EQ(select_linked(two, V{2}), (V{0, 1, 2, 3}));
  EXPECT_EQ(select_linked(two, V{2, 7}), (V{0, 1, 2, 3, 4, 5, 6, 7}));
  const Complex c = grid(4, 3);
  EXPECT_EQ(grow_selection(c, V{7}), (V{2, 6, 7, 8, 12}));
  EXPECT_EQ(shrink_selection(c, V{2, 6, 7, 8, 12}), (V{7}));
  EXPECT_EQ(shrink_selection(c, V{7}), V{});
  EXPECT_EQ(invert_selection(6, V{0, 4}), (V{1, 2, 3, 5}));
  EXPECT_EQ(invert_selection(3, V{}), (V{0, 1, 2}));
}

TEST(Selection, PickEdgeNearestToTheMouseOnScreen) {
  // The 4 x 3 grid seen from +z through an orthographic view onto 600 x 500 pixels: world x in
  // [-1, 5] and y in [-1, 4], so a world unit is 100 pixels and (x, y) is at pixel
  // ((x + 1) * 100, (4 - y) * 100).
  std::vector<double> p;
  const Complex c = grid(4, 3, &p);
  const PickView view{glm::ortho(-1.0, 5.0, -1.0, 4.0, -10.0, 10.0), 600, 500};
  PickIndex index;
  index.build(view, p);
  EXPECT_EQ(pick_edge(index, view, p, c, 250, 303, 10, true), edge(c, 6, 7));   // below the middle of 6-7
  EXPECT_EQ(pick_edge(index, view, p, c, 296, 250, 10, true), edge(c, 7, 12));  // beside 7-12
  EXPECT_EQ(pick_edge(index, view, p, c, 250, 250, 10, true), -1);              // a face's middle
}

TEST(Symmetry, MirrorMapsAndMirroredMovesAcrossTwoPlanes) {
  // The 4 x 4 grid centred on the origin: vertex (i, j) at (i - 2, j - 2, 0).
  std::vector<double> p;
  const Complex c = grid(4, 4, &p);
  for (std::size_t k = 0; k < p.size(); k += 3) p[k] -= 2.0, p[k + 1] -= 2.0;
  auto vid = [](int i, int j) { return static_cast<std::uint32_t>(j * 5 + i); };
  const MirrorMap mx = find_mirror(c, p, 0), my = find_mirror(c, p, 1);
  EXPECT_EQ(mx.unmatched, 0u);
  EXPECT_EQ(mx.problem(), "");
  EXPECT_EQ(mx.mirror[vid(3, 1)], vid(1, 1));
  EXPECT_EQ(mx.mirror[vid(2, 4)], vid(2, 4));  // on the plane x = 0
  EXPECT_EQ(my.mirror[vid(3, 1)], vid(3, 3));
  // A move of (3, 1) mirrors to (1, 1), (3, 3) and (1, 3); (2, 0) on x = 0 keeps its x.
  std::vector<std::uint32_t> vs = {vid(3, 1), vid(2, 0)};
  std::vector<double> d = {0.1, 0.2, 0.3, 0.5, 0.25, 0.0};
  const MirrorMap* maps[2] = {&mx, &my};
  mirror_deltas(maps, vs, d);
  // Images in the order x, y, xy; (2, 0) is its own x image, and its xy image is its y image.
  EXPECT_EQ(vs, (std::vector<std::uint32_t>{vid(3, 1), vid(2, 0), vid(1, 1), vid(3, 3), vid(2, 4), vid(1, 3)}));
  EXPECT_EQ(d, (std::vector<double>{0.1, 0.2, 0.3, 0.0, 0.25, 0.0, -0.1, 0.2, 0.3, 0.1, -0.2, 0.3, 0.0, -0.25, 0.0,
                                    -0.1, -0.2, 0.3}));
  // A grid moved off centre has no mirror image for most points, and says which.
  std::vector<double> shifted = p;
  for (std::size_t k = 0; k < shifted.size(); k += 3) shifted[k] += 0.3;
  const MirrorMap bad = find_mirror(c, shifted, 0);
  EXPECT_GT(bad.unmatched, 0u);
  EXPECT_NE(bad.problem().find("X mirror: "), std::string::npos);
}

}  // namespace
}  // namespace sublift
