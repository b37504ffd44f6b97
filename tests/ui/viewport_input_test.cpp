// Viewport bindings: Blender's and Maya's habits map to the right camera actions; the panel
// layout leaves the right rectangle to the viewport.
#include <gtest/gtest.h>

#include <string>

#include "ui/panels.h"
#include "ui/viewport_input.h"

namespace sublift {
namespace {

InputEvent drag(bool left, bool middle, bool right, Modifiers mods, double dx, double dy) {
  InputEvent e;
  e.type = InputEvent::Type::MouseMove;
  e.left = left;
  e.middle = middle;
  e.right = right;
  e.mods = mods;
  e.dx = dx;
  e.dy = dy;
  return e;
}

InputEvent key(Key k, Modifiers mods = {}) {
  InputEvent e;
  e.type = InputEvent::Type::KeyPress;
  e.key = k;
  e.mods = mods;
  return e;
}

constexpr Modifiers kNone{};
constexpr Modifiers kShift{true, false, false};
constexpr Modifiers kCtrl{false, true, false};
constexpr Modifiers kAlt{false, false, true};

TEST(ViewportInputTest, BlenderMiddleDragOrbits) {
  const CameraAction a = map_viewport_input(drag(false, true, false, kNone, 12.0, -3.0));
  EXPECT_EQ(a.type, CameraActionType::Orbit);
  EXPECT_EQ(a.dx, 12.0);
  EXPECT_EQ(a.dy, -3.0);
}

TEST(ViewportInputTest, BlenderShiftMiddleDragPans) {
  const CameraAction a = map_viewport_input(drag(false, true, false, kShift, -5.0, 7.0));
  EXPECT_EQ(a.type, CameraActionType::Pan);
  EXPECT_EQ(a.dx, -5.0);
  EXPECT_EQ(a.dy, 7.0);
}

TEST(ViewportInputTest, BlenderCtrlMiddleDragZoomsInWhenDraggingUp) {
  const CameraAction up = map_viewport_input(drag(false, true, false, kCtrl, 0.0, -40.0));
  EXPECT_EQ(up.type, CameraActionType::Zoom);
  EXPECT_DOUBLE_EQ(up.steps, 40.0 / kPixelsPerZoomStep);
  const CameraAction down = map_viewport_input(drag(false, true, false, kCtrl, 0.0, 20.0));
  EXPECT_LT(down.steps, 0.0);
}

TEST(ViewportInputTest, WheelZooms) {
  InputEvent e;
  e.type = InputEvent::Type::Wheel;
  e.wheel = 2.0;
  const CameraAction in = map_viewport_input(e);
  EXPECT_EQ(in.type, CameraActionType::Zoom);
  EXPECT_EQ(in.steps, 2.0);
  e.wheel = -1.0;
  EXPECT_EQ(map_viewport_input(e).steps, -1.0);
  e.wheel = 0.0;
  EXPECT_EQ(map_viewport_input(e).type, CameraActionType::None);
}

TEST(ViewportInputTest, MayaAltBindings) {
  EXPECT_EQ(map_viewport_input(drag(true, false, false, kAlt, 3.0, 1.0)).type,
            CameraActionType::Orbit);
  EXPECT_EQ(map_viewport_input(drag(false, true, false, kAlt, 3.0, 1.0)).type,
            CameraActionType::Pan);
  const CameraAction zoom = map_viewport_input(drag(false, false, true, kAlt, 30.0, 10.0));
  EXPECT_EQ(zoom.type, CameraActionType::Zoom);
  EXPECT_GT(zoom.steps, 0.0);  // right/down dollies in, as in Maya
  EXPECT_LT(map_viewport_input(drag(false, false, true, kAlt, -30.0, -10.0)).steps, 0.0);
}

TEST(ViewportInputTest, PlainLeftAndRightDragsAreLeftForTools) {
  EXPECT_EQ(map_viewport_input(drag(true, false, false, kNone, 9.0, 9.0)).type,
            CameraActionType::None);
  EXPECT_EQ(map_viewport_input(drag(false, false, true, kNone, 9.0, 9.0)).type,
            CameraActionType::None);
  EXPECT_EQ(map_viewport_input(drag(true, true, false, kNone, 9.0, 9.0)).type,
            CameraActionType::None);
}

TEST(ViewportInputTest, NoMotionNoAction) {
  EXPECT_EQ(map_viewport_input(drag(false, true, false, kNone, 0.0, 0.0)).type,
            CameraActionType::None);
}

TEST(ViewportInputTest, FrameKeys) {
  for (Key k : {Key::F, Key::Home, Key::NumpadPeriod}) {
    EXPECT_EQ(map_viewport_input(key(k)).type, CameraActionType::Frame);
  }
}

TEST(ViewportInputTest, NumpadViewsAndCtrlOpposites) {
  EXPECT_EQ(map_viewport_input(key(Key::Numpad1)).type, CameraActionType::ViewFront);
  EXPECT_EQ(map_viewport_input(key(Key::Numpad3)).type, CameraActionType::ViewRight);
  EXPECT_EQ(map_viewport_input(key(Key::Numpad7)).type, CameraActionType::ViewTop);
  EXPECT_EQ(map_viewport_input(key(Key::Numpad1, kCtrl)).type, CameraActionType::ViewBack);
  EXPECT_EQ(map_viewport_input(key(Key::Numpad3, kCtrl)).type, CameraActionType::ViewLeft);
  EXPECT_EQ(map_viewport_input(key(Key::Numpad7, kCtrl)).type, CameraActionType::ViewBottom);
  EXPECT_EQ(map_viewport_input(key(Key::Numpad5)).type, CameraActionType::ToggleOrthographic);
}

TEST(ViewportInputTest, UnboundKeysDoNothing) {
  EXPECT_EQ(map_viewport_input(key(Key::None)).type, CameraActionType::None);
  EXPECT_EQ(map_viewport_input(key(Key::F, kAlt)).type, CameraActionType::None);
}

TEST(ViewportInputTest, HelpListsEveryNavigation) {
  // The help panel must mention each action the mapping produces, for both habits.
  std::string text;
  for (const MouseBinding& b : mouse_bindings()) {
    text += std::string(b.action) + " " + std::string(b.blender) + " " + std::string(b.maya) + "\n";
  }
  for (const KeyBinding& b : key_bindings()) {
    text += std::string(b.keys) + " " + std::string(b.action) + "\n";
  }
  for (const char* word : {"Orbit", "Pan", "Zoom", "wheel", "Frame", "Numpad 5", "Alt + left",
                           "Alt + right", "Ctrl + Numpad"}) {
    EXPECT_NE(text.find(word), std::string::npos) << word;
  }
}

TEST(PanelLayoutTest, ViewportIsTheWindowMinusSidePanelAndStatusLine) {
  const PanelLayout layout;
  const ScreenRect r = viewport_rect(1280.0f, 800.0f, layout);
  EXPECT_EQ(r.x, layout.side_width);
  EXPECT_EQ(r.y, 0.0f);
  EXPECT_EQ(r.width, 1280.0f - layout.side_width);
  EXPECT_EQ(r.height, 800.0f - layout.status_height);
  // A window narrower than the panel leaves an empty viewport, never a negative one.
  const ScreenRect tiny = viewport_rect(100.0f, 10.0f, layout);
  EXPECT_EQ(tiny.width, 0.0f);
  EXPECT_EQ(tiny.height, 0.0f);
}

}  // namespace
}  // namespace sublift
