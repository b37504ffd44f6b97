// The .lattice reader and writer: good files, every kind of bad file (each error names the
// line it comes from), and exact round trips of positions, cells and feature dims.
#include <gtest/gtest.h>

#include "core/complex/complex_build.h"
#include "core/base/file_io.h"
#include "core/io/lattice/lattice_format.h"
#include "core/complex/refine.h"
#include "tests/io_test_util.h"

using namespace sublift;
using sublift::testing::dims_by_vertices;
using sublift::testing::input_error;
using sublift::testing::TempDir;

namespace {

const std::string kCubeVerts =
    "sublift-lattice 1\n"
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n";  // lines 2-9

std::string error_of(const std::string& text, std::size_t* line = nullptr) {
  return input_error([&] { read_lattice(text, "t.lattice"); }, line);
}

// Expects an InputError on `line` whose message names the file and contains `needle`.
void expect_error(const std::string& text, std::size_t line, const std::string& needle) {
  sublift::testing::expect_input_error([](const std::string& t, const std::string& f) { read_lattice(t, f); }, text, "t.lattice", line, needle);
}

}  // namespace

TEST(LatticeFormat, HexShorthandAndGeneralCellGiveTheSameCube) {
  const Shape a = read_lattice(kCubeVerts + "hex 0 1 2 3 4 5 6 7\n", "a.lattice");
  const Shape b = read_lattice(kCubeVerts +
                                   "# the same cube as a general cell\ncell\n"
                                   "f 0 3 2 1\nf 4 5 6 7\nf 0 1 5 4\nf 1 2 6 5\nf 2 3 7 6\nf 3 0 4 7\nend\n",
                               "b.lattice");
  for (const Shape* s : {&a, &b}) {
    EXPECT_EQ(s->base.dim, 3);
    EXPECT_EQ(s->base.num_vertices, 8u);
    EXPECT_EQ(s->base.num_edges(), 12u);
    EXPECT_EQ(s->base.num_faces(), 6u);
    EXPECT_EQ(s->base.num_cells(), 1u);
    EXPECT_TRUE(s->report.empty());
    EXPECT_NO_THROW(validate(s->base));
  }
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.positions[3 * 6 + 0], 1.0);
  EXPECT_EQ(dims_by_vertices(a.base), dims_by_vertices(b.base));
}

TEST(LatticeFormat, ReadsEveryShorthandAndSharedFaces) {
  // A prism on top of a cube, a pyramid beside it, a tetrahedron on the pyramid.
  const std::string text = kCubeVerts +
                           "v 0.5 0 1.8\nv 0.5 1 1.8\n"  // 8, 9: prism ridge
                           "v 2 0.5 0.5\n"                // 10: pyramid apex
                           "v 2 0.5 1.5\n"                // 11: tetra apex
                           "hex 0 1 2 3 4 5 6 7\n"
                           "wedge 4 5 8 7 6 9\n"
                           "pyramid 1 2 6 5 10\n"
                           "tet 5 6 10 11\n";
  const Shape s = read_lattice(text, "m.lattice");
  EXPECT_EQ(s.base.num_cells(), 4u);
  // Faces: hex 6 + wedge 5 + pyramid 5 + tet 4, minus 3 shared (hex/wedge, hex/pyramid, pyramid/tet).
  EXPECT_EQ(s.base.num_faces(), 6u + 5 + 5 + 4 - 3);
  std::size_t shared = 0;
  for (std::uint32_t f = 0; f < s.base.num_faces(); ++f) shared += s.base.face_cells.size(f) == 2;
  EXPECT_EQ(shared, 3u);
}

TEST(LatticeFormat, CommentsBomAndCrlfAreAccepted) {
  std::string text = "\xEF\xBB\xBF" + kCubeVerts + "  # indented comment\n\nhex 0 1 2 3 4 5 6 7   # trailing\n";
  std::string crlf;
  for (char c : text) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  const Shape s = read_lattice(crlf, "c.lattice");
  EXPECT_EQ(s.base.num_cells(), 1u);
  EXPECT_EQ(s.positions.size(), 24u);
}

TEST(LatticeFormat, TagsSetFeatureDims) {
  const Shape s = read_lattice(kCubeVerts + "hex 0 1 2 3 4 5 6 7\ncrease 0 1 2\ncorner 7\n", "t.lattice");
  const auto d = dims_by_vertices(s.base);
  EXPECT_EQ(d.edges.at({0, 1}), 1);
  EXPECT_EQ(d.edges.at({1, 2}), 1);
  EXPECT_EQ(d.edges.at({2, 3}), 2);  // boundary surface of the lattice, untagged
  EXPECT_EQ(d.vertices[1], 1);       // two crease edges: on the curve
  EXPECT_EQ(d.vertices[7], 0);       // corner
}

