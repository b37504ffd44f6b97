#include "app/modeler/modeler_controller.h"

#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <numbers>
#include <utility>

#include "app/modeler/modeler_view.h"
#include "core/edit/selection.h"
#include "core/base/errors.h"

namespace sublift {
namespace {

ModelerState::FitSettings fit_settings(const FitRequest& r) {
  ModelerState::FitSettings s;
  s.base_vertices = static_cast<std::uint32_t>(std::max(0, r.base_vertices));
  s.feature_angle_deg = r.feature_angle_deg;
  s.levels = r.levels;
  s.scheme = static_cast<Scheme>(r.scheme);
  return s;
}

FitRequest fit_request(const ModelerState::FitSettings& s) {
  FitRequest r;
  r.base_vertices = static_cast<int>(std::min<std::uint32_t>(s.base_vertices, INT32_MAX));
  r.feature_angle_deg = static_cast<float>(s.feature_angle_deg);
  r.levels = s.levels;
  r.scheme = static_cast<int>(s.scheme);
  return r;
}

constexpr double kPickRadiusPx = 10.0;
constexpr double kAutosaveSeconds = 120.0;
constexpr float kStatusHeight = 28.0f;
constexpr glm::vec3 kWindowClear{0.11f, 0.12f, 0.13f};

std::string trimmed(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  return s;
}

}  // namespace

ModelerController::ModelerController(bool interactive) : interactive_(interactive), background_jobs_(interactive) {}

ModelerController::~ModelerController() {
  cancel_job();
  if (job_ && job_->result.valid()) job_->result.wait();
}

void ModelerController::cancel_job() {
  if (job_) job_->cancel = true;
}

bool ModelerController::poll_job(bool wait) {
  if (!job_) return false;
  if (!wait && job_->result.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return false;
  std::unique_ptr<Job> job = std::move(job_);
  try {
    message = job->result.get()(model);
    error.clear();
    pick_dirty_ = stats_dirty_ = true;
  } catch (const Cancelled&) {
    message = job->title + " cancelled; nothing changed";
  } catch (const std::exception& e) {
    fail(e, job->title + ": ");
  }
  return true;
}

template <class Work>
void ModelerController::start_job(std::string title, Work work) {
  job_ = std::make_unique<Job>();
  job_->title = std::move(title);
  Job* job = job_.get();
  const auto progress = [job](const char* stage, double fraction) {
    job->stage = stage;
    job->permille = static_cast<int>(1000 * fraction);
    return !job->cancel.load();
  };
  job_->result = std::async(background_jobs_ ? std::launch::async : std::launch::deferred, [work, progress] { return work(progress); });
  if (!background_jobs_) poll_job(true);
}

std::string ModelerController::recovery_path() {
  namespace fs = std::filesystem;
  fs::path dir;
  if (const char* d = std::getenv("SUBLIFT_RECOVERY_DIR"); d != nullptr && *d != '\0') {
    dir = d;
  } else if (const char* x = std::getenv("XDG_STATE_HOME"); x != nullptr && *x != '\0') {
    dir = fs::path(x) / "sublift";
  } else if (const char* h = std::getenv("HOME"); h != nullptr && *h != '\0') {
    dir = fs::path(h) / ".local" / "state" / "sublift";
  } else {
    dir = fs::temp_directory_path() / "sublift";
  }
  return (dir / "recovery.sublift").string();
}

void ModelerController::fail(const std::exception& e, const std::string& context) {
  error = context + trimmed(e.what());
  message.clear();
}

void ModelerController::open(const std::string& path, bool ask) {
  if (ask && interactive_ && model.has_session() && model.session().dirty()) {
    pending_ = Pending{Pending::Kind::Open, path};
    unsaved_prompt_ = true;
    return;
  }
  try {
    model.open(path);
    framed = false;
    pick_dirty_ = stats_dirty_ = true;
    error.clear();
    message = "Opened " + path;
    if (const int n = model.rebuild_offer().levels; n > 0)
      message += ": it was subdivided " + std::to_string(n) + " time" + (n == 1 ? "" : "s") +
                 " elsewhere (Hierarchy > Rebuild " + std::to_string(n) + " level" + (n == 1 ? "" : "s") + ")";
    recent_.erase(std::remove(recent_.begin(), recent_.end(), path), recent_.end());
    recent_.insert(recent_.begin(), path);
    if (recent_.size() > 8) recent_.pop_back();
    if (fields.save_path.empty() || !model.project_path().empty()) fields.save_path = model.project_path();
  } catch (const std::exception& e) {
    fail(e, "Cannot open: ");  // the current model stays
  }
}

std::string ModelerController::default_save_path() const {
  if (!model.project_path().empty()) return model.project_path();
  if (!fields.save_path.empty()) return fields.save_path;
  std::filesystem::path p(model.file_path());
  return (p.parent_path() / (p.stem().string() + ".sublift")).string();
}

bool ModelerController::save(const std::string& path) {
  try {
    model.save_project(path);
    fields.save_path = path;
    error.clear();
    message = "Saved " + path;
    return true;
  } catch (const std::exception& e) {
    fail(e, "Cannot save: ");
    return false;
  }
}

void ModelerController::export_to(const std::string& path, bool finest) {
  try {
    const auto notes = model.export_shape(path, finest);
    error.clear();
    message = "Exported " + path;
    for (const std::string& n : notes) message += "\n" + n;
  } catch (const std::exception& e) {
    fail(e, "Cannot export: ");
  }
}

void ModelerController::load_model(const std::string& path) {
  try {
    model.load_model(path);
    error.clear();
    const FfdModelState* f = model.ffd();
    pick_dirty_ = true;
    message = "Loaded " + path + (f->bound ? " (bound to the lattice)" : " (wrap it in a box lattice or open one)");
    framed = false;
  } catch (const std::exception& e) {
    fail(e, "Cannot load the model: ");
  }
}

bool ModelerController::request_quit() {
  if (!interactive_ || !model.has_session() || !model.session().dirty() || quit_confirmed_) return true;
  pending_ = Pending{Pending::Kind::Quit, {}};
  unsaved_prompt_ = true;
  return false;
}

void ModelerController::proceed(const Pending& p) {
  if (p.kind == Pending::Kind::Open) open(p.path, false);
  if (p.kind == Pending::Kind::Quit) quit_confirmed_ = true;
}

void ModelerController::tick(double now) {
  // Playback of an animation: the frame follows the clock.
  const double since = last_tick_ < 0.0 ? 0.0 : now - last_tick_;
  last_tick_ = now;
  if (playing()) {
    try {
      model.advance(std::min(since, 0.25));  // a stall does not skip half the animation
    } catch (const std::exception& e) {
      model.set_playing(false);
      fail(e, "Playback: ");
    }
  }
  if (!interactive_ || !model.has_session()) return;
  if (last_autosave_ < 0.0) last_autosave_ = now;
  const bool busy = model.dragging() || grab_.active || gain_active_ || press_ != Press::None;
  if (busy || !model.session().dirty() || now - last_autosave_ < kAutosaveSeconds) return;
  last_autosave_ = now;
  try {
    const std::string path = recovery_path();
    std::filesystem::create_directories(std::filesystem::path(path).parent_path());
    model.write_recovery(path);
  } catch (const std::exception& e) {
    fail(e, "Autosave failed: ");
  }
}

void ModelerController::clean_exit() {
  if (!interactive_) return;
  std::error_code ec;
  std::filesystem::remove(recovery_path(), ec);
}

void ModelerController::check_recovery() {
  if (!interactive_) return;
  std::error_code ec;
  recovery_prompt_ = std::filesystem::exists(recovery_path(), ec);
}

bool ModelerController::in_viewport(double x, double y) const {
  return x >= view_x_ && y >= view_y_ && x < view_x_ + view_w_ && y < view_y_ + view_h_;
}

PickView ModelerController::pick_view() const {
  return PickView{camera.projection() * camera.view(), camera.viewport_width, camera.viewport_height};
}

const PickIndex& ModelerController::pick_index() {
  const PickView v = pick_view();
  const long long layer = model.animation() ? model.animation()->layer : -1;  // an animation's frame moved the net
  if (pick_dirty_ || v.view_proj != pick_matrix_ || clip_now_ != pick_clip_ || display.xray != pick_xray_ || layer != pick_layer_) {
    pick_layer_ = layer;
    // Points the clipping plane removed from view cannot be picked either.
    const auto xyz = model.net_positions();  // as drawn (compressed while that view is on)
    pick_visible_.clear();
    if (clip_now_ != glm::vec4(0.0f)) {
      pick_visible_.resize(xyz.size() / 3);
      for (std::size_t i = 0; i < pick_visible_.size(); ++i)
        pick_visible_[i] = clip_now_.x * xyz[3 * i] + clip_now_.y * xyz[3 * i + 1] + clip_now_.z * xyz[3 * i + 2] +
                               clip_now_.w >= 0.0;
    }
    // An animation: only the layer shown (the level's other layers are other times).
    if (const auto mask = model.net_pick_mask(); mask.size() == xyz.size() / 3) {
      if (pick_visible_.empty()) pick_visible_.assign(mask.begin(), mask.end());
      else for (std::size_t i = 0; i < mask.size(); ++i) pick_visible_[i] = pick_visible_[i] && mask[i];
    }
    std::vector<float> depth;
    if (!display.xray && depth_source_) depth = depth_source_(camera, v.width, v.height, display);
    const OcclusionDepth occlusion{depth};
    pick_.build(v, xyz, pick_visible_, depth.size() == std::size_t(v.width) * std::size_t(v.height) ? &occlusion : nullptr);
    pick_xray_ = display.xray;
    pick_matrix_ = v.view_proj;
    pick_clip_ = clip_now_;
    pick_dirty_ = false;
  }
  return pick_;
}

void ModelerController::apply_camera(const CameraAction& action) {
  Bounds bounds;
  bounds.empty = true;
  switch (action.type) {
    case CameraActionType::None: break;
    case CameraActionType::Orbit: camera.orbit(action.dx, action.dy); break;
    case CameraActionType::Pan: camera.pan(action.dx, action.dy); break;
    case CameraActionType::Zoom: camera.zoom(action.steps); break;
    case CameraActionType::Frame: framed = false; break;  // framed at the next draw
    case CameraActionType::ViewFront: camera.set_view(ViewPreset::Front); break;
    case CameraActionType::ViewBack: camera.set_view(ViewPreset::Back); break;
    case CameraActionType::ViewRight: camera.set_view(ViewPreset::Right); break;
    case CameraActionType::ViewLeft: camera.set_view(ViewPreset::Left); break;
    case CameraActionType::ViewTop: camera.set_view(ViewPreset::Top); break;
    case CameraActionType::ViewBottom: camera.set_view(ViewPreset::Bottom); break;
    case CameraActionType::ToggleOrthographic: display.orthographic = !display.orthographic; break;
  }
}

void ModelerController::update_grab() {
  if (!model.dragging()) return;
  const auto typed = grab_.typed_value();
  const double s = scale_;
  try {
    if (grab_.mode != 0) return update_rotate_scale();
    glm::dvec3 total(0.0);
    if (typed) {
      if (grab_.axis < 0) {
        total.x = *typed;
      } else if (grab_.exclude) {
        total = glm::dvec3(*typed);
        total[grab_.axis] = 0.0;
      } else {
        total[grab_.axis] = *typed;
      }
    } else {
      total = view_plane_delta(pick_view(), grab_anchor_, (mouse_x_ - grab_x_) * s, (mouse_y_ - grab_y_) * s);
      if (grab_.axis >= 0 && grab_.exclude) {
        total[grab_.axis] = 0.0;
      } else if (grab_.axis >= 0) {
        const double along = total[grab_.axis];
        total = glm::dvec3(0.0);
        total[grab_.axis] = along;
      }
    }
    const double t[3] = {total.x, total.y, total.z};
    model.drag_to(t);
  } catch (const std::exception& e) {
    fail(e, "Cannot move: ");
  }
  pick_dirty_ = true;
}

// Rotate: the mouse's turn about the pivot on screen (or typed degrees) about the constrained
// world axis or the view axis; scale: the ratio of the mouse's distances from the pivot on
// screen (or the typed factor). Visual clockwise on screen is a right-handed turn about the
// view direction, so a world axis pointing at the viewer turns the other way round.
void ModelerController::update_rotate_scale() {
  const auto typed = grab_.typed_value();
  const PickView view = pick_view();
  glm::dvec2 c(0.0);
  double depth = 0.0;
  project_point(view, model.transform_pivot(), c, depth);
  const double s = scale_;
  const glm::dvec2 a = glm::dvec2((grab_x_ - view_x_) * s, (grab_y_ - view_y_) * s) - c;
  const glm::dvec2 b = glm::dvec2((mouse_x_ - view_x_) * s, (mouse_y_ - view_y_) * s) - c;
  if (grab_.mode == 1) {
    const glm::dvec3 forward = camera.forward();
    glm::dvec3 axis = forward;
    if (grab_.axis >= 0) axis = glm::dvec3(0.0), axis[grab_.axis] = 1.0;
    double angle = 0.0;
    if (typed) {
      angle = *typed * std::numbers::pi / 180.0;
    } else {
      angle = std::atan2(a.x * b.y - a.y * b.x, glm::dot(a, b));
      if (glm::dot(axis, forward) < 0.0) angle = -angle;
    }
    model.transform_to(axis, angle, glm::dvec3(1.0));
  } else {
    const double la = glm::length(a);
    const double factor = typed ? *typed : (la > 1.0 ? glm::length(b) / la : 1.0);
    model.transform_to(glm::dvec3(0.0, 0.0, 1.0), 0.0, scale_factors(factor, grab_.axis, grab_.exclude));
  }
}

bool ModelerController::sculpt_key(const WindowEvent& ev) {
  if (ev.key == Key::Escape && adjust_) {
    BrushSettings b = model.brush();
    (adjust_ == 1 ? b.radius : b.strength) = adjust_from_;
    model.set_brush(b);
    adjust_ = 0;
    return true;
  }
  if (ev.key == Key::Enter && adjust_) return adjust_ = 0, true;
  const SculptKey k = map_sculpt_key(ev.key, ev.mods);
  switch (k.action) {
    case SculptKey::Action::None: return ev.key == Key::R && !ev.mods.ctrl;  // no rotate in sculpt mode
    case SculptKey::Action::Brush: {
      BrushSettings b = model.brush();
      b.kind = static_cast<BrushKind>(k.brush);
      model.set_brush(b);
      message = std::string("Brush: ") + brush_name(b.kind);
      return true;
    }
    case SculptKey::Action::Radius:
    case SculptKey::Action::Strength:
      adjust_ = k.action == SculptKey::Action::Radius ? 1 : 2;
      adjust_x_ = mouse_x_;
      adjust_from_ = adjust_ == 1 ? model.brush().radius : model.brush().strength;
      return true;
  }
  return false;
}

void ModelerController::stroke_press(double vx, double vy, const Modifiers& mods) {
  glm::dvec3 origin, dir, hit;
  pixel_ray(pick_view(), vx, vy, origin, dir);
  if (!model.surface_hit(origin, dir, hit)) return;  // a press off the surface strokes nothing
  stroke_brush_ = model.brush();
  BrushSettings b = stroke_brush_;
  if (mods.shift) b.kind = BrushKind::Smooth;  // Blender: Shift smooths while held
  if (mods.ctrl) b.invert = !b.invert;         // Ctrl inverts
  try {
    model.set_brush(b);
    model.begin_stroke();
    stroke_ = true;
    stroke_center_ = hit;
    if (b.kind != BrushKind::Grab) model.dab(Dab{hit, dir, glm::dvec3(0.0)});
  } catch (const std::exception& e) {
    model.set_brush(stroke_brush_);
    stroke_ = false;
    fail(e, "Cannot sculpt: ");
  }
  pick_dirty_ = stats_dirty_ = true;
}

void ModelerController::stroke_move(double vx, double vy, double dx, double dy) {
  try {
    if (model.brush().kind == BrushKind::Grab) {
      // Snake hook: the brush follows the mouse in the view plane through its centre and pulls
      // what it holds along.
      const glm::dvec3 motion = view_plane_delta(pick_view(), stroke_center_, dx, dy);
      model.dab(Dab{stroke_center_, camera.forward(), motion});
      stroke_center_ += motion;
    } else {
      // Dabs evenly spaced along the way from the last one, whatever the mouse's speed.
      glm::dvec3 origin, dir, hit;
      pixel_ray(pick_view(), vx, vy, origin, dir);
      if (model.surface_hit(origin, dir, hit))
        for (const glm::dvec3& c : dab_centres_along(stroke_center_, hit, kDabSpacing * model.brush().radius)) {
          model.dab(Dab{c, dir, glm::dvec3(0.0)});
          stroke_center_ = c;
        }
    }
  } catch (const std::exception& e) {
    fail(e, "Cannot sculpt: ");
  }
  pick_dirty_ = true;
}

void ModelerController::stroke_end() {
  stroke_ = false;
  model.end_drag();
  model.set_brush(stroke_brush_);
  stats_dirty_ = pick_dirty_ = true;
}

void ModelerController::circle_paint(double vx, double vy) {
  const std::vector<std::uint32_t> inside = pick_index().in_circle(vx, vy, circle_radius_px_ * scale_, display.xray);
  if (inside.empty()) return;
  std::vector<unsigned> sel = model.selection();
  if (circle_erase_) {
    std::vector<unsigned> kept;
    std::set_difference(sel.begin(), sel.end(), inside.begin(), inside.end(), std::back_inserter(kept));
    if (kept.size() == sel.size()) return;
    sel = std::move(kept);
  } else {
    const std::size_t before = sel.size();
    sel.insert(sel.end(), inside.begin(), inside.end());
    std::sort(sel.begin(), sel.end());
    sel.erase(std::unique(sel.begin(), sel.end()), sel.end());
    if (sel.size() == before) return;
  }
  model.set_selection(std::move(sel));
}

void ModelerController::select_loop_at(double vx, double vy, bool ring, bool extend) {
  const std::int64_t e = pick_edge(pick_index(), pick_view(), model.net_positions(), model.level_complex(), vx, vy,
                                   kPickRadiusPx, display.xray);
  if (e < 0) return;
  try {
    model.select_loop(static_cast<std::uint32_t>(e), ring, extend);
  } catch (const std::exception& ex) {
    fail(ex, "");
  }
}

void ModelerController::run_command(ModelerCommandType type) {
  if (!model.has_session()) return;
  try {
    switch (type) {
      case ModelerCommandType::None: break;
      case ModelerCommandType::SelectAll: model.select_all(); break;
      case ModelerCommandType::SelectNone: model.set_selection({}); break;
      case ModelerCommandType::SelectInvert: model.select_op(ModelerState::SelectOp::Invert); break;
      case ModelerCommandType::SelectMore: model.select_op(ModelerState::SelectOp::More); break;
      case ModelerCommandType::SelectLess: model.select_op(ModelerState::SelectOp::Less); break;
      case ModelerCommandType::SelectLinked: model.select_op(ModelerState::SelectOp::Linked); break;
      case ModelerCommandType::PickLinked: {
        // Blender's L: what is joined to the point under the mouse joins the selection (Shift+L
        // takes it away).
        const double s = scale_;
        const std::int64_t hit = pick_index().nearest((mouse_x_ - view_x_) * s, (mouse_y_ - view_y_) * s, kPickRadiusPx, display.xray);
        if (hit < 0) break;
        const unsigned one[1] = {static_cast<unsigned>(hit)};
        const std::vector<unsigned> linked = select_linked(model.level_complex(), one);
        std::vector<unsigned> sel = model.selection();
        if (mods_.shift) {
          std::vector<unsigned> kept;
          std::set_difference(sel.begin(), sel.end(), linked.begin(), linked.end(), std::back_inserter(kept));
          sel = std::move(kept);
        } else {
          sel.insert(sel.end(), linked.begin(), linked.end());
        }
        model.set_selection(std::move(sel));
        break;
      }
      case ModelerCommandType::CircleSelect:
        circle_active_ = !circle_active_;
        circle_painting_ = false;
        break;
      case ModelerCommandType::ToggleCrease: message = model.toggle_creases(); break;
      case ModelerCommandType::ToggleCorner: message = model.toggle_corners(); break;
      case ModelerCommandType::ToggleSculpt:
        if (stroke_) stroke_end();
        sculpt_ = !sculpt_;
        message = sculpt_ ? std::string("Sculpt mode: ") + brush_name(model.brush().kind) + " at level " + std::to_string(model.level())
                          : "Edit mode";
        break;
      case ModelerCommandType::LevelUp: model.set_level(model.level() + 1); break;
      case ModelerCommandType::LevelDown: model.set_level(model.level() - 1); break;
      case ModelerCommandType::Subdivide: model.subdivide(); break;
      case ModelerCommandType::PlayPause:
        if (model.animation()) model.set_playing(!model.animation()->playing);
        break;
      case ModelerCommandType::FramePrev:
      case ModelerCommandType::FrameNext:
      case ModelerCommandType::FrameFirst:
      case ModelerCommandType::FrameLast:
        if (const AnimationViewState* a = model.animation()) {  // Blender's arrows: a frame, Shift: an end
          model.set_playing(false);
          const double f = type == ModelerCommandType::FramePrev   ? std::ceil(a->frame) - 1.0
                           : type == ModelerCommandType::FrameNext  ? std::floor(a->frame) + 1.0
                           : type == ModelerCommandType::FrameFirst ? 0.0
                                                                    : a->frames() - 1.0;
          model.set_frame(f);
        }
        break;
      case ModelerCommandType::Undo: model.undo(); break;
      case ModelerCommandType::Redo: model.redo(); break;
      case ModelerCommandType::Save: save(default_save_path()); break;
      case ModelerCommandType::SaveAs:
        if (fields.save_path.empty()) {
          error = "Type a project path in Files, then Save.";
        } else {
          save(fields.save_path);
        }
        break;
      case ModelerCommandType::Open:
        if (fields.open_path.empty()) {
          error = "Type a path in Files (or drop a file on the window), then Open.";
        } else {
          open(fields.open_path);
        }
        break;
      case ModelerCommandType::Export:
        if (fields.export_path.empty()) {
          error = "Type an export path in Files, then Export.";
        } else {
          export_to(fields.export_path, fields.export_finest);
        }
        break;
      case ModelerCommandType::TransformStart: {
        if (sculpt_) {  // sculpt mode's G, S are brushes; R does nothing there
          grab_ = TransformState{};
          break;
        }
        glm::dvec3 sum(0.0);
        const auto pos = model.session().positions(model.level());
        for (const unsigned v : model.selection()) sum += glm::dvec3(pos[3 * v], pos[3 * v + 1], pos[3 * v + 2]);
        grab_anchor_ = sum / static_cast<double>(std::max<std::size_t>(model.selection().size(), 1));
        grab_x_ = mouse_x_;
        grab_y_ = mouse_y_;
        model.begin_transform(grab_.mode == 0 ? TransformMode::Grab
                                              : grab_.mode == 1 ? TransformMode::Rotate : TransformMode::Scale);
        break;
      }
      case ModelerCommandType::CursorToSelected:
        model.set_cursor(pivot_point(Pivot::Median, model.session().positions(model.level()), model.selection(), -1, model.cursor()));
        message = "3-D cursor at the selection's median";
        break;
      case ModelerCommandType::TransformUpdate: update_grab(); break;
      case ModelerCommandType::TransformConfirm: model.end_drag(); break;
      case ModelerCommandType::TransformCancel: model.cancel_drag(); break;
    }
  } catch (const std::exception& e) {
    if (!model.dragging()) grab_ = TransformState{};  // a refused grab (compression view) ends here
    fail(e, "");
  }
  pick_dirty_ = stats_dirty_ = true;
}

void ModelerController::handle(const WindowEvent& ev) {
  const double dx = ev.x - mouse_x_, dy = ev.y - mouse_y_;
  if (ev.type != WindowEvent::Type::Key) {
    mouse_x_ = ev.x;
    mouse_y_ = ev.y;
  }
  mods_ = ev.mods;
  if (!model.has_session() || unsaved_prompt_ || recovery_prompt_ || job_) return;
  const double s = scale_;
  const double vx = (ev.x - view_x_) * s, vy = (ev.y - view_y_) * s;  // viewport pixels
  switch (ev.type) {
    case WindowEvent::Type::Key: {
      if (ev.over_ui) return;
      if (circle_active_ && (ev.key == Key::Escape || ev.key == Key::Enter || ev.key == Key::C)) {
        circle_active_ = circle_painting_ = false;
        return;
      }
      if (sculpt_ && sculpt_key(ev)) return;
      const ModelerCommand c = map_modeler_key(ev.key, ev.mods, grab_, !model.selection().empty());
      if (c.type != ModelerCommandType::None || grab_.active) {
        run_command(c.type);
      } else {
        InputEvent in;
        in.type = InputEvent::Type::KeyPress;
        in.key = ev.key;
        in.mods = ev.mods;
        apply_camera(map_viewport_input(in));
      }
      return;
    }
    case WindowEvent::Type::Wheel: {
      if (ev.over_ui || !in_viewport(ev.x, ev.y)) return;
      if (circle_active_) {
        circle_radius_px_ = std::clamp(circle_radius_px_ * std::pow(1.15, ev.wheel), 4.0, 1000.0);
        return;
      }
      if (ev.mods.ctrl) {
        model.set_soft_radius(soft_radius_after_wheel(model.soft_radius(), ev.wheel, model.default_soft_radius()));
      } else {
        InputEvent in;
        in.type = InputEvent::Type::Wheel;
        in.wheel = ev.wheel;
        in.mods = ev.mods;
        apply_camera(map_viewport_input(in));
      }
      return;
    }
    case WindowEvent::Type::Press: {
      if (ev.over_ui || !in_viewport(ev.x, ev.y)) return;
      held_[ev.button] = true;
      if (grab_.active) {
        grab_ = TransformState{};
        run_command(ev.button == 1 ? ModelerCommandType::TransformCancel : ModelerCommandType::TransformConfirm);
        held_[ev.button] = false;
        return;
      }
      if (circle_active_) {
        if (ev.button == 1) {  // right click leaves circle select, as Esc
          circle_active_ = circle_painting_ = false;
          held_[1] = false;
        } else if (ev.button == 0 && display.net) {
          circle_painting_ = true;
          circle_erase_ = ev.mods.shift;
          circle_paint(vx, vy);
        }
        return;
      }
      if (adjust_) {  // F / Shift+F: a left click keeps the value, a right click restores it
        if (ev.button == 1) {
          BrushSettings b = model.brush();
          (adjust_ == 1 ? b.radius : b.strength) = adjust_from_;
          model.set_brush(b);
        }
        adjust_ = 0;
        held_[ev.button] = false;
        return;
      }
      if (sculpt_ && ev.button == 0 && !ev.mods.alt) {
        stroke_press(vx, vy, ev.mods);
        return;
      }
      if (ev.button == 0 && ev.mods.alt && display.net) {  // a loop on release, unless it becomes a Maya orbit
        alt_click_ = true;
        press_x_ = ev.x;
        press_y_ = ev.y;
      }
      if (ev.button != 0 || ev.mods.alt || !display.net) return;
      press_x_ = ev.x;
      press_y_ = ev.y;
      moved_ = false;
      press_hit_ = pick_index().nearest(vx, vy, kPickRadiusPx, display.xray);
      const auto& sel = model.selection();
      const bool hit_selected = press_hit_ >= 0 && std::binary_search(sel.begin(), sel.end(), static_cast<unsigned>(press_hit_));
      switch (classify_left_press(press_hit_ >= 0, hit_selected, ev.mods.shift)) {
        case PressAction::DragSelection: {
          press_ = Press::Drag;
          const auto pos = model.session().positions(model.level());
          const std::size_t v = static_cast<std::size_t>(press_hit_);
          drag_anchor_ = glm::dvec3(pos[3 * v], pos[3 * v + 1], pos[3 * v + 2]);
          break;
        }
        case PressAction::ClickSelect: press_ = Press::Click; break;
        case PressAction::BoxSelect: press_ = Press::Box; break;
        case PressAction::None: press_ = Press::None; break;
      }
      return;
    }
    case WindowEvent::Type::Release: {
      const bool was_held = held_[ev.button];
      held_[ev.button] = false;
      if (ev.button == 0) circle_painting_ = false;
      if (ev.button == 0 && stroke_) {
        stroke_end();
        return;
      }
      if (ev.button == 0 && std::exchange(alt_click_, false) && was_held) {
        select_loop_at(vx, vy, ev.mods.ctrl, ev.mods.shift);
        return;
      }
      if (ev.button != 0 || !was_held) return;
      const Press press = std::exchange(press_, Press::None);
      std::vector<unsigned> sel = model.selection();
      if (press == Press::Drag) {
        if (model.dragging()) {
          model.end_drag();
          stats_dirty_ = true;
        } else {
          apply_click(sel, press_hit_, false);  // a click on a selected point selects it alone
          model.set_selection(sel);
        }
      } else if (press == Press::Click && !moved_) {
        apply_click(sel, press_hit_, ev.mods.shift);
        model.set_selection(sel);
        model.set_active(press_hit_);  // the last one clicked, Blender's active element
      } else if (press == Press::Box) {
        if (moved_) {
          const double px = (press_x_ - view_x_) * s, py = (press_y_ - view_y_) * s;
          const auto inside = pick_index().in_rect(px, py, vx, vy, display.xray);
          apply_box(sel, std::vector<unsigned>(inside.begin(), inside.end()), ev.mods.shift);
        } else if (!ev.mods.shift) {
          sel.clear();
        }
        model.set_selection(sel);
      }
      pick_dirty_ = true;
      return;
    }
    case WindowEvent::Type::Move: {
      if (alt_click_ && std::hypot(ev.x - press_x_, ev.y - press_y_) * s > kDragThresholdPx) alt_click_ = false;
      if (circle_active_) {
        if (circle_painting_) circle_paint(vx, vy);
        return;
      }
      if (adjust_) {
        BrushSettings b = model.brush();
        const double dxs = (ev.x - adjust_x_) * s;
        if (adjust_ == 1) b.radius = adjust_from_ * std::exp(dxs / 150.0);
        else b.strength = std::clamp(adjust_from_ + dxs / 300.0, 0.0, 1.0);
        model.set_brush(b);
        return;
      }
      if (stroke_) {
        stroke_move(vx, vy, dx * s, dy * s);
        return;
      }
      if (grab_.active) {
        if (!grab_.typed_value()) update_grab();
        return;
      }
      if (press_ != Press::None &&
          std::hypot(ev.x - press_x_, ev.y - press_y_) * s > kDragThresholdPx) {
        moved_ = true;
      }
      if (press_ == Press::Drag && moved_) {
        try {
          if (!model.dragging()) model.begin_drag("Move");
          const glm::dvec3 t = view_plane_delta(pick_view(), drag_anchor_, (ev.x - press_x_) * s, (ev.y - press_y_) * s);
          const double total[3] = {t.x, t.y, t.z};
          model.drag_to(total);
        } catch (const std::exception& e) {
          fail(e, "Cannot move: ");
        }
        pick_dirty_ = true;
        return;
      }
      if (held_[1] || held_[2] || (held_[0] && ev.mods.alt)) {
        InputEvent in;
        in.type = InputEvent::Type::MouseMove;
        in.mods = ev.mods;
        in.left = held_[0];
        in.right = held_[1];
        in.middle = held_[2];
        in.dx = dx * s;
        in.dy = dy * s;
        apply_camera(map_viewport_input(in));
        return;
      }
      if (press_ == Press::None && display.net && !ev.over_ui && in_viewport(ev.x, ev.y)) {
        model.set_hover(pick_index().nearest(vx, vy, kPickRadiusPx, display.xray));
      } else if (model.hover() >= 0 && !in_viewport(ev.x, ev.y)) {
        model.set_hover(-1);
      }
      return;
    }
  }
}

void ModelerController::run_replacing(const Replacing& c) {
  switch (c.kind) {
    case Replacing::Kind::Scheme: {
      // The levels are built on a worker thread (a dense mesh's take a while under the triangle
      // schemes), with progress and cancel; the window takes no edits meanwhile.
      if (job_) return;
      std::optional<SchemeSwitchInput> in = model.begin_scheme(static_cast<Scheme>(c.scheme));
      if (!in) return;
      const auto input = std::make_shared<const SchemeSwitchInput>(std::move(*in));
      start_job("Changing the scheme", [input](const SwitchProgress& progress) {
        auto next = std::make_shared<SchemeSwitch>(ModelerState::prepare_scheme(*input, progress));
        return std::function<std::string(ModelerState&)>(
            [input, next](ModelerState& m) { return m.install_scheme(*input, std::move(*next)); });
      });
      return;  // poll_job says what happened (and marks the pick index and statistics stale)
    }
    case Replacing::Kind::DeleteHigher: message = model.delete_higher_levels(); break;
    case Replacing::Kind::DeleteLower: message = model.delete_lower_levels(); break;
  }
  pick_dirty_ = stats_dirty_ = true;
}

void ModelerController::apply_requests(const ModelerPanelRequests& r) {
  try {
    // These replace the session; Ctrl+Z brings the old one back (ModelerState::replace_session).
    if (r.scheme) run_replacing(Replacing{Replacing::Kind::Scheme, *r.scheme});  // the combo lists the enum in order
    if (r.delete_higher || r.delete_lower)
      run_replacing(Replacing{r.delete_higher ? Replacing::Kind::DeleteHigher : Replacing::Kind::DeleteLower});
    if (r.apply_base) message = std::string("Apply base: ") + ModelerState::apply_base_note();
    if (r.export_levels) {
      if (fields.export_path.empty()) {
        error = "Type an export path in Files (name.obj writes name_L0.obj ...), then Export every level.";
      } else {
        const std::vector<std::string> files = model.export_levels(fields.export_path);
        message = "Exported " + std::to_string(files.size()) + " levels: " + files.front() + " .. " + files.back();
      }
    }
    if (r.level) model.set_level(*r.level);
    if (r.view_level) model.set_view_level(*r.view_level);
    if (r.subdivide) model.subdivide();
    if (r.rebuild && !job_) {
      model.check_rebuild();
      start_job("Rebuilding levels", [file = model.file_path(), offer = model.rebuild_offer()](const RebuildProgress& progress) {
        auto prepared = std::make_shared<ModelerState::PreparedRebuild>(ModelerState::prepare_rebuild(file, offer, -1, progress));
        return std::function<std::string(ModelerState&)>([prepared](ModelerState& m) {
          m.install_rebuild(std::move(*prepared));
          const int n = m.session().finest_level();
          return "Rebuilt " + std::to_string(n) + " level" + (n == 1 ? "" : "s") + " with the " +
                 scheme_name(m.session().hierarchy().scheme) + " scheme: the detail is kept as wavelets (history cleared)";
        });
      });
    }
    if (r.fit_preview && !job_) {  // a decimation: seconds for a large mesh, so a job
      model.check_fit();
      start_job("Previewing the base", [file = model.file_path(), settings = fit_settings(*r.fit_preview)](const FitProgress& progress) {
        auto prepared = std::make_shared<ModelerState::FitPreview>(ModelerState::prepare_fit_preview(file, settings, progress));
        return std::function<std::string(ModelerState&)>([prepared](ModelerState& m) { return m.install_fit_preview(std::move(*prepared)); });
      });
    }
    if (r.fit_clear_preview) model.clear_fit_preview();
    if (r.fit && !job_) {
      model.check_fit();
      start_job("Fitting", [file = model.file_path(), settings = fit_settings(*r.fit)](const FitProgress& progress) {
        auto prepared = std::make_shared<ModelerState::PreparedFit>(ModelerState::prepare_fit(file, settings, progress));
        return std::function<std::string(ModelerState&)>([prepared](ModelerState& m) { return m.install_fit(std::move(*prepared)); });
      });
    }
    if (r.rebuild_show_stop && model.show_rebuild_stop()) message = "Selected the vertex near where the mesh stops being a split";
    if (r.undo) model.undo();
    if (r.redo) model.redo();
    if (r.history_jump) model.jump_to(*r.history_jump);
    if (r.local_frames) model.set_local_frames(*r.local_frames);
    if (r.colour_channel) model.set_colour_channel(*r.colour_channel);
    if (r.channel_keep && model.colour_channel() >= 0)
      model.set_channel_keep(model.attribute_names()[std::size_t(model.colour_channel())].name, *r.channel_keep);
    if (r.colour_level) model.set_colour_level(*r.colour_level);
    if (r.soft_radius) model.set_soft_radius(*r.soft_radius);
    if (r.pivot) model.set_pivot(static_cast<Pivot>(*r.pivot));
    if (r.sculpt) sculpt_ = *r.sculpt;
    if (r.brush) model.set_brush(*r.brush);
    if (r.symmetry_axis >= 0) {
      const std::string problem = model.set_symmetry(r.symmetry_axis, r.symmetry_on);
      if (!problem.empty()) error = problem + ": those points are edited without a mirror image.";
    }
    if (r.basis) {
      basis_request_ = *r.basis;  // kept even when it fails, so the panel shows what was typed
      try {
        model.set_basis(*r.basis);
      } catch (const std::exception& e) {
        fail(e, "Basis: ");
      }
    }
    if (r.pin_basis) model.pin_basis();
    if (r.clear_pin) model.clear_pin();
    if (r.wrap_box) {
      model.wrap_model_in_box(fields.box[0], fields.box[1], fields.box[2], fields.box_margin);
      pick_dirty_ = stats_dirty_ = true;
      framed = false;
    }
    if (r.bind) model.bind_model(*r.bind == 1 ? Outside::Nearest : Outside::Stay);
    if (r.unbind) model.unbind_model();
    if (r.remove_model) model.remove_model();
    if (r.gain_begin && !gain_active_) {
      model.begin_gain(r.gain_level);
      gain_active_ = true;
    }
    if (r.gain_level >= 0 && r.gain_value != model.session().gain(r.gain_level)) {
      model.set_gain(r.gain_level, r.gain_value);
    }
    if (r.gain_end && gain_active_) {
      model.end_gain();
      gain_active_ = false;
    }
  } catch (const std::exception& e) {
    fail(e, "");
  }
  try {
    if (r.compress_fraction) {
      compress_fraction_ = *r.compress_fraction;
      model.set_compression(compress_fraction_);
      pick_dirty_ = true;
    }
    if (r.compress_apply) {
      const std::size_t kept = model.compression_on() ? model.compression().kept : 0;
      model.apply_compression();
      error.clear();
      message = "Applied the compression (" + std::to_string(kept) + " wavelets kept); Undo restores the full shape";
      pick_dirty_ = stats_dirty_ = true;
    }
    if (r.compress_off) {
      model.compression_off();
      pick_dirty_ = true;
    }
  } catch (const std::exception& e) {
    fail(e, "Compression: ");
  }
  try {
    if (r.animation_open) {
      AnimationOptions o;
      o.frames = r.animation_open->frames;
      o.levels = r.animation_open->levels;
      o.animation = r.animation_open->clip;
      o.cyclic = r.animation_open->cyclic;
      model.open_animation(r.animation_open->paths, o);
      const AnimationViewState& a = *model.animation();
      error.clear();
      message = "Opened the animation " + r.animation_open->paths.front() + ": " + std::to_string(a.frames()) +
                " frames as a space-time lattice (Space plays, Left/Right step a frame)";
      pick_dirty_ = stats_dirty_ = true;
      framed = false;
    }
    if (r.animation_frame) model.set_frame(*r.animation_frame);
    if (r.animation_play) model.set_playing(*r.animation_play);
    if (r.animation_ghosts) model.set_ghosts(*r.animation_ghosts);
    if (r.animation_export) {
      const std::vector<std::string> files = model.export_animation(*r.animation_export);
      error.clear();
      message = "Exported the animation: " + files.front() + (files.size() > 1 ? " .. " + files.back() : std::string());
    }
  } catch (const std::exception& e) {
    fail(e, "Animation: ");
  }
  if (r.open) open(*r.open);
  if (r.load_model) load_model(*r.load_model);
  if (r.export_model) {
    try {
      model.export_model(*r.export_model);
      error.clear();
      message = "Exported the model to " + *r.export_model;
    } catch (const std::exception& e) {
      fail(e, "Cannot export the model: ");
    }
  }
  if (r.save) save(*r.save);
  if (r.export_path) export_to(*r.export_path, r.export_finest);
  apply_camera(r.camera);
  if (r.scheme || r.level || r.subdivide || r.rebuild || r.rebuild_show_stop || r.fit || r.fit_preview || r.fit_clear_preview || r.undo || r.redo || r.history_jump || r.gain_level >= 0 || r.gain_end) {
    pick_dirty_ = stats_dirty_ = true;
  }
}

namespace {

BasisReadout readout_of(const BasisDisplay& d) {
  const BasisFunction& f = d.function;
  BasisReadout o;
  char title[160];
  const BasisRequest& q = d.settings.request;
  std::snprintf(title, sizeof title, "%s %s %u of level %d, K = %d (%s)", q.dual ? "dual" : "primal",
                q.kind == BasisKind::Scaling ? "scaling" : "wavelet", q.index, d.level,
                f.extra_levels, f.limit ? "limit values" : "control values");
  o.title = title;
  o.support = f.support.size();
  o.support_per_level = f.support_per_level;
  o.integral = f.integral;
  o.min = f.min;
  o.max = f.max;
  std::copy(f.moment, f.moment + 3, o.moment);
  o.plot = d.plot;
  return o;
}

}  // namespace

void ModelerController::fill_ffd_data(FfdPanelData& p) const {
  const FfdModelState* f = model.ffd();
  p.lattice = model.has_session() && model.dim() == 3;
  if (f == nullptr) return;
  p.loaded = true;
  p.model_name = std::filesystem::path(f->model.path).filename().string();
  p.notes = f->model.notes;
  p.note = f->note;
  p.vertices = f->model.num_vertices();
  p.faces = f->model.faces.rows();
  p.bound = f->bound;
  p.outside_mode = f->outside == Outside::Nearest ? 1 : 0;
  if (f->bound) {
    const FfdReport& rep = f->binding.report;
    p.bound_count = rep.bound;
    p.outside = rep.outside;
    p.nearest = rep.nearest;
    p.bind_ms = rep.ms;
    p.moved = f->last_moved;
    p.deform_ms = f->last_deform_ms;
  }
}

void ModelerController::fill_compression_data(CompressionPanelData& c) const {
  const Session& s = model.session();
  c.on = model.compression_on();
  c.fraction = compress_fraction_;
  c.total = s.num_vertices(s.finest_level()) - s.num_vertices(0);
  if (!c.on) return;
  const CompressionReadout& r = model.compression();
  c.fraction = r.fraction;
  c.kept = r.kept;
  c.total = r.total;
  c.l2_error = r.l2_error;
  c.linf_error = r.linf_error;
  c.ms = r.ms;
}

void ModelerController::fill_basis_data(BasisPanelData& b) const {
  const Session& s = model.session();
  const BasisSettings& set = model.basis_on() ? model.basis_settings() : basis_request_;
  const int level = set.request.level >= 0 && set.request.level <= s.finest_level() ? set.request.level : model.level();
  const Complex& cj = s.hierarchy().levels[static_cast<std::size_t>(level)];
  b.settings = set;
  b.settings.on = model.basis_on();
  b.settings.request.level = level;
  b.finest = s.finest_level();
  b.default_extra_levels = default_extra_levels(cj, kModelerBasisVertices, s.hierarchy().scheme, level);
  b.scaling_count = cj.num_vertices;
  b.wavelet_end = static_cast<unsigned>(predicted_level_counts(cj, 1, s.hierarchy().scheme, level).back());
  b.curve = cj.dim == 1;
  b.lattice = cj.dim == 3;
  if (!model.selection().empty()) {
    const unsigned v = model.selection().front();
    if (const auto t = basis_target_at(s.hierarchy(), model.level(), BasisKind::Scaling, v)) {
      b.selected_scaling_level = t->level, b.selected = t->index;
    }
    if (const auto t = basis_target_at(s.hierarchy(), model.level(), BasisKind::Wavelet, v)) {
      b.selected_wavelet_level = t->level, b.selected_wavelet = t->index;
    }
  }
  if (model.basis_on()) {
    b.computed = true;
    b.current = readout_of(model.basis());
  }
  if (model.pinned() != nullptr) {
    b.pinned = true;
    b.pin = readout_of(*model.pinned());
  }
}

void ModelerController::sync_fit_form() {
  if (model.scripted_fit_count() == scripted_fit_seen_) return;
  scripted_fit_seen_ = model.scripted_fit_count();
  fields.fit = fit_request(model.scripted_fit());
}

void ModelerController::draw_frame(ModelerView& view, int fb_width, int fb_height) {
  sync_fit_form();
  const ImGuiIO& io = ImGui::GetIO();
  const float dw = io.DisplaySize.x, dh = io.DisplaySize.y;
  const PanelLayout layout;
  const ScreenRect r = viewport_rect(dw, dh, layout);
  view_x_ = r.x;
  view_y_ = r.y;
  view_w_ = r.width;
  view_h_ = r.height;
  scale_ = dw > 0.0f ? static_cast<float>(fb_width) / dw : 1.0f;
  clip_now_ = display.clip ? view.clip_plane(display) : glm::vec4(0.0f);

  ImGui::NewFrame();
  ModelerPanelData d;
  if (model.has_session()) {
    const Session& s = model.session();
    d.file_name = std::filesystem::path(model.file_path()).filename().string();
    d.file_path = model.file_path();
    d.warnings = model.import_warnings();
    d.dim = model.dim();
    d.scheme = static_cast<int>(s.hierarchy().scheme);
    d.level = model.level();
    d.finest = s.finest_level();
    d.rebuild_levels = model.rebuild_offer().levels;
    d.rebuild_scheme = scheme_name(model.rebuild_offer().scheme);
    // Why it holds no (more) levels: for meshes that hold some, and for dense ones (1000+
    // vertices) a modeler may expect to hold some; small hand-made meshes stay quiet.
    if (model.rebuild_offer().checked && (model.rebuild_offer().levels > 0 || s.num_vertices(0) >= 1000))
      d.rebuild_stop = model.rebuild_offer().stop;
    d.rebuild_stop_located = model.rebuild_offer().stop_vertex != UINT32_MAX;
    d.can_fit = model.can_fit();
    d.file_vertices = model.file_vertices();
    d.fit_preview = model.fit_preview() != nullptr;
    const std::size_t key[4] = {s.undo_position(), s.history().size(), static_cast<std::size_t>(s.topology_version()),
                                static_cast<std::size_t>(model.serial())};
    if (!std::equal(key, key + 4, stats_key_)) stats_dirty_ = true;
    if (stats_dirty_ && !model.dragging() && !gain_active_) {
      std::copy(key, key + 4, stats_key_);
      level_cache_ = model.level_rows();
      stats_dirty_ = false;
    }
    d.levels = level_cache_;
    d.gains.assign(s.gains().begin(), s.gains().end());
    d.local_frames = s.detail_frames() == DetailFrames::Local;
    for (const HistoryEntry& e : s.history()) d.history.push_back(e.label);
    d.undo_position = s.undo_position();
    d.resynthesis_ms = s.last_report().resynthesis_ms;
    d.vertices_updated = s.last_report().vertices_updated;
    d.selected = model.selection().size();
    d.soft_radius = model.soft_radius();
    d.pivot = static_cast<int>(model.pivot());
    d.view_level = model.view_level();
    for (int a = 0; a < 3; ++a) d.symmetry[a] = model.symmetry(a);
    d.sculpt = sculpt_;
    d.brush = model.brush();
    d.colour_level = model.colour_level();
    d.colour_channel = model.colour_channel();
    d.textured = !model.texture().empty() && !model.level_uv(0).empty();
    d.channel_group.clear();
    d.channel_keep = 1.0;
    if (d.colour_channel >= 0)
      for (const ChannelGroup& g : model.attribute_groups())
        if (d.colour_channel >= g.range.first && d.colour_channel < g.range.first + g.range.count) {
          d.channel_group = g.name;
          d.channel_keep = model.channel_keep(g.name);
        }
    d.channels.clear();
    for (const VertexAttribute& a : model.attribute_names()) d.channels.push_back(a.name);
    d.dirty = s.dirty();
    fill_basis_data(d.basis);
    fill_compression_data(d.compression);
  }
  fill_ffd_data(d.ffd);
  if (const AnimationViewState* a = model.has_session() ? model.animation() : nullptr) {
    AnimationPanelData& p = d.animation;
    p.on = true;
    p.frames = a->frames();
    p.base_steps = a->anim.st.base_steps;
    p.levels = a->anim.st.levels();
    p.cyclic = a->anim.st.cyclic;
    p.playing = a->playing;
    p.frame = a->frame;
    p.fps = a->fps();
    p.time = (a->anim.times.empty() ? 0.0 : a->anim.times.front()) + a->frame / p.fps;
    p.ghosts = a->ghosts;
    p.level = model.level();
    p.layer = a->layer;
    p.layer_frame = a->layer_frame(model.level(), a->layer);
  }
  d.error = error;
  d.message = message;
  d.frame_ms = frame_ms;
  d.recent = recent_;
  const ModelerPanelRequests req = draw_modeler_panel(d, display, fields, 0.0f, 0.0f, r.x, r.height);

  char right[96];
  std::snprintf(right, sizeof right, "resynthesis %.2f ms   frame %.2f ms", d.resynthesis_ms, frame_ms);
  std::string left = d.file_name + "   level " + std::to_string(d.level) + "/" + std::to_string(d.finest);
  if (model.has_session()) {
    if (const AnimationViewState* a = model.animation()) {  // one time: the layer's points, the frame's surface
      char frame[32];
      std::snprintf(frame, sizeof frame, "%.2f", a->frame);
      left += "   frame " + std::string(frame) + "/" + std::to_string(a->frames() - 1) + "   " +
              std::to_string(a->anim.st.surface_vertices(d.level)) + " control points   " +
              std::to_string(model.limit_positions().size() / 3) + " surface vertices   " + std::to_string(d.selected) + " selected";
    } else {
      left += "   " + std::to_string(model.session().num_vertices(d.level)) + " control points   " +
              std::to_string(model.limit_positions().size() / 3) + " limit vertices   " +
              std::to_string(d.selected) + " selected";
    }
    if (d.soft_radius > 0.0) {
      char soft[48];
      std::snprintf(soft, sizeof soft, "   soft %.3g", d.soft_radius);
      left += soft;
    }
    if (model.compression_on()) {
      char shown[48];
      std::snprintf(shown, sizeof shown, "   COMPRESSED %.3g%%", 100.0 * model.compression().fraction);
      left += shown;
    }
    if (circle_active_) left += "   CIRCLE SELECT (Shift: deselect, wheel: size, Esc: done)";
    if (sculpt_) {
      char b[160];
      std::snprintf(b, sizeof b, "   SCULPT %s  radius %.3g  strength %.2f%s", brush_name(model.brush().kind), model.brush().radius,
                    model.brush().strength, adjust_ ? (adjust_ == 1 ? "  (move: radius)" : "  (move: strength)") : "");
      left += b;
    }
    if (grab_.active) {
      static const char* kModes[] = {"GRAB", "ROTATE", "SCALE"};
      static const char* kAxes[] = {"X", "Y", "Z"};
      left += std::string("   ") + kModes[grab_.mode] + " " +
              (grab_.axis < 0 ? std::string(grab_.mode == 1 ? "view" : "free")
                              : std::string(grab_.exclude ? "not " : "") + kAxes[grab_.axis]);
      if (grab_.mode != 0) left += std::string(" about ") + pivot_name(model.pivot());
      if (!grab_.typed.empty()) left += " " + grab_.typed;
    }
  }
  draw_modeler_status(left, right, dw, dh, kStatusHeight);

  // Overlays: rubber band and soft-selection circle.
  ImDrawList* overlay = ImGui::GetForegroundDrawList();
  if (press_ == Press::Box && moved_) {
    overlay->AddRectFilled(ImVec2(static_cast<float>(press_x_), static_cast<float>(press_y_)),
                           ImVec2(static_cast<float>(mouse_x_), static_cast<float>(mouse_y_)), IM_COL32(255, 160, 40, 40));
    overlay->AddRect(ImVec2(static_cast<float>(press_x_), static_cast<float>(press_y_)),
                     ImVec2(static_cast<float>(mouse_x_), static_cast<float>(mouse_y_)), IM_COL32(255, 140, 0, 220));
  }
  if (model.has_session() && model.soft_radius() > 0.0 && in_viewport(mouse_x_, mouse_y_)) {
    const double px = model.soft_radius() / std::max(camera.world_per_pixel(), 1e-12) / std::max(scale_, 0.01f);
    overlay->AddCircle(ImVec2(static_cast<float>(mouse_x_), static_cast<float>(mouse_y_)), static_cast<float>(px),
                       IM_COL32(255, 200, 40, 200), 48, 1.5f);
  }
  if (sculpt_ && model.has_session() && in_viewport(mouse_x_, mouse_y_)) {
    const double px = model.brush().radius / std::max(camera.world_per_pixel(), 1e-12) / std::max(scale_, 0.01f);
    const ImVec2 at(static_cast<float>(adjust_ ? adjust_x_ : mouse_x_), static_cast<float>(mouse_y_));
    overlay->AddCircle(at, static_cast<float>(px), IM_COL32(255, 255, 255, 230), 64, 1.5f);
    overlay->AddCircle(at, static_cast<float>(px * model.brush().strength), IM_COL32(255, 255, 255, 90), 48, 1.0f);
  }
  if (circle_active_ && in_viewport(mouse_x_, mouse_y_))
    overlay->AddCircle(ImVec2(static_cast<float>(mouse_x_), static_cast<float>(mouse_y_)), static_cast<float>(circle_radius_px_),
                       IM_COL32(255, 255, 255, 220), 48, 1.5f);
  // The pivot of R/S: the 3-D cursor as Blender draws it (a red-white ring with a cross), a
  // small dot for the others while a rotate or scale runs.
  if (model.has_session() && (model.pivot() == Pivot::Cursor || (grab_.active && grab_.mode != 0))) {
    glm::dvec2 c;
    double depth = 0.0;
    if (project_point(pick_view(), model.transform_pivot(), c, depth)) {
      const ImVec2 at(static_cast<float>(view_x_ + c.x / scale_), static_cast<float>(view_y_ + c.y / scale_));
      if (model.pivot() == Pivot::Cursor) {
        overlay->AddCircle(at, 10.5f, IM_COL32(255, 255, 255, 230), 24, 1.5f);
        overlay->AddCircle(at, 8.0f, IM_COL32(230, 30, 30, 255), 24, 2.5f);
        overlay->AddLine(ImVec2(at.x - 14, at.y), ImVec2(at.x + 14, at.y), IM_COL32(20, 20, 20, 200));
        overlay->AddLine(ImVec2(at.x, at.y - 14), ImVec2(at.x, at.y + 14), IM_COL32(20, 20, 20, 200));
      } else {
        overlay->AddCircleFilled(at, 3.5f, IM_COL32(255, 255, 255, 220));
      }
      if (grab_.active && grab_.mode != 0)  // Blender's dashed line from the pivot to the mouse
        overlay->AddLine(at, ImVec2(static_cast<float>(mouse_x_), static_cast<float>(mouse_y_)), IM_COL32(20, 20, 20, 160), 1.0f);
    }
  }

  // Prompts.
  const PromptChoice choice =
      draw_unsaved_prompt(unsaved_prompt_, pending_.kind == Pending::Kind::Quit ? "quitting" : "opening another file");
  if (choice != PromptChoice::None) {
    unsaved_prompt_ = false;
    const Pending p = std::exchange(pending_, Pending{});
    if (choice == PromptChoice::Save) {
      if (save(default_save_path())) proceed(p);
    } else if (choice == PromptChoice::Discard) {
      proceed(p);
    }
  }
  if (job_) {
    if (draw_progress_prompt(true, job_->title.c_str(), job_->stage.load(), static_cast<float>(job_->permille.load()) / 1000.0f))
      cancel_job();
    poll_job();
  } else {
    draw_progress_prompt(false, "", "", 0.0f);
  }
  const PromptChoice recover = draw_recovery_prompt(recovery_prompt_, recovery_path());
  if (recover != PromptChoice::None) {
    recovery_prompt_ = false;
    const std::string path = recovery_path();
    if (recover == PromptChoice::Recover) {
      open(path, false);
      model.set_project_path({});  // Save must not write over the recovery file
      fields.save_path.clear();
      message = "Recovered the autosave; save it under a name of your own.";
    }
    std::error_code ec;
    std::filesystem::remove(path, ec);
  }
  ImGui::Render();

  apply_requests(req);
  clear_framebuffer(fb_width, fb_height, kWindowClear);
  if (!model.has_session()) return;

  const ViewportRect rect{static_cast<int>(std::lround(r.x * scale_)),
                          static_cast<int>(std::lround((dh - r.y - r.height) * scale_)),
                          static_cast<int>(std::lround(r.width * scale_)),
                          static_cast<int>(std::lround(r.height * scale_))};
  camera.set_viewport(rect.width, rect.height);
  camera.orthographic = display.orthographic;
  view.sync(model);
  const UpAxis up = display.z_up ? UpAxis::Z : UpAxis::Y;
  if (camera.up_axis != up) {
    camera.up_axis = up;
    framed = false;
  }
  if (!framed) {
    frame_bounds(camera, view.bounds());
    framed = true;
  }
  if (rect.width > 0 && rect.height > 0) view.draw(camera, rect, display);
}

}  // namespace sublift
