// sublift-cli with the triangle schemes of paper 004: a real scan resampled onto the octahedron,
// analysed and synthesised back; subdivide; the coefficients table and its errors.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/io/lattice/shape_io.h"
#include "tests/cli_run.h"
#include "tests/io_test_util.h"

using namespace sublift;
using namespace sublift::testing;

namespace {

nlohmann::json json_of(const std::vector<std::string>& args) {
  const ProcessResult r = run_cli(args, 120);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return r.exit_code == 0 ? nlohmann::json::parse(r.out) : nlohmann::json{};
}

}  // namespace

// resample-sphere writes OUT and BASE so that analyze accepts them; synthesize gives OUT back.
TEST(CliTri, ResampledScanAnalysesAndSynthesisesBack) {
  const std::filesystem::path scan = std::filesystem::path(SUBLIFT_SHARED_DATA) / "scans/bunny_npm_lowres.obj";
  if (!std::filesystem::exists(scan)) GTEST_SKIP() << "no third-party data at " << scan << " (SUBLIFT_SHARED_DATA)";
  TempDir dir("sublift_cli_tri");
  const std::string fine = dir.file("fine.obj"), base = dir.file("base.obj");
  json_of({"resample-sphere", scan.string(), "--levels", "3", "-o", fine, "--base-out", base, "--json", "--force"});  // ears: 1 ray hits twice
  const Shape original = read_shape(fine);
  for (const char* scheme : {"linear-tri", "butterfly", "loop"}) {
    SCOPED_TRACE(scheme);
    const std::string project = dir.file(std::string(scheme) + ".sublift"), back = dir.file(std::string(scheme) + ".obj");
    const auto a = json_of({"analyze", fine, "--base", base, "--scheme", scheme, "--levels", "3", "-o", project, "--json"});
    EXPECT_EQ(a["scheme"], scheme);
    EXPECT_EQ(a["disc"], 2);
    EXPECT_EQ(a["vertices"], 258);
    const ProcessResult s = run_cli({"synthesize", project, "-o", back});
    ASSERT_EQ(s.exit_code, 0) << s.err;
    const Shape again = read_shape(back);
    ASSERT_EQ(again.positions.size(), original.positions.size());
    double worst = 0;
    for (std::size_t i = 0; i < again.positions.size(); ++i)
      worst = std::max(worst, std::abs(again.positions[i] - original.positions[i]));
    EXPECT_LT(worst, 1e-6) << "OBJ text keeps about 9 digits";
  }
}

TEST(CliTri, SubdivideKeepsOldVerticesForTheInterpolatingSchemes) {
  TempDir dir("sublift_cli_tri_sub");
  const std::string base = dir.file("tet.obj");
  std::ofstream(base) << "v 1 1 1\nv -1 -1 1\nv -1 1 -1\nv 1 -1 -1\nf 1 2 3\nf 1 4 2\nf 1 3 4\nf 2 4 3\n";
  for (const char* scheme : {"linear-tri", "butterfly", "loop"}) {
    const std::string out = dir.file(std::string(scheme) + ".obj");
    const auto j = json_of({"subdivide", base, "--scheme", scheme, "--levels", "2", "-o", out, "--json"});
    const Shape s = read_shape(out);
    ASSERT_EQ(s.positions.size(), 3u * 34u) << scheme;  // V = 4 -> 10 -> 34
    const bool keeps = std::string(scheme) != "loop";
    EXPECT_EQ(s.positions[0] == 1.0 && s.positions[1] == 1.0 && s.positions[2] == 1.0, keeps) << scheme;
  }
}

TEST(CliTri, CoefficientsTable) {
  for (const char* scheme : {"linear-tri", "butterfly", "loop"}) {
    SCOPED_TRACE(scheme);
    const auto j = json_of({"coefficients", "--scheme", scheme, "--valence", "6", "--disc", "1", "--json"});
    ASSERT_EQ(j["alpha"].size(), 10u);  // a, b and their 8 neighbours
    ASSERT_EQ(j["disc"].size(), 10u);
    EXPECT_EQ(j["disc"][0]["ring"], 0);
    EXPECT_DOUBLE_EQ(j["disc"][1]["x"].get<double>(), 1.0);
    // Mirror symmetry across the edge: alpha_a = alpha_b, and a's ring is symmetric.
    EXPECT_NEAR(j["alpha"][0].get<double>(), j["alpha"][1].get<double>(), 1e-14);
    EXPECT_NEAR(j["alpha"][2].get<double>(), j["alpha"][6].get<double>(), 1e-14);
    EXPECT_LT(j["residual"].get<double>(), 1e-12);
    // Valence 4 at the first end: the disc shrinks by the two missing spokes.
    const auto k = json_of({"coefficients", "--scheme", scheme, "--valence", "4", "--json"});
    const auto six = json_of({"coefficients", "--scheme", scheme, "--json"});
    EXPECT_LT(k["alpha"].size(), six["alpha"].size());
    EXPECT_GT(k["norm"].get<double>(), 0.0);
  }
  // The linear 1-disc alpha at a and b: 41/212 (docs/triangle_wavelets.md).
  const auto lin = json_of({"coefficients", "--scheme", "linear-tri", "--disc", "1", "--json"});
  EXPECT_NEAR(lin["alpha"][0].get<double>(), 41.0 / 212.0, 1e-14);
  for (const std::vector<std::string>& bad : std::vector<std::vector<std::string>>{
           {"coefficients", "--scheme", "loop", "--valence", "2"},
           {"coefficients", "--scheme", "loop", "--disc", "4"},
           {"coefficients", "--scheme", "butterfly", "--valences", "6", "6", "6", "6"}}) {
    const ProcessResult r = run_cli(bad);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_FALSE(r.err.empty());
  }
}