TEST(LatticeFormat, InnerFeatureFaceBetweenTwoCells) {
  const std::string text = kCubeVerts + "v 0 0 2\nv 1 0 2\nv 1 1 2\nv 0 1 2\n"
                           "hex 0 1 2 3 4 5 6 7\nhex 4 5 6 7 8 9 10 11\nfeature_face 7 6 5 4\n";
  const Shape s = read_lattice(text, "f.lattice");
  EXPECT_EQ(dims_by_vertices(s.base).faces.at({4, 5, 6, 7}), 2);
  const Shape plain = read_lattice(kCubeVerts + "v 0 0 2\nv 1 0 2\nv 1 1 2\nv 0 1 2\n"
                                                "hex 0 1 2 3 4 5 6 7\nhex 4 5 6 7 8 9 10 11\n",
                                   "g.lattice");
  EXPECT_EQ(dims_by_vertices(plain.base).faces.at({4, 5, 6, 7}), 3);
}

TEST(LatticeFormat, RefusesBadHeaders) {
  expect_error("", 0, "empty");
  expect_error("v 0 0 0\n", 1, "sublift-lattice 1");
  expect_error("sublift-lattice 2\n", 1, "unsupported .lattice version 2");
  expect_error("sublift-lattice one\n", 1, "sublift-lattice VERSION");
  expect_error("sublift-lattice 1\n", 0, "no vertices and no cells");
  expect_error(kCubeVerts, 0, "no cells");
}

TEST(LatticeFormat, UnclosedCellBlocksNameTheCellLine) {
  // EOF inside the block: the error names the `cell` line (10).
  expect_error(kCubeVerts + "cell\nf 0 3 2 1\nf 4 5 6 7\n", 10, "cell is not closed");
  // A new statement before `end`: still the cell's line, and it mentions the intruder's line.
  const std::string text = kCubeVerts + "cell\nf 0 3 2 1\nhex 0 1 2 3 4 5 6 7\n";
  expect_error(text, 10, "on line 12");
  expect_error(kCubeVerts + "f 0 1 2\n", 10, "'f' outside");
  expect_error(kCubeVerts + "end\n", 10, "'end' without a 'cell'");
}

TEST(LatticeFormat, OpenPolyhedronNamesTheCellLineAndEdge) {
  // Five faces of a cube: the top face is missing, so its 4 edges are used once.
  const std::string text = kCubeVerts + "hex 0 1 2 3 4 5 6 7\n"
                           "cell\nf 0 3 2 1\nf 0 1 5 4\nf 1 2 6 5\nf 2 3 7 6\nf 3 0 4 7\nend\n";
  std::size_t line = 0;
  const std::string e = error_of(text, &line);
  EXPECT_EQ(line, 11u) << e;
  EXPECT_NE(e.find("cell 1 is not closed"), std::string::npos) << e;
  EXPECT_NE(e.find("used by 1 of its faces"), std::string::npos) << e;
  expect_error(kCubeVerts + "cell\nf 0 1 2\nf 0 2 3\nend\n", 10, "has 2 faces");
}

TEST(LatticeFormat, RefusesDanglingAndMalformedIndices) {
  expect_error(kCubeVerts + "hex 0 1 2 3 4 5 6 8\n", 10, "names vertex 8, but the vertices are 0..7");
  expect_error(kCubeVerts + "hex 0 1 2 3 4 5 6\n", 10, "takes 8 vertex indices, got 7");
  expect_error(kCubeVerts + "tet 0 1 2 -3\n", 10, "out of range");
  expect_error(kCubeVerts + "pyramid 0 1 x 3 4\n", 10, "'x' is not a vertex index");
  expect_error(kCubeVerts + "cell\nf 0 1\nend\n", 11, "fewer than 3 vertices");
  expect_error(kCubeVerts + "cell\nf 0 1 2 1\nend\n", 11, "repeats vertex 1");
  expect_error(kCubeVerts + "cell\nf 0 3 2 1\nf 1 2 3 0\nend\n", 12, "same face twice");
}

