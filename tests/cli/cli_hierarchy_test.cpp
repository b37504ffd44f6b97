// sublift-cli subdivide / analyze / synthesize / info on projects, end to end as a script
// would run them: exact reconstruction, --keep 0 = subdivision of the base, JSON fields,
// usage and input errors.
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/base/file_io.h"
#include "core/base/magnitude.h"
#include "core/io/project/project_io.h"
#include "core/multires/hierarchy.h"
#include "core/io/lattice/shape_io.h"
#include "tests/io_test_util.h"
#include "tests/cli_run.h"
#include "tests/run_process.h"

namespace fs = std::filesystem;
using sublift::testing::ProcessResult;
using sublift::testing::run_process;
using sublift::testing::TempDir;
using sublift::testing::move_vertex;
using sublift::testing::relative_error;

namespace {

const std::string kAssets = SUBLIFT_ASSETS_DIR;

ProcessResult cli(const std::vector<std::string>& args) { return sublift::testing::run_cli(args); }

void ok(const ProcessResult& r) {
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(r.timed_out);
}

std::vector<double> positions(const std::string& path) { return sublift::read_shape(path).positions; }


struct Input {
  std::string base;  // path
  std::string out_ext;
};


// A curve with integer coordinates (open chain and closed loop).
std::string integer_curve(const TempDir& dir) {
  const std::string path = dir.file("curve_int.obj");
  std::ofstream(path) << "v 0 0 0\nv 4 0 0\nv 8 4 0\nv 8 8 4\nv -4 0 0\nv -8 4 0\nv -4 8 0\n"
                         "l 1 2 3 4\nl 1 5 6 7 1\n";
  return path;
}

}  // namespace

TEST(CliHierarchy, SubdivideAnalyzeSynthesizeReproduces) {
  TempDir dir("sublift_cli_roundtrip");
  const std::vector<Input> inputs = {{kAssets + "/cube.obj", "obj"},           {kAssets + "/crease_loop.obj", "obj"},
                                     {kAssets + "/mixed_polygons.obj", "ply"}, {integer_curve(dir), "obj"},
                                     {kAssets + "/cube_cell.lattice", "lattice"}, {kAssets + "/prism_ring.lattice", "vtk"},
                                     {kAssets + "/pyramid_cell.lattice", "lattice"},
                                     {kAssets + "/feature_surface.lattice", "vtk"}};
  for (const Input& in : inputs) {
    for (const char* scheme : {"linear", "cubic"}) {
      for (bool integer : {false, true}) {
        SCOPED_TRACE(in.base + " " + scheme + (integer ? " --integer" : ""));
        const std::string fine = dir.file("fine." + in.out_ext), back = dir.file("back." + in.out_ext);
        const std::string keep0 = dir.file("keep0." + in.out_ext), project = dir.file("p.sublift");
        std::vector<std::string> flags = {"--scheme", scheme, "--levels", "2"};
        if (integer) flags.push_back("--integer");
        auto with = [&](std::vector<std::string> a) {
          a.insert(a.end(), flags.begin(), flags.end());
          return a;
        };
        ok(cli(with({"subdivide", in.base, "-o", fine})));
        ok(cli(with({"analyze", fine, "--base", in.base, "-o", project})));
        ok(cli({"synthesize", project, "-o", back}));
        ok(cli({"synthesize", project, "--keep", "0", "-o", keep0}));
        const auto a = positions(fine), b = positions(back), k = positions(keep0);
        if (integer) {
          // Integer inputs, integer transform: bit-exact, files identical.
          EXPECT_EQ(a, b);
          EXPECT_EQ(a, k);
          EXPECT_TRUE(sublift::read_file_bytes(fine) == sublift::read_file_bytes(back));
        } else {
          EXPECT_LT(relative_error(a, b), 1e-12);
          EXPECT_LT(relative_error(a, k), 1e-12);
        }
      }
    }
  }
}

