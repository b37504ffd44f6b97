// The modeler's tools (issue 19) on the controller with synthetic keys and mouse: rotate and
// scale (axes, typed values, pivots, cancel, undo), and through `sublift --script`.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>
#include <string>
#include <vector>

#include "app/modeler/script_runner.h"
#include "core/analysis/limit_surface.h"
#include "core/edit/level_ops.h"
#include "core/edit/selection.h"
#include "tests/modeler/controller_fixture.h"
#include "core/base/errors.h"
#include "core/io/lattice/shape_io.h"
#include "tests/io_test_util.h"
#include "tests/test_shapes.h"

namespace sublift {
namespace {

using testing::Fixture;

bool same_bits(std::span<const double> a, std::span<const double> b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

std::vector<std::vector<double>> all_levels(const ModelerState& m) {
  std::vector<std::vector<double>> out;
  for (int l = 0; l <= m.session().finest_level(); ++l) out.emplace_back(m.session().positions(l).begin(), m.session().positions(l).end());
  return out;
}

// Every level is the synthesis of the session's coefficients with its gains (what a fresh open
// of the saved project would show).
void expect_fresh(const ModelerState& m) {
  Hierarchy shown = m.session().hierarchy();
  apply_gains(shown, m.session().gains());
  for (int l = 0; l <= m.session().finest_level(); ++l)
    EXPECT_LT(testing::max_abs_diff(synthesize(shown, l), m.session().positions(l)), 1e-11) << "level " << l;
}

glm::dvec3 point(const ModelerState& m, unsigned v) {
  const auto p = m.session().positions(m.level());
  return {p[3 * v], p[3 * v + 1], p[3 * v + 2]};
}

void type_number(Fixture& f, const std::string& text) {
  for (const char ch : text) {
    if (ch == '-') f.key(Key::Minus);
    else if (ch == '.') f.key(Key::Period);
    else f.key(static_cast<Key>(static_cast<int>(Key::Digit0) + (ch - '0')));
  }
}

TEST(ModelerTransform, RotateTypedDegreesAboutZThroughTheMedianIsOneUndoStep) {
  Fixture f;
  f.app.model.set_selection({0, 1, 2, 3});
  const auto before = all_levels(f.app.model);
  const glm::dvec3 median = f.app.model.transform_pivot();
  f.key(Key::R);
  ASSERT_TRUE(f.app.grabbing());
  f.key(Key::Z);
  type_number(f, "90");
  f.key(Key::Enter);
  EXPECT_EQ(f.app.error, "");
  EXPECT_FALSE(f.app.grabbing());
  ASSERT_EQ(f.app.model.session().history().size(), 1u);
  EXPECT_EQ(f.app.model.session().history()[0].label, "Rotate");
  for (const unsigned v : {0u, 1u, 2u, 3u}) {
    const auto* b = &before[static_cast<std::size_t>(f.app.model.level())][3 * v];
    const glm::dvec3 r(b[0] - median.x, b[1] - median.y, b[2] - median.z);
    const glm::dvec3 p = point(f.app.model, v);
    EXPECT_NEAR(p.x, median.x - r.y, 1e-12);  // a quarter turn about +Z: (x, y) -> (-y, x)
    EXPECT_NEAR(p.y, median.y + r.x, 1e-12);
    EXPECT_EQ(p.z, b[2]);
  }
  expect_fresh(f.app.model);
  testing::expect_shown_equals_fresh(f);
  f.key(Key::Z, {false, true, false});  // Ctrl+Z
  const auto undone = all_levels(f.app.model);
  for (std::size_t l = 0; l < before.size(); ++l) EXPECT_TRUE(same_bits(undone[l], before[l])) << l;
  f.key(Key::Y, {false, true, false});  // Ctrl+Y
  EXPECT_NEAR(point(f.app.model, 0).x, median.x - (before[static_cast<std::size_t>(f.app.model.level())][1] - median.y), 1e-12);
}

TEST(ModelerTransform, ScaleWithShiftAxisExcludesItAndEscapeCancelsBitForBit) {
  Fixture f;
  f.app.model.set_selection({4, 5, 6});
  const auto before = all_levels(f.app.model);
  // Mouse scaling, then Esc: nothing left, not even a redo.
  double x = 0, y = 0;
  ASSERT_TRUE(f.window_position(5, x, y));
  f.send(WindowEvent::Type::Move, x + 40, y + 30);
  f.key(Key::S);
  f.send(WindowEvent::Type::Move, x + 90, y + 70);
  const auto L = static_cast<std::size_t>(f.app.model.level());
  EXPECT_FALSE(same_bits(all_levels(f.app.model)[L], before[L]));
  f.key(Key::Escape);
  for (std::size_t l = 0; l < before.size(); ++l) EXPECT_TRUE(same_bits(all_levels(f.app.model)[l], before[l])) << l;
  EXPECT_TRUE(f.app.model.session().history().empty());

  // S, Shift+Z, 2, Enter: x and y double about the median, z stays.
  const glm::dvec3 c = f.app.model.transform_pivot();
  f.key(Key::S);
  f.key(Key::Z, {true, false, false});
  type_number(f, "2");
  f.key(Key::Enter);
  for (const unsigned v : {4u, 5u, 6u}) {
    const auto* b = &before[static_cast<std::size_t>(f.app.model.level())][3 * v];
    const glm::dvec3 p = point(f.app.model, v);
    EXPECT_NEAR(p.x, c.x + 2.0 * (b[0] - c.x), 1e-12);
    EXPECT_NEAR(p.y, c.y + 2.0 * (b[1] - c.y), 1e-12);
    EXPECT_EQ(p.z, b[2]);
  }
  EXPECT_EQ(f.app.model.session().history().back().label, "Scale");
  expect_fresh(f.app.model);

  // A right click cancels too.
  const auto scaled = all_levels(f.app.model);
  f.key(Key::S);
  f.send(WindowEvent::Type::Move, x + 10, y + 10);
  f.send(WindowEvent::Type::Press, x + 10, y + 10, 1);
  f.send(WindowEvent::Type::Release, x + 10, y + 10, 1);
  EXPECT_FALSE(f.app.grabbing());
  EXPECT_TRUE(same_bits(all_levels(f.app.model)[0], scaled[0]));
  EXPECT_EQ(f.app.model.session().history().size(), 1u);
}

TEST(ModelerTransform, MouseRotationFollowsTheTurnAboutThePivotOnScreen) {
  // A quarter turn of the mouse about the pivot's projection rotates by a quarter turn about
  // the view axis; a right-handed turn about the view direction looks clockwise (y down).
  Fixture f;
  const unsigned v = f.visible_point();
  f.app.model.set_selection({v});
  f.app.model.set_pivot(Pivot::Cursor);
  f.app.model.set_cursor(point(f.app.model, v) + glm::dvec3(0.3, 0.0, 0.0));
  glm::dvec2 c;
  double depth = 0;
  ASSERT_TRUE(project_point(f.view(), f.app.model.cursor(), c, depth));
  const double cx = c.x + testing::kViewX, cy = c.y;
  f.send(WindowEvent::Type::Move, cx + 50, cy);
  const glm::dvec3 p0 = point(f.app.model, v);
  f.key(Key::R);
  f.send(WindowEvent::Type::Move, cx, cy + 50);  // clockwise on screen by 90 degrees
  f.key(Key::Enter);
  const glm::dvec3 k = f.app.camera.forward();
  const glm::dvec3 r0 = p0 - f.app.model.cursor();
  const glm::dvec3 expect = f.app.model.cursor() + glm::cross(k, r0) + k * glm::dot(k, r0);
  const glm::dvec3 p = point(f.app.model, v);
  EXPECT_LT(glm::length(p - expect), 1e-9 * (1.0 + glm::length(r0)));
}

TEST(ModelerTransform, PivotsActiveCursorAndOriginThroughTheScript) {
  ModelerState m;
  m.open(std::string(SUBLIFT_ASSETS_DIR) + "/torus_quad.obj");
  ASSERT_EQ(m.level(), 0);
  const auto start = all_levels(m);
  auto run = [&](const std::string& text) {
    ScriptRunner runner("tools.txt", text);
    const ScriptStep step = runner.next(m);
    ASSERT_EQ(step.kind, ScriptStep::Kind::End) << step.message;
  };
  // Scale 0 about the active point: the selection collapses onto it, which stays.
  run("select 0 1 2\nactive 2\npivot active\nscale 0\n");
  for (const unsigned v : {0u, 1u, 2u})
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(m.session().positions(0)[3 * v + c], start[0][6 + c], 1e-15);
  expect_fresh(m);
  run("undo\npivot cursor\ncursor 1 2 3\nrotate 0 0 1 180\n");  // a half turn about the cursor's vertical
  for (const unsigned v : {0u, 1u, 2u}) {
    EXPECT_NEAR(point(m, v).x, 2.0 - start[0][3 * v], 1e-12);
    EXPECT_NEAR(point(m, v).y, 4.0 - start[0][3 * v + 1], 1e-12);
    EXPECT_NEAR(point(m, v).z, start[0][3 * v + 2], 1e-12);
  }
  expect_fresh(m);
  run("undo\npivot origin\nscale 1 -1 1\n");  // a mirror through y = 0, exact
  for (const unsigned v : {0u, 1u, 2u}) {
    EXPECT_EQ(point(m, v).x, start[0][3 * v]);
    EXPECT_EQ(point(m, v).y, -start[0][3 * v + 1]);
    EXPECT_EQ(point(m, v).z, start[0][3 * v + 2]);
  }
  ASSERT_NE(start[0][4], 0.0);  // vertex 1 is off the mirror plane
  EXPECT_EQ(m.session().history().size(), 1u);
  EXPECT_EQ(m.session().undo_position(), 1u);
  EXPECT_FALSE(m.dragging());
  ASSERT_TRUE(m.undo());
  for (std::size_t l = 0; l < start.size(); ++l) EXPECT_TRUE(same_bits(all_levels(m)[l], start[l])) << l;
}

TEST(ModelerTransform, ScriptRefusalsSayWhy) {
  ModelerState m;
  m.open(std::string(SUBLIFT_ASSETS_DIR) + "/torus_quad.obj");
  auto error_of = [&](const std::string& text) {
    ScriptRunner run("bad.txt", text);
    const ScriptStep s = run.next(m);
    return s.kind == ScriptStep::Kind::Error ? s.message : std::string("no error");
  };
  EXPECT_EQ(error_of("rotate z 10"), "script:1: rotate needs a selection (use 'select INDEX...')");
  EXPECT_EQ(error_of("select 0\nrotate w 10"), "script:2: rotate axis must be x, y, z or three numbers");
  EXPECT_EQ(error_of("select 0\nrotate 0 0 0 10"), "script:2: the rotation axis must not be zero");
  EXPECT_EQ(error_of("scale 1 2"), "script:1: usage: scale S | scale SX SY SZ");
  EXPECT_EQ(error_of("pivot centre"), "script:1: unknown pivot 'centre' (median, active, cursor or origin)");
  EXPECT_EQ(error_of("select 0\nactive 5"), "script:2: active 5: the active point must be selected");
  EXPECT_TRUE(m.session().history().empty());
}

}  // namespace
}  // namespace sublift

namespace sublift {
namespace {

std::vector<std::vector<double>> levels_of(const ModelerState& m) {
  std::vector<std::vector<double>> out;
  for (int l = 0; l <= m.session().finest_level(); ++l) out.emplace_back(m.session().positions(l).begin(), m.session().positions(l).end());
  return out;
}

// A torus with an edit at every level and gains that are not 1, so that every level's shape
// depends on all the coefficients below it.
ModelerState edited_torus(const std::string& scheme) {
  ModelerState m;
  m.open(std::string(SUBLIFT_ASSETS_DIR) + "/torus_quad.obj");
  ScriptRunner run("levels.txt", "scheme " + scheme + "\nsubdivide\nlevel 0\nselect 3\nmove 0 0 0.2\nlevel 1\nselect 20 21\n"
                                 "move 0.05 0 0\nlevel 2\nselect 100\nmove 0 0.03 0\ngain 1 0.5\nlevel 3\nselect 700\nmove 0 0 -0.02\n");
  const ScriptStep s = run.next(m);
  EXPECT_EQ(s.kind, ScriptStep::Kind::End) << s.message;
  return m;
}

TEST(ModelerLevels, DeleteHigherKeepsTheLowerLevels) {
  for (const std::string scheme : {"cubic", "linear", "sqrt2"}) {
    SCOPED_TRACE(scheme);
    ModelerState m = edited_torus(scheme);
    const auto before = levels_of(m);
    const std::vector<double> gains(m.session().gains().begin(), m.session().gains().end());
    m.set_level(2);
    const std::string note = m.delete_higher_levels();
    EXPECT_NE(note.find("deleted levels 3.."), std::string::npos) << note;
    ASSERT_EQ(m.session().finest_level(), 2);
    EXPECT_EQ(m.level(), 2);
    // Unchanged up to rounding: the old session kept its levels by local resynthesis, the new
    // one synthesises them afresh from the same coefficients.
    for (int l = 0; l <= 2; ++l) EXPECT_LT(testing::max_abs_diff(levels_of(m)[l], before[l]), 1e-12) << "level " << l;
    EXPECT_EQ(std::vector<double>(m.session().gains().begin(), m.session().gains().end()),
              std::vector<double>(gains.begin(), gains.begin() + 2));
    EXPECT_TRUE(m.session().history().empty());
    EXPECT_TRUE(m.session().dirty());  // a save is needed to keep this
    expect_fresh(m);
    EXPECT_THROW(m.delete_higher_levels(), Error);  // nothing above the finest
  }
}

TEST(ModelerLevels, DeleteLowerMakesTheEditLevelTheBaseAndKeepsEveryFinerLevel) {
  for (const std::string scheme : {"cubic", "linear", "sqrt2"}) {
    SCOPED_TRACE(scheme);
    ModelerState m = edited_torus(scheme);
    const auto before = levels_of(m);
    const int J = m.session().finest_level();
    m.set_level(1);
    m.set_selection({5, 9});
    const std::string note = m.delete_lower_levels();
    EXPECT_NE(note.find("level 1 is the new base"), std::string::npos) << note;
    ASSERT_EQ(m.session().finest_level(), J - 1);
    EXPECT_EQ(m.level(), 0);
    EXPECT_EQ(m.selection(), (std::vector<unsigned>{5, 9}));  // the same points, now of level 0
    for (int k = 0; k <= J - 1; ++k)
      EXPECT_LT(testing::max_abs_diff(levels_of(m)[k], before[static_cast<std::size_t>(k) + 1]), 1e-12) << "level " << k;
    EXPECT_EQ(m.session().gain(0), 0.5);  // old level 1's gain
    expect_fresh(m);
    EXPECT_TRUE(m.session().dirty());
    // The new base edits like any base: a move at level 0 resynthesises the finer levels.
    m.begin_drag("Move");
    const double d[3] = {0.0, 0.1, 0.0};
    m.drag_to(d);
    m.end_drag();
    expect_fresh(m);
    EXPECT_THROW(m.delete_lower_levels(), Error);  // level 0 already is the base
  }
}

TEST(ModelerLevels, ExportEveryLevelAndScriptCommands) {
  const testing::TempDir dir("sublift_export_levels");
  ModelerState m = edited_torus("cubic");
  ScriptRunner run("levels.txt", "export-levels " + dir.file("shape.obj") + "\napply-base\nlevel 2\ndelete higher\n"
                                 "delete lower\n");
  const ScriptStep s = run.next(m);
  ASSERT_EQ(s.kind, ScriptStep::Kind::End) << s.message;
  EXPECT_EQ(m.session().finest_level(), 0);  // 2 became the finest, then the base
  for (int l = 0; l <= 3; ++l) {
    const Shape shape = read_shape(dir.file("shape_L" + std::to_string(l) + ".obj"));
    EXPECT_EQ(shape.base.num_vertices, edited_torus("cubic").session().num_vertices(l)) << l;
  }
  ScriptRunner net("levels.txt", "export-net 0 " + dir.file("net 0.obj") + "\n");
  ASSERT_EQ(net.next(m).kind, ScriptStep::Kind::End);
  EXPECT_EQ(read_shape(dir.file("net 0.obj")).base.num_vertices, m.session().num_vertices(0));
  ScriptRunner bad("bad.txt", "delete middle\n");
  EXPECT_EQ(bad.next(m).message, "script:1: usage: delete higher|lower");
  EXPECT_NE(std::string(ModelerState::apply_base_note()).find("nothing to apply"), std::string::npos);
}

}  // namespace
}  // namespace sublift

namespace sublift {
namespace {

using testing::Fixture;

constexpr Modifiers kCtrl{false, true, false}, kShift{true, false, false}, kAlt{false, false, true},
    kCtrlAlt{false, true, true};

TEST(ModelerSelection, InvertGrowShrinkAndLinkedKeys) {
  Fixture f;
  const std::uint32_t n = f.app.model.session().num_vertices(f.app.model.level());
  f.app.model.set_selection({5});
  f.key(Key::NumpadPlus, kCtrl);
  const std::vector<unsigned> grown = grow_selection(f.app.model.level_complex(), std::vector<unsigned>{5});
  EXPECT_EQ(f.app.model.selection(), grown);
  EXPECT_EQ(grown.size(), 5u);  // a regular quad vertex and its four neighbours
  f.key(Key::NumpadMinus, kCtrl);
  EXPECT_EQ(f.app.model.selection(), (std::vector<unsigned>{5}));
  f.key(Key::I, kCtrl);
  EXPECT_EQ(f.app.model.selection().size(), n - 1);
  f.app.model.set_selection({5});
  f.key(Key::L, kCtrl);  // a torus is one piece
  EXPECT_EQ(f.app.model.selection().size(), n);
  // L under the mouse adds what is joined to the point there; Shift+L takes it away.
  f.app.model.set_selection({});
  const unsigned v = f.visible_point();
  double x = 0, y = 0;
  ASSERT_TRUE(f.window_position(v, x, y));
  f.send(WindowEvent::Type::Move, x, y);
  f.key(Key::L);
  EXPECT_EQ(f.app.model.selection().size(), n);
  f.key(Key::L, kShift);
  EXPECT_TRUE(f.app.model.selection().empty());
}

// The net edge under the mouse: the one nearest to the middle of the projected segment of an
// edge of the front-most point.
bool edge_middle(Fixture& f, std::uint32_t& edge, double& x, double& y) {
  const unsigned v = f.visible_point();
  const Complex& c = f.app.model.level_complex();
  for (const std::uint32_t e : c.vertex_edges.row(v)) {
    double ax, ay, bx, by;
    if (!f.window_position(c.edge_verts[2 * e], ax, ay) || !f.window_position(c.edge_verts[2 * e + 1], bx, by)) continue;
    if (std::hypot(bx - ax, by - ay) < 30) continue;  // too short on screen to aim at its middle
    edge = e, x = 0.5 * (ax + bx), y = 0.5 * (ay + by);
    return true;
  }
  return false;
}

TEST(ModelerSelection, AltClickSelectsTheEdgeLoopAndAltDragStillOrbits) {
  Fixture f;
  std::uint32_t e = 0;
  double x = 0, y = 0;
  ASSERT_TRUE(edge_middle(f, e, x, y));
  f.click(x, y, kAlt);
  const Complex& c = f.app.model.level_complex();
  const std::vector<unsigned> loop = f.app.model.selection();
  EXPECT_TRUE(std::binary_search(loop.begin(), loop.end(), c.edge_verts[2 * e]));
  EXPECT_TRUE(std::binary_search(loop.begin(), loop.end(), c.edge_verts[2 * e + 1]));
  // The torus (12 x 8 quads) closes every loop round one of its two circles.
  EXPECT_TRUE(loop.size() == 12 || loop.size() == 8) << loop.size();
  // Ctrl+Alt: the ring, the other way round; Shift adds.
  f.click(x, y, kCtrlAlt);
  const std::vector<unsigned> ring = f.app.model.selection();
  EXPECT_EQ(ring.size(), 2 * (20 - loop.size()));
  f.click(x, y, Modifiers{true, false, true});  // Shift+Alt: the loop joins the ring
  EXPECT_EQ(f.app.model.selection().size(), ring.size() + loop.size() - 2);
  // An Alt+drag is a Maya orbit: the camera turns and the selection stays.
  const glm::dvec3 eye = f.app.camera.eye();
  f.app.model.set_selection({});
  f.send(WindowEvent::Type::Move, x, y, 0, kAlt);
  f.send(WindowEvent::Type::Press, x, y, 0, kAlt);
  f.send(WindowEvent::Type::Move, x + 60, y + 20, 0, kAlt);
  f.send(WindowEvent::Type::Release, x + 60, y + 20, 0, kAlt);
  EXPECT_TRUE(f.app.model.selection().empty());
  EXPECT_GT(glm::length(f.app.camera.eye() - eye), 1e-6);
}

TEST(ModelerSelection, CircleSelectPaintsAndShiftErases) {
  Fixture f;
  const unsigned v = f.visible_point();
  double x = 0, y = 0;
  ASSERT_TRUE(f.window_position(v, x, y));
  f.key(Key::C);
  ASSERT_TRUE(f.app.circle_selecting());
  f.send(WindowEvent::Type::Move, x, y);
  f.send(WindowEvent::Type::Press, x, y);
  f.send(WindowEvent::Type::Release, x, y);
  const std::vector<unsigned> first = f.app.model.selection();
  EXPECT_TRUE(std::binary_search(first.begin(), first.end(), v));
  // What the circle covers, by the picking index's own rule (40 pixels, front points only).
  PickIndex index;
  index.build(f.view(), f.app.model.session().positions(f.app.model.level()));
  const std::vector<std::uint32_t> inside = index.in_circle(x - testing::kViewX, y, 40.0, true);
  for (const unsigned u : first) EXPECT_TRUE(std::binary_search(inside.begin(), inside.end(), u)) << u;
  // A stroke adds where it passes: down at v, up at a front point far from it.
  unsigned far = v;
  double fx = 0, fy = 0;
  for (unsigned u = 0; u < f.app.model.session().num_vertices(f.app.model.level()) && far == v; ++u)
    if (f.window_position(u, fx, fy) && std::hypot(fx - x, fy - y) > 100 && index.nearest(fx - testing::kViewX, fy, 10.0, false) == u)
      far = u;
  ASSERT_NE(far, v);
  f.send(WindowEvent::Type::Press, x, y);
  f.send(WindowEvent::Type::Move, fx, fy);
  f.send(WindowEvent::Type::Release, fx, fy);
  EXPECT_GT(f.app.model.selection().size(), first.size());
  EXPECT_TRUE(std::binary_search(f.app.model.selection().begin(), f.app.model.selection().end(), far));
  f.send(WindowEvent::Type::Press, x, y, 0, kShift);
  f.send(WindowEvent::Type::Release, x, y, 0, kShift);
  EXPECT_FALSE(std::binary_search(f.app.model.selection().begin(), f.app.model.selection().end(), v));
  f.key(Key::Escape);
  EXPECT_FALSE(f.app.circle_selecting());
  EXPECT_TRUE(f.app.model.session().history().empty());  // selection is no edit
}

TEST(ModelerSelection, ScriptSelectWords) {
  ModelerState m;
  m.open(std::string(SUBLIFT_ASSETS_DIR) + "/torus_quad.obj");
  const std::int64_t e = find_edge(m.level_complex(), 0, 1);
  ASSERT_GE(e, 0);
  ScriptRunner run("sel.txt", "select loop 0 1\n");
  ASSERT_EQ(run.next(m).kind, ScriptStep::Kind::End);
  EXPECT_EQ(m.selection(), edge_vertices(m.level_complex(), edge_loop(m.level_complex(), static_cast<std::uint32_t>(e))));
  ScriptRunner more("sel.txt", "select 0\nselect more\nselect more\nselect less\nselect invert\nselect invert\n");
  ASSERT_EQ(more.next(m).kind, ScriptStep::Kind::End);
  EXPECT_EQ(m.selection(), grow_selection(m.level_complex(), std::vector<unsigned>{0}));
  ScriptRunner bad("bad.txt", "select loop 0 50\n");
  EXPECT_EQ(bad.next(m).message, "script:1: select loop: vertices 0 and 50 share no edge");
}

// Mirror editing on the torus, symmetric across x = 0: a move, a rotation and a scale of
// points on one side move their images on the other by the mirrored amounts; undo restores both.
TEST(ModelerSymmetry, MirroredMovesRotationsAndScalesOnASymmetricMesh) {
  ModelerState m;
  m.open(std::string(SUBLIFT_ASSETS_DIR) + "/torus_quad.obj");
  EXPECT_EQ(m.set_symmetry(0, true), "");
  const MirrorMap& map = m.mirror_map(0);
  EXPECT_EQ(map.unmatched, 0u);
  EXPECT_EQ(map.by_topology, 0u);  // exact positions: all found by position
  const auto start = all_levels(m);
  const auto p0 = m.session().positions(0);
  unsigned v = 0;
  while (p0[3 * v] < 0.3) ++v;  // a point well off the plane
  const unsigned w = static_cast<unsigned>(map.mirror[v]);
  ASSERT_NE(v, w);
  EXPECT_NEAR(p0[3 * w], -p0[3 * v], 1e-12);
  ScriptRunner run("sym.txt", "select " + std::to_string(v) + "\nmove 0.1 0.05 -0.02\npivot origin\nrotate z 30\nscale 1.5\n");
  ASSERT_EQ(run.next(m).kind, ScriptStep::Kind::End);
  const auto p = m.session().positions(0);
  EXPECT_NEAR(p[3 * w], -p[3 * v], 1e-12);  // the images stay mirrored through every step
  EXPECT_NEAR(p[3 * w + 1], p[3 * v + 1], 1e-12);
  EXPECT_NEAR(p[3 * w + 2], p[3 * v + 2], 1e-12);
  EXPECT_NE(p[3 * v], start[0][3 * v]);
  expect_fresh(m);
  EXPECT_EQ(m.session().history().size(), 3u);
  for (int i = 0; i < 3; ++i) ASSERT_TRUE(m.undo());
  for (std::size_t l = 0; l < start.size(); ++l) EXPECT_TRUE(same_bits(all_levels(m)[l], start[l])) << l;
  // A point on the plane keeps x = 0 (its own image).
  unsigned on = 0;
  while (map.mirror[on] != on) ++on;
  ScriptRunner plane("sym.txt", "select " + std::to_string(on) + "\nmove 0.3 0.1 0\n");
  ASSERT_EQ(plane.next(m).kind, ScriptStep::Kind::End);
  EXPECT_EQ(m.session().positions(0)[3 * on], start[0][3 * on]);
  EXPECT_NEAR(m.session().positions(0)[3 * on + 1], start[0][3 * on + 1] + 0.1, 1e-12);
}

TEST(ModelerSymmetry, AsymmetricMeshIsNamedAndNearlySymmetricOneMatchesByTopology) {
  // The torus with one point moved off its mirror position: found by topology all the same.
  ModelerState exact, m;
  exact.open(std::string(SUBLIFT_ASSETS_DIR) + "/torus_quad.obj");
  m.open(std::string(SUBLIFT_ASSETS_DIR) + "/torus_quad.obj");
  ScriptRunner nudge("sym.txt", "select 30 31\nmove 0.01 0.004 0\n");
  ASSERT_EQ(nudge.next(m).kind, ScriptStep::Kind::End);
  EXPECT_EQ(m.set_symmetry(0, true), "");
  EXPECT_GE(m.mirror_map(0).by_topology, 2u);  // the moved points (and their images)
  EXPECT_EQ(m.mirror_map(0).mirror, exact.mirror_map(0).mirror);
  // A mesh that is not symmetric: named, with the first points that have no image.
  ModelerState a;
  a.open(std::string(SUBLIFT_ASSETS_DIR) + "/mixed_polygons.obj");
  ScriptRunner run("sym.txt", "symmetry x on\n");
  const ScriptStep s = run.next(a);
  ASSERT_EQ(s.kind, ScriptStep::Kind::Error);
  EXPECT_NE(s.message.find("X mirror: "), std::string::npos) << s.message;
  EXPECT_NE(s.message.find("have no mirror image (first: "), std::string::npos) << s.message;
  EXPECT_TRUE(a.symmetry(0));
}

}  // namespace
}  // namespace sublift

namespace sublift {
namespace {

// The mean change of the distance of level `l`'s moved points from the torus's centre circle
// (radius 1 in the xz plane; torus_quad.obj's tube circles lie across it), relative to `before`.
double mean_radial_change(const ModelerState& m, const std::vector<double>& before, int l) {
  const auto p = m.session().positions(l);
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t v = 0; 3 * v < p.size(); ++v) {
    auto tube = [&](const double* x) { return std::hypot(std::hypot(x[0], x[2]) - 1.0, x[1]); };
    const double d = tube(&p[3 * v]) - tube(&before[3 * v]);
    if (d != 0.0) sum += d, ++n;
  }
  return n ? sum / static_cast<double>(n) : 0.0;
}

// The window position of the limit surface point facing the viewer most squarely.
void facing_point(const Fixture& f, double& x, double& y) {
  const auto& lim = f.app.model.limit_positions();
  const auto& nor = f.app.model.limit_normals();
  const glm::dvec3 k = f.app.camera.forward();
  double best = 0.0;
  for (std::size_t v = 0; 3 * v < lim.size(); ++v) {
    const double facing = -(nor[3 * v] * k.x + nor[3 * v + 1] * k.y + nor[3 * v + 2] * k.z);
    glm::dvec2 s;
    double depth = 0;
    if (facing > best && project_point(f.view(), glm::dvec3(lim[3 * v], lim[3 * v + 1], lim[3 * v + 2]), s, depth))
      best = facing, x = s.x + testing::kViewX, y = s.y;
  }
}

TEST(ModelerSculpt, StrokesAreOneUndoStepAndCtrlInverts) {
  Fixture f;
  f.app.model.set_level(1);
  f.key(Key::Tab, kCtrl);
  ASSERT_TRUE(f.app.sculpting());
  f.key(Key::I);  // inflate
  EXPECT_EQ(f.app.model.brush().kind, BrushKind::Inflate);
  const auto before = all_levels(f.app.model);
  double x = 0, y = 0;
  facing_point(f, x, y);
  // A stroke across the surface from the point facing the viewer.
  f.send(WindowEvent::Type::Move, x, y + 4);
  f.send(WindowEvent::Type::Press, x, y + 4);
  ASSERT_TRUE(f.app.stroking()) << f.app.error;
  f.send(WindowEvent::Type::Move, x + 15, y + 6);
  f.send(WindowEvent::Type::Move, x + 30, y + 8);
  f.send(WindowEvent::Type::Release, x + 30, y + 8);
  EXPECT_FALSE(f.app.stroking());
  ASSERT_EQ(f.app.model.session().history().size(), 1u);
  EXPECT_EQ(f.app.model.session().history()[0].label, "Brush inflate");
  EXPECT_GT(mean_radial_change(f.app.model, before[1], 1), 0.0);  // inflate pushes the tube out
  expect_fresh(f.app.model);
  testing::expect_shown_equals_fresh(f);
  // Ctrl: the same stroke deflates; the brush is back to inflate afterwards.
  const auto mid = all_levels(f.app.model);
  f.send(WindowEvent::Type::Move, x, y + 4, 0, kCtrl);
  f.send(WindowEvent::Type::Press, x, y + 4, 0, kCtrl);
  f.send(WindowEvent::Type::Move, x + 30, y + 8, 0, kCtrl);
  f.send(WindowEvent::Type::Release, x + 30, y + 8, 0, kCtrl);
  EXPECT_LT(mean_radial_change(f.app.model, mid[1], 1), 0.0);
  EXPECT_FALSE(f.app.model.brush().invert);
  // Undo twice: bit for bit where it started.
  f.key(Key::Z, kCtrl);
  f.key(Key::Z, kCtrl);
  for (std::size_t l = 0; l < before.size(); ++l) EXPECT_TRUE(same_bits(all_levels(f.app.model)[l], before[l])) << l;
  // A press off the surface strokes nothing; R does not rotate in sculpt mode.
  f.send(WindowEvent::Type::Press, testing::kViewX + 5, 5);
  f.send(WindowEvent::Type::Release, testing::kViewX + 5, 5);
  f.app.model.set_selection({0});
  f.key(Key::R);
  EXPECT_FALSE(f.app.grabbing());
  EXPECT_EQ(f.app.model.session().undo_position(), 0u);
  f.key(Key::Tab, kCtrl);
  EXPECT_FALSE(f.app.sculpting());
}

TEST(ModelerSculpt, BrushKeysAndRadiusAdjustWithTheMouse) {
  Fixture f;
  f.key(Key::Tab, kCtrl);
  const std::pair<Key, BrushKind> keys[] = {{Key::X, BrushKind::Draw}, {Key::S, BrushKind::Smooth}, {Key::G, BrushKind::Grab},
                                            {Key::P, BrushKind::Pinch}, {Key::I, BrushKind::Inflate}};
  for (const auto& [k, kind] : keys) {
    f.key(k);
    EXPECT_EQ(f.app.model.brush().kind, kind);
  }
  f.key(Key::T, kShift);
  EXPECT_EQ(f.app.model.brush().kind, BrushKind::Flatten);
  const double r0 = f.app.model.brush().radius;
  f.send(WindowEvent::Type::Move, 600, 300);
  f.key(Key::F);
  f.send(WindowEvent::Type::Move, 750, 300);  // 150 px to the right: e times the radius
  EXPECT_NEAR(f.app.model.brush().radius, r0 * std::exp(1.0), 1e-12 * r0);
  f.key(Key::Escape);  // back to where it was
  EXPECT_EQ(f.app.model.brush().radius, r0);
  f.send(WindowEvent::Type::Move, 600, 300);
  f.key(Key::F, kShift);
  f.send(WindowEvent::Type::Move, 660, 300);
  f.send(WindowEvent::Type::Press, 660, 300);  // a click keeps it
  f.send(WindowEvent::Type::Release, 660, 300);
  EXPECT_NEAR(f.app.model.brush().strength, 0.5 + 60.0 / 300.0, 1e-12);
}

TEST(ModelerSculpt, ScriptStrokesWithSymmetryAndGrab) {
  ModelerState m;
  m.open(std::string(SUBLIFT_ASSETS_DIR) + "/torus_quad.obj");
  const auto start = all_levels(m);
  const std::vector<double> p = start[0];
  // A draw stroke at vertex 0 (x = 1.4, y = 0, z = 0) with x symmetry: the image across x = 0
  // moves the mirrored way.
  ScriptRunner run("sculpt.txt", "symmetry x on\nbrush draw 0.5 0.6\nstroke 1.4 0 0\n");
  ASSERT_EQ(run.next(m).kind, ScriptStep::Kind::End);
  const MirrorMap& map = m.mirror_map(0);
  const unsigned w = static_cast<unsigned>(map.mirror[0]);
  const auto q = m.session().positions(0);
  EXPECT_NE(q[0], p[0]);
  EXPECT_NEAR(q[3 * w] - p[3 * w], -(q[0] - p[0]), 1e-12);
  EXPECT_NEAR(q[3 * w + 1] - p[3 * w + 1], q[1] - p[1], 1e-12);
  expect_fresh(m);
  EXPECT_EQ(m.session().history().back().label, "Brush draw");
  // Grab: the points near the first centre follow the motion to the second (weight 1 at 0).
  ScriptRunner grab("sculpt.txt", "undo\nsymmetry x off\nbrush grab 0.3 1\nbrush falloff constant\nstroke 1.4 0 0 1.4 0 0.2\n");
  ASSERT_EQ(grab.next(m).kind, ScriptStep::Kind::End);
  EXPECT_NEAR(m.session().positions(0)[2], start[0][2] + 0.2, 1e-12);
  EXPECT_EQ(m.session().positions(0)[3 * w + 2], start[0][3 * w + 2]);  // no symmetry now
  ScriptRunner bad("bad.txt", "brush clay\n");
  EXPECT_EQ(bad.next(m).message, "script:1: unknown brush 'clay' (draw, inflate, smooth, grab, flatten or pinch)");
  ScriptRunner lattice("lat.txt", "open " + std::string(SUBLIFT_ASSETS_DIR) + "/hex_block_4.lattice\nbrush draw 0.5\nstroke 0 0 0\n");
  EXPECT_NE(lattice.next(m).message.find("needs a surface"), std::string::npos);
}

}  // namespace
}  // namespace sublift

