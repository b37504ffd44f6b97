// Exported glTF must pass the Khronos glTF Validator: deformed Box, BoxTextured (.gltf with its
// external texture, and .glb) and Fox are exported and validated by tests/gltf_validate.mjs
// (npm gltf-validator, installed into the build folder by the gltf_validator_install fixture).
// Skips only when node is not installed.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "core/io/model/model.h"
#include "tests/io_test_util.h"
#include "tests/run_process.h"

namespace {

namespace fs = std::filesystem;
using namespace sublift;

const fs::path kGltf = fs::path(SUBLIFT_SHARED_DATA) / "gltf";
const fs::path kNodeTools = SUBLIFT_NODE_TOOLS;
const fs::path kScript = SUBLIFT_VALIDATE_SCRIPT;

bool node_installed() {
  try {
    return sublift::testing::run_process({"node", "--version"}, 30).exit_code == 0;
  } catch (...) {
    return false;
  }
}

// Runs the validator on `file`; returns its JSON report line (fails the test on a bad run).
nlohmann::json validate(const fs::path& file, int* exit_code) {
  const sublift::testing::ProcessResult r = sublift::testing::run_process({"node", kScript.string(), kNodeTools.string(), file.string()}, 60);
  *exit_code = r.exit_code;
  EXPECT_TRUE(r.exit_code == 0 || r.exit_code == 1) << "validator run failed (exit " << r.exit_code << "):\n" << r.err;
  if (!nlohmann::json::accept(r.out)) {
    ADD_FAILURE() << "validator printed no report:\n" << r.out << r.err;
    return {};
  }
  return nlohmann::json::parse(r.out);
}

class GltfValidator : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::is_directory(kGltf)) GTEST_SKIP() << "glTF models not found at " << kGltf << " (../shared/data absent)";
    if (!node_installed()) GTEST_SKIP() << "node is not installed: the Khronos glTF validator cannot run (scripts/deps.sh installs it)";
    ASSERT_TRUE(fs::exists(kNodeTools / "node_modules" / "gltf-validator" / "package.json"))
        << "gltf-validator missing in " << kNodeTools << ": the ctest fixture gltf_validator_install puts it there "
        << "(or: npm install --prefix " << kNodeTools << " gltf-validator)";
  }
};

// The deformation of model_io_test: p -> p + (0.1 y, 0, 0.05 x z / L).
std::vector<double> deform(const std::vector<double>& p) {
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (std::size_t i = 0; i < p.size(); ++i) lo[i % 3] = std::min(lo[i % 3], p[i]), hi[i % 3] = std::max(hi[i % 3], p[i]);
  const double L = std::hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
  std::vector<double> q = p;
  for (std::size_t v = 0; v < p.size() / 3; ++v) {
    q[3 * v] += 0.1 * p[3 * v + 1];
    q[3 * v + 2] += 0.05 * p[3 * v] * p[3 * v + 2] / L;
  }
  return q;
}

TEST_F(GltfValidator, DeformedExportsHaveNoErrors) {
  sublift::testing::TempDir dir("sublift_gltf_validator");
  const std::pair<const char*, const char*> cases[] = {
      {"Box/Box.glb", "box.glb"},
      {"BoxTextured/BoxTextured.gltf", "textured/box_textured.gltf"},  // another folder: the png is copied
      {"BoxTextured/BoxTextured.glb", "box_textured.glb"},
      {"BoxTextured/BoxTextured.gltf", "box_textured_from_gltf.glb"},
      {"Fox/Fox.glb", "fox.glb"},
      {"SimpleSkin/SimpleSkin.gltf", "simple_skin.gltf"},
  };
  fs::create_directories(dir.path() / "textured");
  for (const auto& [source, output] : cases) {
    SCOPED_TRACE(source);
    const Model m = import_model((kGltf / source).string());
    const fs::path out = dir.path() / output;
    export_model(m, deform(m.positions), out.string());
    int code = -1;
    const nlohmann::json report = validate(out, &code);
    EXPECT_EQ(code, 0) << report.dump();
    EXPECT_EQ(report.value("errors", -1), 0) << report.dump(2);
  }
}