TEST(CliHierarchy, KeepZeroIsTheSubdivisionOfTheBase) {
  TempDir dir("sublift_cli_keep");
  // A finest shape that is not a pure subdivision: perturb the subdivided torus.
  const std::string base = kAssets + "/torus_quad.obj", fine = dir.file("fine.obj");
  ok(cli({"subdivide", base, "--scheme", "cubic", "--levels", "2", "-o", fine}));
  const std::string moved = move_vertex(sublift::read_file_bytes(fine), 300, 0.25);
  std::ofstream(fine) << moved;
  const std::string project = dir.file("p.sublift");
  ok(cli({"analyze", fine, "--base", base, "--scheme", "cubic", "--levels", "2", "-o", project}));
  ok(cli({"synthesize", project, "--keep", "0", "-o", dir.file("k0.obj")}));
  ok(cli({"subdivide", base, "--scheme", "cubic", "--levels", "2", "-o", dir.file("sub.obj")}));
  const auto k0 = positions(dir.file("k0.obj")), sub = positions(dir.file("sub.obj"));
  const double err = relative_error(sub, k0);
  EXPECT_GT(err, 0.0);   // the base itself changed: analysis is not interpolation
  EXPECT_LT(err, 0.1);
  // It is a pure subdivision: analysing it again leaves only round-off in the wavelets.
  const std::string again = dir.file("again.sublift");
  ok(cli({"analyze", dir.file("k0.obj"), "--base", base, "--scheme", "cubic", "--levels", "2", "-o", again}));
  const auto stats = nlohmann::json::parse(cli({"info", again, "--json"}).out);
  for (const auto& l : stats["per_level"]) EXPECT_LT(l["wavelet_max"].get<double>(), 1e-12);
  ok(cli({"synthesize", project, "--keep", "1", "-o", dir.file("k1.obj")}));
  EXPECT_LT(relative_error(positions(fine), positions(dir.file("k1.obj"))), 1e-12);
  // Level 0 of the project is the analysed base; level 1 has the refined count.
  const ProcessResult r = cli({"synthesize", project, "--level", "1", "-o", dir.file("l1.obj"), "--json"});
  ok(r);
  EXPECT_EQ(nlohmann::json::parse(r.out)["vertices"], 96 * 4);
}

TEST(CliHierarchy, KeepZeroEqualsSubdivideOfTheBaseExactlyInIntegerMode) {
  TempDir dir("sublift_cli_keep_int");
  const std::string base = kAssets + "/cube_cell.lattice", fine = dir.file("fine.lattice");
  ok(cli({"subdivide", base, "--scheme", "cubic", "--levels", "3", "--integer", "-o", fine}));
  // Perturb: analysing gives non-zero wavelets; --keep 0 drops them.
  const std::string moved = move_vertex(sublift::read_file_bytes(fine), 40, 7.0);
  std::ofstream(fine) << moved;
  const std::string project = dir.file("p.sublift");
  ok(cli({"analyze", fine, "--base", base, "--scheme", "cubic", "--levels", "3", "--integer", "-o", project}));
  ok(cli({"synthesize", project, "-o", dir.file("back.lattice")}));
  EXPECT_TRUE(positions(fine) == positions(dir.file("back.lattice")));  // bit-exact reconstruction
  // --keep 0 is a pure subdivision of the project's base: analysing it again gives exactly
  // zero wavelets and the same level-0 control net.
  ok(cli({"synthesize", project, "--keep", "0", "-o", dir.file("k0.lattice")}));
  EXPECT_FALSE(positions(dir.file("k0.lattice")) == positions(fine));
  const std::string again = dir.file("again.sublift");
  ok(cli({"analyze", dir.file("k0.lattice"), "--base", base, "--scheme", "cubic", "--levels", "3", "--integer", "-o", again}));
  const auto stats = nlohmann::json::parse(cli({"info", again, "--json"}).out);
  for (const auto& l : stats["per_level"]) EXPECT_EQ(l["wavelet_max"].get<double>(), 0.0);
  ok(cli({"synthesize", project, "--level", "0", "-o", dir.file("b0.lattice")}));
  ok(cli({"synthesize", again, "--level", "0", "-o", dir.file("b1.lattice")}));
  EXPECT_TRUE(positions(dir.file("b0.lattice")) == positions(dir.file("b1.lattice")));
  const ProcessResult info = cli({"info", project, "--json"});
  ok(info);
  const auto j = nlohmann::json::parse(info.out);
  double largest = 0;
  for (const auto& l : j["per_level"]) largest = std::max(largest, l["wavelet_max"].get<double>());
  EXPECT_GT(largest, 0.0);
}

