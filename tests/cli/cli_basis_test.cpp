// sublift-cli basis (issue 5): PLY with a `value` property at the level J+K vertices, curve JSON,
// lattices, projects, the --json fields and the usage and input errors.
#include <cmath>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/multires/basis.h"
#include "core/complex/complex_build.h"
#include "core/base/file_io.h"
#include "core/multires/hierarchy.h"
#include "core/io/project/project_io.h"
#include "core/io/lattice/shape_io.h"
#include "core/complex/shapes.h"
#include "tests/io_test_util.h"
#include "tests/cli_run.h"

namespace sublift {
namespace {

using testing::ProcessResult;
using testing::TempDir;

ProcessResult cli(const std::vector<std::string>& args) { return testing::run_cli(args); }

struct Ply {
  std::size_t vertices = 0, faces = 0;
  bool has_value = false;
  std::vector<double> xyz, values;
};

Ply read_ply(const std::string& path) {
  std::istringstream in(read_file_bytes(path));
  Ply p;
  std::string line;
  while (std::getline(in, line) && line != "end_header") {
    std::istringstream l(line);
    std::string a, b;
    l >> a >> b;
    if (a == "element" && b == "vertex") l >> p.vertices;
    if (a == "element" && b == "face") l >> p.faces;
    if (line == "property double value") p.has_value = true;
  }
  for (std::size_t v = 0; v < p.vertices; ++v) {
    double x, y, z, f;
    in >> x >> y >> z >> f;
    p.xyz.insert(p.xyz.end(), {x, y, z});
    p.values.push_back(f);
  }
  return p;
}

// Level J of a base as the CLI builds it: complex and positions.
std::pair<Complex, std::vector<double>> level_of(const Complex& base, const std::vector<double>& pos, Scheme s, int J) {
  Hierarchy h = make_hierarchy(base, J, s, 3);
  set_base(h, pos);
  return {h.levels[std::size_t(J)], synthesize(h, J)};
}

TEST(CliBasis, SurfacePlyAndJson) {
  TempDir dir("sublift_cli_basis_surface");
  const SurfaceMesh m = make_quad_torus(8, 6);
  const Complex base = complex_from_surface_mesh(m);
  const std::vector<double> pos = flatten_positions(m);
  write_shape(dir.file("torus.obj"), base, pos);
  const ProcessResult r = cli({"basis", dir.file("torus.obj"), "--scheme", "cubic", "--level", "1", "--vertex", "5",
                               "--levels", "2", "-o", dir.file("phi.ply"), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["level"], 1);
  EXPECT_EQ(j["kind"], "scaling");
  EXPECT_EQ(j["index"], 5);
  EXPECT_EQ(j["dual"], false);
  EXPECT_EQ(j["levels"], 2);
  EXPECT_EQ(j["support_per_level"].size(), 3u);
  EXPECT_EQ(j["support_per_level"][0], 1);
  EXPECT_GT(j["support"].get<int>(), 9);
  EXPECT_NEAR(j["integral"].get<double>(), 0.25, 1e-12);  // a level-1 B-spline on unit base quads
  EXPECT_EQ(j["moments"].size(), 3u);
  EXPECT_NEAR(j["max"].get<double>(), 4.0 / 9.0, 1e-12);
  EXPECT_EQ(j["output"], dir.file("phi.ply"));

  const auto [level1, xyz1] = level_of(base, pos, Scheme::Cubic, 1);
  BasisRequest req;
  req.level = 1;
  req.index = 5;
  req.extra_levels = 2;
  std::vector<double> fine;
  const BasisFunction b = basis_function(level1, Scheme::Cubic, req, xyz1, &fine);
  const Ply p = read_ply(dir.file("phi.ply"));
  EXPECT_TRUE(p.has_value);
  ASSERT_EQ(p.vertices, b.finest.num_vertices);
  EXPECT_EQ(p.vertices, 48u * 64);
  EXPECT_EQ(p.faces, b.finest.num_faces());
  for (std::size_t v = 0; v < p.vertices; ++v) {
    ASSERT_EQ(p.values[v], b.values[v]) << v;  // 17 digits: exact
    ASSERT_EQ(p.xyz[3 * v], fine[3 * v]) << v;
  }

  // Wavelet and dual.
  const ProcessResult w = cli({"basis", dir.file("torus.obj"), "--scheme", "linear", "--level", "0", "--wavelet", "50",
                               "--dual", "-o", dir.file("w.ply"), "--json"});
  ASSERT_EQ(w.exit_code, 0) << w.err;
  const auto jw = nlohmann::json::parse(w.out);
  EXPECT_EQ(jw["kind"], "wavelet");
  EXPECT_EQ(jw["dual"], true);
  EXPECT_EQ(jw["levels"], 4);
  EXPECT_EQ(jw["support_per_level"][0], 0);
  EXPECT_NEAR(jw["integral"].get<double>(), 0.0, 1e-13);
}

TEST(CliBasis, CurveJsonLatticeAndProject) {
  TempDir dir("sublift_cli_basis_other");
  std::vector<double> cp;
  const Complex loop = make_curve_loop(10, cp);
  write_shape(dir.file("loop.obj"), loop, cp);
  const ProcessResult r =
      cli({"basis", dir.file("loop.obj"), "--scheme", "linear", "--level", "0", "--vertex", "3", "-o", dir.file("phi.json")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(read_file_bytes(dir.file("phi.json")));
  ASSERT_EQ(j["values"].size(), 10u * 64);  // default K = 6 for curves
  ASSERT_EQ(j["positions"].size(), 10u * 64);
  EXPECT_EQ(j["positions"][0].size(), 3u);
  EXPECT_EQ(j["values"][3], 1.0);
  double sum = 0;
  for (const auto& v : j["values"]) sum += v.get<double>();
  EXPECT_NEAR(sum, 64.0, 1e-12);  // hat of width 2 sampled at spacing 1/64

  std::vector<double> hp;
  const Complex block = make_hex_block(2, hp);
  write_shape(dir.file("block.lattice"), block, hp);
  const ProcessResult l = cli({"basis", dir.file("block.lattice"), "--scheme", "cubic", "--level", "0", "--vertex", "13",
                               "--levels", "2", "-o", dir.file("block.ply"), "--json"});
  ASSERT_EQ(l.exit_code, 0) << l.err;
  const Ply p = read_ply(dir.file("block.ply"));
  EXPECT_TRUE(p.has_value);
  EXPECT_EQ(p.vertices, 9u * 9 * 9);
  EXPECT_EQ(p.faces, 6u * 8 * 8);  // boundary quads of the level-2 block
  // The block's centre is one level-0 step from the boundary, whose surface rules cut the
  // function off: less than the interior B-spline's integral 1.
  const double integral = nlohmann::json::parse(l.out)["integral"].get<double>();
  EXPECT_GT(integral, 0.3);
  EXPECT_LT(integral, 1.0);

  // A project: its base and scheme.
  Hierarchy h = make_hierarchy(block, 1, Scheme::Linear, 3);
  set_base(h, hp);
  write_project(dir.file("block.sublift"), h);
  const ProcessResult q = cli({"basis", dir.file("block.sublift"), "--level", "0", "--vertex", "13", "--levels", "1",
                               "-o", dir.file("q.ply"), "--json"});
  ASSERT_EQ(q.exit_code, 0) << q.err;
  const auto jq = nlohmann::json::parse(q.out);
  EXPECT_EQ(jq["scheme"], "linear");
  EXPECT_EQ(jq["support"], 27);
}

TEST(CliBasis, Errors) {
  TempDir dir("sublift_cli_basis_errors");
  const SurfaceMesh m = make_quad_torus(8, 6);
  write_shape(dir.file("torus.obj"), complex_from_surface_mesh(m), flatten_positions(m));
  const std::string in = dir.file("torus.obj"), out = dir.file("o.ply");
  auto run = [&](std::vector<std::string> extra) {
    std::vector<std::string> args = {"basis", in};
    args.insert(args.end(), extra.begin(), extra.end());
    return cli(args);
  };
  ProcessResult r = run({"--scheme", "cubic", "--level", "0", "--wavelet", "7", "-o", out});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("v vertex"), std::string::npos) << r.err;
  r = run({"--scheme", "cubic", "--level", "0", "-o", out});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--vertex"), std::string::npos) << r.err;
  r = run({"--scheme", "cubic", "--level", "0", "--vertex", "1", "--wavelet", "60", "-o", out});
  EXPECT_EQ(r.exit_code, 2);
  r = run({"--scheme", "cubic", "--level", "11", "--vertex", "1", "-o", out});  // 48 * 4^11 vertices
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("levels"), std::string::npos) << r.err;
  r = run({"--scheme", "cubic", "--level", "13", "--vertex", "1", "-o", out});
  EXPECT_EQ(r.exit_code, 2);
  r = run({"--scheme", "cubic", "--level", "0", "--vertex", "48", "-o", out});
  EXPECT_EQ(r.exit_code, 2);
  r = run({"--scheme", "cubic", "--level", "0", "--wavelet", "48", "--levels", "0", "-o", out});
  EXPECT_EQ(r.exit_code, 2);
  r = run({"--scheme", "cubic", "--level", "0", "--vertex", "1", "-o", dir.file("o.json")});
  EXPECT_EQ(r.exit_code, 2);
  r = run({"--level", "0", "--vertex", "1", "-o", out});
  EXPECT_EQ(r.exit_code, 2);  // --scheme is required for shape files
  r = cli({"basis", dir.file("missing.obj"), "--scheme", "cubic", "--level", "0", "--vertex", "1", "-o", out});
  EXPECT_EQ(r.exit_code, 1);
  // A good wavelet on an edge vertex.
  r = run({"--scheme", "cubic", "--level", "0", "--wavelet", "48", "--levels", "1", "-o", out});
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

}  // namespace
}  // namespace sublift

namespace sublift {
namespace {

// Width and height from a PNG's IHDR chunk, or {0, 0} when `bytes` is not a PNG.
std::pair<std::uint32_t, std::uint32_t> png_size(const std::string& bytes) {
  if (bytes.size() < 24 || bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") != 0 || bytes.compare(12, 4, "IHDR") != 0) return {0, 0};
  auto be = [&](std::size_t at) {
    std::uint32_t v = 0;
    for (std::size_t i = 0; i < 4; ++i) v = (v << 8) | static_cast<unsigned char>(bytes[at + i]);
    return v;
  };
  return {be(16), be(20)};
}

// --png for a surface and a lattice: exit 0 and an 800x600 PNG. Skipped when the CLI has no
// renderer (SUBLIFT_WITH_GUI=OFF) or headless EGL is unavailable. Pixels are not decoded here
// (no PNG decoder in the tests): a uniform 800x600 picture compresses to well under 10 kB, so a
// larger file is taken as "something was drawn".
TEST(CliBasis, PngForSurfaceAndLattice) {
  TempDir dir("sublift_cli_basis_png");
  const std::string assets = SUBLIFT_ASSETS_DIR;
  const std::vector<std::vector<std::string>> cases = {
      {assets + "/quad_grid_boundary.obj", "--level", "1", "--wavelet", "120"},
      {assets + "/hex_block_4.lattice", "--level", "0", "--vertex", "62", "--levels", "2"}};
  for (const auto& c : cases) {
    const std::string png = (dir.path() / "b.png").string(), ply = (dir.path() / "b.ply").string();
    std::vector<std::string> args = {"basis"};
    args.insert(args.end(), c.begin(), c.end());
    args.insert(args.end(), {"--scheme", "cubic", "-o", ply, "--png", png});
    const ProcessResult r = cli(args);
    if (r.exit_code != 0 && (r.err.find("no renderer") != std::string::npos || r.err.find("EGL") != std::string::npos))
      GTEST_SKIP() << "no headless rendering here: " << r.err;
    ASSERT_EQ(r.exit_code, 0) << c[0] << ": " << r.err;
    const std::string bytes = read_file_bytes(png);
    EXPECT_EQ(png_size(bytes), (std::pair<std::uint32_t, std::uint32_t>(800, 600))) << c[0];
    EXPECT_GT(bytes.size(), 10000u) << c[0];
  }
}

}  // namespace
}  // namespace sublift
