#pragma once
// The modeler's ImGui panel (edit level, per-level table, detail equalizer, frames, colouring,
// basis functions, compression, history, files, display, timing) and its modal prompts. Plain data in, requests out: the app
// applies them to its ModelerState (ui knows nothing of app or render, DESIGN.md).
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/edit/brush.h"
#include "core/fit/fit_levels.h"
#include "core/multires/hierarchy.h"
#include "ui/basis_settings.h"
#include "ui/viewport_input.h"

namespace sublift {

/// Display switches of the modeler viewport, edited in place by the panel.
struct ModelerDisplay {
  bool smooth = true;
  bool wireframe = false;
  bool net = true;
  bool xray = false;
  bool depth_cue = false;
  bool clip = false;
  int clip_axis = 2;          // 0 X, 1 Y, 2 Z
  float clip_offset = 0.5f;   // 0..1 across the bounds along the axis
  bool clip_flip = false;
  bool orthographic = false;
  bool z_up = false;
  bool texture = true;        // a textured model drawn with its texture (when it has one)
};

/// Readouts of one computed basis function.
struct BasisReadout {
  std::string title;             // "primal scaling 12 of level 1, K = 4 (limit values)"
  std::size_t support = 0;       // finest vertices with a non-zero value
  std::vector<std::uint32_t> support_per_level;
  double integral = 0, min = 0, max = 0;
  double moment[3] = {0, 0, 0};
  std::vector<float> plot;       // curves: values along the curve
};

/// The Basis section (issue 5): the mode's settings and the current function's readouts.
struct BasisPanelData {
  // As shown: on = the mode is on; request.level = j of the function (the edit level when off);
  // request.extra_levels = K asked for (-1: default).
  BasisSettings settings{.request = {.level = 0}};
  int finest = 0;
  int default_extra_levels = 4;  // core's default for this complex
  long long scaling_count = 0;   // level-j vertices: scaling indices 0..scaling_count-1
  long long wavelet_end = 0;     // wavelet indices scaling_count..wavelet_end-1 (e/f/c of level j+1)
  // What "At selection" picks (basis_target_at): level and index per kind, -1: nothing.
  int selected_scaling_level = -1, selected_wavelet_level = -1;
  long long selected = -1, selected_wavelet = -1;
  bool curve = false, lattice = false;
  bool computed = false;
  BasisReadout current;
  bool pinned = false;
  BasisReadout pin;
};

/// The FFD section (issue 6): a model deformed by the lattice being edited.
struct FfdPanelData {
  bool loaded = false, bound = false, lattice = false;  // lattice: the session is a volume
  std::string model_name, note;
  std::vector<std::string> notes;  // import decisions (instancing, skins, images)
  std::size_t vertices = 0, faces = 0;
  std::size_t bound_count = 0, outside = 0, nearest = 0;
  int outside_mode = 0;            // 0 stay, 1 nearest
  double bind_ms = 0.0, deform_ms = 0.0;
  std::size_t moved = 0;           // model vertices the last lattice operation recomputed
};

/// The Animation section (docs/animation.md): the time shown, playback, ghosts.
struct AnimationPanelData {
  bool on = false;
  int frames = 0, base_steps = 0, levels = 0;
  bool cyclic = false, playing = false;
  double frame = 0, time = 0, fps = 24;
  int ghosts = 0;
  int level = 0, layer = 0, layer_frame = 0;  // the edit level's layer shown and its frame
};

/// The Compression section (docs/compression.md): the kept fraction and what it costs.
struct CompressionPanelData {
  bool on = false;                    // the compressed shape is shown
  double fraction = 1.0;              // slider value (the last one asked for while off)
  std::size_t kept = 0, total = 0;    // wavelets kept / in all (total also while off)
  double l2_error = 0.0, linf_error = 0.0;  // relative to the bounding-box diagonal
  double ms = 0.0;
};

/// A fit's settings from the Fit section (docs/fit.md).
struct FitRequest {
  int base_vertices = 0;  // 0: the default (1/64 of the mesh's)
  float feature_angle_deg = 60.0f;
  int levels = 0;         // 0: to about the mesh's vertex count
  int scheme = static_cast<int>(kDefaultFitScheme);  // Scheme's value
};

/// What the panel shows (filled by the app each frame).
struct ModelerPanelData {
  std::string file_name, file_path;
  std::string error;                  // last failed action, with file/line/reason
  std::string message;                // last successful file action
  std::vector<std::string> warnings;  // import report lines
  int dim = 2;
  int scheme = 1;                     // Scheme's value: 0 linear, 1 cubic, 2 sqrt2
  int level = 0, finest = 0;
  int view_level = -1;                // the level whose limit is drawn (-1: the finest)
  int rebuild_levels = 0;             // the opened mesh was subdivided this many times elsewhere
  std::string rebuild_scheme;         // the scheme a rebuild would use
  std::string rebuild_stop;           // why it holds no more levels (empty: not checked)
  bool rebuild_stop_located = false;  // a vertex near that can be shown
  bool can_fit = false;               // an opened surface mesh file: Fit base mesh... is offered
  std::uint32_t file_vertices = 0;    // the opened mesh's vertices (the default base is 1/64)
  bool fit_preview = false;           // a base preview is drawn
  std::vector<LevelStats> levels;     // levels 0..finest (the finest has no wavelets of its own)
  std::vector<double> gains;          // per level 0..finest-1
  bool local_frames = false;
  std::vector<std::string> history;   // labels, oldest first
  std::size_t undo_position = 0;
  double resynthesis_ms = 0.0, frame_ms = 0.0;
  std::size_t vertices_updated = 0;
  std::size_t selected = 0;
  double soft_radius = 0.0;
  int pivot = 0;                      // Pivot's value: median, active, cursor, origin
  bool symmetry[3] = {false, false, false};  // mirror editing across x = 0, y = 0, z = 0
  bool sculpt = false;                // sculpt mode: left drags are brush strokes
  BrushSettings brush;
  int colour_level = -1;
  bool textured = false;              // the shown surface has UVs and a texture to draw
  std::vector<std::string> channels;  // attribute channels the surface can be coloured by
  int colour_channel = -1;
  std::string channel_group;          // the coloured channel's compression group, its kept fraction
  double channel_keep = 1.0;
  bool dirty = false;
  std::vector<std::string> recent;    // recently opened files, newest first
  BasisPanelData basis;
  FfdPanelData ffd;
  CompressionPanelData compression;
  AnimationPanelData animation;
};

/// Text fields the panel edits in place (paths typed by the user).
struct FileFields {
  std::string open_path, save_path, export_path;
  FitRequest fit;  // the Fit section's settings
  bool export_finest = true;
  std::string model_path, model_export_path;  // FFD
  int box[3] = {4, 4, 4};
  float box_margin = 0.05f;
  // Animation: the files (one glTF, or OBJ/PLY/OFF frames separated by spaces) and options.
  std::string animation_paths, animation_export_path;
  int animation_frames = 0, animation_levels = 2, animation_clip = 0;
  bool animation_cyclic = false;
};

/// An animation to open (the Animation section's Open).
struct AnimationOpenRequest {
  std::vector<std::string> paths;
  int frames = 0, levels = 2, clip = -1;
  bool cyclic = false;
};

/// What the user asked for this frame.
struct ModelerPanelRequests {
  std::optional<int> scheme, level, colour_level, view_level, colour_channel;
  std::optional<double> channel_keep;  // for ModelerPanelData::channel_group
  std::optional<std::size_t> history_jump;
  std::optional<bool> local_frames;
  int gain_level = -1;                // a gain slider moved: level and value
  double gain_value = 1.0;
  bool gain_begin = false, gain_end = false;  // the slider drag started / ended
  bool subdivide = false, undo = false, redo = false;
  bool delete_higher = false, delete_lower = false, apply_base = false;  // Blender's Multires buttons
  bool export_levels = false;         // every level's net: the export path's name + _L0 .. _LJ
  bool rebuild = false;               // rebuild the opened mesh's levels (docs/rebuild.md)
  bool rebuild_show_stop = false;     // select the vertex where detection stopped
  std::optional<FitRequest> fit_preview, fit;  // preview the base / fit (docs/fit.md)
  bool fit_clear_preview = false;
  std::optional<std::string> open;    // path to open
  std::optional<std::string> save;    // path to save the project to
  std::optional<std::string> export_path;
  bool export_finest = true;
  std::optional<double> soft_radius;
  std::optional<int> pivot;           // the pivot of rotate and scale (Pivot's value)
  std::optional<bool> sculpt;         // sculpt mode switched
  std::optional<BrushSettings> brush; // a brush setting changed
  int symmetry_axis = -1;             // a mirror checkbox changed: its axis and new state
  bool symmetry_on = false;
  std::optional<BasisSettings> basis;  // the Basis section's settings after the user changed one
  bool pin_basis = false, clear_pin = false;
  // FFD: load a model, wrap it in a box lattice (fields.box, fields.box_margin), bind (with the
  // outside mode), unbind, remove, export.
  std::optional<std::string> load_model, export_model;
  bool wrap_box = false, unbind = false, remove_model = false;
  std::optional<int> bind;  // the outside mode: 0 stay, 1 nearest
  // Compression: show the largest fraction of the wavelets, make it an edit, back to the full shape.
  std::optional<double> compress_fraction;
  bool compress_apply = false, compress_off = false;
  // Animation: open, the frame shown, play or pause, ghost frames, export.
  std::optional<AnimationOpenRequest> animation_open;
  std::optional<double> animation_frame;
  std::optional<bool> animation_play;
  std::optional<int> animation_ghosts;
  std::optional<std::string> animation_export;
  CameraAction camera;
};

/// Draws the side panel; `display` and `fields` are edited in place.
ModelerPanelRequests draw_modeler_panel(const ModelerPanelData& data, ModelerDisplay& display, FileFields& fields,
                                        float x, float y, float width, float height);

/// Answers of the modal prompts.
enum class PromptChoice { None, Save, Discard, Cancel, Recover };

/// The unsaved-changes prompt (Save / Discard / Cancel) while `open` is true.
PromptChoice draw_unsaved_prompt(bool open, const std::string& what);
/// The recovery prompt (Recover / Discard) while `open` is true.
PromptChoice draw_recovery_prompt(bool open, const std::string& path);

/// A modal progress window for long work while `open` is true: `stage` and a bar at `fraction`
/// (0..1). True when Cancel (or Esc) was pressed.
bool draw_progress_prompt(bool open, const std::string& title, const std::string& stage, float fraction);

/// The status line for the modeler.
void draw_modeler_status(const std::string& left, const std::string& right, float display_width,
                         float display_height, float height);

}  // namespace sublift
