// sublift-cli with --scheme sqrt2 (Wang & Ma's interpolatory sqrt(2) wavelets, paper 001), end to
// end through the binary: level counts against closed forms derived from the refinement rules
// (docs/sqrt2_refinement.md), interpolation of the old vertices, exact analysis/synthesis round
// trips (float and --integer), info/edit on sqrt2 projects, interpolating basis functions, the
// usage errors that only sqrt2 has, and the noise experiment.
#include <cmath>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/base/file_io.h"
#include "core/io/lattice/shape_io.h"
#include "tests/io_test_util.h"
#include "tests/cli_run.h"
#include "tests/run_process.h"

using sublift::testing::ProcessResult;
using sublift::testing::run_process;
using sublift::testing::TempDir;
using sublift::testing::move_vertex;
using sublift::testing::relative_error;
using nlohmann::json;

namespace {

const std::string kAssets = SUBLIFT_ASSETS_DIR;

ProcessResult cli(const std::vector<std::string>& args) { return sublift::testing::run_cli(args); }

// Runs and expects exit code 0; the parsed stdout when it is JSON, else null.
json ok(const std::vector<std::string>& args) {
  const ProcessResult r = cli(args);
  std::string joined;
  for (const auto& a : args) joined += a + " ";
  EXPECT_EQ(r.exit_code, 0) << joined << "\n" << r.err;
  EXPECT_FALSE(r.timed_out) << joined;
  return json::accept(r.out) ? json::parse(r.out) : json();
}

std::vector<double> positions(const std::string& path) { return sublift::read_shape(path).positions; }


double largest_abs(const std::vector<double>& a) {
  double m = 0;
  for (double x : a) m = std::max(m, std::abs(x));
  return m;
}


// Counts of a manifold surface as the sqrt(2) refinement rules act on them: S = sum of face
// sizes, C = curve edges (boundary and crease), Sc = (curve edge, face beside it) pairs.
struct Counts {
  std::uint64_t v, e, f, s, c, sc;
};

// Level J counts, derived by hand from docs/sqrt2_refinement.md, not from the engine:
// even levels are the Catmull-Clark topology (two sqrt2 steps = one 1-to-4 split):
//   V' = V + E + F, E' = 2E + S, F' = S, then all quads (S' = 4F'), curves split (C, Sc double);
// a keep step from an even level adds a face point per face, a quad per inner edge and a
// triangle per face beside a curve edge, and keeps the curve edges:
//   V' = V + F, E' = C + S, F' = (E - C) + Sc.
Counts sqrt2_counts(Counts b, int levels) {
  for (int j = 0; j + 2 <= levels; j += 2) {
    b = {b.v + b.e + b.f, 2 * b.e + b.s, b.s, 4 * b.s, 2 * b.c, 2 * b.sc};
  }
  if (levels % 2) b = {b.v + b.f, b.c + b.s, (b.e - b.c) + b.sc, 0, b.c, b.sc};
  return b;
}

struct Asset {
  std::string file;
  Counts base;  // from assets/README.md and the files' tags
};

// cube: closed; grid: 4 x 4 open (16 boundary edges); crease loop: a ring of 4 tagged crease
// edges (2 faces each); dart: 6 x 6 grid, 24 boundary edges plus 3 crease edges ending inside;
// mixed polygons: closed, 3-, 4- and 5-gons (sum of sizes = 2E).
const std::vector<Asset> kAssetsCounts = {
    {"cube.obj", {8, 12, 6, 24, 0, 0}},
    {"quad_grid_boundary.obj", {25, 40, 16, 64, 16, 16}},
    {"crease_loop.obj", {16, 28, 14, 56, 4, 8}},
    {"crease_dart_flat.obj", {49, 84, 36, 144, 27, 24 + 2 * 3}},
    {"mixed_polygons.obj", {11, 20, 11, 40, 0, 0}},
};

Counts base_counts(const std::string& file) {
  for (const Asset& a : kAssetsCounts)
    if (a.file == file) return a.base;
  ADD_FAILURE() << "no counts for " << file;
  return {};
}

// Values of the 'value' property of an ASCII PLY written by 'basis'.
std::vector<double> ply_values(const std::string& path) {
  std::istringstream in(sublift::read_file_bytes(path));
  std::string line;
  std::size_t n = 0;
  while (std::getline(in, line) && line != "end_header")
    if (line.rfind("element vertex ", 0) == 0) n = std::stoul(line.substr(15));
  std::vector<double> values;
  for (std::size_t i = 0; i < n && std::getline(in, line); ++i) {
    std::istringstream l(line);
    double x, y, z, v;
    l >> x >> y >> z >> v;
    values.push_back(v);
  }
  EXPECT_EQ(values.size(), n) << path;
  return values;
}

}  // namespace

