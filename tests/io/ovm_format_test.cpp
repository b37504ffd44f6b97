// OpenVolumeMesh's ASCII .ovm (issue 20): the shared samples from DiamondLaplace and
// OpenVolumeMesh's own test files, exact round trips, inward half-faces (OpenVolumeMesh's
// convention) checked by a parser of the test's own, property blocks named as not kept, and every kind of bad file naming its line.
#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <sstream>

#include "core/base/file_io.h"
#include "core/complex/refine.h"
#include "core/io/lattice/lattice_format.h"
#include "core/io/lattice/ovm_format.h"
#include "core/io/lattice/shape_io.h"
#include "tests/io_test_util.h"

using namespace sublift;
using sublift::testing::dims_by_vertices;
using sublift::testing::input_error;
using sublift::testing::TempDir;

namespace {

// One unit cube as OpenVolumeMesh writes it, every half-face pointing into the cell: bottom face 0
// runs 0-1-2-3 (normal +z, inward) and is taken as it is (half-face 0); the other five faces
// point out and are taken reversed (odd half-faces).
const std::string kCube =
    "OVM ASCII\n"
    "Vertices\n8\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"    // lines 2-11: vertices on 4-11
    "Edges\n12\n0 1\n1 2\n2 3\n3 0\n4 5\n5 6\n6 7\n7 4\n0 4\n1 5\n2 6\n3 7\n"  // lines 12-25
    "Faces\n6\n"                                                                 // lines 26-27
    "4 0 2 4 6\n"     // 0-1-2-3 (up)
    "4 8 10 12 14\n"  // 4-5-6-7 (up: outward for the top)
    "4 0 18 9 17\n"   // 0-1-5-4 (front, -y)
    "4 2 20 11 19\n"  // 1-2-6-5 (+x)
    "4 4 22 13 21\n"  // 2-3-7-6 (+y)
    "4 6 16 15 23\n"  // 3-0-4-7 (-x); lines 28-33
    "Polyhedra\n1\n6 0 3 5 7 9 11\n";  // lines 34-36

std::string error_of(const std::string& text, std::size_t* line = nullptr) {
  return input_error([&] { read_ovm(text, "t.ovm"); }, line);
}

// Expects an InputError on `line` whose message names the file and contains `needle`.
void expect_error(const std::string& text, std::size_t line, const std::string& needle) {
  sublift::testing::expect_input_error([](const std::string& t, const std::string& f) { read_ovm(t, f); }, text, "t.ovm", line, needle);
}

std::string replace(std::string s, const std::string& from, const std::string& to) {
  const std::size_t at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return s.replace(at, from.size(), to);
}

// Volumes of the cells of an .ovm text, parsed here on its own (no Sublift reader), signed so
// that they are positive when every half-face points into its cell by the right-hand rule.
std::vector<double> inward_volumes(const std::string& text) {
  std::istringstream in(text);
  std::string word;
  std::size_t n = 0;
  in >> word >> word >> word >> n;  // OVM ASCII Vertices n
  std::vector<std::array<double, 3>> p(n);
  for (auto& x : p) in >> x[0] >> x[1] >> x[2];
  in >> word >> n;
  std::vector<std::array<std::size_t, 2>> e(n);
  for (auto& x : e) in >> x[0] >> x[1];
  in >> word >> n;
  std::vector<std::vector<std::size_t>> faces(n);
  for (auto& f : faces) {
    std::size_t d = 0, h = 0;
    in >> d;
    for (std::size_t i = 0; i < d; ++i) {
      in >> h;
      f.push_back(e[h / 2][h % 2]);  // the half-edge's start
    }
  }
  in >> word >> n;
  std::vector<double> vol(n, 0.0);
  for (double& v : vol) {
    std::size_t d = 0, hf = 0;
    in >> d;
    for (std::size_t i = 0; i < d; ++i) {
      in >> hf;
      std::vector<std::size_t> loop = faces[hf / 2];
      if (hf % 2) std::reverse(loop.begin(), loop.end());
      for (std::size_t k = 1; k + 1 < loop.size(); ++k) {
        const auto &a = p[loop[0]], &b = p[loop[k]], &c = p[loop[k + 1]];
        v -= (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0])) / 6.0;
      }
    }
  }
  return vol;
}

std::filesystem::path shared(const std::string& rel) { return std::filesystem::path(SUBLIFT_SHARED_DATA) / rel; }

}  // namespace

