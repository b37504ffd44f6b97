#pragma once
// ModelerState: everything the modeler shows and edits, without GL or ImGui — the editing
// Session, the open file, the current edit level, the selection and soft-selection radius, the
// finest level's limit surface (positions, normals, display faces) and what changed since the
// viewport last uploaded. The GUI's mouse/keys and `sublift --script` both drive it, so a
// scripted `move` and a mouse drag run the same code (begin_drag / drag_to / end_drag).
//
// Display faces: a surface shows the finest complex's own faces; a lattice the outward
// boundary faces of the finest complex (boundary_surface.h); a curve none (its limit polyline
// is drawn from the finest edges instead).
//
// Wavelet colouring (colour_by_level >= 0): core/analysis/wavelet_colour.h.
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "app/modeler/animation_view_state.h"
#include "app/modeler/basis_view_state.h"
#include "app/modeler/ffd_view_state.h"
#include "core/analysis/compress.h"
#include "core/base/csr.h"
#include "core/multires/hierarchy.h"
#include "core/multires/limit.h"
#include "core/edit/brush.h"
#include "core/edit/scheme_switch.h"
#include "core/edit/session.h"
#include "core/edit/symmetry.h"
#include "core/edit/transform.h"
#include "core/io/project/project_io.h"
#include "core/fit/fit_levels.h"
#include "core/multires/rebuild.h"
#include "core/complex/face_varying.h"

namespace sublift {

/// What changed since the viewport last synchronised (take_view_update()).
struct ViewUpdate {
  bool topology = false;               // new file, subdivide, level change: re-upload everything
  std::vector<std::uint32_t> surface;  // finest limit vertices whose position/normal changed
  std::vector<std::uint32_t> net;      // control points of the current level that moved
  bool state = false;                  // selection, hover or soft weights changed
  bool scalar = false;                 // wavelet colouring changed
  bool basis = false;                  // the basis-function display changed (on, off, new values)
  bool model_topology = false;         // FFD: a model was loaded or removed
  bool model = false;                  // FFD: the model's positions and normals changed
  bool fit_preview = false;            // the base a fit would start from, shown or cleared
  bool ghosts = false;                 // animation: the ghost frames changed
};

/// The compression view's numbers (docs/compression.md).
struct CompressionReadout {
  double fraction = 1.0;                     // kept fraction asked for, 0..1
  std::size_t kept = 0, total = 0;           // wavelets kept / in all
  double l2_error = 0.0, linf_error = 0.0;   // vs the full shape, / its bounding-box diagonal
  double ms = 0.0;                           // the last synthesis, limit and normals
};

class ModelerState {
 public:
  static constexpr int kDefaultLevels = 2;
  /// Opening a mesh adds up to kDefaultLevels levels, fewer where that would pass this many
  /// finest vertices.
  static constexpr double kMaxOpenVertices = 2.0e6;

  /// Opens a shape (OBJ/OFF/PLY, glTF/GLB, curve OBJ, .lattice, .ovm, .vtk) as a hierarchy of `levels` levels
  /// of `scheme`, or a `.sublift` project with its gains, frames and current level. Throws
  /// sublift::Error; on failure the current session is left untouched.
  void open(const std::string& path, int levels = kDefaultLevels, Scheme scheme = Scheme::Cubic);
  bool has_session() const { return session_ != nullptr; }
  /// Bumped whenever a new session is installed (open, scheme change).
  std::uint64_t serial() const { return serial_; }

