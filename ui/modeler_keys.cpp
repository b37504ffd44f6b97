#include "ui/modeler_keys.h"

#include <algorithm>
#include <charconv>
#include <cmath>

namespace sublift {
namespace {

ModelerCommand command(ModelerCommandType type) { return ModelerCommand{type}; }

int digit_of(Key key) {
  if (key < Key::Digit0 || key > Key::Digit9) return -1;
  return static_cast<int>(key) - static_cast<int>(Key::Digit0);
}

ModelerCommand map_transform_key(Key key, const Modifiers& mods, TransformState& grab) {
  if (key == Key::Escape) {
    grab = TransformState{};
    return command(ModelerCommandType::TransformCancel);
  }
  if (key == Key::Enter) {
    grab = TransformState{};
    return command(ModelerCommandType::TransformConfirm);
  }
  if (mods.ctrl || mods.alt) return {};
  if (key == Key::X || key == Key::Y || key == Key::Z) {
    const int axis = key == Key::X ? 0 : (key == Key::Y ? 1 : 2);
    const bool exclude = mods.shift;
    const bool same = grab.axis == axis && grab.exclude == exclude;
    grab.axis = same ? -1 : axis;  // the same key again frees the axis
    grab.exclude = !same && exclude;
    return command(ModelerCommandType::TransformUpdate);
  }
  if (const int d = digit_of(key); d >= 0) {
    grab.typed.push_back(static_cast<char>('0' + d));
    return command(ModelerCommandType::TransformUpdate);
  }
  if (key == Key::Minus || key == Key::NumpadMinus) {
    // '-' flips the sign wherever it is typed (Blender's habit).
    if (!grab.typed.empty() && grab.typed.front() == '-') {
      grab.typed.erase(grab.typed.begin());
    } else {
      grab.typed.insert(grab.typed.begin(), '-');
    }
    return command(ModelerCommandType::TransformUpdate);
  }
  if (key == Key::Period) {
    if (grab.typed.find('.') == std::string::npos) grab.typed.push_back('.');
    return command(ModelerCommandType::TransformUpdate);
  }
  if (key == Key::Backspace) {
    if (!grab.typed.empty()) grab.typed.pop_back();
    return command(ModelerCommandType::TransformUpdate);
  }
  return {};
}

}  // namespace

std::optional<double> TransformState::typed_value() const {
  if (typed.empty()) return std::nullopt;
  std::string text = typed;
  if (text.back() == '.') text.pop_back();
  // Leading zeros added by appending to a fresh string (an insert in place trips GCC 12's
  // -Wrestrict false positive).
  if (!text.empty() && text.front() == '.') text = std::string("0").append(text);
  if (text.size() > 1 && text[0] == '-' && text[1] == '.') text = std::string("-0").append(text, 1);
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

ModelerCommand map_modeler_key(Key key, const Modifiers& mods, TransformState& grab, bool has_selection) {
  if (grab.active) return map_transform_key(key, mods, grab);
  const bool ctrl = mods.ctrl, shift = mods.shift, alt = mods.alt;
  switch (key) {
    case Key::A:
      if (ctrl || shift) return {};
      return command(alt ? ModelerCommandType::SelectNone : ModelerCommandType::SelectAll);
    case Key::I:
      return ctrl && !shift && !alt ? command(ModelerCommandType::SelectInvert) : ModelerCommand{};
    case Key::NumpadPlus:
      return ctrl && !shift && !alt ? command(ModelerCommandType::SelectMore) : ModelerCommand{};
    case Key::NumpadMinus:
      return ctrl && !shift && !alt ? command(ModelerCommandType::SelectLess) : ModelerCommand{};
    case Key::L:
      if (alt || (ctrl && shift)) return {};
      return command(ctrl ? ModelerCommandType::SelectLinked : ModelerCommandType::PickLinked);
    case Key::C:
      return ctrl || shift || alt ? ModelerCommand{} : command(ModelerCommandType::CircleSelect);
    case Key::Tab:
      return ctrl && !shift && !alt ? command(ModelerCommandType::ToggleSculpt) : ModelerCommand{};
    case Key::D:
      if (alt) return {};
      if (ctrl) return shift ? ModelerCommand{} : command(ModelerCommandType::Subdivide);
      return command(shift ? ModelerCommandType::LevelDown : ModelerCommandType::LevelUp);
    case Key::PageUp:
      return ctrl || alt || shift ? ModelerCommand{} : command(ModelerCommandType::LevelUp);
    case Key::PageDown:
      return ctrl || alt || shift ? ModelerCommand{} : command(ModelerCommandType::LevelDown);
    case Key::Z:
      if (!ctrl || alt) return {};
      return command(shift ? ModelerCommandType::Redo : ModelerCommandType::Undo);
    case Key::Y:
      return ctrl && !shift && !alt ? command(ModelerCommandType::Redo) : ModelerCommand{};
    case Key::S:
      if (alt) return {};
      if (!ctrl) {
        if (shift) return command(ModelerCommandType::CursorToSelected);
        if (!has_selection) return {};
        grab = TransformState{};
        grab.active = true;
        grab.mode = 2;
        return command(ModelerCommandType::TransformStart);
      }
      return command(shift ? ModelerCommandType::SaveAs : ModelerCommandType::Save);
    case Key::O:
      return ctrl && !shift && !alt ? command(ModelerCommandType::Open) : ModelerCommand{};
    case Key::E:
      if (alt) return {};
      if (shift) return command(ctrl ? ModelerCommandType::ToggleCorner : ModelerCommandType::ToggleCrease);
      return ctrl ? command(ModelerCommandType::Export) : ModelerCommand{};
    case Key::Space:
      return ctrl || shift || alt ? ModelerCommand{} : command(ModelerCommandType::PlayPause);
    case Key::Left:
      if (ctrl || alt) return {};
      return command(shift ? ModelerCommandType::FrameFirst : ModelerCommandType::FramePrev);
    case Key::Right:
      if (ctrl || alt) return {};
      return command(shift ? ModelerCommandType::FrameLast : ModelerCommandType::FrameNext);
    case Key::G:
    case Key::R:
      if (ctrl || shift || alt || !has_selection) return {};
      grab = TransformState{};
      grab.active = true;
      grab.mode = key == Key::G ? 0 : 1;
      return command(ModelerCommandType::TransformStart);
    default:
      return {};
  }
}

SculptKey map_sculpt_key(Key key, const Modifiers& mods) {
  using A = SculptKey::Action;
  if (mods.ctrl || mods.alt) return {};
  auto brush = [](int b) { return SculptKey{A::Brush, b}; };
  switch (key) {
    case Key::X: return mods.shift ? SculptKey{} : brush(0);
    case Key::I: return mods.shift ? SculptKey{} : brush(1);
    case Key::S: return mods.shift ? SculptKey{} : brush(2);
    case Key::G:
    case Key::K: return mods.shift ? SculptKey{} : brush(3);
    case Key::T: return mods.shift ? brush(4) : SculptKey{};
    case Key::P: return mods.shift ? SculptKey{} : brush(5);
    case Key::F: return SculptKey{mods.shift ? A::Strength : A::Radius, 0};
    default: return {};
  }
}

double soft_radius_after_wheel(double radius, double notches, double start) {
  if (notches == 0.0) return radius;
  if (radius <= 0.0) return notches > 0.0 ? start : 0.0;
  const double next = radius * std::pow(1.15, notches);
  return next < start / 20.0 ? 0.0 : next;
}

PressAction classify_left_press(bool hit, bool hit_selected, bool shift) {
  if (!hit) return PressAction::BoxSelect;
  if (hit_selected && !shift) return PressAction::DragSelection;
  return PressAction::ClickSelect;
}

void apply_click(std::vector<unsigned>& selection, long long hit, bool shift) {
  if (!shift) {
    selection.clear();
    if (hit >= 0) selection.push_back(static_cast<unsigned>(hit));
    return;
  }
  if (hit < 0) return;
  const auto v = static_cast<unsigned>(hit);
  const auto it = std::lower_bound(selection.begin(), selection.end(), v);
  if (it != selection.end() && *it == v) {
    selection.erase(it);
  } else {
    selection.insert(it, v);
  }
}

void apply_box(std::vector<unsigned>& selection, const std::vector<unsigned>& inside, bool shift) {
  if (!shift) selection.clear();
  selection.insert(selection.end(), inside.begin(), inside.end());
  std::sort(selection.begin(), selection.end());
  selection.erase(std::unique(selection.begin(), selection.end()), selection.end());
}

const std::vector<KeyBinding>& modeler_key_bindings() {
  static const std::vector<KeyBinding> bindings = {
      {"Click / Shift+click", "Select / toggle point"},
      {"Drag empty space", "Box select (Shift adds)"},
      {"Drag selected point", "Move in view plane"},
      {"A / Alt+A / Ctrl+I", "Select all / none / invert"},
      {"Alt+click / Ctrl+Alt+click", "Edge loop / ring (Shift adds)"},
      {"L / Shift+L / Ctrl+L", "Linked under mouse / deselect / to selection"},
      {"Ctrl+numpad + / -", "Grow / shrink selection"},
      {"C", "Circle select (Shift paints off)"},
      {"G, then X/Y/Z, digits", "Grab, axis, distance"},
      {"R / S, then X/Y/Z, digits", "Rotate (degrees) / scale"},
      {"Shift+X/Y/Z in G/R/S", "Exclude that axis"},
      {"Enter / Esc", "Confirm / cancel transform"},
      {"Shift+S", "3-D cursor to selection"},
      {"Ctrl+Tab", "Sculpt mode on / off"},
      {"Shift+E / Ctrl+Shift+E (level 0)", "Crease edges / corners of the selection"},
      {"Sculpt: X I S G P, Shift+T", "Draw, inflate, smooth, grab, pinch, flatten"},
      {"Sculpt: F / Shift+F", "Brush radius / strength"},
      {"Sculpt: drag (Ctrl inverts, Shift smooths)", "Stroke at the edit level"},
      {"Ctrl+wheel", "Soft selection radius"},
      {"PgUp/PgDn, D/Shift+D", "Finer / coarser level"},
      {"Ctrl+D", "Subdivide once more"},
      {"Ctrl+Z / Ctrl+Shift+Z, Y", "Undo / redo"},
      {"Ctrl+S / O / E", "Save / open / export"},
      {"Space, Left / Right, Shift+Left / Right", "Animation: play / pause, a frame back / on, first / last"},
  };
  return bindings;
}

}  // namespace sublift
