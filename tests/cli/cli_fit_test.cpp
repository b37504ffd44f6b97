// sublift-cli fit (issue 17, a first version): a sphere comes in as a base and fitted levels
// within 0.5 % of its diagonal; a thin scan fits; bad usage exits 2.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "core/analysis/sphere_resample.h"
#include "core/io/lattice/shape_io.h"
#include "tests/cli_run.h"
#include "tests/io_test_util.h"

using namespace sublift;
using namespace sublift::testing;

TEST(CliFit, SphereFitsWithinHalfAPercent) {
  TempDir dir("sublift_cli_fit");
  const std::string mesh = dir.file("sphere.obj"), out = dir.file("fit.sublift"), obj = dir.file("fit.obj");
  const GeodesicSphere g = geodesic_sphere(5);
  std::vector<double> xyz;
  for (const auto& d : g.directions) xyz.insert(xyz.end(), {d.x, d.y, d.z});
  write_shape(mesh, g.fine, xyz);
  const ProcessResult r = run_cli({"fit", mesh, "--base-vertices", "100", "--levels", "2", "-o", out, "--json"}, 120);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["base"]["vertices"], 100);
  EXPECT_EQ(j["euler"]["base"], 2);
  EXPECT_EQ(j["levels"].size(), 2u);
  EXPECT_LT(j["input_to_fit_max"].get<double>(), 0.005);
  EXPECT_TRUE(std::filesystem::exists(out));
  ASSERT_EQ(run_cli({"fit", mesh, "--base-vertices", "100", "--levels", "1", "-o", obj}, 120).exit_code, 0);
  EXPECT_EQ(read_shape(obj).base.num_vertices, 100u * 4 - 6);  // V0 + E0 of a genus-0 triangle mesh (E0 = 3 V0 - 6)
  // Usage errors.
  EXPECT_EQ(run_cli({"fit", mesh, "--scheme", "cubic", "-o", out}).exit_code, 2);
  EXPECT_EQ(run_cli({"fit", mesh, "--levels", "9", "-o", out}).exit_code, 2);
  EXPECT_EQ(run_cli({"fit", mesh, "--feature-angle", "200", "-o", out}).exit_code, 2);
}

// The npm bunny with the default base (about 30 vertices): so coarse at the ears that faces'
// patches meet themselves there; once refused, now fitted.
TEST(CliFit, ThinScanFits) {
  const std::filesystem::path scan = std::filesystem::path(SUBLIFT_SHARED_DATA) / "scans/bunny_npm_lowres.obj";
  if (!std::filesystem::exists(scan)) GTEST_SKIP() << "no third-party data at " << scan << " (SUBLIFT_SHARED_DATA)";
  TempDir dir("sublift_cli_fit_bunny");
  const ProcessResult r = run_cli({"fit", scan.string(), "--json", "-o", dir.file("b.sublift")}, 120);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["euler"]["base"], 2);
  EXPECT_EQ(j["levels"].size(), 3u);
  EXPECT_TRUE(std::filesystem::exists(dir.file("b.sublift")));
}
