#pragma once
// Maps raw viewport input to camera actions, with Blender's and Maya's habits side by side.
// Pure data in, data out: no GLFW, no ImGui, no GL, so the bindings are unit-tested.
//
// Blender: middle-drag orbit, Shift+middle pan, Ctrl+middle zoom, wheel zoom, F / Home /
//          numpad period frame, numpad 1/3/7 front/right/top, Ctrl+numpad 1/3/7 back/left/bottom,
//          numpad 5 perspective/orthographic.
// Maya:    Alt+left orbit, Alt+middle pan, Alt+right zoom.
#include <string_view>
#include <vector>

namespace sublift {

enum class Key {
  None,
  F,
  Home,
  NumpadPeriod,
  Numpad1,
  Numpad3,
  Numpad5,
  Numpad7,
  // Modeler keys (ui/modeler_keys.h); the camera mapping ignores them.
  A, D, G, R, X, Y, Z, S, O, E, L, C, I, K, T, P, Tab,
  NumpadPlus, NumpadMinus,
  PageUp, PageDown, Escape, Enter, Backspace, Minus, Period, Space, Left, Right,
  Digit0, Digit1, Digit2, Digit3, Digit4, Digit5, Digit6, Digit7, Digit8, Digit9,
};

struct Modifiers {
  bool shift = false;
  bool ctrl = false;
  bool alt = false;
};

/// One input event seen by the viewport (already known not to belong to the UI).
struct InputEvent {
  enum class Type { MouseMove, Wheel, KeyPress };
  Type type = Type::MouseMove;
  Modifiers mods;
  // MouseMove: buttons held during the move and the move in pixels (y grows downwards).
  bool left = false, middle = false, right = false;
  double dx = 0.0, dy = 0.0;
  double wheel = 0.0;  // Wheel: notches, positive away from the user
  Key key = Key::None;  // KeyPress
};

enum class CameraActionType {
  None,
  Orbit,       // dx, dy in pixels
  Pan,         // dx, dy in pixels
  Zoom,        // steps, positive zooms in
  Frame,
  ViewFront,
  ViewBack,
  ViewRight,
  ViewLeft,
  ViewTop,
  ViewBottom,
  ToggleOrthographic,
};

struct CameraAction {
  CameraActionType type = CameraActionType::None;
  double dx = 0.0, dy = 0.0;
  double steps = 0.0;
};

/// Pixels of drag that make one zoom step (Ctrl+middle and Alt+right drags).
inline constexpr double kPixelsPerZoomStep = 20.0;

/// The camera action an event asks for; None when the event means nothing to the viewport.
CameraAction map_viewport_input(const InputEvent& event);

/// One row of the mouse help table: an action and its Blender and Maya drags.
struct MouseBinding {
  std::string_view action;
  std::string_view blender;
  std::string_view maya;
};

/// One row of the key help table.
struct KeyBinding {
  std::string_view keys;
  std::string_view action;
};

/// The mouse bindings above, for the help panel.
const std::vector<MouseBinding>& mouse_bindings();

/// The key bindings above, for the help panel.
const std::vector<KeyBinding>& key_bindings();

}  // namespace sublift
