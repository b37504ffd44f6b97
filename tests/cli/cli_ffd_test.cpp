// sublift-cli ffd and its edits file (issue 6): no edit gives the model back, an edit of every
// level-0 lattice point by the same vector translates the model by it (glTF and OBJ), a single
// level-0 edit leaves vertices outside its support bit-identical, JSON fields, usage and input
// errors with file and line.
#include <cmath>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/ffd/box_lattice.h"
#include "core/base/errors.h"
#include "core/ffd/ffd_edits.h"
#include "core/ffd/ffd_scene.h"
#include "core/io/model/model.h"
#include "core/io/lattice/shape_io.h"
#include "tests/cli_run.h"
#include "tests/io_test_util.h"

namespace sublift {
namespace {

using testing::ProcessResult;
using testing::TempDir;

ProcessResult cli(const std::vector<std::string>& args) { return testing::run_cli(args); }

std::string asset(const std::string& name) { return std::string(SUBLIFT_ASSETS_DIR) + "/" + name; }

void write_text(const std::string& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary);
  f << text;
}

double diagonal(const std::vector<double>& xyz) {
  const auto b = bounding_box(xyz.data(), xyz.size() / 3);
  return std::hypot(b[1][0] - b[0][0], b[1][1] - b[0][1], b[1][2] - b[0][2]);
}

TEST(FfdEdits, ParsesLinesCommentsAndBlanks) {
  const auto e = parse_ffd_edits("# header\n\n0 3 0.5 -1 2e-3\n  1 10 0 0 0   # trailing\r\n", "e.txt");
  ASSERT_EQ(e.size(), 2u);
  EXPECT_EQ(e[0].level, 0);
  EXPECT_EQ(e[0].index, 3u);
  EXPECT_EQ(e[0].delta[0], 0.5);
  EXPECT_EQ(e[0].delta[1], -1.0);
  EXPECT_EQ(e[0].delta[2], 2e-3);
  EXPECT_EQ(e[0].line, 3u);
  EXPECT_EQ(e[1].level, 1);
  EXPECT_EQ(e[1].line, 4u);
  EXPECT_TRUE(parse_ffd_edits("", "empty.txt").empty());
  EXPECT_TRUE(parse_ffd_edits("# only a comment\n\n", "c.txt").empty());
}

TEST(FfdEdits, ErrorsNameFileAndLine) {
  const std::pair<std::string, std::string> cases[] = {
      {"0 1 2 3\n", "e.txt:1: expected 'level index dx dy dz', got 4 fields"},
      {"\n-1 0 0 0 0\n", "e.txt:2: level must be a non-negative integer"},
      {"0 1.5 0 0 0\n", "e.txt:1: index must be a non-negative integer"},
      {"0 1 0 nan 0\n", "e.txt:1: dy must be a finite number"},
      {"0 1 0 0 1e999\n", "e.txt:1: dz must be a finite number"},
  };
  for (const auto& [text, expect] : cases) {
    try {
      parse_ffd_edits(text, "e.txt");
      ADD_FAILURE() << "no error for " << text;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(expect), std::string::npos) << e.what();
    }
  }
  Hierarchy h = make_hierarchy(read_shape(asset("cube_cell.lattice")).base, 1, Scheme::Cubic, 3);
  EXPECT_NO_THROW(check_ffd_edits(parse_ffd_edits("0 7 0 0 0\n1 26 0 0 0\n", "e.txt"), h, "e.txt"));
  try {
    check_ffd_edits(parse_ffd_edits("0 7 0 0 0\n0 8 0 0 0\n", "e.txt"), h, "e.txt");
    ADD_FAILURE() << "index 8 of a cube accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("e.txt:2: index 8 is not a vertex of level 0 (it has 8)"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(check_ffd_edits(parse_ffd_edits("2 0 0 0 0\n", "e.txt"), h, "e.txt"), InputError);
}

// Every level-0 point of a 2x2x2 box lattice moved by d: the lattice's whole hierarchy moves
// by d (zero details), so every bound vertex moves by exactly d.
std::string translate_all(std::uint32_t n, const double d[3]) {
  std::string text = "# every level-0 point by the same vector\n";
  for (std::uint32_t i = 0; i < n; ++i) {
    char line[128];
    std::snprintf(line, sizeof line, "0 %u %.17g %.17g %.17g\n", i, d[0], d[1], d[2]);
    text += line;
  }
  return text;
}

TEST(CliFfd, NoEditGivesTheModelBackAndATranslationTranslatesIt) {
  TempDir dir("sublift_cli_ffd_translate");
  const std::string model = asset("torus_quad.obj");
  const Model before = import_model(model);
  write_text(dir.file("none.txt"), "# nothing\n");
  ProcessResult r = cli({"ffd", "--box", "2", "2", "2", "--model", model, "--edits", dir.file("none.txt"), "-o",
                         dir.file("same.obj"), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["vertices"], 96);
  EXPECT_EQ(j["bound"], 96);
  EXPECT_EQ(j["outside"], 0);
  EXPECT_EQ(j["edits"], 0);
  EXPECT_EQ(j["lattice_vertices"], 27);
  EXPECT_EQ(j["lattice_levels"], 2);
  EXPECT_EQ(j["finest_lattice_cells"], 8 * 64);
  const Model same = import_model(dir.file("same.obj"));
  const double size = diagonal(before.positions);
  ASSERT_EQ(same.positions.size(), before.positions.size());
  for (std::size_t i = 0; i < before.positions.size(); ++i) {
    EXPECT_NEAR(same.positions[i], before.positions[i], 1e-9 * size);
  }

  const double d[3] = {0.25, -0.5, 1.0};
  write_text(dir.file("move.txt"), translate_all(27, d));
  r = cli({"ffd", "--box", "2", "2", "2", "--model", model, "--edits", dir.file("move.txt"), "-o",
           dir.file("moved.obj"), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["moved"], 96);
  const Model moved = import_model(dir.file("moved.obj"));
  for (std::size_t v = 0; v < before.num_vertices(); ++v) {
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(moved.positions[3 * v + k], before.positions[3 * v + k] + d[k], 1e-9 * size);
  }
}

TEST(CliFfd, GltfTranslationKeepsTheRestAndMovesEveryVertex) {
  const std::string box = std::string(SUBLIFT_SHARED_DATA) + "/gltf/Box/Box.glb";
  if (!std::ifstream(box)) GTEST_SKIP() << "shared data not found (" << box << "): ../shared/data is absent";
  TempDir dir("sublift_cli_ffd_gltf");
  const Model before = import_model(box);
  const double d[3] = {0.1, 0.2, -0.3};
  write_text(dir.file("move.txt"), translate_all(27, d));
  const ProcessResult r = cli({"ffd", "--box", "2", "2", "2", "--margin", "0.1", "--model", box, "--edits",
                               dir.file("move.txt"), "-o", dir.file("box.gltf"), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Model after = import_model(dir.file("box.gltf"));  // .glb in, .gltf out: same family
  ASSERT_EQ(after.num_vertices(), before.num_vertices());
  EXPECT_EQ(after.faces.items, before.faces.items);
  for (std::size_t v = 0; v < before.num_vertices(); ++v) {
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(after.positions[3 * v + k], before.positions[3 * v + k] + d[k], 1e-6);
  }
}

// One level-0 point of a 4x4x4 box moved: model vertices whose cells lie outside that point's
// support at the finest level come back bit for bit (17 significant digits in the OBJ), and
// the ones next to it move.
TEST(CliFfd, OneLevelZeroEditIsLocal) {
  TempDir dir("sublift_cli_ffd_local");
  const std::string model = asset("torus_quad.obj");
  const Model before = import_model(model);
  write_text(dir.file("corner.txt"), "0 0 0.3 0.3 0.3\n");  // the box's first corner
  const ProcessResult r = cli({"ffd", "--box", "4", "4", "4", "--model", model, "--edits", dir.file("corner.txt"),
                               "-o", dir.file("out.obj"), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  const Model after = import_model(dir.file("out.obj"));
  // The same scene in-process tells which vertices the edit may reach (their stencils).
  FfdScene scene = make_ffd_scene(import_model(model), box_lattice_around(before, 4, 4, 4, 0.05));
  const std::uint32_t v0[1] = {0};
  const double delta[3] = {0.3, 0.3, 0.3};
  scene.lattice->move(0, v0, {}, delta);
  const auto touched = update_deformation(scene);
  EXPECT_EQ(j["moved"], touched.size());
  ASSERT_GT(touched.size(), 0u);
  ASSERT_LT(touched.size(), before.num_vertices());
  std::vector<std::uint8_t> reach(before.num_vertices(), 0);
  for (const std::uint32_t t : touched) reach[t] = 1;
  std::size_t moved = 0;
  for (std::size_t v = 0; v < before.num_vertices(); ++v) {
    for (int k = 0; k < 3; ++k) {
      if (!reach[v]) {
        EXPECT_EQ(after.positions[3 * v + k], before.positions[3 * v + k]) << v;
      }
      moved += after.positions[3 * v + k] != before.positions[3 * v + k];
    }
  }
  EXPECT_GT(moved, 0u);
}

TEST(CliFfd, UsageAndInputErrors) {
  TempDir dir("sublift_cli_ffd_errors");
  const std::string model = asset("torus_quad.obj");
  write_text(dir.file("bad.txt"), "\n0 99 0 0 0\n");
  const std::pair<std::vector<std::string>, std::string> cases[] = {
      {{"ffd", "--model", model, "-o", dir.file("o.obj")}, "give exactly one of --lattice L and --box"},
      {{"ffd", "--box", "2", "2", "2", "--lattice", asset("cube_cell.lattice"), "--model", model, "-o", dir.file("o.obj")},
       "give exactly one of"},
      {{"ffd", "--box", "2", "0", "2", "--model", model, "-o", dir.file("o.obj")}, "--box NY must be an integer"},
      {{"ffd", "--box", "2", "2", "2", "--model", model, "-o", dir.file("o.png")}, "OUT must be"},
      {{"ffd", "--box", "2", "2", "2", "--model", model, "--extra-levels", "9", "-o", dir.file("o.obj")},
       "--extra-levels must be 0..6"},
      {{"ffd", "--lattice", asset("cube.obj"), "--model", model, "-o", dir.file("o.obj")}, "not a volume lattice"},
      {{"ffd", "--box", "2", "2", "2", "--model", model, "--edits", dir.file("bad.txt"), "-o", dir.file("o.obj")},
       "bad.txt:2: index 99 is not a vertex of level 0 (it has 27)"},
      {{"ffd", "--box", "2", "2", "2", "--model", model, "-o", dir.file("o.ply")}, "format"},
  };
  for (const auto& [args, expect] : cases) {
    const ProcessResult r = cli(args);
    EXPECT_NE(r.exit_code, 0) << expect;
    EXPECT_NE(r.err.find(expect), std::string::npos) << r.err;
  }
  EXPECT_FALSE(std::ifstream(dir.file("o.obj")).good());  // nothing written on failure
}

}  // namespace
}  // namespace sublift
