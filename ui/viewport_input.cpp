#include "ui/viewport_input.h"

namespace sublift {
namespace {

CameraAction drag(CameraActionType type, const InputEvent& e) {
  return CameraAction{type, e.dx, e.dy, 0.0};
}

CameraAction zoom(double steps) { return CameraAction{CameraActionType::Zoom, 0.0, 0.0, steps}; }

CameraAction action(CameraActionType type) { return CameraAction{type, 0.0, 0.0, 0.0}; }

CameraAction map_mouse_move(const InputEvent& e) {
  if (e.dx == 0.0 && e.dy == 0.0) return {};
  const Modifiers& m = e.mods;
  if (m.alt) {
    // Maya: Alt+left orbit, Alt+middle pan, Alt+right dolly (dragging right/down zooms in).
    if (e.left && !e.middle && !e.right) return drag(CameraActionType::Orbit, e);
    if (e.middle && !e.left && !e.right) return drag(CameraActionType::Pan, e);
    if (e.right && !e.left && !e.middle) return zoom((e.dx + e.dy) / kPixelsPerZoomStep);
    return {};
  }
  if (!e.middle || e.left || e.right) return {};
  // Blender: middle orbit, Shift+middle pan, Ctrl+middle zoom (drag up zooms in).
  if (m.shift && !m.ctrl) return drag(CameraActionType::Pan, e);
  if (m.ctrl && !m.shift) return zoom(-e.dy / kPixelsPerZoomStep);
  if (!m.shift && !m.ctrl) return drag(CameraActionType::Orbit, e);
  return {};
}

CameraAction map_key(const InputEvent& e) {
  const bool ctrl = e.mods.ctrl;
  if (e.mods.alt || e.mods.shift) return {};
  switch (e.key) {
    case Key::F:
    case Key::Home:
    case Key::NumpadPeriod:
      return ctrl ? CameraAction{} : action(CameraActionType::Frame);
    case Key::Numpad1:
      return action(ctrl ? CameraActionType::ViewBack : CameraActionType::ViewFront);
    case Key::Numpad3:
      return action(ctrl ? CameraActionType::ViewLeft : CameraActionType::ViewRight);
    case Key::Numpad7:
      return action(ctrl ? CameraActionType::ViewBottom : CameraActionType::ViewTop);
    case Key::Numpad5:
      return ctrl ? CameraAction{} : action(CameraActionType::ToggleOrthographic);
    default:
      break;
  }
  return {};
}

}  // namespace

CameraAction map_viewport_input(const InputEvent& event) {
  switch (event.type) {
    case InputEvent::Type::MouseMove:
      return map_mouse_move(event);
    case InputEvent::Type::Wheel:
      return event.wheel != 0.0 ? zoom(event.wheel) : CameraAction{};
    case InputEvent::Type::KeyPress:
      return map_key(event);
  }
  return {};
}

const std::vector<MouseBinding>& mouse_bindings() {
  static const std::vector<MouseBinding> bindings = {
      {"Orbit", "Middle", "Alt + left"},
      {"Pan", "Shift + middle", "Alt + middle"},
      {"Zoom", "Ctrl + middle, wheel", "Alt + right"},
  };
  return bindings;
}

const std::vector<KeyBinding>& key_bindings() {
  static const std::vector<KeyBinding> bindings = {
      {"F, Home, Numpad .", "Frame the model"},
      {"Numpad 1 / 3 / 7", "Front / right / top"},
      {"Ctrl + Numpad 1/3/7", "Back / left / bottom"},
      {"Numpad 5", "Perspective / ortho"},
  };
  return bindings;
}

}  // namespace sublift
