// sublift-cli rebuild (and analyze without --base): a mesh subdivided elsewhere, in its own
// vertex order, comes in with its levels and goes back out as the same file.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numeric>
#include <random>
#include <sstream>

#include "core/complex/complex_build.h"
#include "core/io/lattice/shape_io.h"
#include "core/multires/hierarchy.h"
#include "tests/cli_run.h"
#include "tests/io_test_util.h"
#include "tests/mesh_fixtures.h"
#include "tests/test_shapes.h"

using namespace sublift;
using namespace sublift::testing;

namespace {

// OBJ text (17 significant digits) of `base` refined `levels` times by `scheme` from random
// base positions with small random detail, vertices and faces shuffled.
std::string shuffled_obj(const fixtures::Polygons& base, int levels, Scheme scheme, unsigned seed, bool break_one_quad = false) {
  Hierarchy h = make_hierarchy(complex_from_polygons(base.num_vertices, base.faces), levels, scheme, 3);
  set_base(h, random_coefficients(3 * std::size_t(base.num_vertices), seed, false));
  const std::vector<double> x = synthesize(h, levels);
  const Complex& fine = h.levels.back();
  std::vector<std::uint32_t> perm;
  const fixtures::Polygons file = fixtures::shuffled({fine.num_vertices, fine.faces, x}, seed, &perm);
  std::ostringstream out;
  char buf[128];
  for (std::uint32_t i = 0; i < perm.size(); ++i) {
    const double* p = &file.positions[3 * std::size_t(i)];
    std::snprintf(buf, sizeof buf, "v %.17g %.17g %.17g\n", p[0], p[1], p[2]);
    out << buf;
  }
  for (std::size_t f = 0; f < file.faces.rows(); ++f) {
    const auto row = file.faces.row(f);
    if (break_one_quad && f == 0 && row.size() == 4) {
      out << "f " << row[0] + 1 << " " << row[1] + 1 << " " << row[2] + 1 << "\n";
      out << "f " << row[0] + 1 << " " << row[2] + 1 << " " << row[3] + 1 << "\n";
      continue;
    }
    out << "f";
    for (std::uint32_t v : row) out << " " << v + 1;
    out << "\n";
  }
  return out.str();
}

std::vector<std::string> face_lines(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);)
    if (l.rfind("f ", 0) == 0) lines.push_back(l);
  return lines;
}

}  // namespace