  // ---- editing (each catches nothing: callers show sublift::Error messages) -----------------
  /// Rebuilds the hierarchy with another scheme from level 0's control points, keeping the
  /// finest resolution (wavelets are lost: confirm first when dirty): J levels of a 1-to-4
  /// scheme become 2J sqrt2 levels and back (rounded up). Undo history is cleared. Refused
  /// (Error) while a model is bound, as is subdivide(), and sqrt2 for curves and lattices.
  void set_scheme(Scheme scheme);
  /// The same in three parts, so the costly middle one runs on a worker thread while the
  /// window shows its progress: the checks and a copy of what the switch reads (throws Error;
  /// nullopt when `scheme` is already the session's), the new hierarchy (any thread; throws
  /// Cancelled when `progress` answers false), then installing it (says what happened).
  std::optional<SchemeSwitchInput> begin_scheme(Scheme scheme);
  static SchemeSwitch prepare_scheme(const SchemeSwitchInput& in, const SwitchProgress& progress = {});
  std::string install_scheme(const SchemeSwitchInput& in, SchemeSwitch next);
  /// A mesh (not a project) that another tool subdivided: the levels it holds (0: none or not
  /// checked), the scheme `rebuild` would use, and why it holds no more (docs/rebuild.md).
  struct RebuildOffer {
    bool checked = false;  // the opened file was looked at (a surface mesh, not a project)
    int levels = 0;
    Scheme scheme = Scheme::Cubic;
    std::string stop;                       // why it holds no more levels
    std::uint32_t stop_vertex = UINT32_MAX;  // a file vertex (= level-0 vertex) near that
  };
  /// Selects the vertex where detection stopped, at level 0 (the file's own vertices): the
  /// region that breaks subdivision connectivity, drawn as the selection. False when none.
  bool show_rebuild_stop();
  const RebuildOffer& rebuild_offer() const { return rebuild_offer_; }
  /// Rebuilds the opened mesh's levels (`levels` -1: all it holds) from its file, analysing its
  /// positions: opens at level 0 with the detail as wavelets; history cleared. Throws Error.
  void rebuild_levels(int levels = -1);
  /// The same in three parts, so that the work can run on another thread with progress and
  /// cancel (the modeler's progress window): check_rebuild throws where rebuild_levels would
  /// refuse; prepare_rebuild touches no state (throws Cancelled when `progress` answers false);
  /// install_rebuild installs its result.
  struct PreparedRebuild {
    Rebuilt rebuilt;
    Csr faces;  // the file's faces, in file order
    std::vector<VertexAttribute> attribute_names;  // channels 3.. of rebuilt.hierarchy (values empty)
  };
  void check_rebuild();
  /// Fitting a coarse base and levels to the opened mesh (docs/fit.md), in the same three parts
  /// (check_fit, prepare_fit on any thread, install_fit), with a preview of the base first.
  struct FitSettings {
    std::uint32_t base_vertices = 0;  // 0: the default size (1/64 of the mesh's)
    double feature_angle_deg = 60.0;
    int levels = 0;                   // 0: to about the mesh's vertex count
    Scheme scheme = kDefaultFitScheme;
  };
  struct FitPreview {
    std::vector<std::uint32_t> edges;  // 2 base vertices each
    std::vector<double> positions;     // the base's vertices
    std::uint32_t vertices = 0, faces = 0;
    std::size_t creases = 0, corners = 0;
  };
  struct PreparedFit {
    Fitted fitted;
    std::uint32_t base_vertices = 0;
    FeatureTags file_tags;  // the file's crease and corner tags, which the fit does not carry
    FitSource source;       // the mesh and the base-to-mesh map, saved with the project
  };
  /// True for an opened surface mesh file (not a project): what fitting takes.
  bool can_fit() const { return project_path_.empty() && !file_path_.empty() && session_ && dim() == 2; }
  /// The base a fit would start from, for the view to draw over the mesh, in the same parts as
  /// the fit: prepare_fit_preview on any thread (OpenMesh's decimater: about 20 s at a million
  /// vertices, with progress and Cancel), install_fit_preview (returns what to tell the user).
  /// preview_fit does all three at once (the script command). Throws Error, keeping the last.
  static FitPreview prepare_fit_preview(const std::string& file, const FitSettings& settings, const FitProgress& progress);
  std::string install_fit_preview(FitPreview preview);
  std::string preview_fit(const FitSettings& settings);
  void clear_fit_preview();
  const FitPreview* fit_preview() const { return fit_preview_ ? &*fit_preview_ : nullptr; }
  void check_fit();
  static PreparedFit prepare_fit(const std::string& file, const FitSettings& settings, const FitProgress& progress);
  /// Installs the fit (level 0, history cleared); returns what to tell the user.
  std::string install_fit(PreparedFit prepared);
  /// check_fit, prepare_fit and install_fit in one (the script command `fit`).
  void fit_base(const FitSettings& settings);
  /// The settings the last scripted fit or base preview asked for (fit_base, preview_fit), and
  /// how many have asked: the Fit panel's form shows them, as if typed there.
  const FitSettings& scripted_fit() const { return scripted_fit_; }
  std::uint64_t scripted_fit_count() const { return scripted_fit_count_; }
  static PreparedRebuild prepare_rebuild(const std::string& file, const RebuildOffer& offer, int levels, const RebuildProgress& progress);
  void install_rebuild(PreparedRebuild prepared);
  /// The file order of a rebuilt mesh (empty otherwise); saved with the project.
  const InputOrder& input_order() const { return input_order_; }
  /// The mesh a fitted model was fitted to (empty otherwise); saved with the project.
  const FitSource& fit_source() const { return fit_source_; }
  /// The texture coordinates of level `level` (the base's, refined by the linear rule; saved and
  /// exported with the levels), empty when the model has none or its scheme cannot carry them
  /// (modeler_uv.cpp). The base's UVs follow Delete Lower and rebuild; a fit starts without.
  FaceVaryingUV level_uv(int level) const;
  /// The drawn surface split at its UV seams (split_at_uv_seams of surface_faces() with the shown
  /// level's UVs), for drawing the texture; empty without UVs, a texture, or when the drawn faces
  /// are not the level's (modeler_uv.cpp).
  UvVertexSplit shown_uv_split() const;
  /// The texture the model's UVs map (glTF baseColorTexture), or none.
  const SurfaceTexture& texture() const { return texture_; }
  void set_level(int level);
  /// Blender's separate viewport level: the surface drawn (and brushed, and picked) is the limit
  /// of level `level` (-1: the finest, the default, which follows subdivide); edits, the history,
  /// saves and "finest limit" exports still use every level. Coarser is faster on big models.
  /// Throws Error outside -1..J or while the compression view or the basis mode is on (they draw
  /// the finest surface).
  void set_view_level(int level);
  int view_level() const { return view_level_; }
  /// The level whose limit is shown: view_level() clamped to the finest.
  int shown_level() const;
  void subdivide();
  /// Blender's Multires "Delete Higher" / "Delete Lower" (core/edit/level_ops.h): the levels
  /// above the edit level go / the edit level becomes the base (the edit level becomes 0); the
  /// shape stays, the history is cleared and the session is unsaved. Return what to tell the
  /// user; throw Error when there is nothing to delete, while a model is bound or while the
  /// compression view is on.
  std::string delete_higher_levels();
  std::string delete_lower_levels();
  /// Blender's "Apply Base": nothing to do in Sublift; what to tell the user (kApplyBaseNote).
  static const char* apply_base_note();
  /// Shift+E / Ctrl+Shift+E (core/edit/features.h): marks the base edges joining two selected
  /// points as creases (clears them when they all are creases already) / the selected points
  /// as corners, at level 0 only; the hierarchy is rebuilt on the new features with the shape
  /// and its detail kept. Returns what changed; throws Error away from level 0, with nothing
  /// selected, or while a model is bound or the compression view is on.
  /// `on` given: mark (true) or clear (false) instead of toggling.
  std::string toggle_creases(std::optional<bool> on = std::nullopt);
  std::string toggle_corners(std::optional<bool> on = std::nullopt);

