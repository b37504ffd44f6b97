// Legacy VTK unstructured grids: every supported cell type with VTK's vertex orders, features
// from lower-dimensional cells, binary and version-5 layouts, bad files (each error names the
// cell, type or line), and export/import round trips (hexahedra stay VTK_HEXAHEDRON).
#include <cstring>
#include <filesystem>
#include <sstream>

#include <gtest/gtest.h>

#include "core/complex/complex_build.h"
#include "core/base/file_io.h"
#include "core/io/lattice/lattice_format.h"
#include "core/complex/refine.h"
#include "core/io/lattice/vtk_format.h"
#include "tests/io_test_util.h"

using namespace sublift;
using sublift::testing::dims_by_vertices;
using sublift::testing::input_error;
using sublift::testing::TempDir;

namespace {

const std::string kHeader = "# vtk DataFile Version 3.0\ntest\nASCII\nDATASET UNSTRUCTURED_GRID\n";  // 4 lines
const std::string kCubePoints = "POINTS 8 double\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n";  // 5-13

std::string grid(const std::string& points, const std::string& cells, const std::string& types) {
  return kHeader + points + cells + types;
}

std::string error_of(const std::string& text, std::size_t* line = nullptr) {
  return input_error([&] { read_vtk(text, "t.vtk"); }, line);
}

// Expects an InputError on `line` whose message names the file and contains `needle`.
void expect_error(const std::string& text, std::size_t line, const std::string& needle) {
  sublift::testing::expect_input_error([](const std::string& t, const std::string& f) { read_vtk(t, f); }, text, "t.vtk", line, needle);
}

// The faces of a complex as sets of vertex loops (canonical), sorted.
std::vector<std::vector<std::uint32_t>> face_set(const Complex& c) {
  std::vector<std::vector<std::uint32_t>> f;
  for (std::uint32_t i = 0; i < c.num_faces(); ++i) f.push_back(sublift::canonical_loop(c.faces.row(i)));
  std::sort(f.begin(), f.end());
  return f;
}

// Big-endian bytes of a value.
template <class T>
std::string be(T v) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  if constexpr (std::endian::native == std::endian::little) std::reverse(b, b + sizeof(T));
  return std::string(b, sizeof(T));
}

}  // namespace

TEST(VtkFormat, HexahedronUsesVtkVertexOrder) {
  const Shape s = read_vtk(grid(kCubePoints, "CELLS 1 9\n8 0 1 2 3 4 5 6 7\n", "CELL_TYPES 1\n12\n"), "h.vtk");
  ASSERT_EQ(s.base.num_cells(), 1u);
  EXPECT_EQ(s.base.num_edges(), 12u);
  EXPECT_EQ(s.base.num_vertices, 8u);
  // VTK's hexahedron faces: bottom 0-1-2-3, top 4-5-6-7, sides (0,1,5,4) ...: never a diagonal.
  const auto faces = face_set(s.base);
  const std::vector<std::vector<std::uint32_t>> want = {{0, 1, 2, 3}, {0, 1, 5, 4}, {0, 3, 7, 4},
                                                        {1, 2, 6, 5}, {2, 3, 7, 6}, {4, 5, 6, 7}};
  std::vector<std::vector<std::uint32_t>> want_c;
  for (const auto& f : want) want_c.push_back(sublift::canonical_loop(f));
  std::sort(want_c.begin(), want_c.end());
  EXPECT_EQ(faces, want_c);
  EXPECT_TRUE(s.report.empty());
}