TEST(CliSqrt2, SubdivideCountsFollowTheClosedForms) {
  // The closed cube by hand too: F_j = 6 * 2^j, V_j = 2 + 6 * 2^j (Euler, all quads from level 1).
  for (int j : {1, 2, 3, 5}) {
    const Counts c = sqrt2_counts(kAssetsCounts[0].base, j);
    EXPECT_EQ(c.f, 6u << j);
    EXPECT_EQ(c.v, 2 + (6u << j));
  }
  TempDir dir("sublift_cli_sqrt2_counts");
  for (const Asset& a : kAssetsCounts) {
    for (int J : {1, 2, 3, 5}) {
      SCOPED_TRACE(a.file + " J=" + std::to_string(J));
      const json j = ok({"subdivide", kAssets + "/" + a.file, "--scheme", "sqrt2", "--levels", std::to_string(J), "-o",
                         dir.file("s.obj"), "--json"});
      ASSERT_TRUE(j.is_object());
      const Counts want = sqrt2_counts(a.base, J);
      EXPECT_EQ(j["scheme"], "sqrt2");
      EXPECT_EQ(j["base"]["vertices"], a.base.v);
      EXPECT_EQ(j["base"]["faces"], a.base.f);
      EXPECT_EQ(j["finest"]["dim"], 2);
      EXPECT_EQ(j["finest"]["vertices"], want.v);
      EXPECT_EQ(j["finest"]["edges"], want.e);
      EXPECT_EQ(j["finest"]["faces"], want.f);
      EXPECT_EQ(j["vertices"], want.v);
      // Euler characteristic is kept (2 for the closed spheres, 1 for the disks).
      const long long chi = (long long)want.v - (long long)want.e + (long long)want.f;
      EXPECT_EQ(chi, (long long)a.base.v - (long long)a.base.e + (long long)a.base.f);
      if (J % 2 == 0) {
        // Two sqrt2 levels are one Catmull-Clark level: the same counts as the cubic scheme.
        const json c = ok({"subdivide", kAssets + "/" + a.file, "--scheme", "cubic", "--levels", std::to_string(J / 2),
                           "-o", dir.file("c.obj"), "--json"});
        ASSERT_TRUE(c.is_object());
        for (const char* key : {"vertices", "edges", "faces"}) EXPECT_EQ(j["finest"][key], c["finest"][key]) << key;
      }
    }
  }
}

TEST(CliSqrt2, SubdivideKeepsOldVerticesExactly) {
  // Interpolatory: level j's vertices are the first V_j vertices of every finer level, bit for bit
  // (the .obj files carry 17 significant digits, so the text round trip is exact).
  TempDir dir("sublift_cli_sqrt2_interp");
  for (const Asset& a : kAssetsCounts) {
    SCOPED_TRACE(a.file);
    const std::string in = kAssets + "/" + a.file;
    std::vector<double> coarser = positions(in);
    ASSERT_EQ(coarser.size(), 3 * a.base.v);
    for (int J : {1, 2, 3, 5}) {
      const std::string out = dir.file(std::to_string(J) + "_levels.obj");
      ok({"subdivide", in, "--scheme", "sqrt2", "--levels", std::to_string(J), "-o", out});
      const std::vector<double> fine = positions(out);
      ASSERT_EQ(fine.size(), 3 * sqrt2_counts(a.base, J).v) << J;
      ASSERT_GT(fine.size(), coarser.size());
      EXPECT_TRUE(std::equal(coarser.begin(), coarser.end(), fine.begin())) << "level " << J;
      coarser = fine;
    }
  }
}