  // Operations that replace the session (a scheme change, level deletion, a feature edit) keep
  // the session they replace: undo with an empty history goes back to it, with its own history,
  // and redo forwards again (up to kStructureUndo of them).
  static constexpr std::size_t kStructureUndo = 8;
  bool can_undo() const { return session_->can_undo() || !structure_undo_.empty(); }
  bool can_redo() const { return session_->can_redo() || !structure_redo_.empty(); }
  bool undo();
  bool redo();
  /// Jumps in the history so that entries [0, position) are applied.
  void jump_to(std::size_t position);
  void set_gain(int level, double factor);  // within begin_gain/end_gain: one history entry
  void begin_gain(int level);
  void end_gain();
  void set_local_frames(bool local);

  // A drag of the selection: one history entry; drag_to sets the total translation so far.
  void begin_drag(const std::string& label);
  void drag_to(const double total[3]);
  void end_drag();
  /// Ends the drag and reverts its moves exactly (undo of its entry).
  void cancel_drag();
  bool dragging() const { return dragging_; }
  /// Translation applied by the current drag so far.
  const double* drag_total() const { return drag_total_; }

  // Rotate and scale of the selection (R, S; core/edit/transform.h): begun like a drag (the
  // soft selection fixed at the start, one history entry, end_drag / cancel_drag end it).
  // transform_to sets the whole transform so far, relative to the positions at the start: a
  // rotation by `angle` radians about `axis` through the pivot, then per-axis `factors`.
  void begin_transform(TransformMode mode);
  void transform_to(const glm::dvec3& axis, double angle, const glm::dvec3& factors);
  TransformMode transform_mode() const { return transform_mode_; }
  /// The pivot of the transform in progress (or the one the next would use).
  glm::dvec3 transform_pivot() const;
  Pivot pivot() const { return pivot_; }
  void set_pivot(Pivot p) { pivot_ = p; }
  const glm::dvec3& cursor() const { return cursor_; }
  void set_cursor(const glm::dvec3& c) { cursor_ = c; }
  /// The active control point (the last one clicked or selected alone; -1: none).
  long long active() const { return active_; }
  /// Makes a selected point the active one (ignored when it is not selected).
  void set_active(long long vertex);