TEST(CliHierarchy, InfoOnProjectHasLevelsAndPerLevelStats) {
  TempDir dir("sublift_cli_info");
  const std::string base = kAssets + "/hex_block_4.lattice";
  ok(cli({"subdivide", base, "--scheme", "linear", "--levels", "2", "-o", dir.file("f.vtk")}));
  ok(cli({"analyze", dir.file("f.vtk"), "--base", base, "--scheme", "linear", "--levels", "2", "-o", dir.file("p.sublift")}));
  const ProcessResult r = cli({"info", dir.file("p.sublift"), "--json"});
  ok(r);
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["levels"], 2);
  EXPECT_EQ(j["scheme"], "linear");
  EXPECT_EQ(j["integer"], false);
  EXPECT_EQ(j["channels"], 3);
  EXPECT_EQ(j["dim"], 3);
  EXPECT_EQ(j["vertices"], 125);
  EXPECT_EQ(j["cells"], 64);
  EXPECT_EQ(j["finest_vertices"], 33 * 33 * 33 / 33 / 33 * 0 + 17 * 17 * 17);
  ASSERT_TRUE(j["per_level"].is_array());
  ASSERT_EQ(j["per_level"].size(), 2u);
  const std::uint64_t verts[2] = {125, 9 * 9 * 9};
  for (std::size_t l = 0; l < 2; ++l) {
    const auto& s = j["per_level"][l];
    EXPECT_EQ(s["level"], l);
    EXPECT_EQ(s["vertices"], verts[l]);
    EXPECT_TRUE(s["wavelet_max"].is_number());
    EXPECT_TRUE(s["wavelet_rms"].is_number());
    EXPECT_LT(s["wavelet_max"].get<double>(), 1e-12);  // a pure subdivision has no detail
    EXPECT_LE(s["wavelet_rms"].get<double>(), s["wavelet_max"].get<double>());
  }
  const ProcessResult text = cli({"info", dir.file("p.sublift")});
  ok(text);
  EXPECT_NE(text.out.find("levels:"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("level 1:"), std::string::npos) << text.out;
}

TEST(CliHierarchy, InfoOnLatticeAssetsMatchesTheirConstruction) {
  // Counts follow from how scripts/make_assets.py builds each lattice (assets/README.md).
  struct Known { const char* file; int v, e, f, c; };
  const Known known[] = {{"cube_cell.lattice", 8, 12, 6, 1},       {"hex_block_4.lattice", 125, 300, 240, 64},
                         {"pyramid_cell.lattice", 5, 8, 5, 1},     {"prism_ring.lattice", 18, 8 * 3 + 8 + 8 + 1, 8 * 2 + 8 + 8, 8},
                         {"swept_quads.lattice", 108, 252, 192, 48}, {"feature_surface.lattice", 80, 184, 141, 36}};
  for (const Known& k : known) {
    const ProcessResult r = cli({"info", kAssets + "/" + k.file, "--json"});
    ok(r);
    EXPECT_TRUE(r.err.empty()) << k.file << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["dim"], 3) << k.file;
    EXPECT_EQ(j["vertices"], k.v) << k.file;
    EXPECT_EQ(j["edges"], k.e) << k.file;
    EXPECT_EQ(j["faces"], k.f) << k.file;
    EXPECT_EQ(j["cells"], k.c) << k.file;
  }
  const auto feat = nlohmann::json::parse(cli({"info", kAssets + "/feature_surface.lattice", "--json"}).out);
  EXPECT_EQ(feat["feature_dims"]["faces"]["2"], 66 + 9);  // boundary + the 9 tagged inner faces
  const auto curve = nlohmann::json::parse(cli({"info", kAssets + "/curves/curve.obj", "--json"}).out);
  EXPECT_EQ(curve["polylines"], 2);
  EXPECT_EQ(curve["closed_polylines"], 1);
  EXPECT_EQ(curve["polyline_segments"], 5 + 8);
}