TEST(CliSqrt2, AnalyzeSynthesizeRoundTrip) {
  TempDir dir("sublift_cli_sqrt2_roundtrip");
  const std::vector<std::pair<std::string, int>> cases = {
      {"cube.obj", 3}, {"quad_grid_boundary.obj", 2}, {"crease_loop.obj", 3}, {"crease_dart_flat.obj", 2},
      {"mixed_polygons.obj", 1}};
  for (const auto& [file, J] : cases) {
    SCOPED_TRACE(file + " J=" + std::to_string(J));
    const std::string base = kAssets + "/" + file, fine = dir.file("fine.obj"), project = dir.file("p.sublift");
    const std::vector<std::string> flags = {"--scheme", "sqrt2", "--levels", std::to_string(J)};
    auto with = [&](std::vector<std::string> a) {
      a.insert(a.end(), flags.begin(), flags.end());
      return a;
    };
    ok(with({"subdivide", base, "-o", fine}));
    const double scale = largest_abs(positions(fine));
    // A pure subdivision has no detail: all wavelets are round-off.
    const json an = ok(with({"analyze", fine, "--base", base, "-o", project, "--json"}));
    ASSERT_TRUE(an.is_object());
    EXPECT_EQ(an["scheme"], "sqrt2");
    ASSERT_EQ(an["per_level"].size(), std::size_t(J));
    for (const auto& l : an["per_level"]) EXPECT_LT(l["wavelet_max"].get<double>(), 1e-12 * scale) << l.dump();
    ok({"synthesize", project, "--level", std::to_string(J), "-o", dir.file("back.obj")});
    EXPECT_LT(relative_error(positions(fine), positions(dir.file("back.obj"))), 1e-12);

    // Perturbed: the wavelets carry the detail and the reconstruction is still exact.
    const std::string moved = move_vertex(sublift::read_file_bytes(fine), 10, 0.25);
    std::ofstream(fine) << moved;  // read first: the stream truncates the file
    const json an2 = ok(with({"analyze", fine, "--base", base, "-o", project, "--json"}));
    ASSERT_TRUE(an2.is_object());
    double largest = 0;
    for (const auto& l : an2["per_level"]) largest = std::max(largest, l["wavelet_max"].get<double>());
    EXPECT_GT(largest, 0.01);
    ok({"synthesize", project, "-o", dir.file("back2.obj")});
    EXPECT_LT(relative_error(positions(fine), positions(dir.file("back2.obj"))), 1e-12);
    // Coarser levels of the project have the sqrt2 counts.
    for (int l = 0; l < J; ++l) {
      const json s = ok({"synthesize", project, "--level", std::to_string(l), "-o", dir.file("lv.obj"), "--json"});
      EXPECT_EQ(s["vertices"], sqrt2_counts(base_counts(file), l).v) << "level " << l;
    }
  }
}

TEST(CliSqrt2, IntegerTransformIsLossless) {
  // Both have integer coordinates; an integer perturbation keeps them integer. The dart adds
  // curve points and a crease ending inside.
  TempDir dir("sublift_cli_sqrt2_int");
  const std::vector<std::pair<std::string, int>> cases = {
      {"cube.obj", 2}, {"cube.obj", 3}, {"crease_dart_flat.obj", 3}};
  for (const auto& [file, J] : cases) {
    SCOPED_TRACE(file + " J=" + std::to_string(J));
    const std::string base = kAssets + "/" + file, fine = dir.file("fine.obj"), project = dir.file("p.sublift");
    const std::vector<std::string> flags = {"--scheme", "sqrt2", "--levels", std::to_string(J), "--integer"};
    auto with = [&](std::vector<std::string> a) {
      a.insert(a.end(), flags.begin(), flags.end());
      return a;
    };
    ok(with({"subdivide", base, "-o", fine}));
    for (double x : positions(fine)) EXPECT_EQ(x, std::round(x));  // every lifting term rounded
    const std::string moved = move_vertex(sublift::read_file_bytes(fine), 11, 7.0);
    std::ofstream(fine) << moved;  // read first: the stream truncates the file
    const json an = ok(with({"analyze", fine, "--base", base, "-o", project, "--json"}));
    ASSERT_TRUE(an.is_object());
    EXPECT_EQ(an["integer"], true);
    double largest = 0;
    for (const auto& l : an["per_level"]) largest = std::max(largest, l["wavelet_max"].get<double>());
    EXPECT_GE(largest, 1.0);  // the moved vertex left integer detail
    ok({"synthesize", project, "-o", dir.file("back.obj")});
    EXPECT_TRUE(positions(fine) == positions(dir.file("back.obj")));
    const json info = ok({"info", project, "--json"});
    EXPECT_EQ(info["integer"], true);
    EXPECT_EQ(info["scheme"], "sqrt2");
  }
}

