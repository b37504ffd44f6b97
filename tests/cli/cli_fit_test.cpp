// sublift-cli fit (issue 17, a first version): a sphere comes in as a base and fitted levels
// within 0.5 % of its diagonal; a thin scan fits; bad usage exits 2.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "core/analysis/sphere_resample.h"
#include "core/io/lattice/shape_io.h"
#include "core/io/project/project_io.h"
#include "core/schemes/registry.h"
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
  // Loop's fit (the default is sqrt(2), below).
  const ProcessResult r = run_cli({"fit", mesh, "--scheme", "loop", "--base-vertices", "100", "--levels", "2", "-o", out, "--json"}, 120);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["base"]["vertices"], 100);
  // The base's vertices are mesh vertices, each named once (so a fit can be compared and redone).
  std::vector<std::uint32_t> map = j["base"]["input_vertex"].get<std::vector<std::uint32_t>>();
  ASSERT_EQ(map.size(), 100u);
  {  // the project keeps the map and the mesh it names
    ProjectExtras extras;
    const Hierarchy fitted = read_project(out, &extras);
    EXPECT_EQ(extras.fit_source.base_vertex, map);
    EXPECT_EQ(extras.fit_source.mesh_vertices, g.fine.num_vertices);
    EXPECT_EQ(std::filesystem::path(extras.fit_source.mesh), std::filesystem::absolute(mesh).lexically_normal());
    EXPECT_EQ(fitted.levels[0].num_vertices, 100u);
  }
  std::sort(map.begin(), map.end());
  EXPECT_TRUE(std::adjacent_find(map.begin(), map.end()) == map.end());
  EXPECT_LT(map.back(), g.fine.num_vertices);
  EXPECT_EQ(j["euler"]["base"], 2);
  EXPECT_EQ(j["levels"].size(), 2u);
  EXPECT_LT(j["input_to_fit_max"].get<double>(), 0.005);
  EXPECT_EQ(j["input_to_fit_max"], j["levels"][1]["input_to_net_max"]);
  for (const char* k : {"to_input_max", "input_to_limit_max"}) EXPECT_LT(j["limit"][k].get<double>(), 0.005) << k;
  EXPECT_EQ(j["limit"]["folded_faces"], 0);
  for (const char* k : {"base", "indexing", "hierarchy", "levels", "analysis", "report"}) EXPECT_TRUE(j["stage_ms"].contains(k)) << k;
  EXPECT_TRUE(std::filesystem::exists(out));
  // A tolerance picks the levels: the first whose limit surface lies within it both ways.
  const ProcessResult t = run_cli({"fit", mesh, "--scheme", "loop", "--base-vertices", "100", "--tolerance", "0.2%", "-o", out, "--json"}, 120);
  ASSERT_EQ(t.exit_code, 0) << t.err;
  const nlohmann::json jt = nlohmann::json::parse(t.out);
  EXPECT_TRUE(jt["reached_tolerance"].get<bool>());
  EXPECT_DOUBLE_EQ(jt["tolerance"].get<double>(), 0.002);
  EXPECT_LE(std::max(jt["limit"]["to_input_max"].get<double>(), jt["limit"]["input_to_limit_max"].get<double>()), 0.002);
  const std::size_t used = jt["levels"].size();
  EXPECT_GE(used, 1u);
  if (used > 1) {  // the level above did not reach it: a coarser fit would have done
    const ProcessResult fewer =
        run_cli({"fit", mesh, "--scheme", "loop", "--base-vertices", "100", "--levels", std::to_string(used - 1), "-o", out, "--json"}, 120);
    const nlohmann::json jf = nlohmann::json::parse(fewer.out);
    EXPECT_GT(std::max(jf["limit"]["to_input_max"].get<double>(), jf["limit"]["input_to_limit_max"].get<double>()), 0.002);
  }
  // A base of at most N faces.
  const ProcessResult bf = run_cli({"fit", mesh, "--base-faces", "150", "--levels", "1", "-o", out, "--json"}, 120);
  ASSERT_EQ(bf.exit_code, 0) << bf.err;
  EXPECT_LE(nlohmann::json::parse(bf.out)["base"]["faces"].get<int>(), 150);
  ASSERT_EQ(run_cli({"fit", mesh, "--scheme", "loop", "--base-vertices", "100", "--levels", "1", "-o", obj}, 120).exit_code, 0);
  EXPECT_EQ(read_shape(obj).base.num_vertices, 100u * 4 - 6);  // V0 + E0 of a genus-0 triangle mesh (E0 = 3 V0 - 6)
  // Bertram's cubic scheme and sqrt(2) fit from a quad-dominant base.
  for (const char* scheme : {"cubic", "sqrt2"}) {
    const std::string levels = std::string(scheme) == "sqrt2" ? "2" : "1";
    const ProcessResult q = run_cli({"fit", mesh, "--scheme", scheme, "--base-vertices", "100", "--levels", levels, "-o", out, "--json"}, 120);
    ASSERT_EQ(q.exit_code, 0) << scheme << ": " << q.err;
    const nlohmann::json jq = nlohmann::json::parse(q.out);
    EXPECT_EQ(jq["scheme"], scheme);
    EXPECT_GT(2 * jq["base"]["quads"].get<int>(), jq["base"]["faces"].get<int>()) << scheme;
    EXPECT_EQ(jq["euler"]["base"], 2);
    EXPECT_EQ(jq["limit"]["folded_faces"], 0);
    EXPECT_LT(jq["input_to_fit_max"].get<double>(), 0.01) << scheme;
    EXPECT_EQ(read_project(out).scheme, parse_scheme(scheme));
  }
  // Usage errors.
  EXPECT_EQ(run_cli({"fit", mesh, "--scheme", "sqrt2", "--levels", "13", "-o", out}).exit_code, 2);
  EXPECT_EQ(run_cli({"fit", mesh, "--levels", "13", "-o", out}).exit_code, 2);  // the default, sqrt(2): 12 at most
  EXPECT_EQ(run_cli({"fit", mesh, "--scheme", "loop", "--levels", "7", "-o", out}).exit_code, 2);
  EXPECT_EQ(run_cli({"fit", mesh, "--feature-angle", "200", "-o", out}).exit_code, 2);
  EXPECT_EQ(run_cli({"fit", mesh, "--levels", "2", "--tolerance", "0.01", "-o", out}).exit_code, 2);
  EXPECT_EQ(run_cli({"fit", mesh, "--base-faces", "100", "--base-vertices", "50", "-o", out}).exit_code, 2);
  for (const char* bad : {"1", "0", "-0.1", "abc", "120%"}) EXPECT_EQ(run_cli({"fit", mesh, "--tolerance", bad, "-o", out}).exit_code, 2) << bad;
  // A base larger than the mesh: a clear error, nothing written.
  const std::string none = dir.file("none.sublift");
  const ProcessResult big = run_cli({"fit", mesh, "--base-faces", "100000", "-o", none});
  EXPECT_EQ(big.exit_code, 1);
  EXPECT_NE(big.err.find("more than the mesh's"), std::string::npos) << big.err;
  EXPECT_FALSE(std::filesystem::exists(none));
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
  EXPECT_EQ(j["scheme"], "sqrt2");   // the default
  EXPECT_EQ(j["levels"].size(), 6u);  // three splits of two sqrt(2) steps: about the scan's count
  EXPECT_GT(j["base"]["quads"].get<int>(), 0);
  EXPECT_TRUE(std::filesystem::exists(dir.file("b.sublift")));
}
