// sublift-cli animation (issue 22): a glTF animation and an OBJ sequence in, frames out as glTF
// morph targets and as OBJ files that agree with each other and with the frames read back; the
// JSON report (counts, fit, wavelets, compression per frame and the per-frame baseline); edits
// move only their time support; frame counts that do not fit the levels, sequences that differ
// and bad edits are refused naming what is wrong.
#include <cmath>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/io/mesh/mesh_import.h"
#include "core/io/model/animation.h"
#include "tests/cli_run.h"
#include "tests/io_test_util.h"

namespace sublift {
namespace {

namespace fs = std::filesystem;
using testing::ProcessResult;
using testing::TempDir;

ProcessResult cli(const std::vector<std::string>& args) { return testing::run_cli(args, 120); }

const fs::path kGltf = fs::path(SUBLIFT_SHARED_DATA) / "gltf";

void write_text(const std::string& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary);
  f << text;
}

// A unit cube of quads, moved along x by `dx` and stretched in z by 1 + dx.
std::string cube_frame(double dx) {
  std::string s;
  for (int i = 0; i < 8; ++i)
    s += "v " + std::to_string((i & 1) + dx) + " " + std::to_string((i >> 1) & 1) + " " + std::to_string(((i >> 2) & 1) * (1 + dx)) + "\n";
  s += "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";
  return s;
}

std::vector<std::string> cube_sequence(const TempDir& dir, int frames) {
  std::vector<std::string> files;
  for (int f = 0; f < frames; ++f) {
    files.push_back(dir.file("cube" + std::to_string(f) + ".obj"));
    write_text(files.back(), cube_frame(0.1 * f * f / frames));
  }
  return files;
}

std::vector<double> obj_positions(const std::string& path) {
  const LoadedMesh m = import_surface_mesh(path);
  std::vector<double> x;
  for (const auto& p : m.mesh.positions) x.insert(x.end(), {p.x, p.y, p.z});
  return x;
}

TEST(CliAnimation, MorphCubeToGltfAndObjFramesAgree) {
  if (!fs::is_directory(kGltf)) GTEST_SKIP() << "glTF models not found at " << kGltf << " (../shared/data absent)";
  TempDir dir("sublift_cli_animation_morph");
  const std::string in = (kGltf / "AnimatedMorphCube" / "AnimatedMorphCube.gltf").string();
  const ProcessResult g = cli({"animation", in, "--frames", "9", "--levels", "2", "-o", dir.file("out.glb"), "--json"});
  ASSERT_EQ(g.exit_code, 0) << g.err;
  const nlohmann::json j = nlohmann::json::parse(g.out);
  EXPECT_EQ(j["frames"], 9);
  EXPECT_EQ(j["base_steps"], 2);
  EXPECT_EQ(j["levels"], 2);
  EXPECT_EQ(j["base_vertices"], 8);  // the cube's 24 glTF vertices welded
  EXPECT_EQ(j["lattice_vertices"], 3 * 8);
  EXPECT_EQ(j["lattice_cells"], 2 * 12);  // 12 triangles swept over 2 steps: prisms
  EXPECT_LT(j["fit"]["max_error"].get<double>(), 1e-12);
  EXPECT_GT(j["wavelets"]["time"].get<std::size_t>(), 0u);
  EXPECT_GT(j["wavelets"]["time_energy"].get<double>(), 0.0) << "the cube's morph moves it in time";
  const ProcessResult o = cli({"animation", in, "--frames", "9", "--levels", "2", "-o", dir.file("f_###.obj")});
  ASSERT_EQ(o.exit_code, 0) << o.err;
  ASSERT_TRUE(fs::exists(dir.file("f_000.obj")));
  ASSERT_TRUE(fs::exists(dir.file("f_008.obj")));
  EXPECT_FALSE(fs::exists(dir.file("f_009.obj")));
  // The glTF sampled back at its own keys gives the OBJ frames (float32 of the same numbers).
  const FrameSet back = sample_gltf_animation(dir.file("out.glb"), 0, 9, false);
  for (int f = 0; f < 9; ++f) {
    char name[16];
    std::snprintf(name, sizeof name, "f_%03d.obj", f);
    const std::vector<double> want = obj_positions(dir.file(name));
    ASSERT_EQ(back.num_vertices * 3, want.size());  // no vertex of the finest level is welded away
    const auto got = back.frame(std::size_t(f));
    for (std::size_t i = 0; i < want.size(); ++i) ASSERT_NEAR(got[i], want[i], 1e-5 * (1 + std::abs(want[i]))) << "frame " << f << " value " << i;
  }
}

TEST(CliAnimation, SequenceCompressionReportsEveryFrameAndTheBaseline) {
  TempDir dir("sublift_cli_animation_seq");
  const std::vector<std::string> files = cube_sequence(dir, 9);
  std::vector<std::string> args{"animation"};
  args.insert(args.end(), files.begin(), files.end());
  args.insert(args.end(), {"--levels", "2", "--keep", "0.1", "--json"});
  const ProcessResult r = cli(args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["frames"], 9);
  EXPECT_EQ(j["times"][1].get<double>(), 1.0 / 24);
  const nlohmann::json& c = j["compression"];
  ASSERT_EQ(c["errors"].size(), 9u);
  EXPECT_EQ(c["raw_input_frames"], 9 * 8);
  EXPECT_EQ(c["stored"].get<std::size_t>(), j["lattice_vertices"].get<std::size_t>() + c["kept"].get<std::size_t>());
  EXPECT_GE(c["per_frame"]["stored"].get<std::size_t>(), 9u * 8) << "per-frame stores every frame's base";
  EXPECT_EQ(c["per_frame"]["errors"].size(), 9u);
  double worst = 0;
  for (const auto& e : c["errors"]) worst = std::max(worst, e["max"].get<double>());
  EXPECT_EQ(worst, c["max_error"].get<double>());
  EXPECT_GT(worst, 0.0);
  // An error bound instead: every frame within it.
  args.erase(args.end() - 3, args.end() - 1);  // --keep 0.1
  args.insert(args.end() - 1, {"--linf", "0.002"});
  const ProcessResult b = cli(args);
  ASSERT_EQ(b.exit_code, 0) << b.err;
  const nlohmann::json jb = nlohmann::json::parse(b.out);
  EXPECT_EQ(jb["compression"]["mode"], "linf");
  for (const auto& e : jb["compression"]["errors"]) EXPECT_LE(e["max"].get<double>(), 0.002);
  EXPECT_LT(jb["compression"]["kept"].get<std::size_t>(), jb["compression"]["wavelets"].get<std::size_t>());
}

// --fps on a glTF without --frames: the Fox's 0.708 s walk at 24 fps is 17 intervals, rounded up
// to 5 base steps of 2^2: 21 frames.
TEST(CliAnimation, GltfSampledAtAFrameRate) {
  if (!fs::is_directory(kGltf)) GTEST_SKIP() << "glTF models not found at " << kGltf << " (../shared/data absent)";
  const ProcessResult r = cli({"animation", (kGltf / "Fox" / "Fox.glb").string(), "--animation", "1", "--fps", "24", "--levels", "2", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["frames"], 21);
  EXPECT_EQ(j["base_steps"], 5);
  EXPECT_NEAR(j["times"][20].get<double>() - j["times"][0].get<double>(), 0.708333, 1e-5);
}

TEST(CliAnimation, EditsMoveOnlyTheirTimeSupport) {
  TempDir dir("sublift_cli_animation_edit");
  const std::vector<std::string> files = cube_sequence(dir, 17);  // K = 4 base steps at J = 2
  write_text(dir.file("edits.txt"), "# lift corner 7 at base step 1\n0 4 7 0 0 0.5\n");
  std::vector<std::string> args{"animation"};
  args.insert(args.end(), files.begin(), files.end());
  args.insert(args.end(), {"--levels", "2", "-o", dir.file("plain.obj")});
  ASSERT_EQ(cli(args).exit_code, 0);
  args.back() = dir.file("edited.obj");
  args.insert(args.end(), {"--edits", dir.file("edits.txt")});
  const ProcessResult r = cli(args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (int f = 0; f < 17; ++f) {
    char plain[32], edited[32];
    std::snprintf(plain, sizeof plain, "plain_%04d.obj", f);
    std::snprintf(edited, sizeof edited, "edited_%04d.obj", f);
    const std::vector<double> a = obj_positions(dir.file(plain)), b = obj_positions(dir.file(edited));
    double moved = 0;
    for (std::size_t i = 0; i < a.size(); ++i) moved = std::max(moved, std::abs(a[i] - b[i]));
    // The cubic's level-2 reach is 6 frames; the first frame is the lattice's boundary, refined
    // from its own layer alone, so an edit of another layer leaves it as it was.
    if (std::abs(f - 4) >= 7 || f == 0) EXPECT_EQ(moved, 0.0) << "frame " << f;
    else EXPECT_GT(moved, 1e-4) << "frame " << f;
  }
}

// -o OUT.sublift keeps the animation: as IN it gives the same frames (and takes more edits).
TEST(CliAnimation, AProjectOfTheAnimationOpensAgain) {
  TempDir dir("sublift_cli_animation_project");
  const std::vector<std::string> files = cube_sequence(dir, 9);
  write_text(dir.file("edits.txt"), "0 4 3 0 0.2 0\n");
  std::vector<std::string> args{"animation"};
  args.insert(args.end(), files.begin(), files.end());
  args.insert(args.end(), {"--levels", "2", "--edits", dir.file("edits.txt"), "-o", dir.file("anim.sublift")});
  ASSERT_EQ(cli(args).exit_code, 0);
  args.back() = dir.file("direct.obj");
  ASSERT_EQ(cli(args).exit_code, 0);
  const ProcessResult r = cli({"animation", dir.file("anim.sublift"), "-o", dir.file("again.obj"), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["frames"], 9);
  for (int f = 0; f < 9; ++f) {
    char a[32], b[32];
    std::snprintf(a, sizeof a, "direct_%04d.obj", f);
    std::snprintf(b, sizeof b, "again_%04d.obj", f);
    EXPECT_EQ(obj_positions(dir.file(a)), obj_positions(dir.file(b))) << "frame " << f;
  }
  // A project that is no animation is refused, naming it.
  ASSERT_EQ(cli({"subdivide", files[0], "--scheme", "cubic", "--levels", "1", "-o", dir.file("plain.obj")}).exit_code, 0);
  ASSERT_EQ(cli({"analyze", dir.file("plain.obj"), "--base", files[0], "--scheme", "cubic", "--levels", "1", "-o", dir.file("plain.sublift")}).exit_code, 0);
  const ProcessResult bad = cli({"animation", dir.file("plain.sublift")});
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.err.find("is not an animation's project"), std::string::npos) << bad.err;
}

TEST(CliAnimation, RefusesWhatDoesNotFit) {
  TempDir dir("sublift_cli_animation_bad");
  const std::vector<std::string> files = cube_sequence(dir, 6);
  std::vector<std::string> args{"animation"};
  args.insert(args.end(), files.begin(), files.end());
  args.insert(args.end(), {"--levels", "2"});
  ProcessResult r = cli(args);
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("6 files do not fit 2 levels"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("give 5 or 9 files"), std::string::npos) << r.err;

  write_text(files[2], cube_frame(0.0) + "f 1 2 3\n");  // one more face
  args = {"animation", files[0], files[1], files[2], files[3], files[4], "--levels", "2"};
  r = cli(args);
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("cube2.obj"), std::string::npos) << r.err;

  write_text(files[2], cube_frame(0.0));
  write_text(dir.file("edits.txt"), "0 4 1 0 0 1\n0 3 1 0 0 1\n");
  args.insert(args.end(), {"--edits", dir.file("edits.txt")});
  r = cli(args);
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("edits.txt:2"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("every 4 frames"), std::string::npos) << r.err;

  if (fs::is_directory(kGltf)) {
    r = cli({"animation", (kGltf / "AnimatedMorphCube" / "AnimatedMorphCube.gltf").string(), "--frames", "10", "--levels", "2"});
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.err.find("try 9 or 13"), std::string::npos) << r.err;
    r = cli({"animation", (kGltf / "Box" / "Box.glb").string()});
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.err.find("animation"), std::string::npos) << r.err;
  }
  r = cli({"animation", files[0]});
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("two or more"), std::string::npos) << r.err;
  r = cli({"animation", files[0], files[1], "--keep", "2"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
}

}  // namespace
}  // namespace sublift