TEST(CliSqrt2, InfoAndEditOnASqrt2Project) {
  TempDir dir("sublift_cli_sqrt2_edit");
  const std::string base = kAssets + "/torus_quad.obj", fine = dir.file("fine.obj"), project = dir.file("p.sublift");
  const int J = 4;
  ok({"subdivide", base, "--scheme", "sqrt2", "--levels", "4", "-o", fine});
  // Detail next to the edited vertex 17 (vertex 900 is 0.76 from it), so local frames matter.
  const std::string moved = move_vertex(move_vertex(sublift::read_file_bytes(fine), 17, 0.05), 900, 0.05);
  std::ofstream(fine) << moved;  // read first: the stream truncates the file
  ok({"analyze", fine, "--base", base, "--scheme", "sqrt2", "--levels", "4", "-o", project});

  // The closed torus (12 x 8, chi = 0): V_j = F_j = 96 * 2^j.
  const json info = ok({"info", project, "--json"});
  ASSERT_TRUE(info.is_object());
  EXPECT_EQ(info["scheme"], "sqrt2");
  EXPECT_EQ(info["levels"], J);
  EXPECT_EQ(info["dim"], 2);
  EXPECT_EQ(info["vertices"], 96);
  EXPECT_EQ(info["finest_vertices"], 96 << J);
  ASSERT_EQ(info["per_level"].size(), std::size_t(J));
  for (int l = 0; l < J; ++l) {
    EXPECT_EQ(info["per_level"][l]["level"], l);
    EXPECT_EQ(info["per_level"][l]["vertices"], 96 << l);
    EXPECT_EQ(info["per_level"][l]["wavelets"], 96 << l);  // one face point per face
  }
  const ProcessResult text = cli({"info", project});
  EXPECT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("sqrt2 scheme"), std::string::npos) << text.out;

  ok({"synthesize", project, "-o", dir.file("orig.obj")});
  const std::vector<double> orig = positions(dir.file("orig.obj"));
  const std::size_t n = orig.size() / 3;
  const int level = 2, vertex = 17;
  const double px = orig[3 * vertex], py = orig[3 * vertex + 1], pz = orig[3 * vertex + 2];
  std::vector<double> world;
  for (const bool local : {false, true}) {
    SCOPED_TRACE(local ? "local frames" : "world frames");
    std::vector<std::string> args = {"edit", project, "--level", std::to_string(level), "--vertex", std::to_string(vertex),
                                     "--delta", "0", "0", "0.3", "-o", dir.file("e.obj"), "--json"};
    if (local) args.push_back("--local-frames");
    const json e = ok(args);
    ASSERT_TRUE(e.is_object());
    EXPECT_EQ(e["detail_frames"], local ? "local" : "world");
    EXPECT_EQ(e["finest_vertices"], 96 << J);
    const std::vector<double> edited = positions(dir.file("e.obj"));
    ASSERT_EQ(edited.size(), orig.size());
    // The edited vertex itself moved (interpolatory: in world frames by exactly the delta, as
    // the stored detail is added unchanged); far from it nothing changed. Far: beyond 1.2 on this
    // torus of radii 1 and 0.4 (diameter 2.8), about 4 outer level-2 edges (0.37 long). Local
    // frames also turn the detail wherever the level-2 surface turned, which reaches further:
    // beyond 2.0 (we saw changes up to 1.57).
    const double far = local ? 2.0 : 1.2;
    std::size_t changed = 0, far_changed = 0;
    for (std::size_t v = 0; v < n; ++v) {
      double d2 = 0, m2 = 0;
      for (int k = 0; k < 3; ++k) {
        const double dk = edited[3 * v + k] - orig[3 * v + k];
        m2 += dk * dk;
      }
      const double dx = orig[3 * v] - px, dy = orig[3 * v + 1] - py, dz = orig[3 * v + 2] - pz;
      d2 = dx * dx + dy * dy + dz * dz;
      if (m2 > 1e-24) {
        ++changed;
        if (d2 > far * far) ++far_changed;
      }
    }
    if (!local) {
      EXPECT_NEAR(edited[3 * vertex] - orig[3 * vertex], 0.0, 1e-12);
      EXPECT_NEAR(edited[3 * vertex + 2] - orig[3 * vertex + 2], 0.3, 1e-12);
      world = edited;
    } else {
      EXPECT_GT(relative_error(world, edited), 1e-4);  // the detail near vertex 17 turned
    }
    EXPECT_GT(changed, 0u);
    EXPECT_LT(changed, local ? n / 2 : n / 8);
    EXPECT_EQ(far_changed, 0u);

    // The same edit written as a project reads back and synthesises to the same shape.
    args[11] = dir.file("e.sublift");
    ok(args);
    const json ei = ok({"info", dir.file("e.sublift"), "--json"});
    ASSERT_TRUE(ei.is_object());
    EXPECT_EQ(ei["scheme"], "sqrt2");
    EXPECT_EQ(ei["levels"], J);
    ok({"synthesize", dir.file("e.sublift"), "-o", dir.file("e2.obj")});
    EXPECT_LT(relative_error(edited, positions(dir.file("e2.obj"))), 1e-12);
  }
}