TEST(VtkFormat, ReadsEveryVolumeCellType) {
  struct Case { int type; std::string ids; std::uint32_t faces, edges; };
  const Case cases[] = {{10, "4 0 1 3 4", 4, 6},            // tetra
                        {12, "8 0 1 2 3 4 5 6 7", 6, 12},   // hexahedron
                        {11, "8 0 1 3 2 4 5 7 6", 6, 12},   // voxel (x fastest): same cube
                        {13, "6 0 1 3 4 5 7", 5, 9},        // wedge
                        {14, "5 0 1 2 3 6", 5, 8}};         // pyramid
  for (const Case& c : cases) {
    const std::size_t n = std::count(c.ids.begin(), c.ids.end(), ' ') + 1;
    const std::string text =
        grid(kCubePoints, "CELLS 1 " + std::to_string(n) + "\n" + c.ids + "\n", "CELL_TYPES 1\n" + std::to_string(c.type) + "\n");
    const Shape s = read_vtk(text, "c.vtk");
    EXPECT_EQ(s.base.num_cells(), 1u) << c.type;
    EXPECT_EQ(s.base.num_faces(), c.faces) << c.type;
    EXPECT_EQ(s.base.num_edges(), c.edges) << c.type;
    EXPECT_NO_THROW(validate(s.base)) << c.type;
  }
  // Voxel and hexahedron give the same faces.
  const Shape hex = read_vtk(grid(kCubePoints, "CELLS 1 9\n8 0 1 2 3 4 5 6 7\n", "CELL_TYPES 1\n12\n"), "h.vtk");
  const Shape vox = read_vtk(grid(kCubePoints, "CELLS 1 9\n8 0 1 3 2 4 5 7 6\n", "CELL_TYPES 1\n11\n"), "v.vtk");
  EXPECT_EQ(face_set(hex.base), face_set(vox.base));
}

TEST(VtkFormat, ReadsPolyhedronFaceStream) {
  // The cube as VTK_POLYHEDRON: record = 6 faces, each "4 a b c d" (31 numbers).
  const std::string stream = "31 6 4 0 3 2 1 4 4 5 6 7 4 0 1 5 4 4 1 2 6 5 4 2 3 7 6 4 3 0 4 7\n";
  const Shape s = read_vtk(grid(kCubePoints, "CELLS 1 32\n" + stream, "CELL_TYPES 1\n42\n"), "p.vtk");
  const Shape hex = read_vtk(grid(kCubePoints, "CELLS 1 9\n8 0 1 2 3 4 5 6 7\n", "CELL_TYPES 1\n12\n"), "h.vtk");
  EXPECT_EQ(face_set(s.base), face_set(hex.base));
}

TEST(VtkFormat, LowerDimensionalCellsTagFeatures) {
  // A hex with a crease line on edge 0-1, a corner at 6 and a polygon on its top face.
  const std::string text = grid(kCubePoints, "CELLS 4 18\n8 0 1 2 3 4 5 6 7\n2 0 1\n1 6\n3 2 3 7\n",
                                "CELL_TYPES 4\n12\n3\n1\n5\n");
  const Shape s = read_vtk(text, "f.vtk");
  const auto d = dims_by_vertices(s.base);
  EXPECT_EQ(d.edges.at({0, 1}), 1);
  EXPECT_EQ(d.vertices[6], 0);
  // The triangle 2-3-7 is no face of the hexahedron: ignored with a warning naming its line.
  ASSERT_EQ(s.report.warnings.size(), 1u) << s.report.format("f.vtk");
  EXPECT_NE(s.report.warnings[0].what.find("no face of the shape"), std::string::npos);
  EXPECT_EQ(s.report.warnings[0].first_lines, std::vector<std::size_t>{18});
}

TEST(VtkFormat, SurfaceAndCurveFilesWithoutVolumeCells) {
  const Shape surf = read_vtk(grid(kCubePoints, "CELLS 2 10\n4 0 1 2 3\n4 0 1 5 4\n", "CELL_TYPES 2\n9\n9\n"), "s.vtk");
  EXPECT_EQ(surf.base.dim, 2);
  EXPECT_EQ(surf.base.num_faces(), 2u);
  ASSERT_EQ(surf.report.warnings.size(), 1u);  // vertices 6 and 7 used by no polygon
  EXPECT_EQ(surf.report.warnings[0].count, 2u);
  const Shape curve = read_vtk(grid(kCubePoints, "CELLS 1 9\n8 0 1 2 3 4 5 6 7\n", "CELL_TYPES 1\n4\n"), "c.vtk");
  EXPECT_EQ(curve.base.dim, 1);
  EXPECT_EQ(curve.base.num_edges(), 7u);
}

