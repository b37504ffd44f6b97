// The modeler keeps what a model carries beside its positions (issue 20), on ModelerState without
// a window. UVs: every level's are the base's refined (uv_at_level), saved in the project and back
// on reopening, written with exported levels (and the glTF texture with them), carried to the new
// base by Delete Lower and back by undo, named when a scheme cannot carry them. Attribute
// channels: kept beside the session through drags, saves, exports and Subdivide.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "app/modeler/modeler_state.h"
#include "core/base/errors.h"
#include "core/base/file_io.h"
#include "core/io/lattice/shape_io.h"
#include "core/io/project/project_io.h"
#include "core/multires/level_uv.h"
#include "tests/cli_run.h"
#include "tests/io_test_util.h"

namespace sublift {
namespace {

namespace fs = std::filesystem;

// A cube whose six faces each map the whole texture (seams on every edge).
constexpr char kCubeObj[] =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
    "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
    "f 1/1 4/2 3/3 2/4\nf 5/1 6/2 7/3 8/4\nf 1/1 2/2 6/3 5/4\nf 2/1 3/2 7/3 6/4\nf 3/1 4/2 8/3 7/4\nf 4/1 1/2 5/3 8/4\n";

// A square with a colour and a quality per corner.
constexpr char kColouredSquarePly[] =
    "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
    "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty float quality\n"
    "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
    "0 0 0 255 0 0 0.5\n1 0 0 0 255 0 0.25\n1 1 0 0 0 255 1\n0 1 0 255 255 255 0\n4 0 1 2 3\n";

void expect_same(const FaceVaryingUV& a, const FaceVaryingUV& b, const std::string& what) {
  EXPECT_EQ(a.points, b.points) << what;
  EXPECT_EQ(a.corners, b.corners) << what;
}

TEST(ModelerUv, SavedExportedAndCarriedByDeleteLower) {
  testing::TempDir dir("sublift_modeler_uv");
  { std::ofstream(dir.file("cube.obj")) << kCubeObj; }
  const Shape cube = read_shape(dir.file("cube.obj"));
  ModelerState m;
  m.open(dir.file("cube.obj"), 2, Scheme::Cubic);
  expect_same(m.level_uv(0), cube.uv, "level 0 is the file's");
  const FaceVaryingUV l1 = uv_at_level(m.session().hierarchy(), cube.uv, 1), l2 = uv_at_level(m.session().hierarchy(), cube.uv, 2);
  expect_same(m.level_uv(2), l2, "level 2");

  // Saved with the project, back on reopening.
  m.save_project(dir.file("cube.sublift"));
  ProjectExtras extras;
  read_project(dir.file("cube.sublift"), &extras);
  expect_same(extras.uv, cube.uv, "the project's header");
  ModelerState again;
  again.open(dir.file("cube.sublift"));
  expect_same(again.level_uv(1), l1, "reopened project, level 1");

  // Exported nets carry their level's UVs.
  m.set_level(1);
  m.export_shape(dir.file("net1.obj"), false);
  expect_same(read_shape(dir.file("net1.obj")).uv, l1, "exported level 1");
  // The limit with its UVs to .obj; .ply has no place for them and says so.
  m.export_shape(dir.file("limit.obj"), true);
  expect_same(read_shape(dir.file("limit.obj")).uv, l2, "the exported limit");
  const std::vector<std::string> ply = m.export_shape(dir.file("limit.ply"), true);
  ASSERT_EQ(ply.size(), 1u);
  EXPECT_EQ(ply[0], "texture coordinates not written: .ply has none (use .obj, .gltf or .glb)");

  // Delete Lower: level 1's UVs become the base's; undo brings the old base and its UVs back.
  m.delete_lower_levels();
  expect_same(m.level_uv(0), l1, "the new base");
  expect_same(m.level_uv(1), l2, "the new level 1");
  ASSERT_TRUE(m.undo());
  expect_same(m.level_uv(0), cube.uv, "undone");

  // sqrt2 cannot carry them: said, and nothing saved.
  m.set_scheme(Scheme::Sqrt2);
  EXPECT_TRUE(m.level_uv(0).empty());
  bool said = false;
  for (const std::string& w : m.import_warnings()) said = said || w.find("sqrt2 cannot carry texture coordinates") != std::string::npos;
  EXPECT_TRUE(said);
  m.save_project(dir.file("sqrt2.sublift"));
  ProjectExtras s2;
  read_project(dir.file("sqrt2.sublift"), &s2);
  EXPECT_TRUE(s2.uv.empty());
}

TEST(ModelerUv, ATexturedGltfExportsWithItsTexture) {
  const fs::path box = fs::path(SUBLIFT_SHARED_DATA) / "gltf" / "BoxTextured" / "BoxTextured.glb";
  if (!fs::exists(box)) GTEST_SKIP() << box << " not found (../shared/data absent)";
  testing::TempDir dir("sublift_modeler_uv_gltf");
  ModelerState m;
  m.open(box.string(), 1, Scheme::Loop);
  m.export_shape(dir.file("net.glb"), false);  // level 0's net
  const Shape in = read_shape(box.string()), out = read_shape(dir.file("net.glb"));
  EXPECT_EQ(out.texture.bytes, in.texture.bytes);
  ASSERT_EQ(out.uv.corners.size(), in.uv.corners.size());
  for (std::size_t k = 0; k < in.uv.corners.size(); ++k)
    for (int c = 0; c < 2; ++c)
      EXPECT_EQ(out.uv.points[2 * out.uv.corners[k] + c], in.uv.points[2 * in.uv.corners[k] + c]) << "corner " << k;
  // A saved project keeps the UVs but not the image, and says so.
  bool said = false;
  for (const std::string& w : m.import_warnings()) said = said || w.find("the texture image") != std::string::npos;
  EXPECT_TRUE(said);
}

// A PLY's colours and quality open as channels beside the session: a drag moves the positions,
// the saved project keeps every attribute value as the file's subdivision has it, an exported
// net carries them, and a Subdivide afterwards gives them a level of zero detail.
TEST(ModelerAttributes, KeptThroughEditsSavesAndExports) {
  testing::TempDir dir("sublift_modeler_attributes");
  {
    std::ofstream(dir.file("sq.ply")) << kColouredSquarePly;
  }
  ModelerState m;
  m.open(dir.file("sq.ply"), 2, Scheme::Cubic);
  for (const std::string& w : m.import_warnings()) EXPECT_EQ(w.find("vertex attributes"), std::string::npos) << w;
  m.set_level(0);
  m.set_selection({2});
  m.begin_drag("Move");
  const double d[3] = {0, 0, 0.5};
  m.drag_to(d);
  m.end_drag();
  m.save_project(dir.file("sq.sublift"));
  ProjectExtras x;
  const Hierarchy saved = read_project(dir.file("sq.sublift"), &x);
  ASSERT_EQ(saved.channels, 7);
  ASSERT_EQ(x.attributes.size(), 4u);
  EXPECT_EQ(x.attributes[0].name, "red");
  // The attributes as the file's base subdivided gives them (positions moved, colours not); the
  // PLY `subdivide` writes rounds the uchar channels, so within half a unit of it, exactly the
  // float quality.
  ASSERT_EQ(testing::run_cli({"subdivide", dir.file("sq.ply"), "--scheme", "cubic", "--levels", "2", "-o", dir.file("fine.ply")}).exit_code, 0);
  const Shape fine = read_shape(dir.file("fine.ply"));
  const std::vector<double> values = synthesize(saved, 2);
  for (std::size_t k = 0; k < 4; ++k)
    for (std::size_t v = 0; v < fine.attributes[k].values.size(); ++v) {
      if (k < 3)
        EXPECT_EQ(std::round(values[7 * v + 3 + k]), fine.attributes[k].values[v]) << x.attributes[k].name << " of " << v;
      else
        EXPECT_EQ(float(values[7 * v + 3 + k]), float(fine.attributes[k].values[v])) << "quality of " << v;
    }
  EXPECT_NE(values[7 * 2 + 2], fine.positions[3 * 2 + 2]);  // the drag moved vertex 2
  // An exported net carries its level's attributes.
  m.set_level(1);
  m.export_shape(dir.file("net1.ply"), false);
  // The limit to .obj names the attributes it has no place for.
  const std::vector<std::string> limit = m.export_shape(dir.file("limit.obj"), true);
  ASSERT_EQ(limit.size(), 1u);
  EXPECT_EQ(limit[0], "vertex attributes red, green, blue, quality not written: .obj with normals has no place for them (use .gltf or .glb)");
  const Shape net = read_shape(dir.file("net1.ply"));
  ASSERT_EQ(net.attributes.size(), 4u);
  const std::vector<double> l1 = synthesize(saved, 1);
  for (std::size_t v = 0; v < net.attributes[0].values.size(); ++v) EXPECT_EQ(net.attributes[0].values[v], std::round(l1[7 * v + 3])) << v;
  // Subdivide: a level of zero detail for the attributes too.
  m.subdivide();
  m.save_project(dir.file("sq3.sublift"));
  const Hierarchy three = read_project(dir.file("sq3.sublift"));
  ASSERT_EQ(three.channels, 7);
  ASSERT_EQ(three.finest_level(), 3);
  // Delete Lower: level 1's attribute net is the new base's; undo brings the old base's back.
  m.set_level(1);
  m.delete_lower_levels();
  m.save_project(dir.file("lower.sublift"));
  const Hierarchy lower = read_project(dir.file("lower.sublift"));
  ASSERT_EQ(lower.channels, 7);
  const std::vector<double> base = synthesize(lower, 0);
  for (std::size_t v = 0; v < lower.num_vertices(0); ++v) EXPECT_EQ(base[7 * v + 3], l1[7 * v + 3]) << v;
  ASSERT_TRUE(m.undo());
  m.save_project(dir.file("undone.sublift"));
  EXPECT_EQ(read_project(dir.file("undone.sublift")).channels, 7);
}

// A channel shown as colour (the panel's "Colour by" list and `colour channel NAME`): the shown
// level's values through viridis, a uchar channel over 0..255, a float one over its own range.
TEST(ModelerAttributes, AChannelShownAsColour) {
  testing::TempDir dir("sublift_modeler_channel_colour");
  {
    std::ofstream(dir.file("sq.ply"))
        << "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
           "property uchar red\nproperty float quality\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
           "0 0 0 255 0.5\n1 0 0 0 0.25\n1 1 0 51 1\n0 1 0 255 0\n4 0 1 2 3\n";
  }
  ModelerState m;
  m.open(dir.file("sq.ply"), 0, Scheme::Linear);  // level 0 only: the values are the file's
  ASSERT_EQ(m.attribute_names().size(), 2u);
  m.set_colour_level(-1);
  m.set_colour_channel(0);
  EXPECT_EQ(m.colour_values(), (std::vector<float>{1.0f, 0.0f, 0.2f, 1.0f}));  // red / 255
  m.set_colour_channel(1);
  EXPECT_EQ(m.colour_values(), (std::vector<float>{0.5f, 0.25f, 1.0f, 0.0f}));  // quality over 0..1, its range
  // One value per vertex of the level shown after a subdivide, still in 0..1.
  m.subdivide();
  ASSERT_EQ(m.colour_values().size(), m.session().num_vertices(1));
  for (float v : m.colour_values()) EXPECT_TRUE(v >= 0.0f && v <= 1.0f) << v;
  EXPECT_EQ(m.colour_values()[0], 0.5f);  // the linear scheme keeps the base values
  EXPECT_THROW(m.set_colour_channel(2), Error);
  m.set_colour_channel(-1);
  EXPECT_TRUE(m.colour_values().empty());
}

// One channel group compressed on its own (the panel's Keep slider, `channel-keep NAME F`): the
// saved project's quality wavelets are what compress --group quality keeps at that fraction, the
// positions' and the colour's coefficients are untouched, the shown colour follows, 1 restores.
TEST(ModelerAttributes, AChannelCompressedOnItsOwn) {
  testing::TempDir dir("sublift_modeler_channel_keep");
  {
    std::ofstream(dir.file("sq.ply")) << kColouredSquarePly;
  }
  // Detail in every channel: a cubic subdivision's finest level rebuilt with the linear scheme.
  ASSERT_EQ(testing::run_cli({"subdivide", dir.file("sq.ply"), "--scheme", "cubic", "--levels", "3", "-o", dir.file("fine.ply")}).exit_code, 0);
  ASSERT_EQ(testing::run_cli({"rebuild", dir.file("fine.ply"), "--scheme", "linear", "-o", dir.file("linear.sublift")}).exit_code, 0);
  ModelerState m;
  m.open(dir.file("linear.sublift"));
  m.save_project(dir.file("full.sublift"));
  ASSERT_EQ(m.attribute_groups().size(), 2u);  // colour, quality
  EXPECT_EQ(m.attribute_groups()[1].name, "quality");
  m.set_colour_channel(3);
  const std::vector<float> shown_full = m.colour_values();
  m.set_channel_keep("quality", 0.0);
  EXPECT_EQ(m.channel_keep("quality"), 0.0);
  m.save_project(dir.file("kept0.sublift"));
  const Hierarchy full = read_project(dir.file("full.sublift")), kept = read_project(dir.file("kept0.sublift"));
  ASSERT_EQ(kept.channels, 7);
  const std::size_t nv0 = kept.num_vertices(0);
  std::size_t zero = 0, wavelets = 0;
  for (std::size_t i = 0; i < full.coeffs.size(); ++i) {
    const std::size_t v = i / 7, k = i % 7;
    if (k < 6) {
      EXPECT_EQ(kept.coeffs[i], full.coeffs[i]) << "vertex " << v << " channel " << k;
    }
    if (k == 6 && v >= nv0) ++wavelets, zero += kept.coeffs[i] == 0.0;
  }
  EXPECT_EQ(zero, wavelets);  // keep 0: every quality wavelet dropped
  std::size_t had = 0;
  for (std::size_t i = 7 * nv0 + 6; i < full.coeffs.size(); i += 7) had += full.coeffs[i] != 0.0;
  EXPECT_GT(had, 10u) << "the full project has quality detail to drop";
  EXPECT_NE(m.colour_values(), shown_full);
  // The same as compress --group quality at that fraction.
  const auto r = testing::run_cli({"compress", dir.file("full.sublift"), "--keep", "0", "--group", "quality", "-o", dir.file("cli.sublift")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_project(dir.file("cli.sublift")).coeffs, kept.coeffs);
  // By a channel's name too; 1 gives the full values back.
  EXPECT_THROW(m.set_channel_keep("hue", 0.5), Error);
  m.set_channel_keep("quality", 1.0);
  EXPECT_EQ(m.colour_values(), shown_full);
}

// Rebuild in the modeler carries a file's attributes as rebuild on the CLI does.
TEST(ModelerAttributes, RebuildCarriesThem) {
  testing::TempDir dir("sublift_modeler_attributes_rebuild");
  {
    std::ofstream(dir.file("sq.ply"))
        << "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
           "property float quality\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
           "0 0 0 0.5\n1 0 0 0.25\n1 1 0 1\n0 1 0 0\n4 0 1 2 3\n";
  }
  ASSERT_EQ(testing::run_cli({"subdivide", dir.file("sq.ply"), "--scheme", "cubic", "--levels", "2", "-o", dir.file("fine.ply")}).exit_code, 0);
  ModelerState m;
  m.open(dir.file("fine.ply"), 0, Scheme::Cubic);
  m.rebuild_levels(-1);
  ASSERT_EQ(m.session().finest_level(), 2);
  m.save_project(dir.file("r.sublift"));
  ProjectExtras x;
  const Hierarchy r = read_project(dir.file("r.sublift"), &x);
  ASSERT_EQ(r.channels, 4);
  ASSERT_EQ(x.attributes.size(), 1u);
  EXPECT_EQ(x.attributes[0].name, "quality");
}

}  // namespace
}  // namespace sublift