namespace sublift {
namespace {

TEST(ModelerFeatures, CreaseOnTheBaseKeepsTheShapeAndUndoBringsTheOldHierarchyBack) {
  const testing::TempDir dir("sublift_modeler_crease");
  ModelerState m = edited_torus("cubic");
  m.set_level(0);
  const auto before = levels_of(m);
  const int J = m.session().finest_level();
  const std::int64_t e = find_edge(m.level_complex(), 0, 1);
  ASSERT_GE(e, 0);
  ASSERT_EQ(m.level_complex().edge_dim[static_cast<std::size_t>(e)], 2);
  m.set_selection({0, 1});
  const std::string note = m.toggle_creases();
  EXPECT_NE(note.find("creased 1 edge"), std::string::npos) << note;
  EXPECT_EQ(m.level_complex().edge_dim[static_cast<std::size_t>(e)], 1);
  // The finest shape as shown stays; the detail is re-expressed under the crease rules.
  EXPECT_LT(testing::max_abs_diff(levels_of(m)[static_cast<std::size_t>(J)], before[static_cast<std::size_t>(J)]), 1e-12);
  expect_fresh(m);
  EXPECT_TRUE(m.session().dirty());
  EXPECT_TRUE(m.session().history().empty());
  ASSERT_TRUE(m.can_undo());
  // Saved in the project, and as an OBJ tag of the base.
  m.save_project(dir.file("c.sublift"));
  ModelerState back;
  back.open(dir.file("c.sublift"));
  EXPECT_EQ(back.level_complex().edge_dim[static_cast<std::size_t>(e)], 1);
  m.export_level(dir.file("base.obj"), 0);
  EXPECT_EQ(read_shape(dir.file("base.obj")).base.edge_dim[static_cast<std::size_t>(e)], 1);
  // The crease changes what a base move does.
  ModelerState plain = edited_torus("cubic");
  ScriptRunner move("m.txt", "level 0\nselect 0\nmove 0 0.2 0\n");
  ScriptRunner move2("m.txt", "level 0\nselect 0\nmove 0 0.2 0\n");
  ASSERT_EQ(move.next(m).kind, ScriptStep::Kind::End);
  ASSERT_EQ(move2.next(plain).kind, ScriptStep::Kind::End);
  EXPECT_GT(testing::max_abs_diff(levels_of(m)[static_cast<std::size_t>(J)], levels_of(plain)[static_cast<std::size_t>(J)]), 1e-4);
  // Undo the move, then the crease: the old session with its own history, bit for bit.
  ASSERT_TRUE(m.undo());
  ASSERT_TRUE(m.undo());
  EXPECT_EQ(m.level_complex().edge_dim[static_cast<std::size_t>(e)], 2);
  for (std::size_t l = 0; l < before.size(); ++l) EXPECT_TRUE(same_bits(levels_of(m)[l], before[l])) << l;
  EXPECT_FALSE(m.session().history().empty());  // edited_torus's edits are there again
  ASSERT_TRUE(m.redo());
  EXPECT_EQ(m.level_complex().edge_dim[static_cast<std::size_t>(e)], 1);
  // Clearing it again; corners likewise.
  m.set_selection({0, 1});
  EXPECT_NE(m.toggle_creases().find("cleared 1 edge"), std::string::npos);
  EXPECT_EQ(m.level_complex().edge_dim[static_cast<std::size_t>(e)], 2);
  m.set_selection({7});
  m.toggle_corners();
  EXPECT_EQ(m.level_complex().vertex_dim[7], 0);
  EXPECT_LT(testing::max_abs_diff(levels_of(m)[static_cast<std::size_t>(J)], before[static_cast<std::size_t>(J)]), 1e-12);
}

TEST(ModelerFeatures, RefusalsAndKeys) {
  Fixture f;
  f.app.model.set_level(1);
  f.app.model.set_selection({0, 1});
  EXPECT_THROW(f.app.model.toggle_creases(), Error);
  f.app.model.set_level(0);
  f.app.model.set_selection({});
  EXPECT_THROW(f.app.model.toggle_creases(), Error);
  EXPECT_THROW(f.app.model.toggle_corners(), Error);
  f.app.model.set_selection({0, 1});
  f.key(Key::E, kShift);
  EXPECT_EQ(f.app.model.level_complex().edge_dim[static_cast<std::size_t>(find_edge(f.app.model.level_complex(), 0, 1))], 1);
  f.key(Key::E, Modifiers{true, true, false});
  EXPECT_EQ(f.app.model.level_complex().vertex_dim[0], 0);
  f.key(Key::Z, kCtrl);
  f.key(Key::Z, kCtrl);
  EXPECT_EQ(f.app.model.level_complex().vertex_dim[0], 2);
  ScriptRunner bad("bad.txt", "crease maybe\n");
  EXPECT_EQ(bad.next(f.app.model).message, "script:1: usage: crease mark|clear|toggle");
}

TEST(ModelerFeatures, LevelDeletionsAndSchemeChangesUndoToo) {
  ModelerState m = edited_torus("cubic");
  const auto before = levels_of(m);
  m.set_level(1);
  m.delete_lower_levels();
  m.set_level(1);
  m.delete_higher_levels();
  m.set_scheme(Scheme::Linear);
  ASSERT_TRUE(m.undo());  // linear -> cubic
  EXPECT_EQ(m.session().hierarchy().scheme, Scheme::Cubic);
  ASSERT_TRUE(m.undo());  // delete higher
  ASSERT_TRUE(m.undo());  // delete lower
  ASSERT_EQ(levels_of(m).size(), before.size());
  for (std::size_t l = 0; l < before.size(); ++l) EXPECT_TRUE(same_bits(levels_of(m)[l], before[l])) << l;
  // A new edit after an undo makes a new future: the replaced sessions are not redone over it.
  ScriptRunner edit("e.txt", "level 0\nselect 2\nmove 0.1 0 0\n");
  ASSERT_EQ(edit.next(m).kind, ScriptStep::Kind::End);
  EXPECT_FALSE(m.redo());
  EXPECT_EQ(levels_of(m).size(), before.size());
}

}  // namespace
}  // namespace sublift