TEST(VtkFormat, ReadsVersion5OffsetsAndConnectivity) {
  // As ParaView writes it: METADATA after the points, OFFSETS/CONNECTIVITY arrays.
  const std::string text = "# vtk DataFile Version 5.1\nv5\nASCII\nDATASET UNSTRUCTURED_GRID\n" + kCubePoints +
                           "METADATA\nINFORMATION 2\nNAME L2_NORM_RANGE LOCATION vtkDataArray\nDATA 2 0 1.73205\n"
                           "NAME L2_NORM_FINITE_RANGE LOCATION vtkDataArray\nDATA 2 0 1.73205\n\n"
                           "CELLS 3 12\nOFFSETS vtktypeint64\n0 8 12\nCONNECTIVITY vtktypeint64\n0 1 2 3 4 5 6 7\n4 5 6 7\n"
                           "CELL_TYPES 2\n12\n9\n";
  const Shape s = read_vtk(text, "v5.vtk");
  EXPECT_EQ(s.base.num_cells(), 1u);
  EXPECT_EQ(dims_by_vertices(s.base).faces.at({4, 5, 6, 7}), 2);
  EXPECT_TRUE(s.report.empty()) << s.report.format("v5.vtk");
}

TEST(VtkFormat, ReadsBinaryBigEndian) {
  std::string text = "# vtk DataFile Version 3.0\nbinary\nBINARY\nDATASET UNSTRUCTURED_GRID\nPOINTS 8 double\n";
  const double pts[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1.0 / 3.0}};
  for (const auto& p : pts)
    for (double x : p) text += be(x);
  text += "\nCELLS 1 9\n";
  for (int v : {8, 0, 1, 2, 3, 4, 5, 6, 7}) text += be<std::int32_t>(v);
  text += "\nCELL_TYPES 1\n" + be<std::int32_t>(12) + "\nCELL_DATA 1\nSCALARS x int 1\n";
  const Shape s = read_vtk(text, "b.vtk");
  EXPECT_EQ(s.base.num_cells(), 1u);
  EXPECT_EQ(s.positions[23], 1.0 / 3.0);
  // The cell data end too early: named as not read, the grid kept.
  EXPECT_NE(s.report.not_kept_summary().find("CELL_DATA and what follows it (unreadable: b.vtk:13: unexpected end of file"), std::string::npos)
      << s.report.not_kept_summary();
  // Truncated inside the POINTS block.
  std::size_t line = 0;
  const std::string e = error_of(text.substr(0, 120), &line);
  EXPECT_NE(e.find("cannot fit"), std::string::npos) << e;
}

TEST(VtkFormat, RefusesUnsupportedCellTypesNamingCellTypeAndLine) {
  // Cell 1 is a quadratic tetrahedron (type 24) on CELL_TYPES line 18.
  const std::string text = grid(kCubePoints, "CELLS 2 20\n8 0 1 2 3 4 5 6 7\n10 0 1 2 3 4 5 6 7 0 1\n",
                                "CELL_TYPES 2\n12\n24\n");
  std::size_t line = 0;
  const std::string e = error_of(text, &line);
  EXPECT_NE(e.find("cell 1 has VTK cell type 24 (VTK_QUADRATIC_TETRA)"), std::string::npos) << e;
  EXPECT_EQ(line, 19u);
  expect_error(grid(kCubePoints, "CELLS 1 4\n3 0 1 2\n", "CELL_TYPES 1\n6\n"), 17, "VTK_TRIANGLE_STRIP");
}

TEST(VtkFormat, RefusesLyingCountsBeforeAllocating) {
  expect_error(kHeader + "POINTS 1000000000 double\n0 0 0\n", 5, "cannot fit");
  expect_error(grid(kCubePoints, "CELLS 900000000 900000000\n", ""), 14, "cannot fit");
  expect_error(grid(kCubePoints, "CELLS 2 1\n1 0\n", ""), 14, "exceeds its size");
  expect_error(grid(kCubePoints, "CELLS 1 9\n9 0 1 2 3 4 5 6 7\n", ""), 15, "beyond the CELLS size");
  expect_error(grid(kCubePoints, "CELLS 2 9\n8 0 1 2 3 4 5 6 7\n", ""), 14, "fewer than the 2 cells");
  expect_error(grid(kCubePoints, "CELLS 1 10\n8 0 1 2 3 4 5 6 7 0\n", "CELL_TYPES 1\n12\n"), 14, "does not match");
  expect_error(grid(kCubePoints, "CELLS 1 9\n8 0 1 2 3 4 5 6 7\n", "CELL_TYPES 2\n12\n12\n"), 17, "2 types for 1 cells");
  expect_error(grid(kCubePoints, "CELLS 1 9\n8 0 1 2 3 4 5 6 7\n", "CELL_TYPES -1\n"), 16, "out of range");
  expect_error(grid(kCubePoints, "CELLS 1 32\n31 7 4 0 3 2 1 4 4 5 6 7 4 0 1 5 4 4 1 2 6 5 4 2 3 7 6 4 3 0 4 7\n",
                    "CELL_TYPES 1\n42\n"),
               15, "face stream ends before face 6");
}