// The path end to end: `sublift-cli ffd` wraps the Fox and the textured Box in box
// lattices, bends them at level 0 and dents them at level 1, and writes glTF the validator
// accepts.
TEST_F(GltfValidator, FfdExportsOfBentAndDentedModelsHaveNoErrors) {
  sublift::testing::TempDir dir("sublift_gltf_validator_ffd");
  std::ofstream(dir.path() / "edits.txt") << "# bend: a level-0 corner up, then a level-1 dent\n"
                                             "0 63 0 30 0\n0 62 0 30 0\n1 332 0 -10 0\n";
  const std::pair<const char*, const char*> cases[] = {{"Fox/Fox.glb", "fox_bent.glb"},
                                                       {"BoxTextured/BoxTextured.gltf", "box_bent.gltf"}};
  for (const auto& [source, output] : cases) {
    SCOPED_TRACE(source);
    const fs::path out = dir.path() / output;
    const sublift::testing::ProcessResult r = sublift::testing::run_process(
        {SUBLIFT_CLI, "ffd", "--box", "3", "3", "3", "--model", (kGltf / source).string(), "--edits",
         (dir.path() / "edits.txt").string(), "-o", out.string(), "--json"},
        60);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_GT(nlohmann::json::parse(r.out).value("moved", 0), 0);
    int code = -1;
    const nlohmann::json report = validate(out, &code);
    EXPECT_EQ(code, 0) << report.dump();
    EXPECT_EQ(report.value("errors", -1), 0) << report.dump(2);
  }
}

// Issue 22: `sublift-cli animation` writes the frames as morph targets keyed in time, and the
// validator accepts them: the Fox's walk edited at level 0 (.glb), the morph cube as a cyclic
// loop (.gltf, one more key back to frame 0).
TEST_F(GltfValidator, AnimationExportsHaveNoErrors) {
  sublift::testing::TempDir dir("sublift_gltf_validator_animation");
  std::ofstream(dir.path() / "edits.txt") << "0 4 10 0 5 0\n";
  const std::vector<std::vector<std::string>> cases = {
      {(kGltf / "Fox" / "Fox.glb").string(), "--animation", "1", "--frames", "9", "--levels", "1", "--edits",
       (dir.path() / "edits.txt").string(), "-o", (dir.path() / "fox_walk.glb").string()},
      {(kGltf / "AnimatedMorphCube" / "AnimatedMorphCube.gltf").string(), "--cyclic", "--frames", "12", "--levels", "2",
       "-o", (dir.path() / "cube_loop.gltf").string()}};
  for (const auto& args : cases) {
    SCOPED_TRACE(args.back());
    std::vector<std::string> argv{SUBLIFT_CLI, "animation"};
    argv.insert(argv.end(), args.begin(), args.end());
    const sublift::testing::ProcessResult r = sublift::testing::run_process(argv, 120);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    int code = -1;
    const nlohmann::json report = validate(args.back(), &code);
    EXPECT_EQ(code, 0) << report.dump();
    EXPECT_EQ(report.value("errors", -1), 0) << report.dump(2);
  }
}

// Issue 20: a level written as glTF carries the colours as COLOR_0 (BoxVertexColors subdivided),
// and the validator accepts it.
TEST_F(GltfValidator, SubdividedColouredBoxHasNoErrors) {
  sublift::testing::TempDir dir("sublift_gltf_validator_colours");
  const fs::path out = dir.path() / "box_colours.glb";
  const sublift::testing::ProcessResult r = sublift::testing::run_process(
      {SUBLIFT_CLI, "subdivide", (kGltf / "BoxVertexColors" / "BoxVertexColors.glb").string(), "--scheme", "loop", "--levels", "2",
       "-o", out.string()},
      60);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  int code = -1;
  const nlohmann::json report = validate(out, &code);
  EXPECT_EQ(code, 0) << report.dump();
  EXPECT_EQ(report.value("errors", -1), 0) << report.dump(2);
  EXPECT_EQ(report.value("warnings", -1), 0) << report.dump(2);
}

// Issue 20: BoxTextured subdivided keeps TEXCOORD_0 and its texture (embedded in the .glb, in
// the buffer of the .gltf), and the validator accepts both.
TEST_F(GltfValidator, SubdividedTexturedBoxHasNoErrors) {
  sublift::testing::TempDir dir("sublift_gltf_validator_textured");
  for (const char* name : {"box_textured.glb", "box_textured.gltf"}) {
    const fs::path out = dir.path() / name;
    const sublift::testing::ProcessResult r = sublift::testing::run_process(
        {SUBLIFT_CLI, "subdivide", (kGltf / "BoxTextured" / "BoxTextured.gltf").string(), "--scheme", "cubic", "--levels", "2",
         "-o", out.string()},
        60);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    int code = -1;
    const nlohmann::json report = validate(out, &code);
    EXPECT_EQ(code, 0) << report.dump();
    EXPECT_EQ(report.value("errors", -1), 0) << name << ": " << report.dump(2);
    EXPECT_EQ(report.value("warnings", -1), 0) << name << ": " << report.dump(2);
  }
}

TEST_F(GltfValidator, TheValidatorReportsABrokenFile) {
  // The check above is only as good as the script: a known-invalid model must fail it.
  const fs::path bad = kGltf / "invalid" / "IndexOutOfRange.gltf";
  if (!fs::exists(bad)) GTEST_SKIP() << bad << " not found";
  int code = -1;
  const nlohmann::json report = validate(bad, &code);
  EXPECT_EQ(code, 1);
  EXPECT_GT(report.value("errors", 0), 0) << report.dump(2);
}

}  // namespace