namespace sublift {
namespace {

// The limit surface of level `v` of the session, evaluated afresh (the hierarchy cut at v).
std::vector<double> fresh_limit(const ModelerState& m, int v) {
  const Hierarchy cut = delete_higher(m.session().hierarchy(), v);
  return finest_limit_surface(cut, m.session().positions(v)).positions;
}

TEST(ModelerViewLevel, ACoarserViewportLevelDrawsThatLevelsLimitAndExportsStayFinest) {
  const testing::TempDir dir("sublift_view_level");
  ModelerState m = edited_torus("cubic");
  const int J = m.session().finest_level();
  ASSERT_EQ(J, 3);
  m.set_view_level(1);
  EXPECT_EQ(m.shown_level(), 1);
  EXPECT_EQ(m.limit_positions().size(), 3 * std::size_t(m.session().num_vertices(1)));
  EXPECT_LT(testing::max_abs_diff(m.limit_positions(), fresh_limit(m, 1)), 1e-12);
  // Edits at any level update the shown limit incrementally, as a fresh evaluation would.
  ScriptRunner run("v.txt", "level 0\nselect 3\nmove 0 0.1 0\nlevel 2\nselect 40\nmove 0.05 0 0\nundo\n");
  ASSERT_EQ(run.next(m).kind, ScriptStep::Kind::End);
  EXPECT_LT(testing::max_abs_diff(m.limit_positions(), fresh_limit(m, 1)), 1e-12);
  // "Finest limit" exports are the finest level's, whatever the viewport shows.
  m.export_shape(dir.file("f.obj"), true);
  EXPECT_EQ(read_shape(dir.file("f.obj")).base.num_vertices, m.session().num_vertices(J));
  // The compression view and the basis mode draw the finest level: refused while coarser.
  EXPECT_THROW(m.set_compression(0.5), Error);
  // Subdivide keeps the chosen level; finest follows the new finest.
  m.subdivide();
  EXPECT_EQ(m.shown_level(), 1);
  ScriptRunner back("v.txt", "view-level finest\n");
  ASSERT_EQ(back.next(m).kind, ScriptStep::Kind::End);
  EXPECT_EQ(m.shown_level(), 4);
  EXPECT_EQ(m.limit_positions().size(), 3 * std::size_t(m.session().num_vertices(4)));
  ScriptRunner bad("bad.txt", "view-level 9\n");
  EXPECT_EQ(bad.next(m).message, "script:1: view-level 9 is outside 0..4 (or finest)");
}

}  // namespace
}  // namespace sublift