TEST(VtkFormat, RefusesBadValuesAndStructure) {
  expect_error(kHeader + "POINTS 2 float\n0 0 0\n0 nan 0\n", 7, "non-finite coordinate 'nan'");
  expect_error(kHeader + "POINTS 1 float\n0 0 1e31\n", 5, "magnitude");
  expect_error(grid(kCubePoints, "CELLS 1 9\n8 0 1 2 3 4 5 6 9\n", "CELL_TYPES 1\n12\n"), 15,
               "names vertex 9, but the vertices are 0..7");
  expect_error(grid(kCubePoints, "CELLS 1 8\n7 0 1 2 3 4 5 6\n", "CELL_TYPES 1\n12\n"), 15, "has 7 vertices");
  // Five faces of a cube as a polyhedron: not closed, named with its line.
  expect_error(grid(kCubePoints, "CELLS 1 27\n26 5 4 0 3 2 1 4 0 1 5 4 4 1 2 6 5 4 2 3 7 6 4 3 0 4 7\n", "CELL_TYPES 1\n42\n"),
               15, "is not closed");
  expect_error("solid cube\n", 1, "not a legacy VTK file");
  expect_error("# vtk DataFile Version 3.0\nx\nXML\n", 3, "ASCII or BINARY");
  expect_error("# vtk DataFile Version 3.0\nx\nASCII\nDATASET POLYDATA\n", 4, "only UNSTRUCTURED_GRID");
  expect_error(kHeader + "POINTS 1 double\n0 0 0\nBOGUS 3\n", 7, "unknown keyword 'BOGUS'");
  expect_error(kHeader + kCubePoints, 0, "no CELLS");
  expect_error(kHeader + "POINTS 1 double\n0 0", 5, "cannot fit");
  expect_error(kHeader + "POINTS 2 double\n0 0 0 0 0            ", 6, "unexpected end of file");
  expect_error("", 0, "empty file");
}

TEST(VtkFormat, ExportKeepsHexahedraAndRoundTripsExactly) {
  TempDir dir("sublift_vtk_rt");
  // Hexahedra, a wedge and a pyramid with a feature face, a crease and a corner.
  const std::string text =
      "sublift-lattice 1\n"
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
      "v 0 0 2\nv 1 0 2\nv 1 1 2\nv 0 1 2\nv 0.5 0 2.7\nv 0.5 1 2.7\nv 2 0.5 0.5\n"
      "hex 0 1 2 3 4 5 6 7\nhex 4 5 6 7 8 9 10 11\nwedge 8 9 12 11 10 13\npyramid 1 2 6 5 14\n"
      "feature_face 4 5 6 7\ncrease 0 1\ncorner 3\n";
  Shape s = read_lattice(text, "in.lattice");
  s.positions[2] = 1e-300;
  const std::string path = dir.file("out.vtk");
  write_vtk(path, s.base, s.positions);
  const std::string written = read_file_bytes(path);
  const Shape back = read_vtk(written, path);
  EXPECT_EQ(back.positions, s.positions);
  EXPECT_EQ(back.base.num_cells(), 4u);
  EXPECT_EQ(face_set(back.base), face_set(s.base));
  EXPECT_EQ(dims_by_vertices(back.base), dims_by_vertices(s.base));
  EXPECT_TRUE(back.report.empty()) << back.report.format(path);
  // Cell types: 2 hexahedra, 2 polyhedra, then the feature cells (polygon, line, vertex).
  const std::size_t at = written.find("CELL_TYPES 7\n");
  ASSERT_NE(at, std::string::npos) << written;
  EXPECT_EQ(written.substr(at + 13), "12\n12\n42\n42\n9\n3\n1\n");
}