TEST(CliHierarchy, ConvertMovesLatticesBetweenFormatsWithFeatures) {
  TempDir dir("sublift_cli_convert_lattice");
  const std::string in = kAssets + "/feature_surface.lattice";
  ok(cli({"convert", in, "-o", dir.file("a.vtk")}));
  ok(cli({"convert", dir.file("a.vtk"), "-o", dir.file("b.lattice")}));
  const auto a = nlohmann::json::parse(cli({"info", in, "--json"}).out);
  const auto b = nlohmann::json::parse(cli({"info", dir.file("b.lattice"), "--json"}).out);
  for (const char* key : {"vertices", "edges", "faces", "cells", "feature_dims", "bbox"}) EXPECT_EQ(a[key], b[key]) << key;
  EXPECT_EQ(cli({"convert", kAssets + "/cube.obj", "-o", dir.file("c.lattice")}).exit_code, 2);
}

TEST(CliHierarchy, JsonOutputIsOneDocument) {
  TempDir dir("sublift_cli_json");
  const std::string base = kAssets + "/curves/curve.obj";
  const ProcessResult s = cli({"subdivide", base, "--scheme", "cubic", "--levels", "3", "-o", dir.file("f.obj"), "--json"});
  ok(s);
  const auto j = nlohmann::json::parse(s.out);
  EXPECT_EQ(j["vertices"], 14 + 13 * (1 + 2 + 4));
  EXPECT_EQ(j["finest"]["dim"], 1);
  const ProcessResult a =
      cli({"analyze", dir.file("f.obj"), "--base", base, "--scheme", "cubic", "--levels", "3", "-o", dir.file("p.sublift"), "--json"});
  ok(a);
  EXPECT_TRUE(nlohmann::json::accept(a.out)) << a.out;
  const ProcessResult y = cli({"synthesize", dir.file("p.sublift"), "--keep", "0.5", "-o", dir.file("h.vtk"), "--json"});
  ok(y);
  const auto jy = nlohmann::json::parse(y.out);
  EXPECT_EQ(jy["keep"], 0.5);
  EXPECT_TRUE(jy["kept_wavelets"].is_number_integer());
}

