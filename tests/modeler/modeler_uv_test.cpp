// The modeler keeps a textured model's UVs (issue 20) on ModelerState, without a window: every
// level's UVs are the base's refined (uv_at_level), saved in the project and back on reopening,
// written with exported levels (and the glTF texture with them), carried to the new base by
// Delete Lower and back by undo, and named when a scheme cannot carry them.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "app/modeler/modeler_state.h"
#include "core/base/file_io.h"
#include "core/io/lattice/shape_io.h"
#include "core/io/project/project_io.h"
#include "core/multires/level_uv.h"
#include "tests/io_test_util.h"

namespace sublift {
namespace {

namespace fs = std::filesystem;

// A cube whose six faces each map the whole texture (seams on every edge).
constexpr char kCubeObj[] =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
    "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
    "f 1/1 4/2 3/3 2/4\nf 5/1 6/2 7/3 8/4\nf 1/1 2/2 6/3 5/4\nf 2/1 3/2 7/3 6/4\nf 3/1 4/2 8/3 7/4\nf 4/1 1/2 5/3 8/4\n";

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

}  // namespace
}  // namespace sublift