TEST(CliSqrt2, ScalingFunctionsInterpolate) {
  // An interpolatory scheme's scaling function is 1 at its own vertex and 0 at the other level-J
  // vertices, which keep their indices at every finer level (engine order).
  TempDir dir("sublift_cli_sqrt2_basis");
  struct Case {
    std::string file;
    int J;
    std::uint32_t vertex;
  };
  const std::vector<Case> cases = {{"cube.obj", 1, 3}, {"quad_grid_boundary.obj", 2, 40}, {"crease_loop.obj", 1, 5},
                                   {"crease_dart_flat.obj", 0, 24}, {"mixed_polygons.obj", 3, 0}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.file + " J=" + std::to_string(c.J));
    const Counts base = base_counts(c.file);
    const std::uint64_t nJ = sqrt2_counts(base, c.J).v, nJ1 = sqrt2_counts(base, c.J + 1).v;
    ASSERT_LT(c.vertex, nJ);
    const std::string in = kAssets + "/" + c.file, out = dir.file("b.ply");
    const json j = ok({"basis", in, "--scheme", "sqrt2", "--level", std::to_string(c.J), "--vertex",
                       std::to_string(c.vertex), "--levels", "4", "-o", out, "--json"});
    ASSERT_TRUE(j.is_object());
    EXPECT_EQ(j["scheme"], "sqrt2");
    EXPECT_EQ(j["vertices"], sqrt2_counts(base, c.J + 4).v);
    EXPECT_GE(j["max"].get<double>(), 1.0);
    const std::vector<double> values = ply_values(out);
    ASSERT_EQ(values.size(), sqrt2_counts(base, c.J + 4).v);
    EXPECT_EQ(values[c.vertex], 1.0);
    double other = 0;
    for (std::uint64_t v = 0; v < nJ; ++v)
      if (v != c.vertex) other = std::max(other, std::abs(values[v]));
    EXPECT_LT(other, 1e-12);

    // The wavelet of the first new vertex and the dual functions run; the dual functions are
    // rows of the analysis: a constant has coefficient 1 and zero wavelets, so the dual scaling
    // function's weights sum to 1 and the dual wavelet's to 0.
    const std::string w = std::to_string(nJ);
    const json jw = ok({"basis", in, "--scheme", "sqrt2", "--level", std::to_string(c.J), "--wavelet", w, "--levels", "3",
                        "-o", out, "--json"});
    ASSERT_TRUE(jw.is_object());
    EXPECT_EQ(jw["kind"], "wavelet");
    EXPECT_GT(jw["support"].get<std::uint64_t>(), 0u);
    ASSERT_LT(nJ, nJ1);
    const json jd = ok({"basis", in, "--scheme", "sqrt2", "--level", std::to_string(c.J), "--vertex",
                        std::to_string(c.vertex), "--dual", "--levels", "2", "-o", out, "--json"});
    ASSERT_TRUE(jd.is_object());
    double sum = 0;
    for (double x : ply_values(out)) sum += x;
    EXPECT_NEAR(sum, 1.0, 1e-12);
    ok({"basis", in, "--scheme", "sqrt2", "--level", std::to_string(c.J), "--wavelet", w, "--dual", "--levels", "2", "-o",
        out});
    sum = 0;
    for (double x : ply_values(out)) sum += x;
    EXPECT_NEAR(sum, 0.0, 1e-12);
  }
}