TEST(VtkFormat, ExportedHexahedraHavePositiveVtkOrientation) {
  TempDir dir("sublift_vtk_orient");
  // A 2x2x2 block read from a .lattice whose hexahedra are written in mirrored (negative) order.
  std::string text = "sublift-lattice 1\n";
  auto id = [](int i, int j, int k) { return (k * 3 + j) * 3 + i; };
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) {
        text += "v ";
        text += std::to_string(i) + ' ' + std::to_string(j) + ' ' + std::to_string(k) + '\n';
      }
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        const int c[8] = {id(i, j, k), id(i, j + 1, k), id(i + 1, j + 1, k), id(i + 1, j, k),
                          id(i, j, k + 1), id(i, j + 1, k + 1), id(i + 1, j + 1, k + 1), id(i + 1, j, k + 1)};
        text += "hex";
        for (int v : c) {
          text += ' ';
          text += std::to_string(v);
        }
        text += "\n";
      }
  const Shape s = read_lattice(text, "m.lattice");
  const Complex fine = refine(s.base);
  // Positions of the refined level: the midpoint/centroid rule (the linear scheme's subdivision).
  std::vector<double> xyz(s.positions);
  xyz.resize(3 * std::size_t(fine.num_vertices));
  auto centroid = [&](std::uint32_t child, std::vector<std::uint32_t> vs) {
    for (int t = 0; t < 3; ++t) {
      double sum = 0;
      for (std::uint32_t v : vs) sum += s.positions[3 * v + t];
      xyz[3 * child + t] = sum / double(vs.size());
    }
  };
  const Complex& c = s.base;
  std::uint32_t child = c.num_vertices;
  for (std::uint32_t e = 0; e < c.num_edges(); ++e) centroid(child++, {c.edge_verts[2 * e], c.edge_verts[2 * e + 1]});
  for (std::uint32_t f = 0; f < c.num_faces(); ++f) centroid(child++, {c.faces.row(f).begin(), c.faces.row(f).end()});
  for (std::uint32_t k = 0; k < c.num_cells(); ++k) centroid(child++, {c.cell_verts.row(k).begin(), c.cell_verts.row(k).end()});
  const std::string path = dir.file("fine.vtk");
  write_vtk(path, fine, xyz);
  std::istringstream in(read_file_bytes(path));
  std::string line;
  while (std::getline(in, line) && line.rfind("CELLS", 0) != 0) {}
  int hexes = 0;
  while (std::getline(in, line) && line.rfind("CELL_TYPES", 0) != 0) {
    std::istringstream l(line);
    int n;
    l >> n;
    ASSERT_EQ(n, 8) << line;
    std::uint32_t v[8];
    for (auto& x : v) l >> x;
    auto p = [&](int i) { return std::array<double, 3>{xyz[3 * v[i]], xyz[3 * v[i] + 1], xyz[3 * v[i] + 2]}; };
    auto d = [&](int i) { auto a = p(i), o = p(0); return std::array<double, 3>{a[0] - o[0], a[1] - o[1], a[2] - o[2]}; };
    const auto a = d(1), b = d(3), h = d(4);
    const double jac = a[0] * (b[1] * h[2] - b[2] * h[1]) - a[1] * (b[0] * h[2] - b[2] * h[0]) + a[2] * (b[0] * h[1] - b[1] * h[0]);
    EXPECT_GT(jac, 0) << line;  // 0-1 x 0-3 points toward 4: VTK's right-handed hexahedron
    ++hexes;
  }
  EXPECT_EQ(hexes, 64);
}

TEST(VtkFormat, SharedGmshCubeLoadsWithItsFeatures) {
  const std::filesystem::path f = std::filesystem::path(SUBLIFT_SHARED_DATA) / "lattices/vtk/s01c_cube.vtk";
  if (!std::filesystem::exists(f)) GTEST_SKIP() << f << " not found";
  const Shape s = read_vtk(read_file_bytes(f.string()), f.string());
  EXPECT_EQ(s.base.num_vertices, 263u);
  EXPECT_EQ(s.base.num_cells(), 886u);  // tetrahedra; triangles, lines and points are features
  EXPECT_TRUE(s.report.empty()) << s.report.format(f.string());
  std::size_t corners = 0, creases = 0;
  for (auto d : s.base.vertex_dim) corners += d == 0;
  for (auto d : s.base.edge_dim) creases += d == 1;
  EXPECT_EQ(corners, 8u);   // the cube's corners (Gmsh points)
  EXPECT_EQ(creases, 60u);  // its 12 edges, 5 segments each (Gmsh lines)
  EXPECT_NO_THROW(validate(s.base));
  // Its CELL_DATA (Gmsh's CellEntityIds) is cell values, not vertex channels: named, not dropped silently.
  EXPECT_EQ(s.report.not_kept_summary(), "1 CELL_DATA scalars 'CellEntityIds'");
}