TEST(OvmFormat, ReadsAUnitCube) {
  const Shape s = read_ovm(kCube, "t.ovm");
  EXPECT_EQ(s.base.dim, 3);
  EXPECT_EQ(s.base.num_vertices, 8u);
  EXPECT_EQ(s.base.num_edges(), 12u);
  EXPECT_EQ(s.base.num_faces(), 6u);
  EXPECT_EQ(s.base.num_cells(), 1u);
  EXPECT_EQ(s.positions[3 * 6 + 2], 1.0);
  EXPECT_TRUE(s.report.empty()) << s.report.format("t.ovm");
  EXPECT_NEAR(inward_volumes(kCube).at(0), 1.0, 1e-15);  // the test's parser agrees the half-faces point in
}

TEST(OvmFormat, TheSameCubeAsALatticeHasTheSameComplex) {
  const Shape ovm = read_ovm(kCube, "t.ovm");
  const Shape lat = read_lattice("sublift-lattice 1\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                                 "hex 0 1 2 3 4 5 6 7\n",
                                 "t.lattice");
  EXPECT_EQ(dims_by_vertices(ovm.base), dims_by_vertices(lat.base));
  EXPECT_EQ(ovm.positions, lat.positions);
}

TEST(OvmFormat, HeaderlessFilesAndCommentsAndCaseAreAccepted) {
  const Shape s = read_ovm(replace(replace(kCube, "OVM ASCII\nVertices\n", "VERTICES # OpenVolumeMesh reads this too\n"),
                                   "Polyhedra", "polyhedra"),
                           "t.ovm");
  EXPECT_EQ(s.base.num_cells(), 1u);
  EXPECT_NE(s.report.format("t.ovm").find("no 'OVM ASCII' header line"), std::string::npos) << s.report.format("t.ovm");
  EXPECT_EQ(read_ovm(replace(kCube, "OVM ASCII", "OVM"), "t.ovm").base.num_cells(), 1u);  // NonManifold.ovm's header
}

// A vertex property of one number per vertex is a material value, kept as an attribute channel
// (issue 20); other blocks are named as not kept.
TEST(OvmFormat, VertexPropertiesAreChannelsOtherBlocksAreNamedAsNotKept) {
  std::string text = kCube + "vprop double \"density of the foam\"\n";
  for (int v = 0; v < 8; ++v) text += std::to_string(v) + ".5\n";
  text += "cprop int \"material\"\n7\nvprop vec3d \"flow\"\n";
  for (int v = 0; v < 8; ++v) text += "1 2 3\n";
  const Shape s = read_ovm(text, "t.ovm");
  EXPECT_EQ(s.base.num_cells(), 1u);
  ASSERT_EQ(s.attributes.size(), 1u);
  EXPECT_EQ(s.attributes[0].name, "density of the foam");
  EXPECT_EQ(s.attributes[0].values, (std::vector<double>{0.5, 1.5, 2.5, 3.5, 4.5, 5.5, 6.5, 7.5}));
  EXPECT_EQ(s.report.not_kept_summary(), "1 cell property \"material\" (int), 1 vertex property \"flow\" (vec3d)");
  expect_error(kCube + "vprop double \"d\"\n1\n2 3\n", 39, "vertex property \"d\": value 1 is not one finite number");
  expect_error(kCube + "vprop double \"d\"\n1\n2\n", 37, "vertex property \"d\" needs 8 values; the file ends after 2");
  expect_error(kCube + "vprop double d\n", 37, "a property's name is written in double quotes");
  expect_error(kCube + "Junk here\n", 37, "expected a property block");
}

TEST(OvmFormat, RefusesBadHeadersAndSections) {
  expect_error("", 0, "the file ends before its 'OVM ASCII' header");
  expect_error("PLY\n", 1, "not an OpenVolumeMesh file");
  expect_error(replace(kCube, "OVM ASCII", "OVM BINARY"), 1, "binary .ovm files are not supported");
  expect_error(replace(kCube, "Edges\n", "Edgez\n"), 12, "expected the 'Edges' section, found 'Edgez'");
  expect_error(replace(kCube, "Faces\n6\n", "Faces\nsix\n"), 27, "the faces count must be one non-negative integer");
  expect_error(kCube.substr(0, kCube.find("Polyhedra")), 33, "the file ends before its 'Polyhedra' section");
}

TEST(OvmFormat, CountsThatCannotFitAreRefusedBeforeAnythingIsReserved) {
  expect_error("OVM ASCII\nVertices\n4000000000\n0 0 0\n", 3, "4000000000 vertices cannot fit in the 6 bytes left in the file");
  expect_error(replace(kCube, "Polyhedra\n1\n", "Polyhedra\n999999999999\n"), 35, "999999999999 polyhedra cannot fit");
}

