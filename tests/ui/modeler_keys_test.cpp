// ui/modeler_keys: the modeler's key and mouse bindings as pure data.
#include <gtest/gtest.h>

#include "ui/modeler_keys.h"

namespace sublift {
namespace {

using T = ModelerCommandType;

T key(Key k, Modifiers m = {}, bool has_selection = true) {
  TransformState grab;
  return map_modeler_key(k, m, grab, has_selection).type;
}

Modifiers ctrl() { return Modifiers{false, true, false}; }
Modifiers shift() { return Modifiers{true, false, false}; }
Modifiers alt() { return Modifiers{false, false, true}; }
Modifiers ctrl_shift() { return Modifiers{true, true, false}; }

TEST(ModelerKeysTest, SelectionKeys) {
  EXPECT_EQ(key(Key::A), T::SelectAll);
  EXPECT_EQ(key(Key::A, alt()), T::SelectNone);
  EXPECT_EQ(key(Key::A, ctrl()), T::None);
}

TEST(ModelerKeysTest, LevelKeys) {
  EXPECT_EQ(key(Key::PageUp), T::LevelUp);
  EXPECT_EQ(key(Key::PageDown), T::LevelDown);
  EXPECT_EQ(key(Key::D), T::LevelUp);
  EXPECT_EQ(key(Key::D, shift()), T::LevelDown);
  EXPECT_EQ(key(Key::D, ctrl()), T::Subdivide);
  EXPECT_EQ(key(Key::D, ctrl_shift()), T::None);
}

TEST(ModelerKeysTest, HistoryAndFileKeys) {
  EXPECT_EQ(key(Key::Z, ctrl()), T::Undo);
  EXPECT_EQ(key(Key::Z, ctrl_shift()), T::Redo);
  EXPECT_EQ(key(Key::Y, ctrl()), T::Redo);
  EXPECT_EQ(key(Key::Z), T::None);  // plain Z is only an axis while grabbing
  EXPECT_EQ(key(Key::S, ctrl()), T::Save);
  EXPECT_EQ(key(Key::S, ctrl_shift()), T::SaveAs);
  EXPECT_EQ(key(Key::O, ctrl()), T::Open);
  EXPECT_EQ(key(Key::E, ctrl()), T::Export);
  EXPECT_EQ(key(Key::F), T::None);  // camera keys stay with viewport_input
}

TEST(ModelerKeysTest, GrabNeedsASelection) {
  TransformState grab;
  EXPECT_EQ(map_modeler_key(Key::G, {}, grab, false).type, T::None);
  EXPECT_FALSE(grab.active);
  EXPECT_EQ(map_modeler_key(Key::G, {}, grab, true).type, T::TransformStart);
  EXPECT_TRUE(grab.active);
  EXPECT_EQ(grab.axis, -1);
}

TEST(ModelerKeysTest, GrabAxisAndTypedDistance) {
  TransformState grab;
  map_modeler_key(Key::G, {}, grab, true);
  EXPECT_EQ(map_modeler_key(Key::Z, {}, grab, true).type, T::TransformUpdate);
  EXPECT_EQ(grab.axis, 2);
  map_modeler_key(Key::X, {}, grab, true);
  EXPECT_EQ(grab.axis, 0);
  map_modeler_key(Key::X, {}, grab, true);  // the same axis again frees it
  EXPECT_EQ(grab.axis, -1);
  map_modeler_key(Key::Y, {}, grab, true);
  for (Key k : {Key::Digit1, Key::Period, Key::Digit2, Key::Digit5, Key::Minus}) {
    EXPECT_EQ(map_modeler_key(k, {}, grab, true).type, T::TransformUpdate);
  }
  EXPECT_EQ(grab.typed, "-1.25");
  ASSERT_TRUE(grab.typed_value());
  EXPECT_DOUBLE_EQ(*grab.typed_value(), -1.25);
  map_modeler_key(Key::Period, {}, grab, true);  // a second '.' is ignored
  EXPECT_EQ(grab.typed, "-1.25");
  map_modeler_key(Key::Backspace, {}, grab, true);
  EXPECT_EQ(grab.typed, "-1.2");
  // Other keys are swallowed while grabbing: no undo in the middle of a grab.
  EXPECT_EQ(map_modeler_key(Key::Z, ctrl(), grab, true).type, T::None);
  EXPECT_EQ(map_modeler_key(Key::A, {}, grab, true).type, T::None);
  EXPECT_EQ(map_modeler_key(Key::Enter, {}, grab, true).type, T::TransformConfirm);
  EXPECT_FALSE(grab.active);
  EXPECT_TRUE(grab.typed.empty());
}

TEST(ModelerKeysTest, TransformCancel) {
  TransformState grab;
  map_modeler_key(Key::G, {}, grab, true);
  map_modeler_key(Key::Digit3, {}, grab, true);
  EXPECT_EQ(map_modeler_key(Key::Escape, {}, grab, true).type, T::TransformCancel);
  EXPECT_FALSE(grab.active);
}

TEST(ModelerKeysTest, TypedValueParsing) {
  TransformState g;
  EXPECT_FALSE(g.typed_value());
  g.typed = "-";
  EXPECT_FALSE(g.typed_value());
  g.typed = ".";
  EXPECT_FALSE(g.typed_value());
  g.typed = ".5";
  EXPECT_DOUBLE_EQ(*g.typed_value(), 0.5);
  g.typed = "-.5";
  EXPECT_DOUBLE_EQ(*g.typed_value(), -0.5);
  g.typed = "2.";
  EXPECT_DOUBLE_EQ(*g.typed_value(), 2.0);
}

TEST(ModelerKeysTest, SoftRadiusWheel) {
  EXPECT_DOUBLE_EQ(soft_radius_after_wheel(0.0, 1.0, 0.1), 0.1);
  EXPECT_DOUBLE_EQ(soft_radius_after_wheel(0.0, -1.0, 0.1), 0.0);
  EXPECT_NEAR(soft_radius_after_wheel(0.1, 1.0, 0.1), 0.115, 1e-12);
  EXPECT_NEAR(soft_radius_after_wheel(0.115, -1.0, 0.1), 0.1, 1e-12);
  EXPECT_DOUBLE_EQ(soft_radius_after_wheel(0.0055, -1.0, 0.1), 0.0);  // below start/20: off
  EXPECT_DOUBLE_EQ(soft_radius_after_wheel(0.3, 0.0, 0.1), 0.3);
}

TEST(ModelerKeysTest, LeftPressClassification) {
  EXPECT_EQ(classify_left_press(false, false, false), PressAction::BoxSelect);
  EXPECT_EQ(classify_left_press(false, false, true), PressAction::BoxSelect);
  EXPECT_EQ(classify_left_press(true, true, false), PressAction::DragSelection);
  EXPECT_EQ(classify_left_press(true, true, true), PressAction::ClickSelect);
  EXPECT_EQ(classify_left_press(true, false, false), PressAction::ClickSelect);
}

TEST(ModelerKeysTest, ClickAndBoxSelection) {
  std::vector<unsigned> sel{4, 7};
  apply_click(sel, 2, false);
  EXPECT_EQ(sel, (std::vector<unsigned>{2}));
  apply_click(sel, 9, true);
  EXPECT_EQ(sel, (std::vector<unsigned>{2, 9}));
  apply_click(sel, 2, true);  // Shift on a selected point toggles it off
  EXPECT_EQ(sel, (std::vector<unsigned>{9}));
  apply_click(sel, -1, true);
  EXPECT_EQ(sel, (std::vector<unsigned>{9}));
  apply_click(sel, -1, false);
  EXPECT_TRUE(sel.empty());
  apply_box(sel, {5, 3, 3}, false);
  EXPECT_EQ(sel, (std::vector<unsigned>{3, 5}));
  apply_box(sel, {1, 5}, true);
  EXPECT_EQ(sel, (std::vector<unsigned>{1, 3, 5}));
  apply_box(sel, {8}, false);
  EXPECT_EQ(sel, (std::vector<unsigned>{8}));
}

TEST(ModelerKeysTest, HelpTableListsTheModelerKeys) {
  bool grab = false;
  for (const KeyBinding& b : modeler_key_bindings()) grab |= b.action.find("Grab") != std::string_view::npos;
  EXPECT_TRUE(grab);
}

TEST(ModelerKeysTest, RotateScaleAndExcludedAxes) {
  TransformState t;
  EXPECT_EQ(map_modeler_key(Key::R, {}, t, false).type, T::None);
  EXPECT_EQ(map_modeler_key(Key::S, {}, t, false).type, T::None);
  EXPECT_EQ(map_modeler_key(Key::R, {}, t, true).type, T::TransformStart);
  EXPECT_EQ(t.mode, 1);
  t = {};
  EXPECT_EQ(map_modeler_key(Key::S, {}, t, true).type, T::TransformStart);
  EXPECT_EQ(t.mode, 2);
  // Shift+Z excludes Z; Z then constrains to it; Z again frees; Shift+Z twice frees too.
  EXPECT_EQ(map_modeler_key(Key::Z, shift(), t, true).type, T::TransformUpdate);
  EXPECT_EQ(t.axis, 2);
  EXPECT_TRUE(t.exclude);
  map_modeler_key(Key::Z, {}, t, true);
  EXPECT_EQ(t.axis, 2);
  EXPECT_FALSE(t.exclude);
  map_modeler_key(Key::Z, {}, t, true);
  EXPECT_EQ(t.axis, -1);
  map_modeler_key(Key::X, shift(), t, true);
  map_modeler_key(Key::X, shift(), t, true);
  EXPECT_EQ(t.axis, -1);
  EXPECT_FALSE(t.exclude);
  // Keys that mean something else outside a transform are swallowed inside one.
  EXPECT_EQ(map_modeler_key(Key::A, {}, t, true).type, T::None);
  EXPECT_EQ(map_modeler_key(Key::Escape, {}, t, true).type, T::TransformCancel);
  EXPECT_FALSE(t.active);
  // Outside: Shift+S is the cursor, Ctrl+S still saves, Alt+S nothing.
  EXPECT_EQ(key(Key::S, shift()), T::CursorToSelected);
  EXPECT_EQ(key(Key::S, ctrl()), T::Save);
  EXPECT_EQ(key(Key::S, alt()), T::None);
  EXPECT_EQ(key(Key::R, ctrl()), T::None);
}

TEST(ModelerKeysTest, SculptKeys) {
  using A = SculptKey::Action;
  EXPECT_EQ(key(Key::Tab, ctrl()), T::ToggleSculpt);
  EXPECT_EQ(key(Key::Tab), T::None);
  EXPECT_EQ(map_sculpt_key(Key::X, {}).action, A::Brush);
  EXPECT_EQ(map_sculpt_key(Key::X, {}).brush, 0);
  EXPECT_EQ(map_sculpt_key(Key::S, {}).brush, 2);
  EXPECT_EQ(map_sculpt_key(Key::K, {}).brush, 3);
  EXPECT_EQ(map_sculpt_key(Key::T, shift()).brush, 4);
  EXPECT_EQ(map_sculpt_key(Key::T, {}).action, A::None);
  EXPECT_EQ(map_sculpt_key(Key::F, {}).action, A::Radius);
  EXPECT_EQ(map_sculpt_key(Key::F, shift()).action, A::Strength);
  EXPECT_EQ(map_sculpt_key(Key::S, ctrl()).action, A::None);  // Ctrl+S still saves
  EXPECT_EQ(key(Key::C), T::CircleSelect);
  EXPECT_EQ(key(Key::I, ctrl()), T::SelectInvert);
  EXPECT_EQ(key(Key::NumpadPlus, ctrl()), T::SelectMore);
  EXPECT_EQ(key(Key::NumpadMinus, ctrl()), T::SelectLess);
  EXPECT_EQ(key(Key::L, ctrl()), T::SelectLinked);
  EXPECT_EQ(key(Key::L), T::PickLinked);
}

}  // namespace
}  // namespace sublift