  // ---- sculpt brushes (core/edit/brush.h) ----------------------------------------------------
  const BrushSettings& brush() const { return brush_; }
  /// Throws Error on a radius that is not positive or a strength outside 0..1.
  void set_brush(const BrushSettings& b);
  /// A stroke is one history entry (begun and ended like a drag: end_drag / cancel_drag).
  void begin_stroke();
  /// One dab on the edit level's net (with the mirror images under symmetry); returns how many
  /// control points it moved (0: none in reach).
  std::size_t dab(const Dab& d);
  /// The first point of the shown limit surface on the ray (origin, unit dir); false on a miss.
  bool surface_hit(const glm::dvec3& origin, const glm::dvec3& dir, glm::dvec3& hit) const;

  // ---- symmetry (core/edit/symmetry.h) -------------------------------------------------------
  /// Mirror editing across the world plane across `axis` (0..2; Blender's X/Y/Z mirror): moves,
  /// rotates, scales and brush strokes also move the mirror images of what they move. The
  /// mirror map of the edit level is found when needed (by position, then by topology); returns
  /// what has no mirror image ("" when everything mirrors).
  std::string set_symmetry(int axis, bool on);
  bool symmetry(int axis) const { return symmetry_[static_cast<std::size_t>(axis)]; }
  /// The edit level's mirror map across `axis` (found on first use after a topology or level
  /// change).
  const MirrorMap& mirror_map(int axis);

  // ---- selection ----------------------------------------------------------------------------
  const std::vector<unsigned>& selection() const { return selection_; }
  /// Replaces the selection (indices of the current level; sorted and deduplicated here).
  void set_selection(std::vector<unsigned> selection);
  void select_all();
  /// Topological selection (core/edit/selection.h) on the edit level's net.
  enum class SelectOp { Linked, More, Less, Invert };
  void select_op(SelectOp op);
  /// Selects the loop (or ring, surfaces only) through edge `edge` of the edit level; `extend`
  /// adds it to the selection. Throws Error on a bad edge index.
  void select_loop(std::uint32_t edge, bool ring, bool extend);
  /// The edit level's complex (the net's topology).
  const Complex& level_complex() const { return session_->hierarchy().levels[static_cast<std::size_t>(level_)]; }
  void set_hover(long long vertex);
  long long hover() const { return hover_; }
  double soft_radius() const { return soft_radius_; }
  void set_soft_radius(double radius);
  /// A reasonable first soft radius: 5% of the model's bounding-box diagonal.
  double default_soft_radius() const;