TEST(LatticeFormat, RefusesBadNumbersAndStatements) {
  expect_error("sublift-lattice 1\nv 0 0 0\nv nan 0 0\n", 3, "'nan' is not a finite number");
  expect_error("sublift-lattice 1\nv 0 0 inf\n", 2, "not a finite number");
  expect_error("sublift-lattice 1\nv 0 0 1e31\n", 2, "magnitude");
  expect_error("sublift-lattice 1\nv 0 0\n", 2, "'v x y z'");
  expect_error(kCubeVerts + "hexa 0 1 2 3 4 5 6 7\n", 10, "unknown statement 'hexa'");
  expect_error(kCubeVerts + "cell extra\n", 10, "stands alone");
  std::string binary = kCubeVerts;
  binary += std::string("v 0 0 \x01\x02\n", 9);
  expect_error(binary, 10, "binary data");
}

TEST(LatticeFormat, RefusesTagsThatNameNothing) {
  const std::string cube = kCubeVerts + "hex 0 1 2 3 4 5 6 7\n";  // line 10
  expect_error(cube + "crease 0 6\n", 11, "share no edge");
  expect_error(cube + "crease 0\n", 11, "at least 2");
  expect_error(cube + "corner 8\n", 11, "out of range");
  expect_error(cube + "feature_face 0 1 2\n", 11, "no face of the shape");
  expect_error(cube + "feature_face 0 1\n", 11, "at least 3");
}

TEST(LatticeFormat, UnusedVertexIsReportedNotRefused) {
  const Shape s = read_lattice(kCubeVerts + "v 5 5 5\nhex 0 1 2 3 4 5 6 7\n", "u.lattice");
  ASSERT_EQ(s.report.warnings.size(), 1u);
  EXPECT_NE(s.report.warnings[0].what.find("used by no cell"), std::string::npos);
  EXPECT_EQ(s.report.warnings[0].first_lines, std::vector<std::size_t>{10});
}

TEST(LatticeFormat, WriteReadRoundTripIsExactWithFeatures) {
  TempDir dir("sublift_lattice_rt");
  const std::string text = kCubeVerts +
                           "v 0.1 0.2 2.3\nv 1 0 2\nv 1 1 2\nv 0 1 2\nv 0.5 0.5 3\n"  // 8-12
                           "hex 0 1 2 3 4 5 6 7\nhex 4 5 6 7 8 9 10 11\npyramid 8 9 10 11 12\n"
                           "feature_face 4 5 6 7\ncrease 0 1\ncorner 3\n";
  Shape s = read_lattice(text, "in.lattice");
  s.positions[0] = 1.0 / 3.0;
  s.positions[5] = -2.2250738585072014e-308;
  const std::string path = dir.file("out.lattice");
  write_lattice(path, s.base, s.positions);
  const Shape back = read_lattice(read_file_bytes(path), path);
  EXPECT_EQ(back.positions, s.positions);  // bit-exact (17 significant digits)
  EXPECT_EQ(back.base.num_cells(), 3u);
  EXPECT_EQ(dims_by_vertices(back.base), dims_by_vertices(s.base));
  const std::string written = read_file_bytes(path);
  EXPECT_NE(written.find("\nhex "), std::string::npos) << written;   // hexahedra stay hexahedra
  EXPECT_NE(written.find("\ncell\n"), std::string::npos) << written;  // the pyramid is a general cell
}

TEST(LatticeFormat, RefinedLevelRoundTripKeepsItsFeatureDims) {
  TempDir dir("sublift_lattice_refined");
  const Shape s = read_lattice(kCubeVerts + "v 0 0 2\nv 1 0 2\nv 1 1 2\nv 0 1 2\n"
                                            "hex 0 1 2 3 4 5 6 7\nhex 4 5 6 7 8 9 10 11\n"
                                            "feature_face 4 5 6 7\ncrease 0 1\ncorner 2\n",
                               "in.lattice");
  Complex fine = refine(refine(s.base));
  std::vector<double> xyz(3 * std::size_t(fine.num_vertices));
  for (std::size_t i = 0; i < xyz.size(); ++i) xyz[i] = double((i * 7919) % 1000) / 64.0;
  const std::string path = dir.file("fine.lattice");
  write_lattice(path, fine, xyz);
  const Shape back = read_lattice(read_file_bytes(path), path);
  EXPECT_EQ(back.positions, xyz);
  EXPECT_EQ(back.base.num_cells(), fine.num_cells());
  EXPECT_EQ(dims_by_vertices(back.base), dims_by_vertices(fine));
}

