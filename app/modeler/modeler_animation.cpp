// ModelerState's animation mode (app/modeler/animation_view_state.h): opening, the time shown,
// playback, ghosts and export. The edits themselves are the session's, as for any lattice.
#include <algorithm>
#include <cmath>
#include <numeric>

#include "app/modeler/modeler_state.h"
#include "core/base/errors.h"
#include "core/base/file_io.h"
#include "core/complex/polygon_normal.h"
#include "core/io/model/animation_export.h"

namespace sublift {

void ModelerState::open_animation(std::span<const std::string> inputs, const AnimationOptions& options) {
  install_animation(sublift::open_animation(inputs, options), inputs[0], {}, 0, {});  // may throw: nothing changed yet
}

void ModelerState::install_animation(OpenedAnimation opened, const std::string& path, std::string project, int level,
                                     std::vector<double> gains) {
  auto next = std::make_unique<AnimationViewState>();
  next->anim = std::move(opened);
  auto session = std::make_unique<Session>(next->anim.st.lattice, std::move(gains));
  std::vector<std::string> warnings;
  for (const std::string& n : next->anim.notes) warnings.push_back(n);
  warnings.push_back("animation: " + std::to_string(next->frames()) + " frames, " + std::to_string(next->anim.st.base_steps) +
                     " base time steps, " + std::to_string(next->anim.st.levels()) + " levels" +
                     (next->anim.st.cyclic ? ", cyclic" : ""));
  compression_off();
  basis_off();
  ffd_.reset();
  anim_ = std::move(next);
  file_path_ = path;
  file_vertices_ = session->num_vertices(0);
  project_path_ = std::move(project);
  warnings_ = std::move(warnings);
  clear_pin();
  view_level_ = -1;
  level_ = std::clamp(level, 0, session->finest_level());
  selection_.clear();
  active_ = -1;
  install_new_model(std::move(session));  // rebuild_limit() draws the animation's frame 0
  rebuild_offer_ = {};
  update_.topology = true;
  update_.ghosts = true;
  refresh_state();
}

void ModelerState::rebuild_animation_view() {
  AnimationViewState& a = *anim_;
  const SpaceTime& st = a.anim.st;
  const int J = st.levels();
  refresh_animation_layer(a, level_);
  limit_ = frame_positions(st, session_->positions(J), a.frame);
  faces_ = st.surface_levels.levels[std::size_t(J)].faces;
  normals_ = area_weighted_normals(faces_, limit_);
  stencils_ = {};
  vertex_faces_ = transpose(faces_, limit_.size() / 3);
  stamp_.assign(limit_.size() / 3, 0);
  epoch_ = 0;
  refresh_ghosts(a, session_->positions(J), level_);
  update_.ghosts = true;
}

void ModelerState::set_frame(double frame) {
  if (!anim_) throw Error("no animation is open (open one with 'animation open')");
  if (!std::isfinite(frame)) throw Error("the frame must be a number");
  const int n = anim_->frames();
  if (anim_->anim.st.cyclic) {
    frame = std::fmod(frame, double(n));
    if (frame < 0) frame += n;
  } else {
    frame = std::clamp(frame, 0.0, double(n - 1));
  }
  if (frame == anim_->frame) return;
  if (dragging_) end_drag();
  const int old_layer = anim_->layer;
  anim_->frame = frame;
  rebuild_animation_view();
  if (anim_->layer != old_layer) {  // another layer: the selection belonged to the old one
    selection_.clear();
    active_ = -1;
    hover_ = -1;
  }
  update_.topology = true;
  refresh_state();
}

void ModelerState::set_ghosts(int count) {
  if (!anim_) throw Error("no animation is open");
  if (count < 0 || count > 8) throw Error("ghost frames go from 0 to 8 either side, not " + std::to_string(count));
  anim_->ghosts = count;
  refresh_ghosts(*anim_, session_->positions(session_->finest_level()), level_);
  update_.ghosts = true;
}

void ModelerState::set_playing(bool on) {
  if (!anim_) throw Error("no animation is open");
  anim_->playing = on;
  if (on && !anim_->anim.st.cyclic && anim_->frame >= anim_->frames() - 1) set_frame(0);  // play again from the start
}

void ModelerState::advance(double seconds) {
  if (!anim_ || !anim_->playing || !(seconds > 0)) return;
  const double next = anim_->frame + seconds * anim_->fps();
  if (!anim_->anim.st.cyclic && next >= anim_->frames() - 1) {
    set_frame(anim_->frames() - 1);
    anim_->playing = false;
    return;
  }
  set_frame(next);
}

std::vector<std::string> ModelerState::export_animation(const std::string& path) const {
  if (!anim_) throw Error("no animation is open");
  const SpaceTime& st = anim_->anim.st;
  const int J = st.levels(), n = anim_->frames();
  const std::span<const double> finest = session_->positions(J);
  std::vector<double> frames;
  for (int l = 0; l < n; ++l) {
    const std::vector<double> x = layer_positions(st, finest, J, l);
    frames.insert(frames.end(), x.begin(), x.end());
  }
  const Csr& faces = st.surface_levels.levels[std::size_t(J)].faces;
  const std::string ext = file_extension(path);
  if (ext == "gltf" || ext == "glb") {
    write_animation_gltf(path, faces, frames, anim_->anim.times, st.cyclic, anim_->anim.loop_end);
    return {path};
  }
  if (ext != "obj" && ext != "ply") throw Error(path + ": an animation is exported to .gltf, .glb (morph targets) or .obj, .ply (one file per frame)");
  return write_frame_sequence(path, faces, frames, std::size_t(n));
}

std::span<const std::uint8_t> ModelerState::net_pick_mask() const {
  if (!anim_) return {};
  return anim_->on_layer;
}

SoftWeights ModelerState::selection_weights() const {
  SoftWeights w = soft_selection(session_->positions(level_), selection_, soft_radius_);
  if (!anim_) return w;
  // Points of the level's other layers are other times, however close in space.
  std::size_t k = 0;
  for (std::size_t i = 0; i < w.vertices.size(); ++i)
    if (anim_->on_layer[w.vertices[i]]) w.vertices[k] = w.vertices[i], w.weights[k] = w.weights[i], ++k;
  w.vertices.resize(k);
  w.weights.resize(k);
  return w;
}

void ModelerState::check_not_animation(const char* what) const {
  if (anim_)
    throw Error(std::string(what) + " is not available on an animation (its levels are space-time levels): "
                "move, rotate and scale control points at a frame, or open the frame as a surface");
}

}  // namespace sublift
