// Drives sublift-cli as a user's script would: exit codes, messages, --json documents, the
// bundled assets and the third-party bad-input corpus (../shared/data, skipped when absent).
#include <filesystem>
#include <fstream>
#include <map>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/test_util.h"
#include "tests/run_process.h"

namespace fs = std::filesystem;
using sublift::testing::ProcessResult;
using sublift::testing::run_process;

namespace {

const std::string kCli = SUBLIFT_CLI;
const fs::path kAssets = SUBLIFT_ASSETS_DIR;
const fs::path kShared = SUBLIFT_SHARED_DATA;

bool is_mesh_file(const fs::path& p) {
  const std::string e = p.extension().string();
  return e == ".obj" || e == ".off" || e == ".ply";
}

std::vector<fs::path> mesh_files(const fs::path& dir, bool recursive) {
  std::vector<fs::path> out;
  if (!fs::is_directory(dir)) return out;
  if (recursive) {
    for (auto& e : fs::recursive_directory_iterator(dir))
      if (e.is_regular_file() && is_mesh_file(e.path())) out.push_back(e.path());
  } else {
    for (auto& e : fs::directory_iterator(dir))
      if (e.is_regular_file() && is_mesh_file(e.path())) out.push_back(e.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

ProcessResult info_json(const fs::path& file) {
  return run_process({kCli, "info", file.string(), "--json"}, 10.0);
}

// A process that neither crashed nor hung nor tripped a sanitizer.
void expect_clean_exit(const ProcessResult& r, const std::string& what) {
  EXPECT_FALSE(r.timed_out) << what << " hung";
  EXPECT_EQ(r.signal, 0) << what << " crashed with signal " << r.signal << "\n" << r.err;
  EXPECT_EQ(r.err.find("Sanitizer"), std::string::npos) << what << "\n" << r.err;
  EXPECT_EQ(r.err.find("runtime error"), std::string::npos) << what << "\n" << r.err;
}

}  // namespace

TEST(Cli, UsageErrorsExitWithTwo) {
  EXPECT_EQ(run_process({kCli}).exit_code, 2);
  EXPECT_EQ(run_process({kCli, "frobnicate"}).exit_code, 2);
  EXPECT_EQ(run_process({kCli, "info"}).exit_code, 2);
  EXPECT_EQ(run_process({kCli, "info", "a.obj", "--bogus"}).exit_code, 2);
  EXPECT_EQ(run_process({kCli, "render", (kAssets / "cube.obj").string()}).exit_code, 2);  // no -o
  EXPECT_EQ(run_process({kCli, "render", (kAssets / "cube.obj").string(), "-o", "x.png", "--size", "9x9"}).exit_code, 2);
}

TEST(Cli, EveryCommandHasHelp) {
  for (const char* cmd : {"info", "render", "convert", "subdivide", "analyze", "synthesize"}) {
    const ProcessResult r = run_process({kCli, cmd, "--help"});
    EXPECT_EQ(r.exit_code, 0) << cmd;
    EXPECT_NE(r.out.find(std::string("usage: sublift-cli ") + cmd), std::string::npos) << cmd;
  }
  const ProcessResult top = run_process({kCli, "--help"});
  EXPECT_EQ(top.exit_code, 0);
  EXPECT_NE(top.out.find("info"), std::string::npos);
}

TEST(Cli, MissingFileExitsWithOneAndNamesIt) {
  const ProcessResult r = run_process({kCli, "info", "/no/such/mesh.obj"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("/no/such/mesh.obj"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty());
}

TEST(Cli, InfoJsonOnKnownAssets) {
  // Expected counts follow from how each asset is built (see assets/README.md), not from Sublift.
  struct Known { const char* file; int v, e, f, loops; long long chi; };
  const Known known[] = {{"cube.obj", 8, 12, 6, 0, 2},           {"torus_quad.obj", 12 * 8, 2 * 12 * 8, 12 * 8, 0, 0},
                         {"pyramid.obj", 5, 8, 5, 0, 2},         {"quad_grid_boundary.obj", 25, 40, 16, 1, 1},
                         {"crease_loop.obj", 16, 28, 14, 0, 2}};
  for (const Known& k : known) {
    const ProcessResult r = info_json(kAssets / k.file);
    ASSERT_EQ(r.exit_code, 0) << k.file << r.err;
    const auto j = nlohmann::json::parse(r.out);
    ASSERT_TRUE(j["vertices"].is_number_integer());
    ASSERT_TRUE(j["edges"].is_number_integer());
    ASSERT_TRUE(j["faces"].is_number_integer());
    EXPECT_EQ(j["vertices"], k.v) << k.file;
    EXPECT_EQ(j["edges"], k.e) << k.file;
    EXPECT_EQ(j["faces"], k.f) << k.file;
    EXPECT_EQ(j["boundary_loops"], k.loops) << k.file;
    EXPECT_EQ(j["euler_characteristic"], k.chi) << k.file;
    EXPECT_EQ(j["non_manifold_edges"], 0) << k.file;
    EXPECT_EQ(j["misoriented_edges"], 0) << k.file;
  }
  const auto crease = nlohmann::json::parse(info_json(kAssets / "crease_loop.obj").out);
  EXPECT_EQ(crease["tags"]["crease"], 4);
}

TEST(Cli, InfoOnEveryAssetSucceedsWithoutWarnings) {
  const auto files = mesh_files(kAssets, false);
  ASSERT_GE(files.size(), 6u);
  for (const fs::path& f : files) {
    const ProcessResult r = info_json(f);
    expect_clean_exit(r, f.string());
    EXPECT_EQ(r.exit_code, 0) << f << r.err;
    EXPECT_TRUE(r.err.empty()) << f << r.err;
    const auto j = nlohmann::json::parse(r.out);
    // Surfaces have faces; curve assets (OBJ `l` lines only) have polylines instead.
    EXPECT_GT(j["faces"].get<int>() + j["polylines"].get<int>(), 0) << f;
    if (j["faces"].get<int>() == 0) {
      EXPECT_EQ(j["isolated_vertices"], 0) << f;
    }
    EXPECT_EQ(j["non_manifold_vertices"], 0) << f;
  }
}

TEST(Cli, InfoOnAnUnknownExtensionListsEveryFormatItReads) {
  const fs::path tmp = fs::temp_directory_path() / "sublift_cli_info_ext";
  fs::create_directories(tmp);
  const fs::path f = tmp / "shape.stl";
  std::ofstream(f) << "solid x\nendsolid x\n";
  const ProcessResult r = run_process({kCli, "info", f.string()});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("unsupported format '.stl' (info reads .obj, .off, .ply, .gltf, .glb, .lattice, .ovm, .vtk and .sublift)"),
            std::string::npos)
      << r.err;
}

TEST(Cli, TextInfoIsReadable) {
  const ProcessResult r = run_process({kCli, "info", (kAssets / "mixed_polygons.obj").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* field : {"vertices:", "edges:", "faces:", "face sizes:", "3:", "4:", "5:", "valences:",
                            "boundary:", "non-manifold:", "bounding box:"})
    EXPECT_NE(r.out.find(field), std::string::npos) << field << "\n" << r.out;
}

TEST(Cli, ConvertRoundTripsExactly) {
  const fs::path tmp = fs::temp_directory_path() / "sublift_cli_convert";
  fs::create_directories(tmp);
  const std::string src = (kAssets / "mixed_polygons.obj").string();
  ASSERT_EQ(run_process({kCli, "convert", src, "-o", (tmp / "a.ply").string()}).exit_code, 0);
  ASSERT_EQ(run_process({kCli, "convert", (tmp / "a.ply").string(), "-o", (tmp / "b.off").string()}).exit_code, 0);
  ASSERT_EQ(run_process({kCli, "convert", (tmp / "b.off").string(), "-o", (tmp / "c.obj").string()}).exit_code, 0);
  const auto a = nlohmann::json::parse(info_json(src).out);
  const auto c = nlohmann::json::parse(info_json(tmp / "c.obj").out);
  EXPECT_EQ(a["bbox"], c["bbox"]);  // exact doubles after three conversions
  EXPECT_EQ(a["valences"], c["valences"]);
  EXPECT_EQ(a["faces"], c["faces"]);
  fs::remove_all(tmp);
}

// The product promise is one second per file; the Release run of this test enforces it. Under
// AddressSanitizer (CI runs the suite a second time so) every access is instrumented and the
// same work takes several times longer on a loaded 2-core machine, so there the bound only
// separates "slow" from "hung".
// (testing::kAddressSanitizer: this file's own code is built without instrumentation, so the
// compiler's __SANITIZE_ADDRESS__ does not say it; the CLI it spawns is instrumented.)
constexpr double kSecondsPerFile = sublift::testing::kAddressSanitizer ? 5.0 : 1.0;

// The third-party corpus of broken files: controls load cleanly; every other file ends in a
// clear error (exit 1, message naming the file) or loads with an itemised warning; never a
// crash, hang or sanitizer report, always within a second.
TEST(Cli, BadInputCorpus) {
  const fs::path dir = kShared / "bad_inputs";
  if (!fs::is_directory(dir)) GTEST_SKIP() << "bad-input corpus not found at " << dir << " (../shared/data absent)";
  enum Want { Reject, LoadClean, LoadWarn, Either };
  // What a robust reader must do per ../shared/data/bad_inputs/README.md ("Expected" column).
  const std::map<std::string, Want> want = {
      {"ok_triangle.obj", LoadClean}, {"ok_tetra.off", LoadClean}, {"ok_triangle_ascii.ply", LoadClean},
      {"obj_crlf_only.obj", LoadClean}, {"obj_bom_only.obj", LoadClean}, {"obj_negative_index_valid.obj", LoadClean},
      {"obj_long_line_256k.obj", LoadClean}, {"obj_open_cube_hole.obj", LoadClean},
      {"obj_inconsistent_orientation.obj", LoadClean}, {"obj_nonmanifold_edge_3faces.obj", LoadClean},
      {"obj_bowtie_vertex.obj", LoadClean}, {"obj_vertex_valence_70000.obj", LoadClean},
      {"obj_isolated_vertices.obj", LoadWarn}, {"obj_degenerate_face_1vert.obj", LoadWarn},
      {"obj_degenerate_face_2verts.obj", LoadWarn}, {"obj_repeated_vertex_in_face.obj", LoadWarn},
      {"obj_duplicate_face.obj", LoadWarn}, {"off_index_out_of_range.off", Either},
      {"ply_index_out_of_range.ply", LoadWarn}, {"ply_negative_index.ply", LoadWarn},
      {"obj_empty.obj", Reject}, {"obj_only_comments.obj", Reject}, {"obj_zero_faces.obj", Reject},
      {"obj_binary_garbage.obj", Reject}, {"obj_nan_inf_coords.obj", Reject}, {"obj_1e38_coords.obj", Reject},
      {"off_wrong_magic.off", Reject}, {"off_counts_lie_huge.off", Reject}, {"off_counts_negative.off", Reject},
      {"off_truncated.off", Reject}, {"off_nan.off", Reject}, {"off_binary_counts_huge.off", Reject},
      {"ply_wrong_magic.ply", Reject}, {"ply_no_end_header.ply", Reject}, {"ply_unknown_property_type.ply", Reject},
      {"ply_binary_truncated.ply", Reject}, {"ply_binary_list_count_lie.ply", Reject},
      {"ply_binary_list_count_2e9.ply", Reject}};
  const auto files = mesh_files(dir, false);
  ASSERT_FALSE(files.empty());
  for (const fs::path& f : files) {
    const std::string name = f.filename().string();
    SCOPED_TRACE(name);
    const ProcessResult r = info_json(f);
    expect_clean_exit(r, name);
    EXPECT_LT(r.seconds, kSecondsPerFile) << name << " took " << r.seconds << " s";
    ASSERT_TRUE(r.exit_code == 0 || r.exit_code == 1) << "exit " << r.exit_code << "\n" << r.err;
    if (r.exit_code == 1) {
      EXPECT_NE(r.err.find(f.string()), std::string::npos) << "error must name the file:\n" << r.err;
      EXPECT_NE(r.err.find("error:"), std::string::npos) << r.err;
      EXPECT_TRUE(r.out.empty());
    } else {
      EXPECT_TRUE(nlohmann::json::accept(r.out)) << r.out;
    }
    const bool warned = r.exit_code == 0 && r.err.find("warning:") != std::string::npos;
    const auto it = want.find(name);
    const Want w = it == want.end() ? Either : it->second;
    switch (w) {
      case Reject: EXPECT_EQ(r.exit_code, 1) << r.err; break;
      case LoadClean: EXPECT_EQ(r.exit_code, 0) << r.err; EXPECT_FALSE(warned) << r.err; break;
      case LoadWarn: EXPECT_TRUE(warned) << r.err; break;
      case Either: EXPECT_TRUE(r.exit_code == 1 || warned) << "neither error nor warning:\n" << r.err; break;
    }
  }
}

TEST(Cli, CorpusControlsMatchTheirPlainVersions) {
  const fs::path dir = kShared / "bad_inputs";
  if (!fs::is_directory(dir)) GTEST_SKIP() << "bad-input corpus not found at " << dir;
  // BOM and CRLF variants describe the same 4-vertex, 2-triangle square.
  for (const char* name : {"obj_bom_only.obj", "obj_crlf_only.obj"}) {
    const auto j = nlohmann::json::parse(info_json(dir / name).out);
    EXPECT_EQ(j["vertices"], 4) << name;
    EXPECT_EQ(j["faces"], 2) << name;
    EXPECT_EQ(j["bbox"]["min"], nlohmann::json({0.0, 0.0, 0.0})) << name;
    EXPECT_EQ(j["bbox"]["max"], nlohmann::json({1.0, 1.0, 0.0})) << name;
    EXPECT_EQ(j["boundary_loops"], 1) << name;
  }
  const auto hole = nlohmann::json::parse(info_json(dir / "obj_open_cube_hole.obj").out);
  EXPECT_EQ(hole["boundary_loops"], 1);
  const auto nm = nlohmann::json::parse(info_json(dir / "obj_nonmanifold_edge_3faces.obj").out);
  EXPECT_EQ(nm["non_manifold_edges"], 1);
  EXPECT_EQ(nm["vertices"], 5);  // no vertex duplicated, unlike OpenMesh's reader
  const auto bow = nlohmann::json::parse(info_json(dir / "obj_bowtie_vertex.obj").out);
  EXPECT_EQ(bow["non_manifold_vertices"], 1);
  const auto val = nlohmann::json::parse(info_json(dir / "obj_vertex_valence_70000.obj").out);
  EXPECT_TRUE(val["valences"].contains("70000"));
}

TEST(Cli, RealMeshesOfTheSharedDataLoad) {
  if (!fs::is_directory(kShared)) GTEST_SKIP() << "shared data not found at " << kShared;
  std::vector<fs::path> files = mesh_files(kShared / "control_meshes", true);
  for (const fs::path& f : mesh_files(kShared / "scans", false)) files.push_back(f);
  ASSERT_FALSE(files.empty());
  for (const fs::path& f : files) {
    const ProcessResult r = info_json(f);
    expect_clean_exit(r, f.string());
    EXPECT_EQ(r.exit_code, 0) << f << "\n" << r.err;
  }
}

// Issue 18: non-manifold vertices and edges and inconsistent orientation were counted by
// `info` and never warned about where they matter. Every command that subdivides or edits now
// prints the warning (counts and first elements) and lists it in --json `warnings`.
TEST(Cli, TopologyWarningsFromEveryCommandThatSubdividesOrEdits) {
  const fs::path dir = fs::temp_directory_path() / "sublift_cli_topology";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string bow = (dir / "bowtie.obj").string(), flip = (dir / "flip.obj").string();
  std::ofstream(bow) << "v 0 0 0\nv 1 1 0\nv 1 -1 0\nv -1 1 0\nv -1 -1 0\nf 1 3 2\nf 1 4 5\n";  // two fans at vertex 0
  std::ofstream(flip) << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 4 3\n";  // both run the diagonal 3 -> 1
  const std::string bow_text = "non-manifold vertex: its faces do not form one fan (vertex 0; 0-based)";
  const std::string bow_line = bow + ": warning: 1 x " + bow_text + "\n";
  auto file = [&](const std::string& n) { return (dir / n).string(); };
  auto run = [&](std::vector<std::string> args) {
    args.insert(args.begin(), kCli);
    return run_process(args, 60.0);
  };
  auto expect_warned = [&](const ProcessResult& r, const std::string& line, const char* what) {
    EXPECT_EQ(r.exit_code, 0) << what << "\n" << r.err;
    EXPECT_EQ(r.err, line) << what;
  };
  // subdivide, with the JSON form.
  ProcessResult r = run({"subdivide", bow, "--scheme", "cubic", "--levels", "1", "-o", file("fine.obj"), "--json"});
  expect_warned(r, bow_line, "subdivide");
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["warnings"].size(), 1u) << j.dump();
  EXPECT_EQ(j["warnings"][0]["what"], bow_text);
  EXPECT_EQ(j["warnings"][0]["count"], 1);
  // analyze (the base is subdivided), rebuild (its fine mesh is as non-manifold), edit,
  // compress and basis on the project, the noise experiment, ffd of the mesh as a model.
  r = run({"analyze", file("fine.obj"), "--base", bow, "--scheme", "cubic", "--levels", "1", "-o", file("p.sublift"), "--json"});
  expect_warned(r, bow_line, "analyze");
  EXPECT_EQ(nlohmann::json::parse(r.out)["base_warnings"][0]["what"], bow_text);
  expect_warned(run({"rebuild", file("fine.obj"), "-o", file("r.sublift")}), file("fine.obj") + ": warning: 1 x " + bow_text + "\n", "rebuild");
  const std::string project_line = file("p.sublift") + ": warning: 1 x " + bow_text + "\n";
  r = run({"edit", file("p.sublift"), "--level", "0", "--vertex", "1", "--delta", "0", "0", "1", "-o", file("e.obj"), "--json"});
  expect_warned(r, project_line, "edit");
  EXPECT_EQ(nlohmann::json::parse(r.out)["warnings"][0]["what"], bow_text);
  r = run({"compress", file("p.sublift"), "--keep", "0.5", "-o", file("c.obj"), "--json"});
  expect_warned(r, project_line, "compress");
  EXPECT_EQ(nlohmann::json::parse(r.out)["warnings"][0]["what"], bow_text);
  r = run({"basis", file("p.sublift"), "--level", "0", "--vertex", "0", "-o", file("b.ply"), "--json"});
  expect_warned(r, project_line, "basis");
  EXPECT_EQ(nlohmann::json::parse(r.out)["warnings"][0]["what"], bow_text);
  r = run({"experiment", "noise", "--model", bow, "--scheme", "cubic", "--levels", "1", "--sigma", "0.01", "--json"});
  expect_warned(r, bow_line, "experiment");
  EXPECT_EQ(nlohmann::json::parse(r.out)["warnings"][0]["what"], bow_text);
  r = run({"ffd", "--box", "1", "1", "1", "--model", bow, "-o", file("d.obj"), "--json"});
  expect_warned(r, bow_line, "ffd");
  EXPECT_EQ(nlohmann::json::parse(r.out)["warnings"][0]["what"], bow_text);
  // fit warns before it fails on a mesh this small.
  r = run({"fit", bow, "-o", file("f.sublift")});
  EXPECT_EQ(r.err.substr(0, bow_line.size()), bow_line) << r.err;
  // Inconsistent orientation, named by its edge; a clean mesh says nothing.
  r = run({"subdivide", flip, "--scheme", "linear", "--levels", "1", "-o", file("flip_fine.obj")});
  expect_warned(r, flip + ": warning: 1 x misoriented edge: two faces run it the same way, so the faces are not consistently "
                           "oriented (edge 0-2; 0-based)\n", "subdivide of an inconsistently oriented mesh");
  expect_warned(run({"subdivide", (kAssets / "cube.obj").string(), "--scheme", "cubic", "--levels", "1", "-o", file("cube.obj")}), "",
                "subdivide of a clean mesh");
  fs::remove_all(dir);
}
