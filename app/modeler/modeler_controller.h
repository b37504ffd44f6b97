#pragma once
// ModelerController: the modeler's interaction — viewport mouse and keys (picking, selection,
// drags, grab, soft radius, camera), panel requests, unsaved-changes and recovery prompts,
// autosave — and the one frame both the window and the headless path draw. GL-free except
// draw_frame(), which draws through a ModelerView.
#include <atomic>
#include <cstdint>
#include <future>
#include <memory>
#include <optional>
#include <functional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "app/modeler/modeler_state.h"
#include "core/edit/picking.h"
#include "render/camera.h"
#include "ui/modeler_keys.h"
#include "ui/modeler_panels.h"
#include "ui/panels.h"

namespace sublift {

class ModelerView;

/// A raw viewport/window event in window coordinates (origin top-left).
struct WindowEvent {
  enum class Type { Move, Press, Release, Wheel, Key };
  Type type = Type::Move;
  int button = 0;  // 0 left, 1 right, 2 middle
  double x = 0.0, y = 0.0;
  double wheel = 0.0;
  Key key = Key::None;
  Modifiers mods;
  bool over_ui = false;  // ImGui wants this mouse/keyboard event
};

class ModelerController {
 public:
  /// `interactive`: prompts, recovery and autosave are on (off for scripts and screenshots).
  explicit ModelerController(bool interactive);
  ~ModelerController();  // cancels and waits for a running job
  void set_interactive(bool interactive) { interactive_ = interactive; }

  /// Long work (rebuilding levels) runs on a worker thread with a progress window and Cancel
  /// when on (the default for interactive controllers); off, it runs at once.
  void set_background_jobs(bool on) { background_jobs_ = on; }
  bool job_running() const { return job_ != nullptr; }
  /// Asks the running job to stop; it ends at its next check and changes nothing.
  void cancel_job();
  /// Installs a finished job's result (or reports its failure); true when a job ended. Called
  /// every frame; tests call it to wait.
  bool poll_job(bool wait = false);

  ModelerState model;
  OrbitCamera camera;
  ModelerDisplay display;
  FileFields fields;
  std::string error, message;
  double frame_ms = 0.0;
  bool framed = false;          // frame the model once the viewport size is known

  /// Opens `path` (asks first when there are unsaved changes and `ask`); shows failures.
  void open(const std::string& path, bool ask = true);
  /// Handles one event (the app calls this in order, before draw_frame).
  void handle(const WindowEvent& event);
  /// The window's close button: true when the app may quit now (else a prompt is shown).
  bool request_quit();
  bool quit_confirmed() const { return quit_confirmed_; }
  /// Autosave when due; `now` in seconds.
  void tick(double now);
  /// The Fit panel's form takes the settings of a fit or base preview a script asked for since
  /// the last call (ModelerState::scripted_fit); what was typed there stays otherwise. Each frame.
  void sync_fit_form();
  /// An animation is playing (the window then draws continuously).
  bool playing() const { return model.has_session() && model.animation() && model.animation()->playing; }
  /// Removes the recovery file (clean exit).
  void clean_exit();
  /// Offers to recover an autosave left by a crash (interactive runs only).
  void check_recovery();
  /// Recovery file path: $SUBLIFT_RECOVERY_DIR, $XDG_STATE_HOME/sublift or
  /// ~/.local/state/sublift, + /recovery.sublift.
  static std::string recovery_path();

  /// The viewport rectangle in window coordinates and the framebuffer scale (draw_frame sets
  /// them each frame; tests set them without drawing).
  void set_view_rect(float x, float y, float width, float height, float scale) {
    view_x_ = x, view_y_ = y, view_w_ = width, view_h_ = height, scale_ = scale;
  }
  bool grabbing() const { return grab_.active; }
  bool circle_selecting() const { return circle_active_; }
  /// Sculpt mode (Ctrl+Tab): left drags are brush strokes at the edit level (core/edit/brush.h).
  bool sculpting() const { return sculpt_; }
  void set_sculpt(bool on) { sculpt_ = on; }
  bool stroking() const { return stroke_; }

  /// Where picking gets the surface's depth so that points behind it are not picked without
  /// x-ray (the app passes ModelerView::surface_depth; tests may leave it unset).
  using DepthSource = std::function<std::vector<float>(const OrbitCamera&, int, int, const ModelerDisplay&)>;
  void set_depth_source(DepthSource source) { depth_source_ = std::move(source), pick_dirty_ = true; }

  /// Draws panel, status line, overlays and viewport into the bound framebuffer; the caller has
  /// started the ImGui backend frame. Display size from ImGui's IO.
  void draw_frame(ModelerView& view, int fb_width, int fb_height);