TEST(CliHierarchy, UsageErrorsExitWithTwo) {
  TempDir dir("sublift_cli_usage");
  const std::string cube = kAssets + "/cube.obj", out = dir.file("o.obj");
  const std::vector<std::vector<std::string>> bad = {
      {"subdivide", cube, "--levels", "2", "-o", out},                                  // no scheme
      {"subdivide", cube, "--scheme", "catmark", "--levels", "2", "-o", out},           // unknown scheme
      {"subdivide", cube, "--scheme", "loop", "--levels", "2", "-o", out},              // quads for a triangle scheme
      {"subdivide", cube, "--scheme", "cubic", "-o", out},                              // no levels
      {"subdivide", cube, "--scheme", "cubic", "--levels", "13", "-o", out},            // too many
      {"subdivide", cube, "--scheme", "cubic", "--levels", "x", "-o", out},
      {"subdivide", cube, "--scheme", "cubic", "--levels", "2"},                        // no -o
      {"subdivide", cube, "--scheme", "cubic", "--levels", "2", "-o", dir.file("o.lattice")},  // wrong dim
      {"subdivide", cube, "--scheme", "cubic", "--levels", "2", "-o", out, "--frobnicate"},
      {"subdivide", kAssets + "/hex_block_4.lattice", "--scheme", "cubic", "--levels", "9", "-o", dir.file("o.vtk")},
      {"analyze", cube, "--scheme", "cubic", "--levels", "1", "-o", dir.file("p.obj")},  // no base: rebuild; not .sublift
      {"analyze", cube, "--base", cube, "--scheme", "cubic", "--levels", "1", "-o", out},         // not .sublift
      {"synthesize", "p.sublift"},                                                                // no -o
      {"synthesize", "p.sublift", "--keep", "1.5", "-o", out},
      {"synthesize", "p.sublift", "--level", "-1", "-o", out}};
  for (const auto& args : bad) {
    const ProcessResult r = cli(args);
    std::string joined;
    for (const auto& a : args) joined += a + " ";
    EXPECT_EQ(r.exit_code, 2) << joined << "\n" << r.err;
    EXPECT_NE(r.err.find("sublift-cli " + args[0]), std::string::npos) << r.err;
  }
  const ProcessResult big = cli(bad[9]);
  EXPECT_NE(cli(bad[2]).err.find("needs a triangle mesh; face 0 has 4 corners"), std::string::npos);
  EXPECT_NE(big.err.find("more than the limit"), std::string::npos) << big.err;
  EXPECT_FALSE(fs::exists(dir.file("o.vtk")));
}

TEST(CliHierarchy, InputErrorsExitWithOneAndExplain) {
  TempDir dir("sublift_cli_input");
  const std::string cube = kAssets + "/cube.obj", fine = dir.file("fine.obj"), project = dir.file("p.sublift");
  ok(cli({"subdivide", cube, "--scheme", "cubic", "--levels", "2", "-o", fine}));
  // Wrong number of levels: the vertex counts differ.
  ProcessResult r = cli({"analyze", fine, "--base", cube, "--scheme", "cubic", "--levels", "1", "-o", project});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find(fine), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("98 vertices, the refined base 26"), std::string::npos) << r.err;
  // Same vertex count, other connectivity: faces renumbered.
  std::string text = sublift::read_file_bytes(fine);
  const auto f = text.find("\nf ");
  const auto e = text.find('\n', f + 1);
  std::string face = text.substr(f + 3, e - f - 3);  // "a b c d" -> "b c d a" keeps it; reverse a pair instead
  std::istringstream in(face);
  std::string a, b, c, d;
  in >> a >> b >> c >> d;
  text.replace(f + 3, e - f - 3, a + " " + c + " " + b + " " + d);
  std::ofstream(fine) << text;
  r = cli({"analyze", fine, "--base", cube, "--scheme", "cubic", "--levels", "2", "-o", project});
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("face"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(project));
  // Damaged project.
  std::ofstream(project) << "sublift-project 1\n{}\n";
  r = cli({"synthesize", project, "-o", dir.file("x.obj")});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("malformed header"), std::string::npos) << r.err;
  r = cli({"info", project, "--json"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_TRUE(r.out.empty());
  // Bad lattice input names file and line.
  std::ofstream(dir.file("bad.lattice")) << "sublift-lattice 1\nv 0 0 0\ncell\nf 0 0 0\n";
  r = cli({"subdivide", dir.file("bad.lattice"), "--scheme", "cubic", "--levels", "1", "-o", dir.file("x.lattice")});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find(dir.file("bad.lattice") + ":3:"), std::string::npos) << r.err;
}