namespace sublift {
namespace {

// One fast mouse move leaves dabs all along its way (kDabSpacing), not only where it ends.
TEST(ModelerSculpt, AFastMoveDabsAllAlongTheStroke) {
  Fixture f;
  ModelerState& m = f.app.model;
  m.set_level(m.session().finest_level());  // points close to the surface
  f.key(Key::Tab, kCtrl);
  BrushSettings b = m.brush();
  b.kind = BrushKind::Draw;
  b.radius = 0.03 * (m.default_soft_radius() / 0.05);  // 3 % of the diagonal
  m.set_brush(b);
  double x = 0, y = 0;
  facing_point(f, x, y);
  glm::dvec3 o, d, start, end;
  const PickView view = f.view();
  pixel_ray(view, x - testing::kViewX, y, o, d);
  ASSERT_TRUE(m.surface_hit(o, d, start));
  pixel_ray(view, x - testing::kViewX + 60, y, o, d);
  ASSERT_TRUE(m.surface_hit(o, d, end));
  ASSERT_GT(glm::length(end - start), 4 * b.radius);
  const std::vector<double> before(m.session().positions(m.level()).begin(), m.session().positions(m.level()).end());
  f.send(WindowEvent::Type::Move, x, y);
  f.send(WindowEvent::Type::Press, x, y);
  f.send(WindowEvent::Type::Move, x + 60, y);  // one event
  f.send(WindowEvent::Type::Release, x + 60, y);
  const auto p = m.session().positions(m.level());
  std::size_t middle = 0;
  for (std::size_t v = 0; 3 * v < p.size(); ++v) {
    if (p[3 * v] == before[3 * v] && p[3 * v + 1] == before[3 * v + 1] && p[3 * v + 2] == before[3 * v + 2]) continue;
    const glm::dvec3 q(before[3 * v], before[3 * v + 1], before[3 * v + 2]);
    if (glm::length(q - start) > 1.5 * b.radius && glm::length(q - end) > 1.5 * b.radius) ++middle;
  }
  EXPECT_GT(middle, 0u) << "no dab between the ends of the stroke";
  EXPECT_EQ(m.session().history().size(), 1u);
}

}  // namespace
}  // namespace sublift