  // ---- files --------------------------------------------------------------------------------
  /// Saves the project (.sublift, atomic) and marks the session saved.
  void save_project(const std::string& path);
  /// Exports the finest level (finest = true) or the current level by extension: .obj/.ply/
  /// .gltf/.glb with normals (the limit surface for the finest level; lattices: their boundary),
  /// .lattice/.ovm/.vtk (and .off) through write_shape. Returns notes on what the format dropped.
  std::vector<std::string> export_shape(const std::string& path, bool finest);
  /// The same for the control net of `level` (-1: the finest limit surface).
  std::vector<std::string> export_level(const std::string& path, int level);
  /// Every level's control net at once: PATH's stem + "_L0" .. "_LJ" + its extension, in PATH's
  /// folder. Returns the files written.
  std::vector<std::string> export_levels(const std::string& path);
  /// Writes a recovery project without touching the saved state.
  void write_recovery(const std::string& path) const;

  // ---- what the viewport and panel read -----------------------------------------------------
  const Session& session() const { return *session_; }
  int level() const { return level_; }
  int dim() const { return session_->dim(); }
  const std::string& file_path() const { return file_path_; }
  /// Level-0 vertices of the file as opened (a fit or rebuild later replaces level 0).
  std::uint32_t file_vertices() const { return file_vertices_; }
  /// Where Save writes: the project opened or last saved; empty after opening a mesh.
  const std::string& project_path() const { return project_path_; }
  void set_project_path(std::string path) { project_path_ = std::move(path); }
  const std::vector<std::string>& import_warnings() const { return warnings_; }
  /// Per-level numbers for the panel: level_stats() with a row for the finest level too (its
  /// vertices, no wavelets of its own).
  std::vector<LevelStats> level_rows() const;

  const Csr& surface_faces() const { return faces_; }
  /// The shown level's complex (the finest unless set_view_level chose another).
  const Complex& shown_complex() const { return session_->hierarchy().levels[static_cast<std::size_t>(shown_level())]; }
  /// The limit surface shown (of shown_level(); the compressed one while the compression view is on) (the compressed one while the compression view is on).
  const std::vector<double>& limit_positions() const { return compress_ ? compress_->limit : limit_; }
  const std::vector<double>& limit_normals() const { return compress_ ? compress_->normals : normals_; }
  /// Edges of the current level as vertex pairs, with feature classes for the net renderer.
  const std::vector<std::uint32_t>& net_edges() const;
  std::vector<std::uint8_t> net_edge_features() const;
  std::vector<std::uint8_t> net_vertex_features() const;
  const std::vector<std::uint8_t>& net_state() const { return net_state_; }
  const std::vector<float>& net_soft() const { return net_soft_; }

  /// Wavelet level shown as colour (-1: clay). Values 0..1 per finest vertex.
  int colour_level() const { return colour_level_; }
  void set_colour_level(int level);
  /// Colour the surface by attribute channel `channel` (an index into attribute_names(); -1: off)
  /// through viridis: PLY uchar/ushort values over their type's range, others over the channel's
  /// own minimum to maximum. Replaces the colouring by a level's wavelets, and back.
  void set_colour_channel(int channel);
  int colour_channel() const { return colour_channel_; }
  /// The model's attribute channels (name and type; values empty), in channel order.
  const std::vector<VertexAttribute>& attribute_names() const { return attribute_names_; }
  /// Their groups as compression takes them (core/analysis/compress.h: "colour" for red, green,
  /// blue, alpha; every other channel on its own), ranges within the attribute channels.
  std::vector<ChannelGroup> attribute_groups() const;
  /// Compresses one attribute group on its own (`name`: the group's, or one of its channels'):
  /// the largest fraction `keep` of its wavelets stay, ranked by its own magnitude; positions
  /// and the other groups are untouched. A setting, not an edit: what is shown, saved and
  /// exported is compressed, the full values are kept, 1 gives them back. Throws Error for an
  /// unknown name or a fraction outside 0..1.
  void set_channel_keep(const std::string& name, double keep);
  double channel_keep(const std::string& group) const;
  const std::vector<float>& colour_values() const { return colour_; }

