// Refinement invariants after every level: counts, Euler characteristic, validate(), adjacency
// symmetry, class ordering, and type-n cells where paper 000 says so.
#include <gtest/gtest.h>

#include "core/complex/complex_build.h"
#include "core/base/errors.h"
#include "core/complex/refine.h"
#include "core/complex/shapes.h"
#include "tests/test_lattices.h"

using namespace sublift;
using namespace sublift::testing;

namespace {

long long euler(const Complex& c) {
  return static_cast<long long>(c.num_vertices) - c.num_edges() + c.num_faces() - c.num_cells();
}

void expect_symmetric(const Csr& down, const Csr& up) {
  for (std::size_t r = 0; r < down.rows(); ++r)
    for (std::uint32_t x : down.row(r)) {
      const auto row = up.row(x);
      EXPECT_TRUE(std::binary_search(row.begin(), row.end(), static_cast<std::uint32_t>(r)));
    }
  EXPECT_EQ(down.items.size(), up.items.size());
}

void check_levels(Complex c, int levels, const char* name) {
  SCOPED_TRACE(name);
  const long long chi = euler(c);
  for (int j = 0; j < levels; ++j) {
    Complex next = refine(c);
    EXPECT_NO_THROW(validate(next));
    EXPECT_EQ(next.num_vertices, c.num_vertices + c.num_edges() + c.num_faces() + c.num_cells());
    EXPECT_EQ(next.num_edges(), 2 * c.num_edges() + c.faces.items.size() + c.cell_faces.items.size());
    EXPECT_EQ(next.num_faces(), c.faces.items.size() + c.cell_edges.items.size());
    EXPECT_EQ(next.num_cells(), c.cell_verts.items.size());
    EXPECT_EQ(euler(next), chi);
    for (std::uint32_t f = 0; f < next.num_faces(); ++f) EXPECT_EQ(next.faces.size(f), 4u);
    expect_symmetric(next.faces, next.vertex_faces);
    expect_symmetric(next.face_edges, next.edge_faces);
    expect_symmetric(next.cell_faces, next.face_cells);
    // Children inherit feature dims: class ranges [v | e | f | c].
    for (std::uint32_t e = 0; e < c.num_edges(); ++e) EXPECT_EQ(next.vertex_dim[c.num_vertices + e], c.edge_dim[e]);
    c = std::move(next);
  }
}

}  // namespace

TEST(Refine, InvariantsHoldOnEveryKindOfComplex) {
  std::vector<double> pos;
  check_levels(make_curve_loop(5, pos), 3, "curve");
  check_levels(complex_from_surface_mesh(make_quad_torus(4, 3)), 3, "torus");
  Csr tri;
  tri.items = {0, 1, 2, 0, 2, 3, 0, 3, 4, 1};
  tri.offsets = {0, 3, 6, 10};
  check_levels(complex_from_polygons(5, tri), 3, "open fan with a quad");
  check_levels(make_hex_block(2, pos), 2, "hex block");
  check_levels(pyramid_cell(), 2, "pyramid");
  check_levels(prism_cell(), 2, "prism");
  check_levels(tetra_cell(), 2, "tetrahedron");
}

TEST(Refine, HexahedraAndTypeNCells) {
  const Complex p1 = refine(pyramid_cell());
  ASSERT_EQ(p1.num_cells(), 5u);  // one per pyramid vertex
  std::vector<std::uint32_t> sizes;
  for (std::uint32_t k = 0; k < p1.num_cells(); ++k) sizes.push_back(p1.cell_faces.size(k));
  std::sort(sizes.begin(), sizes.end());
  EXPECT_EQ(sizes, (std::vector<std::uint32_t>{6, 6, 6, 6, 8}));  // the apex becomes a type-4 cell
  // A type-n cell subdivides into two type-n cells and 2n hexahedra (000 sec. 3.4).
  const Complex p2 = refine(p1);
  int type4 = 0, hexes = 0;
  for (std::uint32_t k = 0; k < p2.num_cells(); ++k) {
    type4 += p2.cell_faces.size(k) == 8;
    hexes += p2.cell_faces.size(k) == 6;
  }
  EXPECT_EQ(type4, 2);
  EXPECT_EQ(hexes, 4 * 8 + 8);  // 4 hexahedra give 8 each, the type-4 cell gives 8
  const Complex t1 = refine(tetra_cell());
  for (std::uint32_t k = 0; k < t1.num_cells(); ++k) EXPECT_EQ(t1.cell_faces.size(k), 6u);
}

TEST(Refine, ValidationRejectsBrokenInput) {
  Csr loops, cells;
  loops.items = {0, 3, 2, 1, 0, 1, 4, 1, 2, 4, 2, 3, 4};  // a pyramid missing one side
  loops.offsets = {0, 4, 7, 10, 13};
  cells.items = {0, 1, 2, 3};
  cells.offsets = {0, 4};
  try {
    complex_from_cells(5, loops, cells);
    FAIL() << "unclosed cell accepted";
  } catch (const TopologyError& e) {
    EXPECT_NE(std::string(e.what()).find("cell 0 is not closed"), std::string::npos) << e.what();
  }
  Csr bad;
  bad.items = {0, 1, 1};
  bad.offsets = {0, 3};
  EXPECT_THROW(complex_from_polygons(3, bad), TopologyError);
  bad.items = {0, 1, 7};
  EXPECT_THROW(complex_from_polygons(3, bad), TopologyError);
  bad.items = {0, 1};
  bad.offsets = {0, 2};
  EXPECT_THROW(complex_from_polygons(3, bad), TopologyError);
  FeatureTags t;
  t.crease_edges.push_back({0, 2});
  Csr quad;
  quad.items = {0, 1, 2, 3};
  quad.offsets = {0, 4};
  EXPECT_THROW(complex_from_polygons(4, quad, t), TopologyError);  // 0-2 is a diagonal, no edge
}