TEST(CliRebuild, RebuildThenSynthesizeGivesTheFileBack) {
  TempDir dir("sublift_cli_rebuild");
  const std::string fine = dir.file("fine.obj"), project = dir.file("p.sublift"), back = dir.file("back.obj");
  std::ofstream(fine) << shuffled_obj(fixtures::cube(), 3, Scheme::Cubic, 7);
  const ProcessResult r = run_cli({"rebuild", fine, "-o", project, "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["levels"], 3);
  EXPECT_EQ(j["scheme"], "cubic");
  EXPECT_EQ(j["scheme_picked"], true);
  EXPECT_EQ(j["split"], "quad split");
  ASSERT_EQ(j["per_level"].size(), 4u);
  EXPECT_EQ(j["per_level"][0]["vertices"], 8);
  EXPECT_EQ(j["per_level"][0]["faces"], 6);
  EXPECT_EQ(j["per_level"][3]["faces"], 384);
  EXPECT_EQ(j["components"].size(), 1u);
  EXPECT_TRUE(j["time_ms"].contains("detect"));
  const ProcessResult s = run_cli({"synthesize", project, "-o", back});
  ASSERT_EQ(s.exit_code, 0) << s.err;
  EXPECT_EQ(face_lines(back), face_lines(fine));
  const Shape a = read_shape(fine), b = read_shape(back);
  EXPECT_LE(relative_error(a.positions, b.positions), 1e-12);
  // analyze without --base does the same.
  const ProcessResult an = run_cli({"analyze", fine, "-o", project, "--json"});
  ASSERT_EQ(an.exit_code, 0) << an.err;
  EXPECT_EQ(nlohmann::json::parse(an.out)["levels"], 3);
  // edit writes the finest level in the file's order too.
  const std::string edited = dir.file("edited.obj");
  const ProcessResult e = run_cli({"edit", project, "--level", "0", "--vertex", "0", "--delta", "0.1", "0", "0", "-o", edited});
  ASSERT_EQ(e.exit_code, 0) << e.err;
  EXPECT_EQ(face_lines(edited), face_lines(fine));
}

TEST(CliRebuild, TrianglesPickLoop) {
  TempDir dir("sublift_cli_rebuild_tri");
  const std::string fine = dir.file("fine.obj"), project = dir.file("p.sublift");
  std::ofstream(fine) << shuffled_obj(fixtures::octahedron(), 2, Scheme::Loop, 3);
  const ProcessResult r = run_cli({"rebuild", fine, "-o", project, "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["scheme"], "loop");
  EXPECT_EQ(j["levels"], 2);
  EXPECT_EQ(j["per_level"][0]["vertices"], 6);
}

TEST(CliRebuild, BrokenMeshIsReportedNotRefused) {
  TempDir dir("sublift_cli_rebuild_bad");
  const std::string fine = dir.file("fine.obj"), project = dir.file("p.sublift");
  std::ofstream(fine) << shuffled_obj(fixtures::cube(), 2, Scheme::Cubic, 5, true);
  const ProcessResult r = run_cli({"rebuild", fine, "-o", project, "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["levels"], 0);
  EXPECT_NE(j["stop"].get<std::string>().find("2 triangles among 95 quads near vertex"), std::string::npos) << j["stop"];
  EXPECT_TRUE(j.contains("stop_vertex"));
  // Asking for levels it does not hold is an input error naming the cause.
  const ProcessResult n = run_cli({"rebuild", fine, "--levels", "2", "-o", project});
  EXPECT_EQ(n.exit_code, 1);
  EXPECT_NE(n.err.find("holds 0 levels"), std::string::npos) << n.err;
  EXPECT_NE(n.err.find("triangles among"), std::string::npos) << n.err;
  // Usage errors.
  EXPECT_EQ(run_cli({"rebuild", fine, "-o", dir.file("p.obj")}).exit_code, 2);
  EXPECT_EQ(run_cli({"rebuild", fine, "--levels", "two", "-o", project}).exit_code, 2);
  EXPECT_EQ(run_cli({"rebuild", fine, "--scheme", "quintic", "-o", project}).exit_code, 2);
}

TEST(CliRebuild, LatticeComesBackInItsVertexOrder) {
  TempDir dir("sublift_cli_rebuild_lattice");
  const std::string fine = dir.file("fine.vtk"), project = dir.file("p.sublift"), back = dir.file("back.vtk");
  const ProcessResult s = run_cli({"subdivide", std::string(SUBLIFT_ASSETS_DIR) + "/hex_block_4.lattice", "--scheme", "cubic", "--levels", "1",
                                   "-o", fine});
  ASSERT_EQ(s.exit_code, 0) << s.err;
  const ProcessResult r = run_cli({"rebuild", fine, "-o", project, "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["split"], "1-to-8 lattice split");
  EXPECT_EQ(j["levels"], 3);  // 8^3 cells: the 4^3 block's own 2 levels, and the one applied
  EXPECT_EQ(j["per_level"][0]["vertices"], 8);
  ASSERT_EQ(run_cli({"synthesize", project, "-o", back}).exit_code, 0);
  const Shape a = read_shape(fine), b = read_shape(back);
  EXPECT_LE(relative_error(a.positions, b.positions), 1e-12);
}

TEST(CliRebuild, DataTheProjectDoesNotKeepIsNamed) {
  TempDir dir("sublift_cli_rebuild_uv");
  const std::string fine = dir.file("uv.obj"), project = dir.file("p.sublift");
  std::ofstream(fine) << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\nusemtl skin\nf 1/1/1 2/2/1 3/3/1 4/4/1\n";
  const ProcessResult r = run_cli({"rebuild", fine, "-o", project, "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("not kept in the project (nor written back): 1 normals (vn), 1 materials (usemtl)"), std::string::npos) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["not_kept"].size(), 1u);
  EXPECT_EQ(nlohmann::json::parse(r.out)["uv_points"], 4);  // the texture coordinates are kept (uv_test.cpp)
}

TEST(CliRebuild, LatticeFeatureTagsAreNamedNotDroppedSilently) {
  TempDir dir("sublift_cli_rebuild_features");
  const std::string fine = dir.file("fs1.lattice");
  ASSERT_EQ(run_cli({"subdivide", std::string(SUBLIFT_ASSETS_DIR) + "/feature_surface.lattice", "--scheme", "cubic", "--levels", "1", "-o", fine})
                .exit_code,
            0);
  const ProcessResult r = run_cli({"rebuild", fine, "-o", dir.file("p.sublift")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("lattice feature tags"), std::string::npos) << r.err;
}
