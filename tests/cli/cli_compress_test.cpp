// sublift-cli compress (docs/compression.md): JSON fields, the output by extension (a project
// that reopens to the compressed coefficients, a mesh equal to its finest level), the command
// equal to core's Compressor and to `synthesize --keep`, the gains of a project, usage and input
// errors.
#include <algorithm>
#include <array>
#include <fstream>
#include <set>
#include <sstream>
#include <cmath>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/complex/complex_build.h"
#include "core/analysis/compress.h"
#include "core/edit/session.h"
#include "core/multires/hierarchy.h"
#include "core/io/project/project_io.h"
#include "core/io/lattice/shape_io.h"
#include "core/complex/shapes.h"
#include "tests/cli_run.h"
#include "tests/io_test_util.h"
#include "tests/test_util.h"
#include "tests/noisy_hierarchy.h"

namespace sublift {
namespace {

using testing::ProcessResult;
using testing::TempDir;

ProcessResult cli(const std::vector<std::string>& args) { return testing::run_cli(args); }

// A torus project with detail at every level.
Hierarchy project_hierarchy() { return testing::noisy_torus(12, 8, 3, Scheme::Cubic, 11, 0.02); }

TEST(CliCompress, JsonFieldsAndProjectOutputMatchCore) {
  TempDir dir("sublift_cli_compress_json");
  const Hierarchy h = project_hierarchy();
  write_project(dir.file("in.sublift"), h);
  const Compressor core(h);
  struct Mode {
    const char* option;
    const char* name;
    double value;
    CompressMode mode;
  };
  for (const Mode& m : {Mode{"--keep", "keep", 0.2, CompressMode::Keep},
                        Mode{"--threshold", "threshold", 5e-4, CompressMode::Threshold},
                        Mode{"--linf", "linf", 0.01, CompressMode::Linf}}) {
    SCOPED_TRACE(m.name);
    const ProcessResult r = cli({"compress", dir.file("in.sublift"), m.option, std::to_string(m.value), "-o",
                                 dir.file("out.sublift"), "--json"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    for (const char* key : {"kept", "total", "l2_error", "linf_error", "mode", "value"}) EXPECT_TRUE(j.contains(key)) << key;
    const Compression c = core.run(m.mode, m.value);
    EXPECT_EQ(j["mode"], m.name);
    EXPECT_DOUBLE_EQ(j["value"].get<double>(), m.value);
    EXPECT_EQ(j["kept"].get<std::size_t>(), c.kept);
    EXPECT_EQ(j["total"].get<std::size_t>(), h.num_vertices(3) - h.num_vertices(0));
    EXPECT_DOUBLE_EQ(j["l2_error"].get<double>(), c.l2_error);
    EXPECT_DOUBLE_EQ(j["linf_error"].get<double>(), c.linf_error);
    EXPECT_GT(c.kept, 0u);
    EXPECT_LT(c.kept, c.total);
    if (m.mode == CompressMode::Linf) {
      EXPECT_LE(j["linf_error"].get<double>(), m.value);
    }
    // The project reopens with exactly the compressed coefficients.
    const Hierarchy out = read_project(dir.file("out.sublift"));
    EXPECT_EQ(out.coeffs, c.coeffs);
  }
}

// Issue 20: a compressed project is small on disk (the dropped wavelets a bit each), and --bits
// quantizes the kept ones, reporting the error measured on the file written.
TEST(CliCompress, ProjectsStoreOnlyWhatIsKeptAndBitsReportTheirError) {
  TempDir dir("sublift_cli_compress_bytes");
  const Hierarchy h = project_hierarchy();
  write_project(dir.file("in.sublift"), h);
  const auto run = [&](const std::vector<std::string>& extra, const std::string& out) {
    std::vector<std::string> args = {"compress", dir.file("in.sublift"), "--keep", "0.25", "-o", dir.file(out), "--json"};
    args.insert(args.end(), extra.begin(), extra.end());
    const ProcessResult r = cli(args);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return nlohmann::json::parse(r.out);
  };
  const auto lossless = run({}, "q.sublift");
  EXPECT_EQ(lossless["encoding"], "sparse");
  EXPECT_EQ(lossless["bytes"].get<std::uint64_t>(), std::filesystem::file_size(dir.file("q.sublift")));
  EXPECT_LE(lossless["bytes"].get<double>(), 0.35 * double(std::filesystem::file_size(dir.file("in.sublift"))));
  EXPECT_FALSE(lossless.contains("quantization_linf_error"));
  const auto q8 = run({"--bits", "8"}, "q8.sublift");
  EXPECT_EQ(q8["encoding"], "quantized");
  EXPECT_EQ(q8["bits"], 8);
  EXPECT_LT(q8["bytes"].get<double>(), lossless["bytes"].get<double>());
  // The reported move is the one the file makes: the finest levels of the two projects.
  const std::vector<double> a = synthesize(read_project(dir.file("q.sublift")), 3);
  const std::vector<double> b = synthesize(read_project(dir.file("q8.sublift")), 3);
  double move = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) move = std::max(move, std::abs(a[i] - b[i]));
  EXPECT_GT(move, 0.0);
  EXPECT_DOUBLE_EQ(q8["quantization_linf_error"].get<double>(), move / q8["diagonal"].get<double>());
  EXPECT_GT(q8["quantization_max_error"].get<double>(), 0.0);
}

TEST(CliCompress, MeshOutputIsTheFinestLevelAndEqualsSynthesizeKeep) {
  TempDir dir("sublift_cli_compress_mesh");
  const Hierarchy h = project_hierarchy();
  write_project(dir.file("in.sublift"), h);
  ASSERT_EQ(cli({"compress", dir.file("in.sublift"), "--keep", "0.1", "-o", dir.file("c.sublift")}).exit_code, 0);
  ASSERT_EQ(cli({"compress", dir.file("in.sublift"), "--keep", "0.1", "-o", dir.file("c.obj")}).exit_code, 0);
  ASSERT_EQ(cli({"synthesize", dir.file("in.sublift"), "--keep", "0.1", "-o", dir.file("s.obj")}).exit_code, 0);
  // The mesh is the compressed project's finest level, to 17 digits...
  const Shape mesh = read_shape(dir.file("c.obj"));
  const std::vector<double> fine = synthesize(read_project(dir.file("c.sublift")), 3);
  EXPECT_EQ(mesh.positions, fine);
  // ... and what `synthesize --keep` writes: the same ranking and rounding.
  EXPECT_EQ(read_shape(dir.file("s.obj")).positions, mesh.positions);
  // A human summary without --json.
  const ProcessResult r = cli({"compress", dir.file("in.sublift"), "--keep", "0.5", "-o", dir.file("c2.ply")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("kept 3024 of 6048 wavelets"), std::string::npos) << r.out;
  EXPECT_EQ(read_shape(dir.file("c2.ply")).positions.size(), fine.size());
}

TEST(CliCompress, RegionRawAndGains) {
  TempDir dir("sublift_cli_compress_region");
  const Hierarchy h = project_hierarchy();
  ProjectExtras extras;
  extras.gains = {1.0, 0.5, 1.5};
  extras.current_level = 2;
  write_project(dir.file("in.sublift"), h, extras);
  const ProcessResult r = cli({"compress", dir.file("in.sublift"), "--keep", "0", "--region", "sphere:1,0,0,0.6",
                               "--raw", "-o", dir.file("out.sublift"), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  CompressOptions o;
  o.region = parse_region("sphere:1,0,0,0.6");
  o.normalise = false;
  o.gains = extras.gains;
  const Compressor core(h, o);
  EXPECT_EQ(j["kept"].get<std::size_t>(), core.total() - core.candidates());
  EXPECT_GT(j["kept"].get<std::size_t>(), 0u);
  EXPECT_EQ(j["normalise"], false);
  ProjectExtras back;
  const Hierarchy out = read_project(dir.file("out.sublift"), &back);
  EXPECT_EQ(out.coeffs, core.evaluate(0).coeffs);
  EXPECT_EQ(back.gains, extras.gains);  // the session state goes along
  EXPECT_EQ(back.current_level, 2);
}

// Issue 19: synthesize ignored the saved gains (gain 0 on level 0 and 3 on level 1 came out as
// if every gain were 1) while compress applied them.
TEST(CliCompress, SynthesizeHonoursTheSavedGains) {
  TempDir dir("sublift_cli_synthesize_gains");
  const Hierarchy h = project_hierarchy();
  ProjectExtras extras;
  extras.gains = {0.0, 3.0, 1.0};
  write_project(dir.file("in.sublift"), h, extras);
  const ProcessResult r = cli({"synthesize", dir.file("in.sublift"), "-o", dir.file("s.obj"), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["gains"].get<std::vector<double>>(), extras.gains);
  // What the modeler's session shows with those gains (its own synthesis path).
  const Session session(h, extras.gains);
  const std::vector<double> shown(session.positions(3).begin(), session.positions(3).end());
  const std::vector<double> written = read_shape(dir.file("s.obj")).positions;
  ASSERT_EQ(written.size(), shown.size());
  double err = 0, from_plain = 0;
  const std::vector<double> plain = synthesize(h, 3);
  for (std::size_t i = 0; i < shown.size(); ++i) {
    err = std::max(err, std::abs(written[i] - shown[i]));
    from_plain = std::max(from_plain, std::abs(written[i] - plain[i]));
  }
  EXPECT_LT(err, 1e-12);
  EXPECT_GT(from_plain, 1e-3);  // the gains matter on this project
  // A coarser level sees only the gains below it: level 1 is level 0's net (gain 0).
  ASSERT_EQ(cli({"synthesize", dir.file("in.sublift"), "--level", "1", "-o", dir.file("s1.obj")}).exit_code, 0);
  const std::vector<double> one = read_shape(dir.file("s1.obj")).positions;
  const std::vector<double> shown1(session.positions(1).begin(), session.positions(1).end());
  ASSERT_EQ(one.size(), shown1.size());
  for (std::size_t i = 0; i < one.size(); ++i) EXPECT_NEAR(one[i], shown1[i], 1e-12) << i;
  // --keep ranks with the gains, as compress does: the same mesh.
  ASSERT_EQ(cli({"synthesize", dir.file("in.sublift"), "--keep", "0.3", "-o", dir.file("k.obj")}).exit_code, 0);
  ASSERT_EQ(cli({"compress", dir.file("in.sublift"), "--keep", "0.3", "-o", dir.file("c.obj")}).exit_code, 0);
  EXPECT_EQ(read_shape(dir.file("k.obj")).positions, read_shape(dir.file("c.obj")).positions);
}

TEST(ApplyGains, ScalesEachLevelsWaveletsAndRefusesBadGains) {
  Hierarchy h = project_hierarchy();
  const Hierarchy before = h;
  apply_gains(h, {});
  EXPECT_EQ(h.coeffs, before.coeffs);
  apply_gains(h, std::vector<double>{1.0, -2.0, 1.0});
  for (std::size_t i = 0; i < h.coeffs.size(); ++i) {
    const bool level1 = i >= 3 * std::size_t(h.num_vertices(1)) && i < 3 * std::size_t(h.num_vertices(2));
    EXPECT_EQ(h.coeffs[i], level1 ? -2.0 * before.coeffs[i] : before.coeffs[i]) << i;
  }
  EXPECT_NE(sublift::testing::error_text([&] { apply_gains(h, std::vector<double>{1.0, 1.0}); }).find("2 gains for 3 wavelet levels"),
            std::string::npos);
  EXPECT_NE(sublift::testing::error_text([&] { apply_gains(h, std::vector<double>{1.0, NAN, 1.0}); }).find("level 1 is not finite"),
            std::string::npos);
  Hierarchy integer = make_hierarchy(h.levels.front(), 1, Scheme::Linear, 3, true);
  EXPECT_NE(sublift::testing::error_text([&] { apply_gains(integer, std::vector<double>{0.5}); }).find("integer hierarchy takes no gains"),
            std::string::npos);
}

// synthesize --limit: the finest level's limit surface with normals (issue 19, CLI parity with
// the modeler's export). On the torus every vertex is regular, where the cubic scheme is the
// bicubic B-spline: limit = (16 v + 4 (edge neighbours) + (diagonal neighbours)) / 36.
TEST(CliSynthesize, LimitSurfaceWithNormals) {
  TempDir dir("sublift_cli_synthesize_limit");
  const Hierarchy h = project_hierarchy();
  write_project(dir.file("in.sublift"), h);
  const ProcessResult r = cli({"synthesize", dir.file("in.sublift"), "--limit", "-o", dir.file("lim.obj"), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["limit"], true);
  const std::vector<double> net = synthesize(h, 3);
  const Complex& c = h.levels[3];
  const Shape lim = read_shape(dir.file("lim.obj"));
  ASSERT_EQ(lim.positions.size(), net.size());
  std::vector<std::set<std::uint32_t>> edge_nb(c.num_vertices), face_nb(c.num_vertices);
  for (std::uint32_t f = 0; f < c.num_faces(); ++f) {
    const auto q = c.faces.row(f);
    ASSERT_EQ(q.size(), 4u);
    for (std::size_t k = 0; k < 4; ++k) {
      edge_nb[q[k]].insert(q[(k + 1) % 4]);
      edge_nb[q[k]].insert(q[(k + 3) % 4]);
      face_nb[q[k]].insert(q[(k + 2) % 4]);
    }
  }
  double err = 0;
  for (std::uint32_t v = 0; v < c.num_vertices; ++v) {
    ASSERT_EQ(edge_nb[v].size(), 4u);
    for (int k = 0; k < 3; ++k) {
      double m = 16 * net[3 * v + k];
      for (std::uint32_t u : edge_nb[v]) m += 4 * net[3 * u + k];
      for (std::uint32_t u : face_nb[v]) m += net[3 * u + k];
      err = std::max(err, std::abs(m / 36 - lim.positions[3 * v + k]));
    }
  }
  EXPECT_LT(err, 1e-12);
  // One unit normal per vertex, pointing away from the torus' core circle (radius 1 about z).
  std::ifstream in(dir.file("lim.obj"));
  std::vector<std::array<double, 3>> normals;
  for (std::string line; std::getline(in, line);)
    if (line.rfind("vn ", 0) == 0) {
      std::istringstream w(line.substr(3));
      std::array<double, 3> n{};
      w >> n[0] >> n[1] >> n[2];
      normals.push_back(n);
    }
  ASSERT_EQ(normals.size(), c.num_vertices);
  for (std::uint32_t v = 0; v < c.num_vertices; ++v) {
    const auto& n = normals[v];
    EXPECT_NEAR(n[0] * n[0] + n[1] * n[1] + n[2] * n[2], 1.0, 1e-6);
    const double* p = &lim.positions[3 * v];
    const double rho = std::hypot(p[0], p[1]);
    const double out[3] = {p[0] - p[0] / rho, p[1] - p[1] / rho, p[2]};  // from the core circle
    EXPECT_GT(n[0] * out[0] + n[1] * out[1] + n[2] * out[2], 0.0) << "vertex " << v;
  }
  // glTF too; --limit with a coarser --level is refused.
  ASSERT_EQ(cli({"synthesize", dir.file("in.sublift"), "--limit", "-o", dir.file("lim.glb")}).exit_code, 0);
  EXPECT_GT(std::filesystem::file_size(dir.file("lim.glb")), 12 * c.num_vertices);
  const ProcessResult bad = cli({"synthesize", dir.file("in.sublift"), "--limit", "--level", "1", "-o", dir.file("x.obj")});
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("--limit evaluates the finest level (3)"), std::string::npos) << bad.err;
}

TEST(CliCompress, UsageAndInputErrors) {
  TempDir dir("sublift_cli_compress_errors");
  write_project(dir.file("in.sublift"), project_hierarchy());
  const std::string in = dir.file("in.sublift"), out = dir.file("out.obj");
  struct Case {
    std::vector<std::string> args;
    int code;
    std::string message;
  };
  const std::vector<Case> cases = {
      {{"compress", in, "--keep", "0.2", "--linf", "0.01", "-o", out}, 2, "exactly one of"},
      {{"compress", in, "--keep", "0.2", "--threshold", "0.01", "-o", out}, 2, "exactly one of"},
      {{"compress", in, "-o", out}, 2, "exactly one of"},
      {{"compress", in, "--keep", "1.5", "-o", out}, 2, "--keep must be a fraction in 0..1"},
      {{"compress", in, "--keep", "-0.1", "-o", out}, 2, "--keep must be a fraction in 0..1"},
      {{"compress", in, "--keep", "half", "-o", out}, 2, "--keep needs a number"},
      {{"compress", in, "--linf", "-1", "-o", out}, 2, "must not be negative"},
      {{"compress", in, "--keep", "0.5"}, 2, "missing -o"},
      {{"compress", in, "--keep", "0.5", "--region", "cube:1", "-o", out}, 2, "--region"},
      {{"compress", in, "--keep", "0.5", "-o", dir.file("out.xyz")}, 2, ""},
      {{"compress", dir.file("missing.sublift"), "--keep", "0.5", "-o", out}, 1, "missing.sublift"},
      {{"compress", "--keep", "0.5", "-o", out}, 2, "PROJECT"},
      {{"compress", in, "--keep", "0.5", "--bits", "12", "-o", dir.file("q.sublift")}, 2, "--bits takes 8, 16 or 32, got '12'"},
      {{"compress", in, "--keep", "0.5", "--bits", "8", "-o", out}, 2, "--bits quantizes a project: OUT must be a .sublift file"},
  };
  for (const Case& c : cases) {
    const ProcessResult r = cli(c.args);
    EXPECT_EQ(r.exit_code, c.code) << c.args[2] << " " << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
  }
  EXPECT_FALSE(std::filesystem::exists(out));
  const ProcessResult help = cli({"compress", "--help"});
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.out.find("--threshold T"), std::string::npos);
}

}  // namespace
}  // namespace sublift
