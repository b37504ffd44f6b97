#pragma once
// The GUI's ImGui panels: a side panel on the left (file, mesh statistics, import warnings,
// display toggles, view buttons, key bindings) and a status line along the bottom. They take
// plain data and return what the user asked for; the app applies it (ui knows nothing of
// render, DESIGN.md).
#include <cstddef>
#include <string>

#include "core/analysis/mesh_stats.h"
#include "ui/viewport_input.h"

namespace sublift {

/// Fixed sizes of the docked panels, in ImGui (window) pixels.
struct PanelLayout {
  float side_width = 330.0f;
  float status_height = 28.0f;
};

/// A rectangle in ImGui coordinates (origin top-left).
struct ScreenRect {
  float x = 0.0f, y = 0.0f, width = 0.0f, height = 0.0f;
};

/// What the panel shows about the loaded model.
struct ModelInfo {
  std::string file_name;   // base name, shown prominently
  std::string file_path;   // as given, shown in a tooltip
  MeshStats stats;
  std::string warnings;    // ImportReport::format() text; empty when the import was clean
  std::string error;       // last failed user action (e.g. a dropped file that did not load)
};

/// Display state the panel edits in place.
struct ViewToggles {
  bool shaded = true;
  bool wireframe = true;
  bool orthographic = false;
  bool z_up = false;  // Blender's convention; OBJ and glTF models are usually Y-up
};

/// What the status line shows.
struct StatusInfo {
  std::string file_name;
  std::size_t vertices = 0;
  std::size_t faces = 0;
  std::size_t polylines = 0;
  double frame_ms = 0.0;  // time per frame, averaged over recent frames
  bool orthographic = false;
};

/// The part of a display of `width` x `height` left for the 3-D viewport.
ScreenRect viewport_rect(float width, float height, const PanelLayout& layout = {});

/// Sets Sublift's ImGui colours and spacing; loads a readable font when the system has one.
/// Call once after ImGui::CreateContext() and before the first frame.
void apply_ui_theme(float font_size = 15.0f);

/// Draws the side panel (inside an ImGui frame) and returns the view change its buttons ask
/// for (CameraActionType::None if none). Edits `toggles` in place.
CameraAction draw_side_panel(const ModelInfo& model, ViewToggles& toggles, float display_width,
                             float display_height, const PanelLayout& layout = {});

/// Draws the status line along the bottom of the display (inside an ImGui frame).
void draw_status_line(const StatusInfo& status, float display_width, float display_height,
                      const PanelLayout& layout = {});

}  // namespace sublift