  /// Basis-function mode (issue 5, app/modeler/basis_view_state.h): computes the function of
  /// `settings` on level settings.request.level (-1: the edit level; the level used is stored)
  /// (settings.on false: off). Throws Error and leaves the mode off on a bad level or index. A
  /// change of view settings alone (height, slice, iso) only redraws. Kept when the edit level
  /// changes; turned off when the scheme, file or topology changes; recomputed after edits of
  /// its level's shape (once per drag, at its end). With settings.follow, selecting one control
  /// point shows the function basis_target_at() picks there.
  void set_basis(const BasisSettings& settings);
  bool basis_on() const { return basis_ != nullptr; }
  const BasisSettings& basis_settings() const { return basis_settings_; }
  /// The current function's display (only while basis_on()).
  const BasisDisplay& basis() const { return *basis_; }
  /// Side-by-side comparison: a copy of the current function, kept (and drawn beside it) until
  /// cleared or another file is opened, across level and scheme changes. Throws Error when the
  /// mode is off.
  void pin_basis();
  void clear_pin();
  const BasisDisplay* pinned() const { return pinned_.get(); }

  // ---- compression view (docs/compression.md) ------------------------------------------------
  /// Shows the shape synthesised from the largest `fraction` (0..1) of the wavelets (ranked
  /// once when the view turns on, with the session's gains; the session is not changed): the
  /// limit surface and the edit level's net are the compressed ones. While it is on the shape is
  /// locked: moves, grabs, subdivide, gains, scheme changes, undo, redo and history jumps throw
  /// Error ("Apply or Off first"); levels, selection, display and camera still work; Save and
  /// Export write the full shape. Opening a file or turning the basis mode on turns it off.
  /// Throws Error outside 0..1.
  void set_compression(double fraction);
  /// Back to the full shape (nothing changes when the view is off).
  void compression_off();
  /// Makes the shown compression one undoable edit ("Compress 20%": the finest control net moved
  /// onto the compressed one, folded back into every level) and turns the view off. Throws
  /// Error when the view is off, or when a detail gain is 0 (as any edit at the finest level).
  void apply_compression();
  bool compression_on() const { return compress_ != nullptr; }
  /// The view's numbers (only while compression_on()).
  const CompressionReadout& compression() const { return compress_->readout; }
  /// The edit level's control net as shown: the compressed one while the view is on.
  std::span<const double> net_positions() const;

  // ---- free-form deformation (issue 6, app/modeler/ffd_view_state.h) -------------------------------
  /// Imports a model (.gltf/.glb/.obj/.ply/.off) and binds it to the open lattice; with no
  /// lattice open, wraps it in a 4x4x4 box lattice first (refused when an open surface or curve
  /// has unsaved changes). Throws Error; a failure keeps the current model.
  void load_model(const std::string& path);
  /// Replaces the session by a box lattice of nx x ny x nz hexahedra around the model's current
  /// shape (margin times its bounding-box diagonal on every side, kDefaultLevels levels of the
  /// current scheme) and binds the model to it. Throws Error without a model.
  void wrap_model_in_box(int nx, int ny, int nz, double margin);
  /// Binds the model, as it is now, to the lattice as it is now (its finest level). Throws Error
  /// without a model or when the session is not a lattice.
  void bind_model(Outside outside = Outside::Stay);
  /// The model stays where it is and no longer follows the lattice.
  void unbind_model();
  void remove_model();
  /// Writes the model as it is now in its own format family (core/io/model/model.h export_model).
  void export_model(const std::string& path) const;
  const FfdModelState* ffd() const { return ffd_.get(); }