TEST(LatticeFormat, WriterRefusesNonVolumesAndKeepsOldFileOnFailure) {
  TempDir dir("sublift_lattice_w");
  Csr quad;
  quad.items = {0, 1, 2, 3};
  quad.offsets = {0, 4};
  const Complex surface = complex_from_polygons(4, quad);
  EXPECT_THROW(write_lattice(dir.file("s.lattice"), surface, std::vector<double>(12, 0.0)), InputError);
  const Shape s = read_lattice(kCubeVerts + "hex 0 1 2 3 4 5 6 7\n", "c.lattice");
  EXPECT_THROW(write_lattice("/nonexistent_dir/x.lattice", s.base, s.positions), IoError);
  EXPECT_THROW(write_lattice(dir.file("short.lattice"), s.base, std::vector<double>(3, 0.0)), InputError);
}

// Issue 18: lattices that make no solid. A cell listed twice and a face between three cells
// were accepted; now both are errors naming every cell involved.
TEST(LatticeFormat, RefusesCellsListedTwiceNamingBoth) {
  EXPECT_EQ(error_of(kCubeVerts + "hex 0 1 2 3 4 5 6 7\nhex 0 1 2 3 4 5 6 7\n"),
            "t.lattice:11: cell 1 (hexahedron) has the same vertices as cell 0 (hexahedron) on line 10: a cell listed twice");
  // The same solid again as a general cell, and in another vertex order: still the same cell.
  EXPECT_EQ(error_of(kCubeVerts + "hex 0 1 2 3 4 5 6 7\ncell\nf 0 3 2 1\nf 4 5 6 7\nf 0 1 5 4\nf 1 2 6 5\nf 2 3 7 6\nf 3 0 4 7\nend\n"),
            "t.lattice:11: cell 1 has the same vertices as cell 0 (hexahedron) on line 10: a cell listed twice");
}

TEST(LatticeFormat, RefusesAFaceSharedByThreeCells) {
  // Two pyramids on the cube's top face 4 5 6 7.
  const std::string text = kCubeVerts + "v 0.5 0.5 2\nv 0.5 0.5 3\nhex 0 1 2 3 4 5 6 7\npyramid 4 5 6 7 8\npyramid 4 5 6 7 9\n";
  EXPECT_EQ(error_of(text), "t.lattice:14: face 4 5 6 7 is shared by 3 cells: cell 0 (hexahedron) on line 12, cell 1 (pyramid) on "
                            "line 13, cell 2 (pyramid) on line 14 (a face of a solid bounds at most two cells)");
}

TEST(LatticeFormat, InconsistentlyOrientedCellsAreKeptWithAWarningNamingThem) {
  const std::string cube = "cell\nf 0 3 2 1\nf 4 5 6 7\nf 0 1 5 4\nf 1 2 6 5\nf 2 3 7 6\nf 3 0 4 7\nend\n";
  const Shape good = read_lattice(kCubeVerts + cube, "t.lattice");
  EXPECT_TRUE(good.report.empty()) << good.report.format("t.lattice");
  // The top face turned against the others.
  const Shape flipped = read_lattice(kCubeVerts + "cell\nf 0 3 2 1\nf 7 6 5 4\nf 0 1 5 4\nf 1 2 6 5\nf 2 3 7 6\nf 3 0 4 7\nend\n", "t.lattice");
  EXPECT_EQ(flipped.report.format("t.lattice"),
            "t.lattice: warning: 1 x cells whose faces are not consistently oriented (kept: Sublift orients cells from their "
            "geometry): cell 0 (line 10)\n");
  EXPECT_EQ(flipped.base.num_cells(), good.base.num_cells());
  EXPECT_EQ(flipped.base.faces.items.size(), good.base.faces.items.size());
  // Each cell consistent, but the second one inside out (its faces point in): their shared face
  // runs the same way in both.
  const std::string two = kCubeVerts + "v 0 0 2\nv 1 0 2\nv 1 1 2\nv 0 1 2\nhex 0 1 2 3 4 5 6 7\nhex 8 9 10 11 4 5 6 7\n";
  EXPECT_EQ(read_lattice(two, "t.lattice").report.format("t.lattice"),
            "t.lattice: warning: 2 x cells listing a shared face in the same direction as their neighbour (kept: Sublift "
            "orients cells from their geometry): cell 0 (hexahedron), cell 1 (hexahedron) (lines 14, 15)\n");
  EXPECT_TRUE(read_lattice(kCubeVerts + "v 0 0 2\nv 1 0 2\nv 1 1 2\nv 0 1 2\nhex 0 1 2 3 4 5 6 7\nhex 4 5 6 7 8 9 10 11\n", "t.lattice")
                  .report.empty());
}
