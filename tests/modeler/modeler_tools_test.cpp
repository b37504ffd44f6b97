// The modeler's tools (issue 19) on the controller with synthetic keys and mouse: rotate and
// scale (axes, typed values, pivots, cancel, undo), and through `sublift --script`.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>
#include <string>
#include <vector>

#include "app/modeler/script_runner.h"
#include "tests/modeler/controller_fixture.h"
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

// Every level is the synthesis of the session's coefficients (what a fresh open would show).
void expect_fresh(const ModelerState& m) {
  for (int l = 0; l <= m.session().finest_level(); ++l)
    EXPECT_LT(testing::max_abs_diff(synthesize(m.session().hierarchy(), l), m.session().positions(l)), 1e-11) << "level " << l;
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