  // ---- animation (issue 22, app/modeler/animation_view_state.h) ------------------------------
  /// Opens an animation (one glTF, or two or more OBJ/PLY/OFF frames) as a space-time lattice and
  /// shows it at frame 0, edit level 0. Throws Error; on failure the current session stays.
  void open_animation(std::span<const std::string> inputs, const AnimationOptions& options);
  bool animation_on() const { return anim_ != nullptr; }
  const AnimationViewState* animation() const { return anim_.get(); }
  /// Shows finest frame `frame` (clamped; cyclic: wrapped): the surface there and the edit
  /// level's nearest layer as the net (the selection is cleared when that layer changes).
  void set_frame(double frame);
  /// Ghost frames either side of the current one (0..8).
  void set_ghosts(int count);
  void set_playing(bool on);
  /// Playback: moves the frame on by `seconds` at the animation's frame rate (a cyclic one
  /// wraps, an open one stops at its last frame).
  void advance(double seconds);
  /// Writes the animation's frames (the finest level): .gltf/.glb morph targets, or .obj/.ply
  /// one file per frame. Returns the files written.
  std::vector<std::string> export_animation(const std::string& path) const;
  /// Animation: 1 for the edit level's points that may be picked (the layer shown); else empty.
  std::span<const std::uint8_t> net_pick_mask() const;

  /// Accumulated changes since the last call, for the GPU buffers.
  ViewUpdate take_view_update();

 private:
  void install(std::unique_ptr<Session> session);  // fresh topology
  /// install() for another model (a file, a fit, a rebuild, a box lattice): nothing to undo back
  /// to, and a brush sized to it.
  void install_new_model(std::unique_ptr<Session> session);
  // A replaced session and what belongs to it, for undo across replacements.
  struct Snapshot {
    std::unique_ptr<Session> session;
    InputOrder input_order;
    FitSource fit_source;
    int level = 0;
    std::vector<unsigned> selection;
    // Redo entries: the history of the session that the undo brought back, as it was then; redo
    // goes forward only from there (an edit since then made a new future).
    std::size_t resume_position = 0, resume_history = 0;
  };
  std::vector<Snapshot> structure_undo_, structure_redo_;
  Snapshot take_snapshot();
  void restore(Snapshot s);
  /// Installs `next` in place of the current session, which goes on the structural undo stack.
  void replace_session(std::unique_ptr<Session> next);
  void install_features(const FeatureTags& tags);  // the base with these tags, shape kept (undoable)
  ProjectExtras project_extras() const;             // what a save keeps beside the hierarchy
  void after_operation();                           // pull changed() into limit and update
  void rebuild_limit();
  void refresh_state();   // soft weights, then the per-vertex state
  void refresh_flags();   // the per-vertex state only (hover changes)
  void refresh_colour();
  void clamp_selection();
  /// Soft selection of the edit level (the animation's layer only).
  SoftWeights selection_weights() const;
  void check_not_animation(const char* what) const;  // throws Error in the animation mode
  void rebuild_animation_view();                     // limit, faces, normals, layer, ghosts
  // Installs an opened animation (from files, or a project: its path, edit level and gains).
  void install_animation(OpenedAnimation opened, const std::string& path, std::string project, int level,
                         std::vector<double> gains);

  std::unique_ptr<Session> session_;
  std::unique_ptr<AnimationViewState> anim_;
  RebuildOffer rebuild_offer_;
  std::optional<FitPreview> fit_preview_;
  FitSettings scripted_fit_;
  std::uint64_t scripted_fit_count_ = 0;
  std::uint32_t file_vertices_ = 0;
  InputOrder input_order_;
  FitSource fit_source_;
  // Texture coordinates of every base this model has had (undo brings a base back), each with
  // the base's faces it belongs to; the opened file's own UVs, for rebuild; its texture (exports).
  std::vector<std::pair<Csr, FaceVaryingUV>> uv_bases_;
  FaceVaryingUV file_uv_;
  SurfaceTexture texture_;
  // A model's attribute channels (colours, scalars): the session edits x, y, z and these stay,
  // merged back on saving and written with exports (modeler_attributes.cpp).
  // One set per base the model has had (Delete Lower and Rebuild make new ones; undo brings an
  // old base back, and its set with it).
  std::vector<Hierarchy> attribute_sets_;
  std::vector<std::pair<std::string, double>> channel_keep_;  // group -> fraction of its wavelets kept (< 1)
  std::vector<VertexAttribute> attribute_names_;  // name and type of each, values empty
  /// The attributes fitted to the session (attributes_for), if a set belongs to its base.
  std::optional<Hierarchy> fitted_attributes(std::string* why = nullptr) const;
  /// The hierarchy a save writes: the session's, with the attribute channels when they still fit
  /// its base and levels (else `*why` says why not and the session's alone is returned).
  Hierarchy saved_hierarchy(std::string* why) const;
  /// Level `level`'s attribute values (the saved gains applied), empty when there are none.
  std::vector<VertexAttribute> attributes_at(int level) const;
  std::string attribute_list() const;  // "red, green, blue"
  /// Channel `k`'s values on the shown level's vertices, in 0..1 (set_colour_channel's scale);
  /// empty when the attributes no longer fit the session.
  std::vector<float> channel_colour(int k) const;
  void remember_uv(const Complex& base, FaceVaryingUV uv);
  FaceVaryingUV base_uv() const;
  /// `uv` of `level` (the rebuilt file's level) per corner of the file's faces.
  FaceVaryingUV uv_in_file_order(const FaceVaryingUV& uv, const Complex& level) const;
  std::string file_path_, project_path_;
  std::vector<std::string> warnings_;
  int level_ = 0;
  int view_level_ = -1;  // set_view_level
  std::vector<unsigned> selection_;
  long long hover_ = -1;
  double soft_radius_ = 0.0;
  double model_size_ = 1.0;

