// Per-vertex attributes (issue 20, first slice): PLY colours and scalar properties and OBJ
// `v x y z r g b` colours are read as attributes, carried as channels of their own through
// subdivide, analyze and synthesize, and written back under their names where the format can
// hold them; what it cannot is named.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/base/file_io.h"
#include "core/io/lattice/shape_io.h"
#include "core/io/mesh/mesh_import.h"
#include "core/io/project/project_io.h"
#include "tests/cli_run.h"
#include "tests/io_test_util.h"

using namespace sublift;
using sublift::testing::input_error;
using sublift::testing::ProcessResult;
using sublift::testing::run_cli;
using sublift::testing::TempDir;

namespace {

// A square with a colour and a quality per corner (and normals, which are not kept).
const std::string kSquarePly =
    "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
    "property float nx\nproperty float ny\nproperty float nz\n"
    "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty float quality\n"
    "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
    "0 0 0 0 0 1 255 0 0 0.5\n1 0 0 0 0 1 0 255 0 0.25\n1 1 0 0 0 1 0 0 255 1\n0 1 0 0 0 1 255 255 255 0\n4 0 1 2 3\n";

const VertexAttribute* find(const std::vector<VertexAttribute>& a, const std::string& name) {
  for (const VertexAttribute& x : a)
    if (x.name == name) return &x;
  return nullptr;
}

void write_text(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

// kSquarePly as sq.ply in `dir`, subdivided `levels` times with the cubic scheme (fine.ply) and
// analysed into p.sublift: a project with x, y, z and the four attribute channels.
std::string coloured_project(const TempDir& dir, int levels) {
  write_text(dir.file("sq.ply"), kSquarePly);
  const std::string n = std::to_string(levels);
  EXPECT_EQ(run_cli({"subdivide", dir.file("sq.ply"), "--scheme", "cubic", "--levels", n, "-o", dir.file("fine.ply")}).exit_code, 0);
  EXPECT_EQ(run_cli({"analyze", dir.file("fine.ply"), "--base", dir.file("sq.ply"), "--scheme", "cubic", "--levels", n, "-o",
                     dir.file("p.sublift")}).exit_code, 0);
  return dir.file("p.sublift");
}

}  // namespace

TEST(Attributes, PlyScalarPropertiesAreKeptNormalsAreNot) {
  const Shape s = read_shape_from_memory("sq.ply", kSquarePly);
  ASSERT_EQ(s.attributes.size(), 4u);
  EXPECT_EQ(s.attributes[0].name, "red");
  EXPECT_EQ(s.attributes[0].type, "uchar");
  EXPECT_EQ(s.attributes[3].name, "quality");
  EXPECT_EQ(s.attributes[3].type, "float");
  EXPECT_EQ(s.attributes[1].values, (std::vector<double>{0, 255, 0, 255}));
  EXPECT_EQ(s.attributes[3].values, (std::vector<double>{0.5, 0.25, 1, 0}));
  const std::string not_kept = s.report.not_kept_summary();
  EXPECT_NE(not_kept.find("'nx'"), std::string::npos) << not_kept;
  EXPECT_EQ(not_kept.find("red"), std::string::npos) << not_kept;
  // Values a channel cannot hold are refused, naming the line.
  std::string bad = kSquarePly;
  bad.replace(bad.find("0.25"), 4, "1e31");
  EXPECT_NE(input_error([&] { read_shape_from_memory("bad.ply", bad); }).find("bad.ply:18: vertex property 'quality' of vertex 1 exceeds"),
            std::string::npos)
      << input_error([&] { read_shape_from_memory("bad.ply", bad); });
}

TEST(Attributes, ObjVertexColoursOnEveryVertexOrNamedAsNotKept) {
  const Shape s = read_shape_from_memory("c.obj", "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 0.5\nf 1 2 3\n");
  ASSERT_EQ(s.attributes.size(), 3u);
  EXPECT_EQ(s.attributes[2].name, "blue");
  EXPECT_EQ(s.attributes[2].values, (std::vector<double>{0, 0, 0.5}));
  const Shape some = read_shape_from_memory("c.obj", "v 0 0 0 1 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_TRUE(some.attributes.empty());
  EXPECT_NE(some.report.not_kept_summary().find("vertex colours (on 1 of 3 vertices"), std::string::npos)
      << some.report.not_kept_summary();
}

TEST(Attributes, WritersGiveBackWhatTheFormatHoldsAndNameTheRest) {
  TempDir dir("sublift_attr_write");
  const Shape s = read_shape_from_memory("sq.ply", kSquarePly);
  EXPECT_TRUE(write_shape(dir.file("a.ply"), s.base, s.positions, s.attributes).empty());
  const Shape ply = read_shape(dir.file("a.ply"));
  ASSERT_EQ(ply.attributes.size(), 4u);
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(ply.attributes[k].name, s.attributes[k].name);
    EXPECT_EQ(ply.attributes[k].type, s.attributes[k].type);
    EXPECT_EQ(ply.attributes[k].values, s.attributes[k].values);
  }
  // OBJ holds the colours (as 0..1), not the quality; OFF holds none. Both say so.
  const auto obj_notes = write_shape(dir.file("a.obj"), s.base, s.positions, s.attributes);
  ASSERT_EQ(obj_notes.size(), 1u);
  EXPECT_NE(obj_notes[0].find("cannot hold the vertex attributes quality"), std::string::npos) << obj_notes[0];
  const Shape obj = read_shape(dir.file("a.obj"));
  ASSERT_EQ(obj.attributes.size(), 3u);
  EXPECT_EQ(obj.attributes[0].values, (std::vector<double>{1, 0, 0, 1}));
  const auto off_notes = write_shape(dir.file("a.off"), s.base, s.positions, s.attributes);
  ASSERT_EQ(off_notes.size(), 1u);
  EXPECT_NE(off_notes[0].find(".off cannot hold the vertex attributes red, green, blue, quality"), std::string::npos) << off_notes[0];
}

TEST(Attributes, SubdivideCarriesThemAsChannels) {
  TempDir dir("sublift_attr_subdivide");
  write_text(dir.file("sq.ply"), kSquarePly);
  // Linear: the corners keep their values, edge and face points are the means (exact in binary).
  ProcessResult r = run_cli({"subdivide", dir.file("sq.ply"), "--scheme", "linear", "--levels", "1", "-o", dir.file("l.ply"), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Shape l = read_shape(dir.file("l.ply"));
  ASSERT_EQ(l.attributes.size(), 4u);
  const VertexAttribute& q = *find(l.attributes, "quality");
  ASSERT_EQ(q.values.size(), 9u);
  for (std::uint32_t v = 0; v < 4; ++v) EXPECT_EQ(q.values[v], (std::vector<double>{0.5, 0.25, 1, 0})[v]);
  double mean = 0;
  for (double x : q.values) mean += x;
  // Edge points: means of their ends; the face point: the mean of the corners. Their sum:
  // 4 corners (1.75) + edges (each corner in two: 1.75) + face (0.4375).
  EXPECT_DOUBLE_EQ(mean, 1.75 + 1.75 + 0.4375);
  const VertexAttribute& red = *find(l.attributes, "red");
  for (double x : red.values) EXPECT_EQ(x, std::round(x)) << "uchar written back as whole numbers";
  EXPECT_NE(r.out.find("\"quality\""), std::string::npos) << r.out;
}

TEST(Attributes, AnalyzeAndSynthesizeRoundTripTheChannels) {
  TempDir dir("sublift_attr_project");
  write_text(dir.file("sq.ply"), kSquarePly);
  ASSERT_EQ(run_cli({"subdivide", dir.file("sq.ply"), "--scheme", "cubic", "--levels", "2", "-o", dir.file("fine.ply")}).exit_code, 0);
  ProcessResult r = run_cli({"analyze", dir.file("fine.ply"), "--base", dir.file("sq.ply"), "--scheme", "cubic", "--levels", "2", "-o",
                             dir.file("p.sublift")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ProjectExtras x;
  const Hierarchy h = read_project(dir.file("p.sublift"), &x);
  EXPECT_EQ(h.channels, 7);
  ASSERT_EQ(x.attributes.size(), 4u);
  EXPECT_EQ(x.attributes[3].name, "quality");
  r = run_cli({"info", dir.file("p.sublift")});
  EXPECT_NE(r.out.find("channels:              x y z red green blue quality"), std::string::npos) << r.out;
  ASSERT_EQ(run_cli({"synthesize", dir.file("p.sublift"), "-o", dir.file("back.ply")}).exit_code, 0);
  EXPECT_EQ(read_file_bytes(dir.file("back.ply")), read_file_bytes(dir.file("fine.ply")));  // perfect reconstruction, names kept
  // A project whose names do not match its channels is refused on both sides.
  ProjectExtras wrong = x;
  wrong.attributes.pop_back();
  EXPECT_THROW(write_project(dir.file("w.sublift"), h, wrong), Error);
  std::string bytes = read_file_bytes(dir.file("p.sublift"));
  bytes.replace(bytes.find(",{\"name\":\"quality\",\"type\":\"float\"}"), 34, "");
  EXPECT_NE(input_error([&] { read_project_from_memory("p.sublift", bytes); }).find("3 attribute channels named for 7 channels"),
            std::string::npos);
}

// Edits move positions; the attributes stay (issue 20): `edit` on a project with colour and
// quality channels moves a base vertex, and every level's attribute values are what they were,
// bit for bit, in the project it writes and in the level it exports.
TEST(Attributes, EditsMovePositionsAndKeepTheAttributes) {
  TempDir dir("sublift_attr_edit");
  coloured_project(dir, 2);
  ProcessResult r = run_cli({"edit", dir.file("p.sublift"), "--level", "0", "--vertex", "2", "--delta", "0", "0", "0.5", "-o", dir.file("e.sublift")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ProjectExtras x, y;
  const Hierarchy before = read_project(dir.file("p.sublift"), &x), after = read_project(dir.file("e.sublift"), &y);
  ASSERT_EQ(after.channels, 7);
  EXPECT_EQ(y.attributes.size(), 4u);
  for (int l = 0; l <= 2; ++l) {
    const std::vector<double> a = synthesize(before, l), b = synthesize(after, l);
    bool moved = false;
    for (std::size_t v = 0; v < a.size() / 7; ++v)
      for (int k = 0; k < 7; ++k) {
        if (k >= 3) {
          EXPECT_EQ(b[7 * v + std::size_t(k)], a[7 * v + std::size_t(k)]) << "level " << l << " vertex " << v << " channel " << k;
        }
        moved = moved || b[7 * v + std::size_t(k)] != a[7 * v + std::size_t(k)];
      }
    EXPECT_TRUE(moved) << "level " << l;
  }
  // Written as a level, the attributes go with the moved positions.
  r = run_cli({"edit", dir.file("p.sublift"), "--level", "0", "--vertex", "2", "--delta", "0", "0", "0.5", "-o", dir.file("e.ply")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Shape fine = read_shape(dir.file("fine.ply")), edited = read_shape(dir.file("e.ply"));
  ASSERT_EQ(edited.attributes.size(), 4u);
  for (std::size_t k = 0; k < 4; ++k) EXPECT_EQ(edited.attributes[k].values, fine.attributes[k].values) << fine.attributes[k].name;
  EXPECT_NE(edited.positions, fine.positions);
}

// `set` keeps them too: a level of zero detail on --subdivide, the finest values through a crease
// change (analysed again on the new features), level L's values as the new base's on
// --delete-lower; the project's UVs follow --delete-lower as well.
TEST(Attributes, SetKeepsThemThroughSubdivideCreasesAndDeleteLower) {
  TempDir dir("sublift_attr_set");
  coloured_project(dir, 1);
  const Hierarchy p = read_project(dir.file("p.sublift"));
  const std::vector<double> p1 = synthesize(p, 1);
  ProcessResult r = run_cli({"set", dir.file("p.sublift"), "--subdivide", "1", "--crease", "0", "1", "-o", dir.file("s.sublift"), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("not kept"), std::string::npos) << r.err;
  ProjectExtras x;
  const Hierarchy s = read_project(dir.file("s.sublift"), &x);
  ASSERT_EQ(s.channels, 7);
  EXPECT_EQ(x.attributes.size(), 4u);
  EXPECT_EQ(s.levels[0].edge_dim[0], 1);  // the new crease
  // The finest values are kept through the crease change: those of the project subdivided alone.
  ASSERT_EQ(run_cli({"set", dir.file("p.sublift"), "--subdivide", "1", "-o", dir.file("e.sublift")}).exit_code, 0);
  const std::vector<double> s2 = synthesize(s, 2), e2 = synthesize(read_project(dir.file("e.sublift")), 2);
  ASSERT_EQ(s2.size(), e2.size());
  for (std::size_t v = 0; v < s2.size() / 7; ++v)
    for (int k = 3; k < 7; ++k) EXPECT_NEAR(s2[7 * v + std::size_t(k)], e2[7 * v + std::size_t(k)], 1e-9) << v << " " << k;
  r = run_cli({"set", dir.file("p.sublift"), "--delete-lower", "1", "-o", dir.file("d.sublift")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Hierarchy d = read_project(dir.file("d.sublift"));
  ASSERT_EQ(d.channels, 7);
  const std::vector<double> d0 = synthesize(d, 0);
  ASSERT_EQ(d0.size(), p1.size());
  for (std::size_t i = 0; i < d0.size(); ++i) EXPECT_NEAR(d0[i], p1[i], 1e-12) << i;
  // UVs: a textured quad's project keeps level 1's UVs as the new base's.
  write_text(dir.file("q.obj"), "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3 4/4\n");
  ASSERT_EQ(run_cli({"subdivide", dir.file("q.obj"), "--scheme", "cubic", "--levels", "1", "-o", dir.file("q1.obj")}).exit_code, 0);
  ASSERT_EQ(run_cli({"analyze", dir.file("q1.obj"), "--base", dir.file("q.obj"), "--scheme", "cubic", "--levels", "1", "-o",
                     dir.file("q.sublift")}).exit_code, 0);
  r = run_cli({"set", dir.file("q.sublift"), "--delete-lower", "1", "-o", dir.file("q0.sublift")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ProjectExtras qx;
  read_project(dir.file("q0.sublift"), &qx);
  const Shape q1 = read_shape(dir.file("q1.obj"));
  EXPECT_EQ(qx.uv.points, q1.uv.points);
  EXPECT_EQ(qx.uv.corners, q1.uv.corners);
}

// A lattice's material values (VTK POINT_DATA, OVM vertex properties) are channels like a
// surface's: linear subdivision gives the cell centre the mean of its 8 corners, analyze and
// synthesize give the finest level back, and .ovm carries them as well; .lattice names them.
TEST(Attributes, LatticeMaterialValuesAreChannels) {
  TempDir dir("sublift_attr_lattice");
  write_text(dir.file("cell.vtk"),
             "# vtk DataFile Version 3.0\ncell\nASCII\nDATASET UNSTRUCTURED_GRID\n"
             "POINTS 8 double\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
             "CELLS 1 9\n8 0 1 2 3 4 5 6 7\nCELL_TYPES 1\n12\n"
             "POINT_DATA 8\nSCALARS density double 1\nLOOKUP_TABLE default\n1 2 3 4 5 6 7 8\n");
  ProcessResult r = run_cli({"subdivide", dir.file("cell.vtk"), "--scheme", "linear", "--levels", "1", "-o", dir.file("fine.vtk")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Shape fine = read_shape(dir.file("fine.vtk"));
  ASSERT_EQ(fine.attributes.size(), 1u);
  EXPECT_EQ(fine.attributes[0].name, "density");
  ASSERT_EQ(fine.attributes[0].values.size(), 27u);
  EXPECT_EQ(fine.attributes[0].values.back(), 4.5);  // the cell vertex, last in [v | e | f | c]
  r = run_cli({"subdivide", dir.file("cell.vtk"), "--scheme", "cubic", "--levels", "2", "-o", dir.file("cubic.vtk")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_cli({"analyze", dir.file("cubic.vtk"), "--base", dir.file("cell.vtk"), "--scheme", "cubic", "--levels", "2", "-o", dir.file("p.sublift")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_EQ(read_project(dir.file("p.sublift")).channels, 4);
  ASSERT_EQ(run_cli({"synthesize", dir.file("p.sublift"), "-o", dir.file("back.vtk")}).exit_code, 0);
  EXPECT_EQ(read_file_bytes(dir.file("back.vtk")), read_file_bytes(dir.file("cubic.vtk")));
  r = run_cli({"convert", dir.file("cell.vtk"), "-o", dir.file("cell.ovm")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_shape(dir.file("cell.ovm")).attributes.at(0).values, (std::vector<double>{1, 2, 3, 4, 5, 6, 7, 8}));
  r = run_cli({"convert", dir.file("cell.vtk"), "-o", dir.file("cell.lattice")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find(".lattice cannot hold the vertex attributes density: not written (use .vtk or .ovm)"), std::string::npos) << r.err;
}

// Issue 20: a glTF opens as a surface: its triangles in world space, welded where the file split
// them at seams, what it does not keep named.
TEST(GltfSurface, SharedBoxesOpenWeldedAndClosed) {
  const std::filesystem::path data(SUBLIFT_SHARED_DATA);
  const std::filesystem::path box = data / "gltf/Box/Box.glb", textured = data / "gltf/BoxTextured/BoxTextured.gltf";
  if (!std::filesystem::exists(box)) GTEST_SKIP() << box << " not found (../shared/data is absent)";
  for (const auto& f : {box, textured, data / "gltf/BoxVertexColors/BoxVertexColors.glb"}) {
    SCOPED_TRACE(f.string());
    const Shape s = read_shape(f.string());
    // 24 vertices (4 per face: one per normal) weld into the cube's 8 corners; 12 triangles.
    EXPECT_EQ(s.base.dim, 2);
    EXPECT_EQ(s.base.num_vertices, 8u);
    EXPECT_EQ(s.base.num_faces(), 12u);
    EXPECT_EQ(s.base.num_edges(), 18u);  // closed: V - E + F = 2
    const std::string r = s.report.format(f.string());
    EXPECT_NE(r.find("welded by position: 24 into 8"), std::string::npos) << r;
    // BoxVertexColors' COLOR_0 is kept as channels (gltf_colours_test.cpp), the UVs of both
    // textured boxes and BoxTextured's texture too (uv_test.cpp); the rest is named.
    const bool coloured = f.filename() == "BoxVertexColors.glb", textured_box = f == textured;
    EXPECT_EQ(s.attributes.size(), coloured ? 4u : 0u);
    EXPECT_EQ(s.uv.empty(), !coloured && !textured_box);
    const std::string lost = coloured ? "without their normals, materials or nodes"
                             : textured_box ? "without their normals, colours or nodes"
                                            : "without their normals, UVs, colours, materials or nodes";
    EXPECT_NE(s.report.not_kept_summary().find(lost), std::string::npos) << s.report.not_kept_summary();
  }
  // Subdivided from the CLI like any mesh (the limit of a closed cube: no boundary).
  TempDir dir("sublift_gltf_surface");
  const ProcessResult r = run_cli({"subdivide", box.string(), "--scheme", "loop", "--levels", "2", "-o", dir.file("box.obj"), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_shape(dir.file("box.obj")).base.num_vertices, 8u + 18u + 72u);  // V + E at each level: 8, 26, 98
  EXPECT_NE(input_error([&] { read_shape_from_memory("m.gltf", "{}"); }).find("read from its file"), std::string::npos);
  const std::filesystem::path bad = data / "gltf/invalid/IndexOutOfRange.gltf";
  EXPECT_NE(input_error([&] { read_shape(bad.string()); }), "") << "a bad glTF is refused as by the FFD importer";
}