TEST(OvmFormat, RefusesMalformedRecordsNamingTheirLines) {
  expect_error(replace(kCube, "1 1 0\n", "1 1\n"), 6, "a vertex line is 'x y z'");
  expect_error(replace(kCube, "1 1 0\n", "1 nan 0\n"), 6, "'nan' is not a finite number");
  expect_error(replace(kCube, "1 1 0\n", "1 1e31 0\n"), 6, "exceeds the supported magnitude");
  expect_error(replace(kCube, "12\n0 1\n", "12\n0 8\n"), 14, "vertex index 8 out of range (0..7)");
  expect_error(replace(kCube, "12\n0 1\n", "12\n1 1\n"), 14, "edge 0 joins vertex 1 to itself");
  expect_error(replace(kCube, "4 0 2 4 6\n", "4 0 2 4\n"), 28, "face 0 says 4 half-edges and lists 3");
  expect_error(replace(kCube, "4 0 2 4 6\n", "2 0 2\n"), 28, "at least 3");
  expect_error(replace(kCube, "4 0 2 4 6\n", "4 0 2 4 24\n"), 28, "half-edge index 24 out of range (0..23)");
  expect_error(replace(kCube, "4 0 2 4 6\n", "4 0 2 6 4\n"), 28,
               "face 0: its half-edges do not form a loop (half-edge 2 ends at vertex 2, the next, 6, starts at vertex 3)");
  expect_error(replace(kCube, "6 0 3 5 7 9 11\n", "6 0 3 5 7 9 12\n"), 36, "half-face index 12 out of range (0..11)");
  expect_error(replace(kCube, "6 0 3 5 7 9 11\n", "3 1 2 4\n"), 36, "at least 4");
  // Only five of the cube's six faces: the builder names the open cell.
  const std::string e = error_of(replace(kCube, "6 0 3 5 7 9 11\n", "5 0 3 5 7 9\n"));
  EXPECT_NE(e.find("cell 0"), std::string::npos) << e;
  EXPECT_NE(e.find("t.ovm:36"), std::string::npos) << e;
}

TEST(OvmFormat, WriteReadRoundTripIsExactWithInwardHalfFaces) {
  TempDir dir("sublift_ovm_rt");
  // Two cubes and a pyramid on top, refined once: shared faces between cells, general cells.
  const Shape s = read_lattice("sublift-lattice 1\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                               "v 0 0 2\nv 1 0 2\nv 1 1 2\nv 0 1 2\nv 0.5 0.5 3\n"
                               "hex 0 1 2 3 4 5 6 7\nhex 4 5 6 7 8 9 10 11\npyramid 8 9 10 11 12\n",
                               "in.lattice");
  const Complex fine = refine(s.base);
  const std::vector<double> xyz = sublift::testing::awkward_positions(fine.num_vertices, 5);
  const std::string path = dir.file("fine.ovm");
  const std::vector<double> base_xyz = s.positions;
  write_ovm(dir.file("base.ovm"), s.base, base_xyz);
  const std::string base_text = read_file_bytes(dir.file("base.ovm"));
  for (double v : inward_volumes(base_text)) EXPECT_GT(v, 0.0) << base_text;
  const Shape back = read_ovm(base_text, "base.ovm");
  EXPECT_EQ(back.positions, base_xyz);
  EXPECT_EQ(dims_by_vertices(back.base), dims_by_vertices(s.base));
  EXPECT_TRUE(back.report.empty()) << back.report.format("base.ovm");
  // Bit-exact positions at 17 digits, and the refined complex's faces and cells.
  write_ovm(path, fine, xyz);
  const Shape fine_back = read_ovm(read_file_bytes(path), path);
  EXPECT_EQ(fine_back.positions, xyz);
  EXPECT_EQ(fine_back.base.num_cells(), fine.num_cells());
  EXPECT_EQ(fine_back.base.num_faces(), fine.num_faces());
  EXPECT_EQ(fine_back.base.num_edges(), fine.num_edges());
}

TEST(OvmFormat, WriterRefusesNonVolumesAndShapeIoKnowsTheFormat) {
  TempDir dir("sublift_ovm_w");
  const Shape s = read_ovm(kCube, "t.ovm");
  EXPECT_THROW(write_ovm("/nonexistent_dir/x.ovm", s.base, s.positions), IoError);
  EXPECT_THROW(write_ovm(dir.file("short.ovm"), s.base, std::vector<double>(3, 0.0)), InputError);
  EXPECT_EQ(shape_output_problem("x.ovm", 2), "a .ovm holds volumes; write this surface as .obj or .vtk");
  EXPECT_EQ(shape_output_problem("x.ovm", 3), "");
  // Through write_shape/read_shape by extension; feature tags cannot be kept and are named.
  const Shape tagged = read_lattice("sublift-lattice 1\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                                    "hex 0 1 2 3 4 5 6 7\ncorner 0\n",
                                    "t.lattice");
  const auto notes = write_shape(dir.file("tagged.ovm"), tagged.base, tagged.positions);
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find(".ovm cannot hold feature tags: 0 feature faces, 0 crease edges and 1 corners not written"),
            std::string::npos)
      << notes[0];
  EXPECT_EQ(read_shape(dir.file("tagged.ovm")).base.num_cells(), 1u);
}

