#pragma once
// Modeler hotkeys and mouse gestures as pure data: key (with modifiers) -> command, the grab
// tool's state machine (axis constraint, typed distance), and what a left press/release in the
// viewport means. No GLFW, no ImGui, no GL, so the bindings are unit-tested
// (tests/ui/modeler_keys_test.cpp); the app executes the commands on the session.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ui/viewport_input.h"

namespace sublift {

enum class ModelerCommandType {
  None,
  SelectAll,     // A
  SelectNone,    // Alt+A
  SelectInvert,  // Ctrl+I
  SelectMore,    // Ctrl+numpad +
  SelectLess,    // Ctrl+numpad -
  SelectLinked,  // Ctrl+L: everything joined to the selection
  PickLinked,    // L: everything joined to the point under the mouse (Shift+L: deselect it)
  CircleSelect,  // C: paint the selection with a circle until Esc, Enter or right click
  ToggleSculpt,  // Ctrl+Tab: sculpt mode on / off (Blender's mode switch)
  ToggleCrease,  // Shift+E: crease / uncrease the base edges between selected points
  ToggleCorner,  // Ctrl+Shift+E: corners at / off the selected base points
  LevelUp,       // Page Up, D (finer)
  LevelDown,     // Page Down, Shift+D (coarser)
  Subdivide,     // Ctrl+D
  Undo,          // Ctrl+Z
  Redo,          // Ctrl+Shift+Z, Ctrl+Y
  Save,          // Ctrl+S
  SaveAs,        // Ctrl+Shift+S
  Open,          // Ctrl+O
  Export,        // Ctrl+E
  TransformStart,     // G grab, R rotate, S scale (with a selection)
  TransformUpdate,    // axis or typed value changed during a transform
  TransformConfirm,   // Enter, left click
  TransformCancel,    // Esc, right click
  CursorToSelected,   // Shift+S: the 3-D cursor to the selection's median
  PlayPause,     // Space: play / pause an animation (Blender)
  FramePrev,     // Left: the previous frame
  FrameNext,     // Right: the next frame
  FrameFirst,    // Shift+Left: the first frame
  FrameLast,     // Shift+Right: the last frame
};

struct ModelerCommand {
  ModelerCommandType type = ModelerCommandType::None;
};

/// Transform tool state (Blender's modal G/R/S): active between the key and Enter/Esc. axis -1 =
/// free (grab: the view plane; rotate: about the view axis; scale: uniform), 0/1/2 = X/Y/Z;
/// `exclude` (Shift+axis): grab in the plane across the axis, scale the two other axes (rotate:
/// about the axis, as without Shift). `typed` is the value being typed (digits, '-', '.'; a
/// distance, degrees or a factor), empty = follow the mouse.
struct TransformState {
  bool active = false;
  int mode = 0;  // TransformMode's value: 0 grab, 1 rotate, 2 scale
  int axis = -1;
  bool exclude = false;
  std::string typed;

  /// The typed distance, if `typed` parses as a number ("-" alone or "." alone do not).
  std::optional<double> typed_value() const;
};

/// Maps a key press to a modeler command, updating `grab` (starting a transform only when
/// `has_selection`). During a transform X/Y/Z toggle the axis (Shift+X/Y/Z: exclude it),
/// digits/'-'/'.'/Backspace edit the typed value, Enter confirms and Esc cancels; every other
/// key is swallowed (None).
ModelerCommand map_modeler_key(Key key, const Modifiers& mods, TransformState& grab, bool has_selection);

/// Sculpt mode's keys (Blender's): X draw, I inflate, S smooth, G or K grab (snake hook),
/// Shift+T flatten, P pinch; F / Shift+F adjust radius / strength with the mouse. Other keys
/// (None) go on to map_modeler_key, except the transform keys, which sculpt mode takes.
struct SculptKey {
  enum class Action { None, Brush, Radius, Strength } action = Action::None;
  int brush = 0;  // BrushKind's value (core/edit/brush.h): draw, inflate, smooth, grab, flatten, pinch
};
SculptKey map_sculpt_key(Key key, const Modifiers& mods);

/// Ctrl+wheel: the new soft-selection radius after `notches` (positive grows it 15% a notch);
/// from 0 a positive notch starts at `start` (e.g. 5% of the model size); shrinking below
/// `start` / 20 turns soft selection off (0).
double soft_radius_after_wheel(double radius, double notches, double start);

/// What a left press in the viewport starts.
enum class PressAction {
  None,
  DragSelection,  // on a selected point, no Shift: moves the selection
  ClickSelect,    // on a point (or Shift on a selected one): select on release if not dragged
  BoxSelect,      // on empty space: a rubber band (a click without drag clears the selection)
};

/// Classifies a left press: `hit` = a control point is under the cursor, `hit_selected` = it is
/// selected, `shift` = Shift held.
PressAction classify_left_press(bool hit, bool hit_selected, bool shift);

/// Pixels the mouse must travel before a press becomes a drag.
inline constexpr double kDragThresholdPx = 4.0;

/// How a click or box changes the selection: Shift adds (a click on a selected point toggles it
/// off), otherwise the selection is replaced. Keeps `selection` sorted and unique.
void apply_click(std::vector<unsigned>& selection, long long hit, bool shift);
void apply_box(std::vector<unsigned>& selection, const std::vector<unsigned>& inside, bool shift);

/// The modeler rows of the key help table.
const std::vector<KeyBinding>& modeler_key_bindings();

}  // namespace sublift