  /// Applies the panel's requests (draw_frame does; tests call it without ImGui).
  void apply_panel_requests(const ModelerPanelRequests& r) { apply_requests(r); }
  /// The Basis section's data: settings, what "At selection" picks, readouts (current, pinned).
  void fill_basis_data(BasisPanelData& b) const;
  /// The FFD section's data (model, binding report, last deformation).
  void fill_ffd_data(FfdPanelData& p) const;
  /// The Compression section's data (the view's readout, or the wavelet count while off).
  void fill_compression_data(CompressionPanelData& c) const;
  /// Loads a model for free-form deformation; errors go to `error` like other actions.
  void load_model(const std::string& path);

 private:
  enum class Press { None, Click, Drag, Box };
  struct Pending {
    enum class Kind { None, Open, Quit } kind = Kind::None;
    std::string path;
  };

  void run_command(ModelerCommandType type);
  void apply_camera(const CameraAction& action);
  void apply_requests(const ModelerPanelRequests& r);
  void proceed(const Pending& p);
  bool save(const std::string& path);
  std::string default_save_path() const;
  void export_to(const std::string& path, bool finest);
  bool in_viewport(double x, double y) const;
  PickView pick_view() const;
  const PickIndex& pick_index();
  void update_grab();  // every transform mode
  void update_rotate_scale();
  void circle_paint(double vx, double vy);  // viewport pixels
  void select_loop_at(double vx, double vy, bool ring, bool extend);
  void fail(const std::exception& e, const std::string& context);

  bool interactive_;
  // Viewport rectangle in window coordinates and the framebuffer scale, from the last frame.
  float view_x_ = 0, view_y_ = 0, view_w_ = 1, view_h_ = 1, scale_ = 1;
  double mouse_x_ = 0, mouse_y_ = 0;
  bool held_[3] = {false, false, false};
  Modifiers mods_;
  Press press_ = Press::None;
  double press_x_ = 0, press_y_ = 0;
  long long press_hit_ = -1;
  bool moved_ = false;
  glm::dvec3 drag_anchor_{0.0};
  TransformState grab_;
  bool alt_click_ = false;  // Alt+left pressed and not moved: an edge loop on release
  bool circle_active_ = false, circle_painting_ = false, circle_erase_ = false;
  double circle_radius_px_ = 40.0;
  bool sculpt_ = false, stroke_ = false;
  BrushSettings stroke_brush_;   // the brush before Ctrl (invert) or Shift (smooth) changed it
  glm::dvec3 stroke_center_{0.0};
  int adjust_ = 0;               // F: 1 radius, Shift+F: 2 strength, while the mouse adjusts it
  double adjust_x_ = 0.0, adjust_from_ = 0.0;
  bool sculpt_key(const WindowEvent& ev);  // true when sculpt mode took the key
  void stroke_press(double vx, double vy, const Modifiers& mods);
  void stroke_move(double vx, double vy, double dx, double dy);
  void stroke_end();
  double grab_x_ = 0, grab_y_ = 0;
  glm::dvec3 grab_anchor_{0.0};
  bool gain_active_ = false;
  PickIndex pick_;
  long long pick_layer_ = -1;
  double last_tick_ = -1.0;  // tick()'s last clock, for playback  // the animation layer the index was built for (-1: none)
  bool pick_dirty_ = true;
  glm::dmat4 pick_matrix_{0.0};
  glm::vec4 pick_clip_{0.0f};  // the clipping plane the pick index was built with; 0 = none
  glm::vec4 clip_now_{0.0f};   // the one drawn last
  std::vector<std::uint8_t> pick_visible_;
  bool pick_xray_ = false;
  DepthSource depth_source_;
  Pending pending_;
  bool unsaved_prompt_ = false, recovery_prompt_ = false;
  // Long work (a rebuild, a fit) on a worker thread: its progress, its cancel flag and its
  // result, which installs itself into the model and says what to tell the user.
  struct Job {
    std::string title;  // "Rebuilding levels", "Fitting"
    std::atomic<bool> cancel{false};
    std::atomic<int> permille{0};
    std::atomic<const char*> stage{"starting"};
    std::future<std::function<std::string(ModelerState&)>> result;
  };
  /// Starts `work` (it reports through the progress callback it is given) as the job.
  template <class Work>
  void start_job(std::string title, Work work);
  std::unique_ptr<Job> job_;
  bool background_jobs_;
  // A panel action that replaces the session: a scheme change (its Scheme value) or a level
  // deletion (undone by Ctrl+Z like any edit).
  struct Replacing {
    enum class Kind { Scheme, DeleteHigher, DeleteLower } kind = Kind::Scheme;
    int scheme = 0;
  };
  void run_replacing(const Replacing& c);
  bool quit_confirmed_ = false;
  double last_autosave_ = -1.0;
  bool stats_dirty_ = true;
  std::size_t stats_key_[4] = {~std::size_t(0), 0, 0, 0};  // undo position, history size, topology, session
  std::uint64_t scripted_fit_seen_ = 0;  // model.scripted_fit_count() the form last took
  std::vector<LevelStats> level_cache_;
  std::vector<std::string> recent_;
  BasisSettings basis_request_;  // the Basis section's settings while the mode is off
  double compress_fraction_ = 1.0;  // the Compression slider's last value
};

}  // namespace sublift