// Issue 18: a project whose coefficients are huge but finite opened, and synthesize wrote
// nan/inf with exit 0. Now the reader refuses it, and a synthesis that overflows is refused.
TEST(CliHierarchy, CoefficientsOutOfRangeAreRefusedNotSynthesised) {
  TempDir dir("sublift_cli_overflow");
  const std::string cube = kAssets + "/cube.obj", fine = dir.file("fine.obj"), project = dir.file("p.sublift");
  const std::string out = dir.file("out.obj");
  ok(cli({"subdivide", cube, "--scheme", "cubic", "--levels", "1", "-o", fine}));
  // No zero wavelet, so the project stores its coefficients dense and the last 8 bytes are the
  // last vertex's last channel (a pure subdivision would be stored sparse, docs/file_formats.md).
  sublift::Hierarchy dense = sublift::make_hierarchy(sublift::read_shape(cube).base, 1, sublift::Scheme::Cubic, 3);
  for (std::size_t i = 0; i < dense.coeffs.size(); ++i) dense.coeffs[i] = 0.25 + 0.001 * double(i % 17);
  ASSERT_EQ(sublift::write_project(project, dense).encoding, "dense");
  std::string bytes = sublift::read_file_bytes(project);
  const double huge = 1.7e308;
  std::memcpy(bytes.data() + bytes.size() - 8, &huge, 8);  // the last vertex's last channel
  std::ofstream(project, std::ios::binary) << bytes;
  const std::size_t last = sublift::read_shape(fine).positions.size() / 3 - 1;
  const std::string why = project + ": coefficient at vertex " + std::to_string(last) +
                          ", level 1, channel 2 exceeds the supported magnitude 1e30 (1.7e+308)\n";
  ProcessResult r = cli({"synthesize", project, "-o", out});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "sublift-cli synthesize: error: " + why);
  EXPECT_FALSE(fs::exists(out));
  r = cli({"info", project});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "sublift-cli info: error: " + why);
  EXPECT_EQ(r.out.find("inf"), std::string::npos) << r.out;

  // Every coefficient at the limit: each is readable, their synthesis is not.
  ok(cli({"analyze", fine, "--base", cube, "--scheme", "cubic", "--levels", "1", "-o", project}));
  sublift::Hierarchy h = sublift::read_project(project);
  std::fill(h.coeffs.begin(), h.coeffs.end(), sublift::kMaxCoordinate);
  sublift::write_project(project, h);
  r = cli({"synthesize", project, "-o", out});
  EXPECT_EQ(r.exit_code, 1);
  // Vertex 20, the first face point of the cube's level 1: its face's mean plus lifted wavelets.
  EXPECT_EQ(r.err, "sublift-cli synthesize: error: " + project +
                       ": synthesis overflows at level 1: vertex 20, channel 0 exceeds the supported magnitude 1e30 "
                       "(1.5624999999999998e+30); nothing written\n");
  EXPECT_FALSE(fs::exists(out));
  ok(cli({"synthesize", project, "--level", "0", "-o", out}));  // level 0 is the coefficients themselves
}

// Issue 18: a lattice listing the same hexahedron twice loaded without a word (and its boundary
// exported as vertices without faces); now every command refuses it, exit 1, nothing written.
TEST(CliHierarchy, LatticeWithACellListedTwiceIsRefused) {
  TempDir dir("sublift_cli_twice");
  const std::string in = dir.file("twice.lattice"), out = dir.file("out.lattice");
  std::ofstream(in) << "sublift-lattice 1\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                       "hex 0 1 2 3 4 5 6 7\nhex 0 1 2 3 4 5 6 7\n";
  const std::string why = in + ":11: cell 1 (hexahedron) has the same vertices as cell 0 (hexahedron) on line 10: a cell listed twice\n";
  ProcessResult r = cli({"subdivide", in, "--scheme", "cubic", "--levels", "1", "-o", out});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "sublift-cli subdivide: error: " + why);
  EXPECT_FALSE(fs::exists(out));
  r = cli({"info", in});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "sublift-cli info: error: " + why);
}