namespace sublift {
namespace {

// The brush is the user's: replacing the session (a crease, a level deletion, their undo) keeps
// it; only another model resizes it.
TEST(ModelerSculpt, TheBrushSurvivesSessionReplacements) {
  ModelerState m = edited_torus("cubic");
  BrushSettings b = m.brush();
  b.radius = 0.123;
  m.set_brush(b);
  m.set_level(0);
  m.set_selection({0, 1});
  m.toggle_creases();
  EXPECT_EQ(m.brush().radius, 0.123);
  ASSERT_TRUE(m.undo());
  EXPECT_EQ(m.brush().radius, 0.123);
  m.set_level(1);
  m.delete_lower_levels();
  EXPECT_EQ(m.brush().radius, 0.123);
  m.open(std::string(SUBLIFT_ASSETS_DIR) + "/cube.obj");
  EXPECT_NE(m.brush().radius, 0.123);
}

}  // namespace
}  // namespace sublift

namespace sublift {
namespace {

TEST(ModelerFeatures, UndoSaysWhenItStopsKeepingOldHierarchies) {
  ModelerState m = edited_torus("cubic");
  for (std::size_t i = 0; i < ModelerState::kStructureUndo; ++i) m.set_scheme(i % 2 ? Scheme::Cubic : Scheme::Linear);
  auto said = [&] {
    for (const std::string& w : m.import_warnings())
      if (w.find("the oldest one can no longer be undone") != std::string::npos) return true;
    return false;
  };
  EXPECT_FALSE(said());
  m.set_scheme(Scheme::Linear);
  EXPECT_TRUE(said());
  std::size_t undone = 0;
  while (m.undo()) ++undone;
  // Eight scheme changes back; the first session, with edited_torus's own edits, was dropped.
  EXPECT_EQ(undone, ModelerState::kStructureUndo);
}

}  // namespace
}  // namespace sublift