TEST(CliSqrt2, UsageErrorsExplainWhatIsWrong) {
  TempDir dir("sublift_cli_sqrt2_usage");
  const std::string cube = kAssets + "/cube.obj", curve = kAssets + "/curves/curve.obj",
                    lattice = kAssets + "/cube_cell.lattice";
  struct Bad {
    std::vector<std::string> args;
    std::vector<std::string> words;  // the message must name what is wrong
  };
  const std::vector<Bad> bad = {
      {{"subdivide", curve, "--scheme", "sqrt2", "--levels", "2", "-o", dir.file("c.obj")}, {"surfaces only", "curve"}},
      {{"subdivide", lattice, "--scheme", "sqrt2", "--levels", "2", "-o", dir.file("l.lattice")},
       {"surfaces only", "lattice"}},
      {{"analyze", curve, "--base", curve, "--scheme", "sqrt2", "--levels", "1", "-o", dir.file("p.sublift")},
       {"surfaces only", "curve"}},
      {{"basis", curve, "--scheme", "sqrt2", "--level", "1", "--vertex", "0", "-o", dir.file("b.json")},
       {"surfaces only", "curve"}},
      {{"experiment", "noise", "--scheme", "sqrt2", "--model", lattice, "--levels", "1", "--sigma", "0.01"},
       {"surfaces only", "lattice"}},
      {{"subdivide", cube, "--scheme", "sqrt2", "--levels", "25", "-o", dir.file("o.obj")}, {"0..24", "'25'"}},
      {{"subdivide", cube, "--scheme", "cubic", "--levels", "13", "-o", dir.file("o.obj")}, {"0..12", "'13'"}},
      {{"subdivide", cube, "--scheme", "sqrt3", "--levels", "2", "-o", dir.file("o.obj")},
       {"linear, cubic, sqrt2", "'sqrt3'"}},
      // In range, but the cube at level 24 has 2 + 6 * 2^24 vertices: refused before allocating.
      {{"subdivide", cube, "--scheme", "sqrt2", "--levels", "24", "-o", dir.file("o.obj")}, {"more than the limit"}},
  };
  for (const Bad& b : bad) {
    const ProcessResult r = cli(b.args);
    std::string joined;
    for (const auto& a : b.args) joined += a + " ";
    EXPECT_EQ(r.exit_code, 2) << joined << "\n" << r.err;
    EXPECT_NE(r.err.find("sublift-cli " + b.args[0]), std::string::npos) << r.err;
    for (const std::string& w : b.words) EXPECT_NE(r.err.find(w), std::string::npos) << joined << "\n" << r.err;
    EXPECT_TRUE(r.out.empty()) << joined;
  }
  EXPECT_FALSE(std::filesystem::exists(dir.file("o.obj")));
  EXPECT_FALSE(std::filesystem::exists(dir.file("c.obj")));
  // sqrt2 accepts more levels than cubic: 13 is fine on a small base.
  ok({"subdivide", kAssets + "/pyramid.obj", "--scheme", "sqrt2", "--levels", "13", "-o", dir.file("p.ply")});
}

TEST(CliSqrt2, NoiseExperimentRuns) {
  const json j = ok({"experiment", "noise", "--scheme", "sqrt2", "--model", kAssets + "/torus_quad.obj", "--levels", "4",
                     "--sigma", "0.01", "--seed", "3", "--json"});
  ASSERT_TRUE(j.is_object());
  EXPECT_EQ(j["scheme"], "sqrt2");
  EXPECT_EQ(j["finest_level"], 4);
  EXPECT_EQ(j["finest_vertices"], 96 << 4);
  ASSERT_EQ(j["levels"].size(), 5u);
  EXPECT_EQ(j["levels"][0]["level"], 4);
  EXPECT_EQ(j["levels"][0]["ratio"], 1.0);
  // Low-pass filtering white noise: less noise at every coarser level.
  for (std::size_t k = 1; k < 5; ++k)
    EXPECT_LT(j["levels"][k]["ratio"].get<double>(), j["levels"][k - 1]["ratio"].get<double>()) << k;
}