// Issue 20: a lattice's material values. POINT_DATA scalars (a channel per component), vectors
// and colours become attributes, in order; a FIELD array of one tuple per point too; normals,
// texture coordinates and cell data are named as not kept; a write/read round trip is exact; a
// count that does not match the points, or an unreadable value, is refused with its line.
TEST(VtkFormat, PointDataAreAttributeChannels) {
  const std::string cube = grid(kCubePoints, "CELLS 1 9\n8 0 1 2 3 4 5 6 7\n", "CELL_TYPES 1\n12\n");  // 17 lines
  const std::string text = cube +
                           "POINT_DATA 8\nSCALARS density float\nLOOKUP_TABLE default\n0 1 2 3 4 5 6 7\n"
                           "SCALARS pair double 2\nLOOKUP_TABLE default\n0 10 1 11 2 12 3 13 4 14 5 15 6 16 7 17\n"
                           "NORMALS n float\n0 0 1 0 0 1 0 0 1 0 0 1 0 0 1 0 0 1 0 0 1 0 0 1\n"
                           "FIELD data 1\nheat 1 8 double\n8 7 6 5 4 3 2 1\n"
                           "CELL_DATA 1\nSCALARS material int 1\nLOOKUP_TABLE default\n3\n";
  const Shape s = read_vtk(text, "t.vtk");
  ASSERT_EQ(s.attributes.size(), 4u);
  EXPECT_EQ(s.attributes[0].name, "density");
  EXPECT_EQ(s.attributes[0].type, "float");
  EXPECT_EQ(s.attributes[0].values, (std::vector<double>{0, 1, 2, 3, 4, 5, 6, 7}));
  EXPECT_EQ(s.attributes[1].name, "pair_0");
  EXPECT_EQ(s.attributes[2].name, "pair_1");
  EXPECT_EQ(s.attributes[2].values, (std::vector<double>{10, 11, 12, 13, 14, 15, 16, 17}));
  EXPECT_EQ(s.attributes[3].name, "heat");
  EXPECT_EQ(s.attributes[3].values[0], 8.0);
  EXPECT_EQ(s.report.not_kept_summary(), "1 POINT_DATA normals 'n' (they follow from the shape), 1 CELL_DATA scalars 'material'");
  // Written as POINT_DATA in double and read back: the same values.
  TempDir dir("sublift_vtk_point_data");
  write_vtk(dir.file("out.vtk"), s.base, s.positions, s.attributes);
  const Shape back = read_vtk(read_file_bytes(dir.file("out.vtk")), "out.vtk");
  ASSERT_EQ(back.attributes.size(), 4u);
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(back.attributes[k].name, s.attributes[k].name);
    EXPECT_EQ(back.attributes[k].values, s.attributes[k].values);
  }
  expect_error(cube + "POINT_DATA 7\n", 18, "POINT_DATA 7 does not match the 8 points");
  expect_error(cube + "POINT_DATA 8\nSCALARS d float\nLOOKUP_TABLE default\n0 1 2 x 4 5 6 7\n", 21, "'x' is not a number");
  expect_error(cube + "POINT_DATA 8\nGLYPHS d\n", 19, "unknown keyword 'GLYPHS' in POINT_DATA");
}

// Issue 18: the VTK reader builds its cells through the same checks as .lattice: a hexahedron
// listed twice is refused naming both cells.
TEST(VtkFormat, RefusesACellListedTwice) {
  const std::string text = grid(kCubePoints, "CELLS 2 18\n8 0 1 2 3 4 5 6 7\n8 4 5 6 7 0 1 2 3\n", "CELL_TYPES 2\n12\n12\n");
  EXPECT_EQ(error_of(text), "t.vtk:16: cell 1 (VTK_HEXAHEDRON) has the same vertices as cell 0 (VTK_HEXAHEDRON) on line 15: a cell listed twice");
}
