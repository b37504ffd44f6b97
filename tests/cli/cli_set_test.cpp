// sublift-cli set (issue 19, CLI parity): a project's scheme, levels, gains, frames and edit
// level as the modeler's panel sets them; the shape kept across schemes of one refinement; the
// finest level written as shown; usage and input errors.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/complex/complex_build.h"
#include "core/complex/shapes.h"
#include "core/edit/selection.h"
#include "core/edit/session.h"
#include "core/io/lattice/shape_io.h"
#include "core/io/project/project_io.h"
#include "core/multires/hierarchy.h"
#include "tests/cli_run.h"
#include "tests/io_test_util.h"
#include "tests/noisy_hierarchy.h"

namespace sublift {
namespace {

using testing::ProcessResult;
using testing::TempDir;

ProcessResult cli(const std::vector<std::string>& args) { return testing::run_cli(args); }

double max_diff(std::span<const double> a, std::span<const double> b) {
  if (a.size() != b.size()) return INFINITY;
  double e = 0;
  for (std::size_t i = 0; i < a.size(); ++i) e = std::max(e, std::abs(a[i] - b[i]));
  return e;
}

// A cubic torus project with detail at every level and gains 1, 0.5, 2.
Hierarchy torus_project(const TempDir& dir, const std::string& name) {
  const Hierarchy h = testing::noisy_torus(10, 6, 3, Scheme::Cubic, 5, 0.02);
  ProjectExtras extras;
  extras.gains = {1.0, 0.5, 2.0};
  extras.current_level = 2;
  write_project(dir.file(name), h, extras);
  return h;
}

TEST(CliSet, SchemeOfTheSameRefinementKeepsTheShape) {
  TempDir dir("sublift_cli_set_scheme");
  const Hierarchy h = torus_project(dir, "in.sublift");
  const Session shown(h, {1.0, 0.5, 2.0});
  const ProcessResult r = cli({"set", dir.file("in.sublift"), "--scheme", "linear", "-o", dir.file("lin.sublift"), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["scheme"], "linear");
  EXPECT_EQ(j["levels"], 3);
  EXPECT_EQ(j["gains"].get<std::vector<double>>(), (std::vector<double>{1.0, 1.0, 1.0}));  // baked into the wavelets
  EXPECT_TRUE(j["notes"].empty());
  EXPECT_EQ(j["level"], 2);
  ProjectExtras back;
  const Hierarchy lin = read_project(dir.file("lin.sublift"), &back);
  EXPECT_EQ(lin.scheme, Scheme::Linear);
  EXPECT_LT(max_diff(synthesize(lin, 3), shown.positions(3)), 1e-12);  // the finest shape as it was shown
  // Linear's level 0 is the finest net's linear-wavelet coarse shape, not cubic's: the
  // analysis really ran.
  EXPECT_GT(max_diff(synthesize(lin, 0), shown.positions(0)), 1e-4);
  // And back to cubic: the same shape again.
  ASSERT_EQ(cli({"set", dir.file("lin.sublift"), "--scheme", "cubic", "-o", dir.file("cub.sublift")}).exit_code, 0);
  EXPECT_LT(max_diff(synthesize(read_project(dir.file("cub.sublift")), 3), shown.positions(3)), 1e-12);
}

TEST(CliSet, SqrtTwoStartsFromTheBaseAndSaysSo) {
  TempDir dir("sublift_cli_set_sqrt2");
  const Hierarchy h = torus_project(dir, "in.sublift");
  const ProcessResult r = cli({"set", dir.file("in.sublift"), "--scheme", "sqrt2", "-o", dir.file("s.sublift"), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["levels"], 6);  // two sqrt(2) levels per split: the same finest resolution
  EXPECT_EQ(j["level"], 4);
  ASSERT_EQ(j["notes"].size(), 1u);
  EXPECT_NE(j["notes"][0].get<std::string>().find("start from the base, without the detail"), std::string::npos);
  EXPECT_NE(r.err.find("note: the sqrt2 scheme refines differently from cubic"), std::string::npos) << r.err;
  const Hierarchy s = read_project(dir.file("s.sublift"));
  EXPECT_EQ(synthesize(s, 0), synthesize(h, 0));
  for (std::size_t i = 3 * s.num_vertices(0); i < s.coeffs.size(); ++i) ASSERT_EQ(s.coeffs[i], 0.0) << i;
}

TEST(CliSet, SubdivideGainsFramesAndLevel) {
  TempDir dir("sublift_cli_set_session");
  const Hierarchy h = torus_project(dir, "in.sublift");
  const ProcessResult r = cli({"set", dir.file("in.sublift"), "--subdivide", "1", "--gain", "0", "0", "--gain", "2", "1.5",
                               "--frames", "local", "--level", "1", "-o", dir.file("out.sublift"), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["levels"], 4);
  EXPECT_EQ(j["gains"].get<std::vector<double>>(), (std::vector<double>{0.0, 0.5, 1.5, 1.0}));
  EXPECT_EQ(j["detail_frames"], "local");
  EXPECT_EQ(j["level"], 1);
  ProjectExtras back;
  const Hierarchy out = read_project(dir.file("out.sublift"), &back);
  EXPECT_EQ(back.gains, (std::vector<double>{0.0, 0.5, 1.5, 1.0}));
  EXPECT_TRUE(back.local_frames);
  EXPECT_EQ(back.current_level, 1);
  // The coefficients are the project's, plus a level of zero detail: gains and frames change how
  // they are shown, not what is stored.
  ASSERT_EQ(out.coeffs.size(), 3 * std::size_t(out.num_vertices(4)));
  EXPECT_TRUE(std::equal(h.coeffs.begin(), h.coeffs.end(), out.coeffs.begin()));
  for (std::size_t i = h.coeffs.size(); i < out.coeffs.size(); ++i) ASSERT_EQ(out.coeffs[i], 0.0) << i;
  // The finest level written as a mesh is what the modeler shows with those gains.
  ASSERT_EQ(cli({"set", dir.file("in.sublift"), "--gain", "0", "0", "-o", dir.file("shown.obj")}).exit_code, 0);
  const Session shown(h, {0.0, 0.5, 2.0});
  EXPECT_LT(max_diff(read_shape(dir.file("shown.obj")).positions, shown.positions(3)), 1e-12);
}

TEST(CliSet, UsageAndInputErrors) {
  TempDir dir("sublift_cli_set_errors");
  torus_project(dir, "in.sublift");
  const std::string in = dir.file("in.sublift"), out = dir.file("out.sublift");
  struct Case {
    std::vector<std::string> args;
    int code;
    std::string message;
  };
  const std::vector<Case> cases = {
      {{"set", in, "--gain", "3", "1", "-o", out}, 2, "--gain L must be a whole number in 0..2, got '3'"},
      {{"set", in, "--gain", "0", "lots", "-o", out}, 2, "--gain F must be a number, got 'lots'"},
      {{"set", in, "--frames", "sideways", "-o", out}, 2, "--frames must be world or local, got 'sideways'"},
      {{"set", in, "--scheme", "nurbs", "-o", out}, 2, "--scheme must be linear, cubic"},
      {{"set", in, "--subdivide", "0", "-o", out}, 2, "--subdivide must be a whole number in 1..24, got '0'"},
      {{"set", in, "--level", "9", "-o", out}, 2, "--level must be a whole number in 0..3, got '9'"},
      {{"set", in}, 2, "missing -o OUT"},
      {{"set", in, "--scheme", "loop", "-o", out}, 1, "the loop scheme needs a triangle mesh; face 0 has 4 corners"},
      {{"set", dir.file("none.sublift"), "-o", out}, 1, "none.sublift"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.args.back());
    const ProcessResult r = cli(c.args);
    EXPECT_EQ(r.exit_code, c.code) << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
  }
  EXPECT_FALSE(std::filesystem::exists(out));  // nothing written by a refused command
}

// --delete-higher / --delete-lower and synthesize --every-level (issue 19): each remaining
// level's net, as the project's own synthesis with its gains gave it before.
TEST(CliSet, DeleteHigherAndLowerKeepTheRemainingLevels) {
  TempDir dir("sublift_cli_set_delete");
  torus_project(dir, "in.sublift");
  ProjectExtras extras;
  Hierarchy shown = read_project(dir.file("in.sublift"), &extras);
  apply_gains(shown, extras.gains);
  std::vector<std::vector<double>> before;
  for (int l = 0; l <= 3; ++l) before.push_back(synthesize(shown, l));

  ProcessResult r = cli({"set", dir.file("in.sublift"), "--delete-higher", "2", "-o", dir.file("high.sublift"), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ProjectExtras he;
  Hierarchy high = read_project(dir.file("high.sublift"), &he);
  EXPECT_EQ(high.finest_level(), 2);
  EXPECT_EQ(he.gains, (std::vector<double>{1.0, 0.5}));
  apply_gains(high, he.gains);
  for (int l = 0; l <= 2; ++l) EXPECT_EQ(synthesize(high, l), before[static_cast<std::size_t>(l)]) << l;

  r = cli({"set", dir.file("in.sublift"), "--delete-lower", "1", "-o", dir.file("low.sublift")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ProjectExtras le;
  Hierarchy low = read_project(dir.file("low.sublift"), &le);
  EXPECT_EQ(low.finest_level(), 2);
  EXPECT_EQ(low.num_vertices(0), shown.num_vertices(1));
  EXPECT_EQ(le.gains, (std::vector<double>{0.5, 2.0}));
  EXPECT_EQ(le.current_level, 1);  // the edit level 2 is now level 1
  apply_gains(low, le.gains);
  for (int k = 0; k <= 2; ++k) EXPECT_LT(max_diff(synthesize(low, k), before[static_cast<std::size_t>(k) + 1]), 1e-12) << k;

  // Every level at once: name_L0.obj .. name_L3.obj, each the net of its level.
  r = cli({"synthesize", dir.file("in.sublift"), "--every-level", "-o", dir.file("net.obj"), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["files"].size(), 4u);
  for (int l = 0; l <= 3; ++l) {
    const Shape s = read_shape(dir.file("net_L" + std::to_string(l) + ".obj"));
    EXPECT_LT(max_diff(s.positions, before[static_cast<std::size_t>(l)]), 1e-15) << l;
  }
  for (const auto& args : std::vector<std::vector<std::string>>{
           {"set", dir.file("in.sublift"), "--delete-higher", "4", "-o", dir.file("x.sublift")},
           {"set", dir.file("in.sublift"), "--delete-lower", "-1", "-o", dir.file("x.sublift")},
           {"synthesize", dir.file("in.sublift"), "--every-level", "--level", "1", "-o", dir.file("x.obj")},
       }) {
    const ProcessResult bad = cli(args);
    EXPECT_EQ(bad.exit_code, 2) << bad.err;
  }
}

// --crease / --corner (issue 19): the base edge becomes a crease, the finest level as shown
// stays, and --uncrease takes it away again.
TEST(CliSet, CreaseAndCornerOnTheBase) {
  TempDir dir("sublift_cli_set_crease");
  const Hierarchy h = torus_project(dir, "in.sublift");
  const Session shown(h, {1.0, 0.5, 2.0});
  const std::int64_t e = find_edge(h.levels[0], 0, 1);
  ASSERT_GE(e, 0);
  ProcessResult r = cli({"set", dir.file("in.sublift"), "--crease", "0", "1", "--corner", "5", "-o", dir.file("c.sublift"), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ProjectExtras ce;
  const Hierarchy c = read_project(dir.file("c.sublift"), &ce);
  EXPECT_EQ(c.levels[0].edge_dim[static_cast<std::size_t>(e)], 1);
  EXPECT_EQ(c.levels[0].vertex_dim[5], 0);
  EXPECT_EQ(ce.gains, (std::vector<double>{1.0, 1.0, 1.0}));
  EXPECT_LT(max_diff(synthesize(c, 3), shown.positions(3)), 1e-12);
  r = cli({"set", dir.file("c.sublift"), "--uncrease", "0", "1", "--uncorner", "5", "-o", dir.file("u.sublift")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Hierarchy u = read_project(dir.file("u.sublift"));
  EXPECT_EQ(u.levels[0].edge_dim[static_cast<std::size_t>(e)], 2);
  EXPECT_EQ(u.levels[0].vertex_dim[5], 2);
  r = cli({"set", dir.file("in.sublift"), "--crease", "0", "30", "-o", dir.file("x.sublift")});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("no base edge joins them"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace sublift