TEST(OvmFormat, SharedSamplesLoadWithTheManifestsCounts) {
  struct Sample {
    const char* file;
    std::uint32_t vertices, edges, faces, cells;
  };
  // MANIFEST.md's "OVM: V, E, F, cells" column.
  const Sample samples[] = {{"lattices/ovm/cube_hexahedron_1.ovm", 27, 54, 36, 8},
                            {"lattices/ovm/cube_hexahedron_2.ovm", 125, 300, 240, 64},
                            {"lattices/ovm/cube_pyramids_1.ovm", 21, 60, 54, 14},
                            {"lattices/ovm/cube_tetrahedron_1.ovm", 15, 50, 60, 24},
                            {"lattices/ovm/cube_truncated_1.ovm", 20, 48, 38, 9}};
  for (const Sample& m : samples) {
    const auto f = shared(m.file);
    if (!std::filesystem::exists(f)) GTEST_SKIP() << f << " not found (../shared/data is absent)";
    const std::string text = read_file_bytes(f.string());
    const Shape s = read_ovm(text, f.string());
    EXPECT_EQ(s.base.num_vertices, m.vertices) << m.file;
    EXPECT_EQ(s.base.num_edges(), m.edges) << m.file;
    EXPECT_EQ(s.base.num_faces(), m.faces) << m.file;
    EXPECT_EQ(s.base.num_cells(), m.cells) << m.file;
    EXPECT_TRUE(s.report.empty()) << s.report.format(f.string());
    for (double v : inward_volumes(text)) EXPECT_GT(v, 0.0) << m.file << ": OpenVolumeMesh writes half-faces that point in";
    // Written back by Sublift: the same cells, still outward, positions exact.
    TempDir dir("sublift_ovm_shared");
    write_ovm(dir.file("x.ovm"), s.base, s.positions);
    const std::string again = read_file_bytes(dir.file("x.ovm"));
    for (double v : inward_volumes(again)) EXPECT_GT(v, 0.0) << m.file;
    const Shape back = read_ovm(again, "x.ovm");
    EXPECT_EQ(back.positions, s.positions) << m.file;
    EXPECT_EQ(dims_by_vertices(back.base), dims_by_vertices(s.base)) << m.file;
  }
}

TEST(OvmFormat, OpenVolumeMeshsNonManifoldSampleReportsWhatNoCellUses) {
  const auto f = shared("lattices/ovm/NonManifold.ovm");
  if (!std::filesystem::exists(f)) GTEST_SKIP() << f << " not found (../shared/data is absent)";
  const Shape s = read_ovm(read_file_bytes(f.string()), f.string());
  EXPECT_EQ(s.base.num_cells(), 2u);
  const std::string r = s.report.format(f.string());
  // MANIFEST.md: "1 faces and 3 vertices belong to no cell".
  EXPECT_NE(r.find("1 x faces that belong to no polyhedron (ignored)"), std::string::npos) << r;
  EXPECT_NE(r.find("3 x"), std::string::npos) << r;
}

TEST(OvmFormat, BadInputCorpus) {
  const auto open = shared("bad_inputs/lattice_cell_not_closed.ovm");
  if (!std::filesystem::exists(open)) GTEST_SKIP() << open << " not found (../shared/data is absent)";
  std::size_t line = 0;
  const std::string e = input_error([&] { read_ovm(read_file_bytes(open.string()), open.string()); }, &line);
  EXPECT_NE(e.find("cell 0"), std::string::npos) << e;
  EXPECT_GT(line, 0u) << e;
  // Half-faces pointing every which way: kept, and the warning names the cell.
  const auto flipped = shared("bad_inputs/lattice_inconsistent_face_orientation.ovm");
  const Shape s = read_ovm(read_file_bytes(flipped.string()), flipped.string());
  EXPECT_EQ(s.base.num_cells(), 1u);
  EXPECT_NE(s.report.format(flipped.string()).find("not consistently oriented"), std::string::npos)
      << s.report.format(flipped.string());
}