  bool dragging_ = false;
  double drag_total_[3] = {0, 0, 0};
  TransformMode transform_mode_ = TransformMode::Grab;
  Pivot pivot_ = Pivot::Median;
  glm::dvec3 cursor_{0.0}, transform_pivot_{0.0};
  long long active_ = -1;
  std::vector<double> transform_start_, transform_deltas_;
  std::array<bool, 3> symmetry_{false, false, false};
  BrushSettings brush_;
  std::vector<std::uint32_t> dab_vertices_;
  std::vector<double> dab_deltas_;
  struct BrushComplex {  // the finest level with its upward rows, which the hierarchy leaves out
    Complex complex;
    std::uint64_t serial = 0, topology = 0;
    bool valid = false;
  } brush_complex_;
  const Complex& brush_complex();
  struct MirrorCache {
    MirrorMap map;
    int level = -1;
    std::uint64_t serial = 0, topology = 0;
  };
  std::array<MirrorCache, 3> mirror_cache_;
  /// Moves `vertices` of the edit level by `deltas` (3 each), with their mirror images when
  /// symmetry is on.
  void move_mirrored(std::vector<std::uint32_t> vertices, std::vector<double> deltas);
  SoftWeights drag_weights_;
  std::size_t drag_undo_position_ = 0;
  std::uint64_t seen_topology_ = 0;
  std::uint64_t serial_ = 0;

  LimitStencils stencils_;
  Csr faces_, vertex_faces_;
  std::vector<double> limit_, normals_;
  std::vector<std::uint32_t> stamp_;
  std::uint32_t epoch_ = 0;

  std::vector<std::uint8_t> net_state_;
  std::vector<float> net_soft_;
  std::vector<unsigned> flagged_;  // vertices with a non-zero state
  int colour_level_ = -1;
  int colour_channel_ = -1;
  std::vector<float> colour_;
  ViewUpdate update_;
  BasisSettings basis_settings_;
  std::unique_ptr<FfdModelState> ffd_;
  void ffd_follow();       // after a lattice operation: move the bound model
  void ffd_check_free(const char* what) const;  // throws while a model is bound
  std::unique_ptr<BasisDisplay> basis_, pinned_;
  bool basis_stale_ = false;
  void follow_selection();
  void basis_off();
  void refresh_basis();  // recomputes a stale function (after edits of the shape)

  // The compression view: the ranking of the session's wavelets, built when the view turns on,
  // and the shape of the current fraction (finest net, its limit and normals, the edit level's
  // net). `full`: every wavelet kept, so the session's own shape is shown.
  struct CompressionView {
    Compressor compressor;
    CompressionReadout readout;
    bool full = false;
    std::vector<double> coeffs, finest, limit, normals, net;
  };
  std::unique_ptr<CompressionView> compress_;
  void check_unlocked(const char* what) const;  // throws while the compression view is on
  void refresh_compression_net();
};

/// True when `path` names a `.sublift` project (by extension, any case).
bool is_project_file(const std::string& path);

}  // namespace sublift
