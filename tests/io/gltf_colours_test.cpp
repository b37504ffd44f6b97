// glTF vertex colours as channels (issue 20): BoxVertexColors' COLOR_0 read onto its 8 welded
// vertices (values read by hand from the file), carried through subdivide, rebuild/analyze and
// synthesize and written back as COLOR_0; the round trip gives the same colours; a colour
// that differs between two copies of a position is named.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "core/base/surface_mesh.h"
#include "core/io/lattice/shape_io.h"
#include "core/io/project/project_io.h"
#include "tests/cli_run.h"
#include "tests/io_test_util.h"

namespace sublift {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

const fs::path kBox = fs::path(SUBLIFT_SHARED_DATA) / "gltf" / "BoxVertexColors" / "BoxVertexColors.glb";

const VertexAttribute* attribute(const Shape& s, const std::string& name) {
  for (const VertexAttribute& a : s.attributes)
    if (a.name == name) return &a;
  return nullptr;
}

// The welded vertex at position p.
std::size_t vertex_at(const Shape& s, double x, double y, double z) {
  for (std::size_t v = 0; v < s.positions.size() / 3; ++v)
    if (std::abs(s.positions[3 * v] - x) < 1e-6 && std::abs(s.positions[3 * v + 1] - y) < 1e-6 && std::abs(s.positions[3 * v + 2] - z) < 1e-6)
      return v;
  ADD_FAILURE() << "no vertex at " << x << " " << y << " " << z;
  return 0;
}

TEST(GltfColours, BoxVertexColorsReadOntoTheWeldedVertices) {
  if (!fs::exists(kBox)) GTEST_SKIP() << kBox << " not found (../shared/data absent)";
  const Shape s = read_shape(kBox.string());
  ASSERT_EQ(s.positions.size(), 3u * 8);
  ASSERT_EQ(s.attributes.size(), 4u);  // red, green, blue and alpha (the file's alphas are not all 1)
  const VertexAttribute *r = attribute(s, "red"), *g = attribute(s, "green"), *b = attribute(s, "blue"), *a = attribute(s, "alpha");
  ASSERT_TRUE(r && g && b && a);
  // COLOR_0 (float VEC4) of the copies at these corners, read from the file with python3 (all
  // copies of a corner carry the same colour in this file).
  struct Corner {
    double x, y, z, rgba[4];
  };
  for (const Corner& c : {Corner{-0.5, 0.5, -0.5, {0.0, 0.0101, 1.0, 0.0}}, Corner{0.5, -0.5, -0.5, {0.0175, 0.9957, 0.3621, 0.0217}},
                          Corner{0.5, 0.5, -0.5, {0.8039, 0.8039, 0.8039, 1.0}}}) {
    const std::size_t v = vertex_at(s, c.x, c.y, c.z);
    EXPECT_NEAR(r->values[v], c.rgba[0], 1e-4);
    EXPECT_NEAR(g->values[v], c.rgba[1], 1e-4);
    EXPECT_NEAR(b->values[v], c.rgba[2], 1e-4);
    EXPECT_NEAR(a->values[v], c.rgba[3], 1e-4);
  }
  EXPECT_EQ(r->type, "float");
}

TEST(GltfColours, SubdivideRebuildSynthesizeRoundTrip) {
  if (!fs::exists(kBox)) GTEST_SKIP() << kBox << " not found (../shared/data absent)";
  TempDir dir("sublift_gltf_colours_round_trip");
  const Shape in = read_shape(kBox.string());
  // linear-tri interpolates: every level keeps the base vertices' values.
  auto r = testing::run_cli({"subdivide", kBox.string(), "--scheme", "linear-tri", "--levels", "2", "-o", dir.file("fine.glb")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Shape fine = read_shape(dir.file("fine.glb"));
  ASSERT_EQ(fine.attributes.size(), 4u);
  ASSERT_EQ(fine.positions.size() / 3, 98u);  // 8 + 18 edges at level 1, then 26 + 72
  for (std::size_t k = 0; k < 4; ++k)
    for (std::size_t v = 0; v < 8; ++v)
      EXPECT_EQ(float(fine.attributes[k].values[v]), float(in.attributes[k].values[v])) << fine.attributes[k].name << " of " << v;
  r = testing::run_cli({"analyze", dir.file("fine.glb"), "--scheme", "linear-tri", "--levels", "2", "-o", dir.file("box.sublift"), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["attributes"].size(), 4u);
  r = testing::run_cli({"synthesize", dir.file("box.sublift"), "--level", "2", "-o", dir.file("back.glb")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Shape back = read_shape(dir.file("back.glb"));
  ASSERT_EQ(back.positions.size(), fine.positions.size());
  ASSERT_EQ(back.attributes.size(), 4u);
  for (std::size_t k = 0; k < 4; ++k)
    for (std::size_t v = 0; v < back.attributes[k].values.size(); ++v)
      EXPECT_NEAR(back.attributes[k].values[v], fine.attributes[k].values[v], 1e-6) << back.attributes[k].name << " of " << v;
  // PLY keeps them too, under their names; linear-tri's level 0 holds the base's own colours.
  r = testing::run_cli({"synthesize", dir.file("box.sublift"), "--level", "0", "-o", dir.file("base.ply")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Shape ply = read_shape(dir.file("base.ply"));
  ASSERT_EQ(ply.attributes.size(), 4u);
  for (std::size_t v = 0; v < 8; ++v) {  // the rebuilt base numbers its vertices its own way: matched by position
    const std::size_t w = vertex_at(in, ply.positions[3 * v], ply.positions[3 * v + 1], ply.positions[3 * v + 2]);
    for (std::size_t k = 0; k < 4; ++k) EXPECT_NEAR(ply.attributes[k].values[v], in.attributes[k].values[w], 1e-6) << k << " of " << v;
  }
}

// compress ranks and measures the colour on its own (cli_compress.cpp's channel groups): the JSON
// has a row per group, x, y, z first (the top-level numbers), and the colour's error is in its
// own range.
TEST(GltfColours, CompressReportsPositionAndColourGroups) {
  if (!fs::exists(kBox)) GTEST_SKIP() << kBox << " not found (../shared/data absent)";
  TempDir dir("sublift_gltf_colours_compress");
  auto r = testing::run_cli({"subdivide", kBox.string(), "--scheme", "linear-tri", "--levels", "3", "-o", dir.file("fine.ply")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = testing::run_cli({"analyze", dir.file("fine.ply"), "--scheme", "loop", "--levels", "3", "-o", dir.file("box.sublift")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = testing::run_cli({"compress", dir.file("box.sublift"), "--keep", "0.05", "-o", dir.file("small.sublift"), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("ranked by the magnitude over all"), std::string::npos) << "the old mixed ranking's warning";
  const nlohmann::json j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["groups"].size(), 2u);
  EXPECT_EQ(j["groups"][0]["name"], "position");
  EXPECT_EQ(j["groups"][0]["l2_error"], j["l2_error"]);
  EXPECT_EQ(j["groups"][1]["name"], "colour");
  EXPECT_EQ(j["groups"][1]["channels"].size(), 4u);
  // A linear split analysed with Loop has detail in both; 5 % of it loses some of each.
  EXPECT_GT(j["groups"][0]["l2_error"].get<double>(), 0.0);
  EXPECT_GT(j["groups"][1]["l2_error"].get<double>(), 0.0);
  EXPECT_LT(j["groups"][1]["l2_error"].get<double>(), 0.5);
  EXPECT_EQ(j["groups"][1]["kept"], j["groups"][0]["kept"]) << "the same fraction of each group";
  // --group colour compresses the colour alone: the positions' coefficients are kept bit for bit,
  // the colour loses what it lost above.
  r = testing::run_cli({"compress", dir.file("box.sublift"), "--keep", "0.05", "--group", "colour", "-o", dir.file("colour.sublift"), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json c = nlohmann::json::parse(r.out);
  EXPECT_EQ(c["group"], "colour");
  EXPECT_EQ(c["groups"][0]["untouched"], true);
  EXPECT_EQ(c["groups"][1]["l2_error"], j["groups"][1]["l2_error"]);
  EXPECT_EQ(c["l2_error"], j["groups"][1]["l2_error"]);
  const Hierarchy full = read_project(dir.file("box.sublift")), colour = read_project(dir.file("colour.sublift"));
  std::size_t zeroed = 0;
  for (std::size_t i = 0; i < full.coeffs.size(); ++i) {
    if (i % 7 < 3) {
      EXPECT_EQ(colour.coeffs[i], full.coeffs[i]) << i;
    }
    zeroed += i % 7 >= 3 && colour.coeffs[i] == 0.0 && full.coeffs[i] != 0.0;
  }
  EXPECT_GT(zeroed, 0u);
  r = testing::run_cli({"compress", dir.file("box.sublift"), "--keep", "0.05", "--group", "hue", "-o", dir.file("x.sublift")});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--group hue: the project's groups are position, colour"), std::string::npos) << r.err;
}

// A scalar attribute goes out as the application-specific glTF attribute "_QUALITY" and comes
// back in as "quality" (float, the same values to float precision).
TEST(GltfColours, ScalarAttributesRoundTripAsCustomAttributes) {
  TempDir dir("sublift_gltf_custom");
  std::ofstream(dir.file("q.ply")) << "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                                      "property float quality\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n"
                                      "0 0 0 0.25\n1 0 0 0.5\n1 1 0 0.75\n0 1 0 1.5\n3 0 1 2\n3 0 2 3\n";
  const auto r = testing::run_cli({"subdivide", dir.file("q.ply"), "--scheme", "linear-tri", "--levels", "1", "-o", dir.file("q.glb")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("cannot hold the vertex attributes"), std::string::npos) << r.err;
  const Shape s = read_shape(dir.file("q.glb"));
  const VertexAttribute* q = attribute(s, "quality");
  ASSERT_NE(q, nullptr);
  ASSERT_EQ(q->values.size(), s.positions.size() / 3);
  for (std::size_t v = 0; v < 4; ++v) EXPECT_EQ(q->values[v], (std::array<double, 4>{0.25, 0.5, 0.75, 1.5})[v]);
  // An edge midpoint of the linear split: the mean of its ends (0.25 and 0.5, or another pair).
  bool mean = false;
  for (std::size_t v = 4; v < q->values.size(); ++v) mean = mean || q->values[v] == 0.375;
  EXPECT_TRUE(mean);
}

TEST(GltfColours, CopiesOfAPositionWithOtherColoursAreNamed) {
  if (!fs::exists(kBox)) GTEST_SKIP() << kBox << " not found (../shared/data absent)";
  TempDir dir("sublift_gltf_colours_parted");
  // BoxVertexColors' COLOR_0 is accessor 3 (float VEC4) in bufferView 3; vertex 1's red is the
  // first float of element 1: make it differ from the other copies of its corner.
  std::string bytes;
  {
    std::ifstream f(kBox, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(f), {});
  }
  const std::uint32_t json_length = std::uint32_t(std::uint8_t(bytes[12])) | std::uint32_t(std::uint8_t(bytes[13])) << 8 |
                                    std::uint32_t(std::uint8_t(bytes[14])) << 16 | std::uint32_t(std::uint8_t(bytes[15])) << 24;
  const nlohmann::json j = nlohmann::json::parse(bytes.substr(20, json_length));
  const auto& view = j["bufferViews"][j["accessors"][3]["bufferView"].get<int>()];
  const std::size_t at = 20 + json_length + 8 + view.value("byteOffset", 0) + j["accessors"][3].value("byteOffset", 0) + 16;
  const float half = 0.5f;
  std::memcpy(&bytes[at], &half, 4);
  std::ofstream(dir.file("parted.glb"), std::ios::binary) << bytes;
  const Shape s = read_shape(dir.file("parted.glb"));
  const std::string report = s.report.format("parted.glb") + s.report.not_kept_summary();
  EXPECT_NE(report.find("glTF vertices whose COLOR_0 differs from another copy"), std::string::npos) << report;
  EXPECT_EQ(read_shape(kBox.string()).report.format("box").find("COLOR_0 differs"), std::string::npos);
}

}  // namespace
}  // namespace sublift
