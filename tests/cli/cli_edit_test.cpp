// sublift-cli edit (issue 4): the command's result equals the session's reference path (analyse,
// edit, synthesise everything), JSON fields, soft selection, outputs, usage and input errors.
#include <cmath>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/complex/complex_build.h"
#include "core/multires/hierarchy.h"
#include "core/io/project/project_io.h"
#include "core/edit/brush.h"
#include "core/edit/selection.h"
#include "core/edit/session.h"
#include "core/edit/symmetry.h"
#include "core/io/lattice/shape_io.h"
#include "core/complex/shapes.h"
#include "tests/io_test_util.h"
#include "tests/cli_run.h"
#include "tests/noisy_hierarchy.h"

namespace sublift {
namespace {

using sublift::testing::max_abs_diff;

using testing::ProcessResult;
using testing::TempDir;

ProcessResult cli(const std::vector<std::string>& args) { return testing::run_cli(args); }

// A torus project with detail at every level.
Hierarchy project_hierarchy() { return testing::noisy_torus(12, 8, 3, Scheme::Cubic, 11, 0.01); }

TEST(CliEdit, MatchesFullResynthesisAndReportsTiming) {
  TempDir dir("sublift_cli_edit");
  const Hierarchy h = project_hierarchy();
  write_project(dir.file("in.sublift"), h);
  for (const bool local : {false, true}) {
    std::vector<std::string> args = {"edit", dir.file("in.sublift"), "--level", "1", "--vertex", "7", "--vertex", "50",
                                     "--delta", "-0.1", "0.25", "-0.05", "-o", dir.file("out.sublift"), "--json"};
    if (local) args.push_back("--local-frames");
    const ProcessResult r = cli(args);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["level"], 1);
    EXPECT_EQ(j["moved"], 2);
    EXPECT_EQ(j["detail_frames"], local ? "local" : "world");
    EXPECT_GE(j["resynthesis_ms"].get<double>(), 0.0);
    EXPECT_GT(j["setup_ms"].get<double>(), 0.0);  // opening's one-time work, apart from the edit's
    EXPECT_GT(j["vertices_updated"].get<int>(), 2);
    EXPECT_LT(j["vertices_updated"].get<int>(), int(h.num_vertices(3)));

    Session ref(h);
    if (local) ref.set_detail_frames(DetailFrames::Local);
    const std::uint32_t v[2] = {7, 50};
    const double d[3] = {-0.1, 0.25, -0.05};
    ref.move_full(1, v, {}, d);
    ProjectExtras extras;
    const Hierarchy out = read_project(dir.file("out.sublift"), &extras);
    EXPECT_LT(max_abs_diff(out.coeffs, ref.hierarchy().coeffs), 1e-12);
    EXPECT_EQ(extras.current_level, 1);
    EXPECT_EQ(extras.local_frames, local);
  }
  // The finest level as a mesh, 17 digits: the same shape.
  ASSERT_EQ(cli({"edit", dir.file("in.sublift"), "--level", "0", "--vertex", "3", "--delta", "0", "0", "0.3", "-o",
                 dir.file("out.obj")})
                .exit_code,
            0);
  Session ref(h);
  const std::uint32_t v[1] = {3};
  const double d[3] = {0, 0, 0.3};
  ref.move_full(0, v, {}, d);
  EXPECT_LT(max_abs_diff(read_shape(dir.file("out.obj")).positions, ref.positions(3)), 1e-12);
  // synthesize --json reports the full synthesis time to compare with.
  const ProcessResult s = cli({"synthesize", dir.file("in.sublift"), "-o", dir.file("s.obj"), "--json"});
  ASSERT_EQ(s.exit_code, 0) << s.err;
  EXPECT_GE(nlohmann::json::parse(s.out)["synthesis_ms"].get<double>(), 0.0);
}

TEST(CliEdit, FalloffMovesANeighbourhood) {
  TempDir dir("sublift_cli_edit_falloff");
  write_project(dir.file("in.sublift"), project_hierarchy());
  const ProcessResult r = cli({"edit", dir.file("in.sublift"), "--level", "0", "--vertex", "0", "--falloff", "1.2",
                               "--delta", "0", "0.1", "0", "-o", dir.file("out.sublift"), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_GT(j["moved"].get<int>(), 1);
  EXPECT_LT(j["moved"].get<int>(), 96);
}

// --rotate and --scale (issue 19): the result equals moving each point to where the transform
// takes it, computed here by hand, with the full resynthesis.
TEST(CliEdit, RotateAndScaleAboutAPivot) {
  TempDir dir("sublift_cli_edit_rotate");
  const Hierarchy h = project_hierarchy();
  write_project(dir.file("in.sublift"), h);
  const std::uint32_t vs[2] = {7, 50};
  auto expect_like = [&](const std::vector<std::string>& args, auto target) {
    const ProcessResult r = cli(args);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    Session ref(h);
    for (const std::uint32_t v : vs) {
      const auto p = ref.positions(1);
      const glm::dvec3 from(p[3 * v], p[3 * v + 1], p[3 * v + 2]);
      const glm::dvec3 to = target(from, v);
      const double d[3] = {to.x - from.x, to.y - from.y, to.z - from.z};
      ref.move_full(1, std::span<const std::uint32_t>(&v, 1), {}, d);
    }
    const Hierarchy out = read_project(dir.file("out.sublift"));
    EXPECT_LT(max_abs_diff(out.coeffs, ref.hierarchy().coeffs), 1e-12);
  };
  // A quarter turn about +Z through (0.5, 0, 2): (x, y) -> (0.5 - y, x - 0.5).
  expect_like({"edit", dir.file("in.sublift"), "--level", "1", "--vertex", "7", "--vertex", "50", "--rotate", "z", "90",
               "--pivot", "0.5,0,2", "-o", dir.file("out.sublift")},
              [](glm::dvec3 p, std::uint32_t) { return glm::dvec3(0.5 - p.y, p.x - 0.5, p.z); });
  // Scale (2, 1, 0.5) about the active point (the last --vertex, 50), which stays put.
  Session probe(h);
  const auto p = probe.positions(1);
  const glm::dvec3 a(p[150], p[151], p[152]);
  expect_like({"edit", dir.file("in.sublift"), "--level", "1", "--vertex", "7", "--vertex", "50", "--scale", "2,1,0.5",
               "--pivot", "active", "-o", dir.file("out.sublift")},
              [&](glm::dvec3 q, std::uint32_t) { return a + (q - a) * glm::dvec3(2, 1, 0.5); });
  // The JSON says what ran and about which point.
  const ProcessResult r = cli({"edit", dir.file("in.sublift"), "--level", "1", "--vertex", "7", "--scale", "3",
                               "-o", dir.file("out.sublift"), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["transform"], "scale");
  EXPECT_EQ(j["pivot"][0].get<double>(), p[21]);  // median of one point: the point
  // Refusals: two transforms, a pivot for a move, a bad axis or factor.
  for (const auto& args : std::vector<std::vector<std::string>>{
           {"edit", dir.file("in.sublift"), "--level", "0", "--vertex", "1", "--scale", "2", "--delta", "1", "0", "0", "-o", dir.file("o.sublift")},
           {"edit", dir.file("in.sublift"), "--level", "0", "--vertex", "1", "--delta", "1", "0", "0", "--pivot", "origin", "-o", dir.file("o.sublift")},
           {"edit", dir.file("in.sublift"), "--level", "0", "--vertex", "1", "--rotate", "0,0,0", "5", "-o", dir.file("o.sublift")},
           {"edit", dir.file("in.sublift"), "--level", "0", "--vertex", "1", "--rotate", "w", "5", "-o", dir.file("o.sublift")},
           {"edit", dir.file("in.sublift"), "--level", "0", "--vertex", "1", "--scale", "2,2", "-o", dir.file("o.sublift")},
           {"edit", dir.file("in.sublift"), "--level", "0", "--vertex", "1", "--scale", "2", "--pivot", "centre", "-o", dir.file("o.sublift")},
       }) {
    const ProcessResult bad = cli(args);
    EXPECT_EQ(bad.exit_code, 2) << bad.err;
    EXPECT_FALSE(bad.err.empty());
  }
}

// --brush and --mirror (issue 19): a dab equals brush_dab + move_each on the same net; with
// --mirror x the images across x = 0 move the mirrored way.
TEST(CliEdit, BrushDabAndMirror) {
  TempDir dir("sublift_cli_edit_brush");
  const Hierarchy h = project_hierarchy();
  write_project(dir.file("in.sublift"), h);
  Session probe(h);
  const auto p = probe.positions(1);
  std::uint32_t v = 0;
  while (p[3 * v] < 0.5) ++v;  // a point well off the plane x = 0
  const std::string at[3] = {std::to_string(p[3 * v]), std::to_string(p[3 * v + 1]), std::to_string(p[3 * v + 2])};
  ProcessResult r = cli({"edit", dir.file("in.sublift"), "--level", "1", "--brush", "inflate", "--at", at[0], at[1], at[2],
                         "--radius", "0.3", "--strength", "0.7", "-o", dir.file("b.sublift"), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["transform"], "brush inflate");
  EXPECT_GT(j["moved"].get<int>(), 1);
  EXPECT_EQ(j["mirrored"], 0);
  // The same dab here: what the command wrote.
  Session ref(h);
  Complex c = ref.hierarchy().levels[1];
  build_adjacency(c);
  BrushSettings b;
  b.kind = BrushKind::Inflate;
  b.radius = 0.3;
  b.strength = 0.7;
  Dab d;
  d.center = {std::stod(at[0]), std::stod(at[1]), std::stod(at[2])};
  d.view_dir = glm::dvec3(0.0);
  std::vector<std::uint32_t> vs;
  std::vector<double> deltas;
  brush_dab(b, d, c, ref.positions(1), vs, deltas);
  ref.move_each(1, vs, deltas);
  EXPECT_LT(max_abs_diff(read_project(dir.file("b.sublift")).coeffs, ref.hierarchy().coeffs), 1e-12);
  // The noisy torus's base is not symmetric: the JSON and stderr say which points have no image.
  r = cli({"edit", dir.file("in.sublift"), "--level", "0", "--vertex", "0", "--delta", "0.1", "0", "0", "--mirror", "x",
           "-o", dir.file("m.sublift"), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto jn = nlohmann::json::parse(r.out);
  EXPECT_NE(jn["mirror_problems"][0].get<std::string>().find("have no mirror image"), std::string::npos) << r.out;
  // Every control point is counted once: found by position, by topology or not at all.
  const auto& mn = jn["mirror_maps"][0];
  EXPECT_EQ(mn["axis"], "x");
  EXPECT_GT(mn["unmatched"].get<std::size_t>(), 0u);
  EXPECT_EQ(mn["by_position"].get<std::size_t>() + mn["by_topology"].get<std::size_t>() + mn["unmatched"].get<std::size_t>(),
            read_project(dir.file("in.sublift")).levels[0].num_vertices);
  // An exactly symmetric one: the image of the moved point moves the mirrored way.
  const SurfaceMesh sm = make_quad_torus(12, 8);
  Hierarchy sym = make_hierarchy(complex_from_surface_mesh(sm), 2, Scheme::Cubic, 3);
  set_base(sym, flatten_positions(sm));
  write_project(dir.file("sym.sublift"), sym);
  r = cli({"edit", dir.file("sym.sublift"), "--level", "0", "--vertex", "0", "--delta", "0.1", "0", "0", "--mirror", "x",
           "-o", dir.file("m.sublift"), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto jm = nlohmann::json::parse(r.out);
  EXPECT_EQ(jm["moved"], 1);
  EXPECT_EQ(jm["mirrored"], 1);
  EXPECT_TRUE(jm["mirror_problems"].empty());
  EXPECT_EQ(jm["mirror_maps"][0]["by_position"], sm.num_vertices());  // exact positions: all by position
  EXPECT_EQ(jm["mirror_maps"][0]["by_topology"], 0);
  EXPECT_EQ(jm["mirror_maps"][0]["unmatched"], 0);
  Session before(sym);
  const Hierarchy m = read_project(dir.file("m.sublift"));
  Session after(m);
  const MirrorMap map = find_mirror(before.hierarchy().levels[0], before.positions(0), 0);
  const std::int64_t w = map.mirror[0];
  ASSERT_GE(w, 0);
  EXPECT_NEAR(after.positions(0)[3 * w] - before.positions(0)[3 * w], -0.1, 1e-12);
  for (const auto& args : std::vector<std::vector<std::string>>{
           {"edit", dir.file("in.sublift"), "--level", "0", "--brush", "clay", "--at", "0", "0", "0", "-o", dir.file("x.sublift")},
           {"edit", dir.file("in.sublift"), "--level", "0", "--brush", "draw", "-o", dir.file("x.sublift")},
           {"edit", dir.file("in.sublift"), "--level", "0", "--brush", "grab", "--at", "0", "0", "0", "-o", dir.file("x.sublift")},
           {"edit", dir.file("in.sublift"), "--level", "0", "--vertex", "1", "--brush", "draw", "--at", "0", "0", "0", "-o", dir.file("x.sublift")},
           {"edit", dir.file("in.sublift"), "--level", "0", "--vertex", "1", "--delta", "1", "0", "0", "--mirror", "w", "-o", dir.file("x.sublift")},
       }) {
    const ProcessResult bad = cli(args);
    EXPECT_EQ(bad.exit_code, 2) << bad.err;
  }
}

// --loop / --ring / --linked / --grow (issue 19): the modeler's selection tools pick the moved
// points; the JSON counts them as the core functions do.
TEST(CliEdit, SelectionToolsPickThePoints) {
  TempDir dir("sublift_cli_edit_select");
  const Hierarchy h = project_hierarchy();
  write_project(dir.file("in.sublift"), h);
  const Complex& c = h.levels[0];
  const std::int64_t e = find_edge(c, 0, 1);
  ASSERT_GE(e, 0);
  const std::size_t loop = edge_vertices(c, edge_loop(c, static_cast<std::uint32_t>(e))).size();
  const std::size_t ring = edge_vertices(c, edge_ring(c, static_cast<std::uint32_t>(e))).size();
  auto moved = [&](std::vector<std::string> select) {
    std::vector<std::string> args = {"edit", dir.file("in.sublift"), "--level", "0"};
    args.insert(args.end(), select.begin(), select.end());
    for (const char* x : {"--delta", "0", "0.1", "0", "-o"}) args.push_back(x);
    args.push_back(dir.file("o.sublift"));
    args.push_back("--json");
    const ProcessResult r = cli(args);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return r.exit_code == 0 ? nlohmann::json::parse(r.out)["moved"].get<std::size_t>() : std::size_t(0);
  };
  EXPECT_EQ(moved({"--loop", "0", "1"}), loop);
  EXPECT_EQ(moved({"--ring", "0", "1"}), ring);
  EXPECT_EQ(moved({"--linked", "5"}), std::size_t(c.num_vertices));  // a torus is one piece
  EXPECT_EQ(moved({"--vertex", "5", "--grow", "1"}), grow_selection(c, std::vector<unsigned>{5}).size());
  EXPECT_EQ(cli({"edit", dir.file("in.sublift"), "--level", "0", "--loop", "0", "50", "--delta", "0", "0", "0", "-o",
                 dir.file("o.sublift")}).exit_code, 2);
}

TEST(CliEdit, Errors) {
  TempDir dir("sublift_cli_edit_errors");
  write_project(dir.file("in.sublift"), project_hierarchy());
  const std::string in = dir.file("in.sublift"), out = dir.file("o.sublift");
  // Usage: exit 2 with the reason.
  for (const auto& args : std::vector<std::vector<std::string>>{
           {"edit", in, "--level", "0", "--vertex", "1", "-o", out},                              // no delta
           {"edit", in, "--level", "0", "--delta", "1", "0", "0", "-o", out},                    // no vertex
           {"edit", in, "--level", "9", "--vertex", "1", "--delta", "1", "0", "0", "-o", out},   // level
           {"edit", in, "--level", "0", "--vertex", "96", "--delta", "1", "0", "0", "-o", out},  // index
           {"edit", in, "--level", "0", "--vertex", "1", "--delta", "1", "x", "0", "-o", out},   // number
           {"edit", in, "--level", "0", "--vertex", "1", "--delta", "1", "0"},                     // short
       }) {
    const ProcessResult r = cli(args);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_FALSE(r.err.empty());
  }
  // Bad input: exit 1. Local frames on a lattice; a missing project.
  const Shape lattice = read_shape(std::string(SUBLIFT_ASSETS_DIR) + "/prism_ring.lattice");
  Hierarchy lh = make_hierarchy(lattice.base, 1, Scheme::Cubic, 3);
  set_base(lh, lattice.positions);
  write_project(dir.file("lattice.sublift"), lh);
  ProcessResult r = cli({"edit", dir.file("lattice.sublift"), "--level", "0", "--vertex", "1", "--delta", "1", "0", "0",
                         "--local-frames", "-o", out});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("local detail frames need a surface"), std::string::npos) << r.err;
  r = cli({"edit", dir.file("missing.sublift"), "--level", "0", "--vertex", "1", "--delta", "1", "0", "0", "-o", out});
  EXPECT_EQ(r.exit_code, 1);
}

}  // namespace
}  // namespace sublift
