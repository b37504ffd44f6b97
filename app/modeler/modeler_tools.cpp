// ModelerState's tools (issue 19): rotate and scale, mirror editing, sculpt brushes, the
// selection tools, base features, level deletion and the undo across session replacements.
// The math is in core/edit (transform, symmetry, brush, selection, features, level_ops); this
// file applies it to the session, the selection and the view (app/modeler/modeler_state.h).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include "app/modeler/modeler_state.h"
#include "core/base/errors.h"
#include "core/complex/feature_tags.h"
#include "core/edit/features.h"
#include "core/edit/level_ops.h"
#include "core/edit/selection.h"

namespace sublift {

std::string ModelerState::delete_higher_levels() {
  check_not_animation("deleting levels");
  ffd_check_free("deleting levels");
  check_unlocked("deleting levels");
  if (dragging_) end_drag();
  const int J = session_->finest_level();
  if (level_ == J) throw Error("there are no levels above level " + std::to_string(level_));
  std::vector<double> gains(session_->gains().begin(), session_->gains().begin() + level_);
  auto session = std::make_unique<Session>(delete_higher(session_->hierarchy(), level_), std::move(gains));
  if (session_->detail_frames() == DetailFrames::Local) session->set_detail_frames(DetailFrames::Local);
  session->mark_unsaved();
  const int level = level_;
  replace_session(std::move(session));  // level 0 is unchanged: the fit's base map still holds
  std::string note = "deleted levels " + std::to_string(level + 1) + ".." + std::to_string(J) + "; level " +
                     std::to_string(level) + " is the finest (Ctrl+Z undoes)";
  if (input_order_.level > level && !input_order_.empty()) {
    input_order_ = {};
    note += "; the vertex order of the file this mesh was rebuilt from belonged to a deleted level and is not kept";
  }
  update_.topology = true;
  refresh_state();
  return note;
}

std::string ModelerState::delete_lower_levels() {
  check_not_animation("deleting levels");
  ffd_check_free("deleting levels");
  check_unlocked("deleting levels");
  if (dragging_) end_drag();
  if (level_ == 0) throw Error("level 0 is already the base: there are no levels below it");
  const int L = level_;
  const std::span<const double> net = session_->positions(L);
  std::vector<double> gains(session_->gains().begin() + L, session_->gains().end());
  auto session = std::make_unique<Session>(delete_lower(session_->hierarchy(), L, net), std::move(gains));
  if (session_->detail_frames() == DetailFrames::Local) session->set_detail_frames(DetailFrames::Local);
  session->mark_unsaved();
  FaceVaryingUV uv = level_uv(L);  // level L's UVs are the new base's
  std::optional<Hierarchy> attributes = fitted_attributes();  // and level L's attribute net theirs
  if (attributes) {
    Hierarchy shown = *attributes;
    apply_gains(shown, session_->gains());
    attributes = delete_lower(*attributes, L, synthesize(shown, L));
  }
  replace_session(std::move(session));  // the selection: old level L's vertices are the new level 0's
  remember_uv(session_->hierarchy().levels.front(), std::move(uv));
  if (attributes) attribute_sets_.push_back(std::move(*attributes));
  level_ = 0;
  clamp_selection();
  std::string note = "level " + std::to_string(L) + " is the new base; levels 0.." + std::to_string(L - 1) +
                     " are deleted (Ctrl+Z undoes)";
  if (!input_order_.empty()) {
    if (input_order_.level >= L) {
      input_order_.level -= L;
    } else {
      input_order_ = {};
      note += "; the vertex order of the file this mesh was rebuilt from belonged to a deleted level and is not kept";
    }
  }
  if (!fit_source_.empty()) {
    fit_source_ = {};
    note += "; the fit's map from the old base to the mesh it was fitted to is not kept";
  }
  update_.topology = true;
  refresh_state();
  return note;
}

const char* ModelerState::apply_base_note() { return kApplyBaseNote; }

std::vector<std::string> ModelerState::export_levels(const std::string& path) {
  const std::filesystem::path p(path);
  std::vector<std::string> written;
  for (int l = 0; l <= session_->finest_level(); ++l) {
    const std::string file = (p.parent_path() / (p.stem().string() + "_L" + std::to_string(l) + p.extension().string())).string();
    for (const std::string& note : export_level(file, l)) warnings_.push_back(file + ": " + note);
    written.push_back(file);
  }
  return written;
}

ModelerState::Snapshot ModelerState::take_snapshot() {
  Snapshot s;
  s.session = std::move(session_);
  s.input_order = input_order_;
  s.fit_source = fit_source_;
  s.level = level_;
  s.selection = selection_;
  return s;
}

void ModelerState::restore(Snapshot s) {
  install(std::move(s.session));
  input_order_ = std::move(s.input_order);
  fit_source_ = std::move(s.fit_source);
  level_ = std::clamp(s.level, 0, session_->finest_level());
  selection_ = std::move(s.selection);
  clamp_selection();
  active_ = -1;
  update_.topology = true;
  refresh_state();
}

void ModelerState::replace_session(std::unique_ptr<Session> next) {
  const InputOrder order = input_order_;
  const FitSource fit = fit_source_;
  const int level = level_;
  std::vector<unsigned> selection = selection_;
  structure_undo_.push_back(take_snapshot());
  if (structure_undo_.size() > kStructureUndo) {  // said, not dropped silently
    structure_undo_.erase(structure_undo_.begin());
    warnings_.push_back("undo keeps the last " + std::to_string(kStructureUndo) +
                        " hierarchy changes (scheme, levels, features): the oldest one can no longer be undone");
  }
  structure_redo_.clear();
  install(std::move(next));
  input_order_ = order;  // callers change what no longer holds
  fit_source_ = fit;
  level_ = std::clamp(level, 0, session_->finest_level());
  selection_ = std::move(selection);
  clamp_selection();
}

std::string ModelerState::toggle_creases(std::optional<bool> on) {
  check_not_animation("marking creases");
  ffd_check_free("marking creases");
  check_unlocked("marking creases");
  if (level_ != 0) throw Error("creases are a property of the base: mark them on level 0 (Shift+D goes coarser)");
  const Complex& c = level_complex();
  if (c.dim != 2) throw Error("creases are marked on surfaces (a lattice's features come from its file's tags)");
  const std::vector<std::uint32_t> edges = edges_within(c, selection_);
  if (edges.empty()) throw Error("select two or more joined points of level 0 to crease the edges between them");
  bool all = true;
  for (const std::uint32_t e : edges) all = all && c.edge_dim[e] <= 1;
  if (on) all = !*on;
  install_features(with_creases(c, derive_feature_tags(c), edges, !all));
  return std::string(all ? "cleared " : "creased ") + std::to_string(edges.size()) + " edge" + (edges.size() == 1 ? "" : "s") +
         " of the base; the shape and its detail are kept (Ctrl+Z undoes)";
}

void ModelerState::install_features(const FeatureTags& tags) {
  auto next = std::make_unique<Session>(with_base_features(*session_, tags));  // core/edit/features.h
  if (session_->detail_frames() == DetailFrames::Local) next->set_detail_frames(DetailFrames::Local);
  next->mark_unsaved();
  replace_session(std::move(next));
  update_.topology = true;
  refresh_state();
}

std::string ModelerState::toggle_corners(std::optional<bool> on) {
  check_not_animation("marking corners");
  ffd_check_free("marking corners");
  check_unlocked("marking corners");
  if (level_ != 0) throw Error("corners are a property of the base: mark them on level 0 (Shift+D goes coarser)");
  if (selection_.empty()) throw Error("select the points of level 0 to make corners");
  const Complex& c = level_complex();
  bool all = true;
  for (const unsigned v : selection_) all = all && c.vertex_dim[v] == 0;
  if (on) all = !*on;
  install_features(with_corners(derive_feature_tags(c), selection_, !all));
  return std::string(all ? "cleared " : "made ") + std::to_string(selection_.size()) + " corner" +
         (selection_.size() == 1 ? "" : "s") + " of the base; the shape and its detail are kept (Ctrl+Z undoes)";
}

void ModelerState::begin_transform(TransformMode mode) {
  if (mode == TransformMode::Grab) return begin_drag("Grab");
  const glm::dvec3 pivot = transform_pivot();  // before the drag starts: it then returns the fixed one
  begin_drag(mode == TransformMode::Rotate ? "Rotate" : "Scale");
  transform_mode_ = mode;
  transform_pivot_ = pivot;
  const std::span<const double> p = session_->positions(level_);
  transform_start_.resize(3 * drag_weights_.vertices.size());
  for (std::size_t k = 0; k < drag_weights_.vertices.size(); ++k)
    for (int c = 0; c < 3; ++c) transform_start_[3 * k + c] = p[3 * std::size_t(drag_weights_.vertices[k]) + c];
}

void ModelerState::transform_to(const glm::dvec3& axis, double angle, const glm::dvec3& factors) {
  if (!dragging_ || transform_mode_ == TransformMode::Grab) return;
  if (!std::isfinite(angle) || !std::isfinite(factors.x) || !std::isfinite(factors.y) || !std::isfinite(factors.z))
    throw Error("the transform is not finite");
  transform_deltas(transform_start_, session_->positions(level_), drag_weights_.vertices, drag_weights_.weights,
                   transform_pivot_, axis, angle, factors, transform_deltas_);
  move_mirrored(drag_weights_.vertices, transform_deltas_);
  after_operation();
}

void ModelerState::move_mirrored(std::vector<std::uint32_t> vertices, std::vector<double> deltas) {
  std::vector<const MirrorMap*> maps;
  for (int a = 0; a < 3; ++a)
    if (symmetry_[static_cast<std::size_t>(a)]) maps.push_back(&mirror_map(a));
  if (!maps.empty()) mirror_deltas(maps, vertices, deltas);
  session_->move_each(level_, vertices, deltas);
}

void ModelerState::set_brush(const BrushSettings& b) {
  if (!(b.radius > 0.0) || !std::isfinite(b.radius)) throw Error("the brush radius must be a positive distance");
  if (!(b.strength >= 0.0 && b.strength <= 1.0)) throw Error("the brush strength must be in 0..1");
  brush_ = b;
}

void ModelerState::begin_stroke() {
  check_not_animation("sculpting");
  begin_drag(std::string("Brush ") + brush_name(brush_.kind));
  if (brush_needs_normals(brush_.kind) && dim() != 2) {
    cancel_drag();
    throw Error(std::string("the ") + brush_name(brush_.kind) + " brush moves along the surface normal and needs a surface");
  }
}

const Complex& ModelerState::brush_complex() {
  if (level_ < session_->finest_level()) return level_complex();
  BrushComplex& b = brush_complex_;
  if (!b.valid || b.serial != serial_ || b.topology != session_->topology_version()) {
    b.complex = level_complex();
    build_adjacency(b.complex);
    b.serial = serial_;
    b.topology = session_->topology_version();
    b.valid = true;
  }
  return b.complex;
}

std::size_t ModelerState::dab(const Dab& d) {
  if (!dragging_) return 0;
  brush_dab(brush_, d, brush_complex(), session_->positions(level_), dab_vertices_, dab_deltas_);
  if (dab_vertices_.empty()) return 0;
  const std::size_t n = dab_vertices_.size();
  move_mirrored(dab_vertices_, dab_deltas_);
  after_operation();
  return n;
}

bool ModelerState::surface_hit(const glm::dvec3& origin, const glm::dvec3& dir, glm::dvec3& hit) const {
  return ray_hit(limit_positions(), faces_, origin, dir, hit);
}

std::string ModelerState::set_symmetry(int axis, bool on) {
  if (axis < 0 || axis > 2) throw Error("the mirror axis must be x, y or z");
  if (on) check_not_animation("mirror editing");
  symmetry_[static_cast<std::size_t>(axis)] = on;
  return on && session_ ? mirror_map(axis).problem() : std::string();
}

const MirrorMap& ModelerState::mirror_map(int axis) {
  MirrorCache& c = mirror_cache_[static_cast<std::size_t>(axis)];
  if (c.level != level_ || c.serial != serial_ || c.topology != session_->topology_version()) {
    c.map = find_mirror(level_complex(), session_->positions(level_), axis);
    c.level = level_;
    c.serial = serial_;
    c.topology = session_->topology_version();
  }
  return c.map;
}

void ModelerState::set_active(long long vertex) {
  if (vertex >= 0 && std::binary_search(selection_.begin(), selection_.end(), static_cast<unsigned>(vertex))) active_ = vertex;
}

glm::dvec3 ModelerState::transform_pivot() const {
  if (dragging_ && transform_mode_ != TransformMode::Grab) return transform_pivot_;
  if (!session_) return glm::dvec3(0.0);
  return pivot_point(pivot_, session_->positions(level_), selection_, active_, cursor_);
}

void ModelerState::select_op(SelectOp op) {
  const Complex& c = level_complex();
  switch (op) {
    case SelectOp::Linked: selection_ = select_linked(c, selection_); break;
    case SelectOp::More: selection_ = grow_selection(c, selection_); break;
    case SelectOp::Less: selection_ = shrink_selection(c, selection_); break;
    case SelectOp::Invert: selection_ = invert_selection(c.num_vertices, selection_); break;
  }
  if (active_ >= 0 && !std::binary_search(selection_.begin(), selection_.end(), static_cast<unsigned>(active_))) active_ = -1;
  refresh_state();
}

void ModelerState::select_loop(std::uint32_t edge, bool ring, bool extend) {
  const Complex& c = level_complex();
  if (edge >= c.num_edges())
    throw Error("edge " + std::to_string(edge) + " is not on level " + std::to_string(level_) + " (it has " +
                std::to_string(c.num_edges()) + ")");
  if (ring && c.dim != 2) throw Error("edge rings are for surfaces; use a loop on curves and lattices");
  std::vector<unsigned> picked = edge_vertices(c, ring ? edge_ring(c, edge) : edge_loop(c, edge));
  if (extend) picked.insert(picked.end(), selection_.begin(), selection_.end());
  set_selection(std::move(picked));
}

}  // namespace sublift
