// Boundary surfaces of lattices: the faces of one cell, oriented outward. Checked by counts,
// by the enclosed volume (divergence theorem) against the known volume, by every directed edge
// being matched by its reverse (a consistently oriented closed surface) and, for convex cells,
// by each Newell normal pointing away from its cell's centroid.
#include <cmath>
#include <filesystem>
#include <map>
#include <numeric>

#include <gtest/gtest.h>

#include "core/analysis/boundary_surface.h"
#include "core/complex/complex_build.h"
#include "core/base/errors.h"
#include "core/multires/hierarchy.h"
#include "core/io/lattice/lattice_format.h"
#include "core/io/lattice/shape_io.h"
#include "core/complex/shapes.h"

using namespace sublift;

namespace {

struct V3 {
  double x, y, z;
};
V3 at(const std::vector<double>& p, std::uint32_t v) { return {p[3 * v], p[3 * v + 1], p[3 * v + 2]}; }
V3 operator-(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
V3 cross(V3 a, V3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

// Volume enclosed by the faces: (1/3) sum over faces of the integral of x . n (fans from corner 0).
double signed_volume(const Csr& faces, const std::vector<double>& xyz) {
  double v = 0;
  for (std::size_t f = 0; f < faces.rows(); ++f) {
    const auto c = faces.row(f);
    for (std::size_t i = 1; i + 1 < c.size(); ++i) v += dot(at(xyz, c[0]), cross(at(xyz, c[i]), at(xyz, c[i + 1])));
  }
  return v / 6;
}

// Newell normal (right-hand rule over the corner order) and centroid of a face.
V3 newell(std::span<const std::uint32_t> c, const std::vector<double>& xyz) {
  V3 n{0, 0, 0};
  for (std::size_t i = 0; i < c.size(); ++i) {
    const V3 p = at(xyz, c[i]), q = at(xyz, c[(i + 1) % c.size()]);
    n.x += (p.y - q.y) * (p.z + q.z);
    n.y += (p.z - q.z) * (p.x + q.x);
    n.z += (p.x - q.x) * (p.y + q.y);
  }
  return n;
}
V3 centroid(std::span<const std::uint32_t> c, const std::vector<double>& xyz) {
  V3 s{0, 0, 0};
  for (std::uint32_t v : c) s = {s.x + xyz[3 * v], s.y + xyz[3 * v + 1], s.z + xyz[3 * v + 2]};
  return {s.x / c.size(), s.y / c.size(), s.z / c.size()};
}

// Every directed edge (a, b) of the surface is matched by as many (b, a): closed and
// consistently oriented (also along non-manifold edges).
void expect_closed_and_consistent(const Csr& faces) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> count;
  for (std::size_t f = 0; f < faces.rows(); ++f) {
    const auto c = faces.row(f);
    for (std::size_t i = 0; i < c.size(); ++i) {
      const std::uint32_t a = c[i], b = c[(i + 1) % c.size()];
      count[{std::min(a, b), std::max(a, b)}] += a < b ? 1 : -1;
    }
  }
  for (const auto& [e, n] : count) EXPECT_EQ(n, 0) << "edge " << e.first << "-" << e.second;
}

// The faces bounding exactly one cell, counted by hand from cell_faces.
std::vector<std::uint32_t> faces_of_one_cell(const Complex& c) {
  std::vector<int> n(c.num_faces(), 0);
  for (std::uint32_t f : c.cell_faces.items) ++n[f];
  std::vector<std::uint32_t> ids;
  for (std::uint32_t f = 0; f < c.num_faces(); ++f)
    if (n[f] == 1) ids.push_back(f);
  return ids;
}

// Each output face has the corners of its complex face (same cycle, either direction).
void expect_same_loops(const Complex& c, const Csr& out, const std::vector<std::uint32_t>& ids) {
  ASSERT_EQ(out.rows(), ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i) {
    const auto a = out.row(i), b = c.faces.row(ids[i]);
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(a[0], b[0]);  // a reversed face keeps its first corner
    const bool same = std::equal(a.begin(), a.end(), b.begin());
    const bool reversed = std::equal(a.begin() + 1, a.end(), b.rbegin());
    EXPECT_TRUE(same || reversed) << "face " << ids[i];
  }
}

}  // namespace

TEST(BoundarySurface, HexBlockHasSixNSquaredOutwardFaces) {
  for (int n : {1, 2, 3, 5}) {
    SCOPED_TRACE("n = " + std::to_string(n));
    std::vector<double> xyz;
    const Complex c = make_hex_block(n, xyz);
    std::vector<std::uint32_t> ids;
    const Csr b = boundary_faces(c, xyz, &ids);
    EXPECT_EQ(b.rows(), std::size_t(6 * n * n));
    EXPECT_EQ(ids, faces_of_one_cell(c));
    expect_same_loops(c, b, ids);
    EXPECT_NEAR(signed_volume(b, xyz), double(n * n * n), 1e-9);
    expect_closed_and_consistent(b);
    // On a box every boundary normal points away from the box centre, with area 1.
    const V3 mid{n / 2.0, n / 2.0, n / 2.0};
    for (std::size_t f = 0; f < b.rows(); ++f) {
      const V3 nn = newell(b.row(f), xyz);
      EXPECT_NEAR(std::sqrt(dot(nn, nn)), 2.0, 1e-12);  // Newell gives twice the area
      EXPECT_GT(dot(nn, centroid(b.row(f), xyz) - mid), 0.0) << "face " << ids[f];
    }
  }
}

TEST(BoundarySurface, RefinedLevelWithoutAdjacency) {
  // The finest level of a hierarchy has no derived adjacency; the boundary needs none.
  std::vector<double> xyz;
  Hierarchy h = make_hierarchy(make_hex_block(2, xyz), 2, Scheme::Linear, 3);
  set_base(h, xyz);
  const std::vector<double> fine = synthesize(h, 2);
  const Csr b = boundary_faces(h.levels[2], fine);
  EXPECT_EQ(b.rows(), std::size_t(6 * 8 * 8));
  EXPECT_NEAR(signed_volume(b, fine), 8.0, 1e-9);  // linear refinement of a box is the box
  expect_closed_and_consistent(b);
}

TEST(BoundarySurface, AssetLatticesEncloseAPositiveVolume) {
  int tested = 0;
  for (const auto& e : std::filesystem::directory_iterator(SUBLIFT_ASSETS_DIR)) {
    if (e.path().extension() != ".lattice") continue;
    SCOPED_TRACE(e.path().filename().string());
    const Shape s = read_shape(e.path().string());
    ASSERT_EQ(s.base.dim, 3);
    std::vector<std::uint32_t> ids;
    const Csr b = boundary_faces(s.base, s.positions, &ids);
    EXPECT_GT(b.rows(), 0u);
    EXPECT_EQ(ids, faces_of_one_cell(s.base));
    expect_same_loops(s.base, b, ids);
    expect_closed_and_consistent(b);
    EXPECT_GT(signed_volume(b, s.positions), 0.0);
    // The sample cells are convex: each normal points away from its cell's vertex centroid.
    for (std::size_t f = 0; f < b.rows(); ++f) {
      ASSERT_EQ(s.base.face_cells.size(ids[f]), 1u);
      const auto cell_verts = s.base.cell_verts.row(s.base.face_cells.row(ids[f])[0]);
      EXPECT_GT(dot(newell(b.row(f), s.positions), centroid(b.row(f), s.positions) - centroid(cell_verts, s.positions)), 0.0)
          << "face " << ids[f];
    }
    ++tested;
  }
  EXPECT_GE(tested, 4);
}

TEST(BoundarySurface, NonConvexCellWithFacesInAnyOrientation) {
  // One L-shaped prism (area 5, height 1) whose faces are listed in mixed orientations. Its
  // vertex centroid (4/3, 4/3) lies on the wrong side of the face at y = 1, x in 1..3, so a
  // centroid test would turn that face inward.
  const std::string text =
      "sublift-lattice 1\n"
      "v 0 0 0\nv 3 0 0\nv 3 1 0\nv 1 1 0\nv 1 3 0\nv 0 3 0\n"
      "v 0 0 1\nv 3 0 1\nv 3 1 1\nv 1 1 1\nv 1 3 1\nv 0 3 1\n"
      "cell\n"
      "f 0 1 2 3 4 5\n"    // bottom, normal +z (inward)
      "f 6 7 8 9 10 11\n"  // top, normal +z (outward)
      "f 0 1 7 6\n"        // y = 0, outward
      "f 1 2 8 7\n"        // x = 3, outward
      "f 2 3 9 8\n"        // y = 1, inward
      "f 3 4 10 9\n"       // x = 1, inward
      "f 4 10 11 5\n"      // y = 3, inward
      "f 5 0 6 11\n"       // x = 0, inward
      "end\n";
  const Shape s = read_lattice(text, "l.lattice");
  std::vector<std::uint32_t> ids;
  const Csr b = boundary_faces(s.base, s.positions, &ids);
  ASSERT_EQ(b.rows(), 8u);
  expect_closed_and_consistent(b);
  EXPECT_NEAR(signed_volume(b, s.positions), 5.0, 1e-12);
  // The face at y = 1 between x = 1 and x = 3 faces +y.
  bool found = false;
  for (std::size_t f = 0; f < b.rows(); ++f) {
    const V3 c = centroid(b.row(f), s.positions);
    if (std::abs(c.x - 2) < 1e-12 && std::abs(c.y - 1) < 1e-12) {
      const V3 n = newell(b.row(f), s.positions);
      EXPECT_GT(n.y, 0.0);
      EXPECT_NEAR(n.x, 0.0, 1e-12);
      found = true;
    }
  }
  EXPECT_TRUE(found);
}

TEST(BoundarySurface, TwoCellsShareAnInnerFaceThatIsDropped) {
  std::vector<double> xyz;
  const Complex c = make_hex_block(1, xyz);
  // Two hexes stacked: read back through the lattice format to get a shared face.
  const Shape s = read_lattice(
      "sublift-lattice 1\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
      "v 0 0 2\nv 1 0 2\nv 1 1 2\nv 0 1 2\nhex 0 1 2 3 4 5 6 7\nhex 4 5 6 7 8 9 10 11\n",
      "two.lattice");
  std::vector<std::uint32_t> ids;
  const Csr b = boundary_faces(s.base, s.positions, &ids);
  EXPECT_EQ(s.base.num_faces(), 11u);
  EXPECT_EQ(b.rows(), 10u);
  EXPECT_NEAR(signed_volume(b, s.positions), 2.0, 1e-12);
  expect_closed_and_consistent(b);
  // Mirrored positions (negative determinant) still give outward faces.
  std::vector<double> mirrored = s.positions;
  for (std::size_t i = 0; i < mirrored.size(); i += 3) mirrored[i] = -mirrored[i];
  EXPECT_NEAR(signed_volume(boundary_faces(s.base, mirrored), mirrored), 2.0, 1e-12);
  EXPECT_EQ(c.dim, 3);
}

TEST(BoundarySurface, SurfacesPassThroughAndBadInputThrows) {
  const SurfaceMesh t = make_quad_torus(5, 4);
  Csr faces;
  faces.offsets = t.face_offsets;
  faces.items = t.face_indices;
  const Complex surface = complex_from_polygons(static_cast<std::uint32_t>(t.num_vertices()), faces, {});
  const std::vector<double> xyz = flatten_positions(t);
  std::vector<std::uint32_t> ids{42};
  const Csr b = boundary_faces(surface, xyz, &ids);
  EXPECT_EQ(b.offsets, surface.faces.offsets);
  EXPECT_EQ(b.items, surface.faces.items);
  std::vector<std::uint32_t> iota(surface.num_faces());
  std::iota(iota.begin(), iota.end(), 0u);
  EXPECT_EQ(ids, iota);
  // Too few coordinates.
  std::vector<double> block;
  const Complex c = make_hex_block(2, block);
  block.pop_back();
  EXPECT_THROW(boundary_faces(c, block), Error);
  // A cell that is not closed (one face left out of its row) is a TopologyError, not a crash.
  Complex open = make_hex_block(1, block);
  open.cell_faces.items.pop_back();
  open.cell_faces.offsets.back() -= 1;
  EXPECT_THROW(boundary_faces(open, block), TopologyError);
}
