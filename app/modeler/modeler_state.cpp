#include "app/modeler/modeler_state.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numeric>
#include <sstream>

#include "core/analysis/wavelet_colour.h"
#include "core/base/file_io.h"
#include "core/complex/feature_tags.h"
#include "core/edit/level_ops.h"
#include "core/analysis/boundary_surface.h"
#include "core/analysis/limit_surface.h"
#include "core/analysis/mesh_stats.h"
#include "core/base/bounds.h"
#include "core/base/errors.h"
#include "core/ffd/ffd_scene.h"
#include "core/io/project/project_io.h"
#include "core/complex/face_varying.h"
#include "core/multires/level_uv.h"
#include "core/base/channels.h"
#include "core/edit/attribute_channels.h"
#include "core/io/lattice/shape_io.h"
#include "core/complex/polygon_normal.h"
#include "core/io/model/surface_export.h"
#include "core/complex/complex_build.h"
#include "core/edit/scheme_switch.h"
#include "core/multires/rebuild.h"
#include "core/fit/fit_levels.h"

namespace sublift {
namespace {

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

// The model's size for soft radii; 1 for an empty or degenerate shape.
double model_size_of(const std::vector<double>& xyz) {
  const double d = bbox_diagonal(xyz);
  return d > 0.0 ? d : 1.0;
}

}  // namespace

bool is_project_file(const std::string& path) { return lower_extension(path) == ".sublift"; }

void ModelerState::open(const std::string& path, int levels, Scheme scheme) {
  // Everything is built aside first: a failure leaves the current session as it was.
  std::unique_ptr<Session> session;
  std::vector<std::string> warnings;
  int level = 0;
  bool project = false;
  RebuildOffer offer;
  InputOrder order;
  FitSource source;
  FaceVaryingUV base_uv, file_uv;  // the opened base's UVs; a mesh file's own, for rebuild
  std::optional<Hierarchy> attributes;  // channels 3.. (colours, scalars), beside the session
  std::vector<VertexAttribute> attribute_names;
  SurfaceTexture texture;
  if (is_project_file(path)) {
    ProjectExtras extras;
    Hierarchy h = read_project(path, &extras);
    if (!extras.animation.empty())  // an animation's project opens in the animation mode
      return install_animation(reopen_animation(path, h, extras.animation), path, path, extras.current_level, extras.gains);
    ImportReport topology;  // of the base the session subdivides and edits
    add_topology_warnings(topology, h.levels.front());
    std::istringstream in(topology.format(std::filesystem::path(path).filename().string()));
    for (std::string line; std::getline(in, line);)
      if (!line.empty()) warnings.push_back(line);
    order = std::move(extras.input_order);
    source = std::move(extras.fit_source);
    base_uv = std::move(extras.uv);
    if (h.channels > 3) {  // the session moves x, y, z; the attributes stay
      attributes = channel_range(h, 3, h.channels - 3);
      attribute_names = extras.attributes;
      if (attribute_names.size() != std::size_t(h.channels - 3)) {
        attribute_names.clear();
        for (int k = 3; k < h.channels; ++k) attribute_names.push_back({"channel " + std::to_string(k), "float", {}});
      }
      h = channel_range(h, 0, 3);
    }
    session = std::make_unique<Session>(std::move(h), extras.gains);
    if (extras.local_frames) session->set_detail_frames(DetailFrames::Local);
    level = extras.current_level;
    project = true;
  } else {
    Shape shape = read_shape(path);
    if (!shape.texture.empty())  // exports carry it; a project keeps the UVs only
      warnings.push_back("the texture image '" + shape.texture.name + "' is not kept in a saved project (exported levels carry it)");
    if (!shape.uv.empty() && !uv_refinement_problem(scheme).empty())
      warnings.push_back("texture coordinates: " + uv_refinement_problem(scheme));
    base_uv = shape.uv;
    file_uv = std::move(shape.uv);
    texture = std::move(shape.texture);
    add_topology_warnings(shape.report, shape.base);  // non-manifold or misoriented: said before it surprises
    if (!shape.report.empty()) {
      std::istringstream in(shape.report.format(std::filesystem::path(path).filename().string()));
      for (std::string line; std::getline(in, line);) {
        if (!line.empty()) warnings.push_back(line);
      }
    }
    // Data of the file the modeler does not keep, so saving or exporting loses it.
    if (const std::string s = shape.report.not_kept_summary(); !s.empty()) warnings.push_back("not kept (saving or exporting drops it): " + s);
    // Subdivided elsewhere? Then offer to rebuild its levels (docs/rebuild.md).
    if (shape.base.dim >= 2) {
      offer.scheme = shape.base.dim == 3 ? Scheme::Cubic : rebuild_auto_scheme(shape.base.faces);
      offer.checked = true;
      try {
        const DetectedLevels d =
            shape.base.dim == 3 ? detect_volume_levels(shape.base, max_levels(offer.scheme), shape.positions)
                                : detect_levels(shape.base.num_vertices, shape.base.faces, rebuild_split(offer.scheme),
                                                max_levels(offer.scheme), shape.positions);
        offer.levels = d.levels;
        offer.stop = d.stop;
        offer.stop_vertex = d.stop_vertex;
      } catch (const Error& e) {  // detection refuses what it cannot take (loose vertices): the mesh still opens
        offer.stop = e.what();
      }
    }
    // A dense mesh is its own finest level already: refine it only while the finest level stays
    // within kMaxOpenVertices (a million-vertex scan opens without the 16 M-vertex levels).
    while (levels > 0 && predicted_level_counts(shape.base, levels, scheme).back() > kMaxOpenVertices) --levels;
    if (!shape.attributes.empty()) {  // colours and scalars: their own channels over the same levels
      attributes = make_hierarchy(shape.base, levels, scheme, int(shape.attributes.size()));
      set_base(*attributes, with_attributes({}, shape.attributes));
      attribute_names = sublift::attribute_names(shape.attributes);
    }
    Hierarchy h = make_hierarchy(std::move(shape.base), levels, scheme, 3);
    set_base(h, shape.positions);
    session = std::make_unique<Session>(std::move(h));
  }
  file_path_ = path;
  file_vertices_ = session->num_vertices(0);
  project_path_ = project ? path : std::string();
  warnings_ = std::move(warnings);
  clear_pin();  // a new model: the comparison belonged to the old one
  view_level_ = -1;
  anim_.reset();  // a file of its own: the animation mode ends
  install_new_model(std::move(session));
  rebuild_offer_ = std::move(offer);
  input_order_ = std::move(order);
  fit_source_ = std::move(source);
  uv_bases_.clear();
  remember_uv(session_->hierarchy().levels.front(), std::move(base_uv));
  attribute_sets_.clear();
  if (attributes) attribute_sets_.push_back(std::move(*attributes));
  colour_channel_ = -1;
  channel_keep_.clear();
  attribute_names_ = std::move(attribute_names);
  file_uv_ = std::move(file_uv);
  texture_ = std::move(texture);
  level_ = std::clamp(level, 0, session_->finest_level());
  selection_.clear();
  active_ = -1;
  update_.topology = true;
  refresh_state();
}

bool ModelerState::show_rebuild_stop() {
  if (rebuild_offer_.stop_vertex == UINT32_MAX || rebuild_offer_.stop_vertex >= session_->num_vertices(0)) return false;
  set_level(0);
  set_selection({rebuild_offer_.stop_vertex});
  return true;
}

void ModelerState::check_rebuild() {
  if (!project_path_.empty() || file_path_.empty()) throw Error("rebuild takes a mesh file, not a project");
  ffd_check_free("rebuilding levels");
  check_unlocked("rebuilding levels");
}

ModelerState::PreparedRebuild ModelerState::prepare_rebuild(const std::string& file, const RebuildOffer& offer, int levels,
                                                            const RebuildProgress& progress) {
  Shape shape = read_shape(file);
  if (shape.base.dim == 1) throw Error("rebuild takes surface meshes and volume lattices, not curves");
  if (shape.base.dim == 3)  // lattices keep their vertex order only (no face rows)
    return {rebuild_volume_hierarchy(shape.base, shape.positions, offer.levels > 0 ? offer.scheme : Scheme::Cubic, levels, false, progress), Csr{}, {}};
  const Scheme scheme = offer.levels > 0 ? offer.scheme : rebuild_auto_scheme(shape.base.faces);
  // The file's colours and scalars are rebuilt with it, as channels after x, y, z.
  std::vector<VertexAttribute> names = sublift::attribute_names(shape.attributes);
  return {rebuild_hierarchy(shape.base.num_vertices, shape.base.faces, shape.positions, scheme, levels, false, 2,
                            derive_feature_tags(shape.base), progress, shape.attributes),
          std::move(shape.base.faces), std::move(names)};
}

void ModelerState::check_fit() {
  if (!can_fit()) throw Error("fitting takes a surface mesh file (OBJ, OFF, PLY), not a project, curve or lattice");
  ffd_check_free("fitting a base mesh");
  check_unlocked("fitting a base mesh");
}

namespace {

BaseMeshOptions base_options(const ModelerState::FitSettings& s) {
  BaseMeshOptions bo;
  bo.target_vertices = s.base_vertices;
  bo.feature_angle_deg = s.feature_angle_deg;
  bo.quads = fit_base_quads(s.scheme);
  return bo;
}

}  // namespace

ModelerState::FitPreview ModelerState::prepare_fit_preview(const std::string& file, const FitSettings& settings, const FitProgress& progress) {
  if (progress && !progress("reading the mesh", 0.0)) throw Cancelled("previewing cancelled");
  const Shape shape = read_shape(file);
  if (shape.base.dim != 2) throw Error("fitting takes surface meshes");
  BaseMeshOptions bo = base_options(settings);
  if (progress) bo.progress = [&](double f) { return progress("the base mesh", f); };
  const BaseMesh b = decimate_to_base(shape.base.num_vertices, shape.base.faces, shape.positions, bo);
  FitPreview p;
  p.positions = b.positions;
  p.vertices = b.num_vertices;
  p.faces = static_cast<std::uint32_t>(b.faces.rows());
  p.creases = b.tags.crease_edges.size();
  p.corners = b.tags.corner_vertices.size();
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;  // each edge once
  for (std::size_t f = 0; f < b.faces.rows(); ++f) {
    const auto r = b.faces.row(f);
    for (std::size_t k = 0; k < r.size(); ++k) edges.emplace_back(std::minmax(r[k], r[(k + 1) % r.size()]));
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  for (const auto& [a, c] : edges) p.edges.insert(p.edges.end(), {a, c});
  return p;
}

std::string ModelerState::install_fit_preview(FitPreview p) {
  std::string m = "The base a fit would start from: " + std::to_string(p.vertices) + " vertices, " + std::to_string(p.faces) + " faces, " +
                  std::to_string(p.creases) + " crease edges, " + std::to_string(p.corners) + " corners (drawn over the mesh)";
  fit_preview_ = std::move(p);
  update_.fit_preview = true;
  return m;
}

std::string ModelerState::preview_fit(const FitSettings& settings) {
  scripted_fit_ = settings;
  ++scripted_fit_count_;
  check_fit();
  return install_fit_preview(prepare_fit_preview(file_path_, settings, {}));
}

void ModelerState::clear_fit_preview() {
  if (!fit_preview_) return;
  fit_preview_.reset();
  update_.fit_preview = true;
}

ModelerState::PreparedFit ModelerState::prepare_fit(const std::string& file, const FitSettings& settings, const FitProgress& progress) {
  if (progress && !progress("reading the mesh", 0.0)) throw Cancelled("fitting cancelled");
  const Shape shape = read_shape(file);
  if (shape.base.dim != 2) throw Error("fitting takes surface meshes");
  if (progress && !progress("the base mesh", 0.0)) throw Cancelled("fitting cancelled");
  BaseMeshOptions bo = base_options(settings);
  if (progress) bo.progress = [&](double f) { return progress("the base mesh", f); };  // Cancel stops the decimation too
  FitOptions fo;
  fo.scheme = settings.scheme;
  fo.levels = settings.levels > 0 ? settings.levels : -1;  // -1: the default for the base made
  fo.progress = progress;
  MeshFit m = fit_mesh(shape.base.num_vertices, shape.base.faces, shape.positions, bo, fo);
  const std::uint32_t base_vertices = m.base.num_vertices;
  return {std::move(m.fitted), base_vertices, derive_feature_tags(shape.base),
          FitSource{std::filesystem::absolute(file).lexically_normal().string(), shape.base.num_vertices, std::move(m.base.input_vertex)}};
}

std::string ModelerState::install_fit(PreparedFit p) {
  const Fitted& f = p.fitted;
  std::ostringstream m;
  m.precision(3);
  const bool limit = !scheme_interpolates(f.hierarchy.scheme);
  const double to = limit ? f.limit_max : f.levels.empty() ? 0.0 : f.levels.back().max;
  const double back = limit ? f.limit_back_max : f.levels.empty() ? 0.0 : f.levels.back().back_max;
  m << "Fitted a base of " << p.base_vertices << " vertices and " << f.levels.size() << " level" << (f.levels.size() == 1 ? "" : "s")
    << " (" << scheme_name(f.hierarchy.scheme) << "): the " << (limit ? "limit surface" : "net") << " lies within " << 100 * to
    << " % of the mesh and the mesh within " << 100 * back << " % of it (of the diagonal); the detail is kept as wavelets (history cleared)";
  if (const std::size_t tags = p.file_tags.crease_edges.size() + p.file_tags.corner_vertices.size(); tags > 0)
    warnings_.push_back("not kept by the fit: the file's " + std::to_string(p.file_tags.crease_edges.size()) + " crease and " +
                        std::to_string(p.file_tags.corner_vertices.size()) +
                        " corner tags (the fitted creases come from the feature angle)");
  if (const std::uint32_t folded = limit ? f.limit_folded : f.levels.empty() ? 0 : f.levels.back().folded; folded > 0)
    warnings_.push_back(std::to_string(folded) + " folded faces in the fitted surface (docs/fit.md)");
  if (!file_uv_.empty())
    warnings_.push_back("texture coordinates not kept by the fit: the fitted base is a new mesh, its corners are not the file's");
  if (!attribute_sets_.empty()) {
    warnings_.push_back("vertex attributes " + attribute_list() + " not kept by the fit: the fitted base is a new mesh");
    attribute_sets_.clear();
  }
  install_new_model(std::make_unique<Session>(std::move(p.fitted.hierarchy)));
  fit_source_ = std::move(p.source);
  rebuild_offer_ = {};
  clear_fit_preview();
  level_ = 0;
  selection_.clear();
  active_ = -1;
  update_.topology = true;
  refresh_state();
  return m.str();
}

void ModelerState::fit_base(const FitSettings& s) {
  scripted_fit_ = s;
  ++scripted_fit_count_;
  check_fit();
  install_fit(prepare_fit(file_path_, s, {}));
}

void ModelerState::rebuild_levels(int levels) {
  check_rebuild();
  install_rebuild(prepare_rebuild(file_path_, rebuild_offer_, levels, {}));
}

void ModelerState::install_rebuild(PreparedRebuild p) {
  Rebuilt& r = p.rebuilt;
  for (const std::string& why : r.features.dropped) warnings_.push_back("feature tag dropped: " + why);
  InputOrder order;
  order.level = r.hierarchy.finest_level();
  order.engine_vertex = std::move(r.engine_vertex);
  order.faces = std::move(p.faces);
  std::string why;
  FaceVaryingUV uv = coarsen_file_uv(r.hierarchy, order.faces, file_uv_, order.engine_vertex, &why);
  if (!file_uv_.empty() && uv.empty()) warnings_.push_back("texture coordinates not kept by the rebuild: " + why);
  std::optional<Hierarchy> attributes;
  if (r.hierarchy.channels > 3) {  // the file's attributes, beside the session
    attributes = channel_range(r.hierarchy, 3, r.hierarchy.channels - 3);
    r.hierarchy = channel_range(r.hierarchy, 0, 3);
  }
  install_new_model(std::make_unique<Session>(std::move(r.hierarchy)));
  remember_uv(session_->hierarchy().levels.front(), std::move(uv));
  if (attributes && p.attribute_names.size() == std::size_t(attributes->channels)) {
    attribute_sets_.push_back(std::move(*attributes));
    attribute_names_ = std::move(p.attribute_names);
  }
  rebuild_offer_ = {};
  input_order_ = std::move(order);
  level_ = 0;
  selection_.clear();
  active_ = -1;
  update_.topology = true;
  refresh_state();
}

void ModelerState::install(std::unique_ptr<Session> session) {
  compress_.reset();  // ranked the old session's wavelets
  input_order_ = {};  // described the old session's levels; callers that keep it set it again
  fit_source_ = {};   // so did the fit's base map
  session_ = std::move(session);
  ++serial_;
  dragging_ = false;
  hover_ = -1;
  seen_topology_ = session_->topology_version();
  basis_off();
  if (ffd_) ffd_->bound = false;  // bound to the old session's lattice
  rebuild_limit();
  model_size_ = model_size_of(limit_);
  if (colour_level_ >= session_->finest_level()) colour_level_ = -1;
  refresh_colour();
}

void ModelerState::install_new_model(std::unique_ptr<Session> session) {
  structure_undo_.clear();  // undo does not go back to another model
  structure_redo_.clear();
  install(std::move(session));
  brush_.radius = 0.08 * model_size_;  // a brush that suits the model (Blender's is in pixels)
}

int ModelerState::shown_level() const {
  const int J = session_->finest_level();
  return view_level_ < 0 ? J : std::min(view_level_, J);
}

void ModelerState::set_view_level(int level) {
  if (level != -1) check_not_animation("a coarser viewport level");
  if (level < -1 || level > session_->finest_level())
    throw Error("viewport level " + std::to_string(level) + " is outside 0.." + std::to_string(session_->finest_level()) +
                " (or -1: the finest)");
  if (compress_) throw Error("the compression view shows the finest level: turn it off to change the viewport level");
  if (basis_) throw Error("the basis mode shows the finest level: turn it off to change the viewport level");
  if (level == view_level_) return;
  view_level_ = level;
  rebuild_limit();
  refresh_colour();
  update_.topology = true;
  refresh_state();
}

void ModelerState::rebuild_limit() {
  if (anim_) return rebuild_animation_view();
  const Hierarchy& full = session_->hierarchy();
  const int V = shown_level();
  // A coarser viewport level: the limit of the hierarchy cut at V (its stencils are V's).
  std::optional<Hierarchy> cut;
  if (V < full.finest_level()) cut = delete_higher(full, V);
  const Hierarchy& h = cut ? *cut : full;
  const int J = V;
  LimitSurface surface = finest_limit_surface(h, session_->positions(J));  // core/analysis/limit_surface.h
  const std::size_t n = h.num_vertices(J);
  stencils_ = std::move(surface.stencils);
  limit_ = std::move(surface.positions);
  normals_ = std::move(surface.normals);
  faces_ = std::move(surface.faces);
  vertex_faces_ = transpose(faces_, n);
  stamp_.assign(n, 0);
  epoch_ = 0;
}

void ModelerState::after_operation() {
  const Session& s = *session_;
  if (s.topology_version() != seen_topology_) {
    seen_topology_ = s.topology_version();
    level_ = std::min(level_, s.finest_level());
    rebuild_limit();
    clamp_selection();
    if (colour_level_ >= s.finest_level()) colour_level_ = -1;
    update_.topology = true;
    basis_off();
    if (ffd_ && ffd_->bound) {  // an undone subdivide: the finest level the binding used is gone
      ffd_->bound = false;
      ffd_->note = "unbound: the lattice's levels changed (bind again)";
    }
    refresh_state();
    refresh_colour();
    return;
  }
  const int J = shown_level();  // the level whose limit is drawn
  const auto changed_fine = s.changed(J);
  if (anim_ && !changed_fine.empty()) {  // the frame shown: recomputed whole (one layer)
    rebuild_animation_view();
    update_.surface.resize(limit_.size() / 3);
    std::iota(update_.surface.begin(), update_.surface.end(), 0u);
  } else if (!changed_fine.empty()) {
    std::vector<std::uint32_t> moved;
    eval_limit_subset(stencils_, s.positions(J).data(), changed_fine, limit_.data(), moved);
    if (faces_.rows() > 0 && !moved.empty()) {
      // Fallback (face) normals also depend on the neighbours: take the moved vertices' faces.
      if (++epoch_ == 0) {
        std::fill(stamp_.begin(), stamp_.end(), 0u);
        epoch_ = 1;
      }
      // Vertices with exact tangents read only control points, so the moved ones suffice there.
      const std::vector<std::int8_t>& exact = stencils_.tangent_sign;
      auto face_based = [&](std::uint32_t w) { return w >= exact.size() || exact[w] == 0; };
      std::vector<std::uint32_t> shade;
      for (const std::uint32_t v : moved) {
        if (stamp_[v] != epoch_) stamp_[v] = epoch_, shade.push_back(v);
        for (const std::uint32_t f : vertex_faces_.row(v)) {
          for (const std::uint32_t w : faces_.row(f)) {
            if (stamp_[w] != epoch_ && face_based(w)) stamp_[w] = epoch_, shade.push_back(w);
          }
        }
      }
      limit_normals_subset(stencils_, faces_, vertex_faces_, s.positions(J).data(), limit_.data(), shade,
                           normals_.data());
      update_.surface.insert(update_.surface.end(), shade.begin(), shade.end());
    } else {
      update_.surface.insert(update_.surface.end(), moved.begin(), moved.end());
    }
  }
  const auto changed_net = s.changed(level_);
  update_.net.insert(update_.net.end(), changed_net.begin(), changed_net.end());
  if (soft_radius_ > 0.0 && !changed_net.empty() && !dragging_) refresh_state();  // weights follow the shape
  if (colour_level_ >= 0) refresh_colour();
  if (basis_ && !s.changed(basis_->level).empty()) basis_stale_ = true;
  ffd_follow();
  if (!dragging_) refresh_basis();
}

void ModelerState::refresh_basis() {
  if (!basis_ || !basis_stale_) return;
  try {
    set_basis(basis_settings_);  // the level-j geometry moved: new positions and moments
  } catch (const Error&) {
    basis_off();
  }
}

void ModelerState::set_scheme(Scheme scheme) {
  if (const std::optional<SchemeSwitchInput> in = begin_scheme(scheme)) install_scheme(*in, prepare_scheme(*in));
}

std::optional<SchemeSwitchInput> ModelerState::begin_scheme(Scheme scheme) {
  check_not_animation("changing the scheme");
  ffd_check_free("changing the scheme");
  check_unlocked("changing the scheme");
  // As `sublift-cli set --scheme`: the same scheme has nothing to rebuild, nothing to undo.
  if (scheme == session_->hierarchy().scheme) return std::nullopt;
  return scheme_switch_input(*session_, scheme);  // core/edit/scheme_switch.h: shape kept where it can be
}

SchemeSwitch ModelerState::prepare_scheme(const SchemeSwitchInput& in, const SwitchProgress& progress) {
  return switch_scheme(in, progress);
}

std::string ModelerState::install_scheme(const SchemeSwitchInput& in, SchemeSwitch next) {
  const Scheme from = in.from, scheme = in.to;
  const bool local = session_->detail_frames() == DetailFrames::Local;
  auto session = std::make_unique<Session>(std::move(next.hierarchy));
  if (local) session->set_detail_frames(DetailFrames::Local);
  session->mark_unsaved();
  const int edit_level = std::min(level_under_scheme(level_, from, scheme), session->finest_level());
  replace_session(std::move(session));  // same refinement: the same levels, so a rebuilt file's order still holds
  if (!base_uv().empty() && !uv_refinement_problem(scheme).empty())
    warnings_.push_back("texture coordinates are not saved or exported under this scheme: " + uv_refinement_problem(scheme));
  level_ = edit_level;
  clamp_selection();
  if (!next.kept_detail) {
    const bool had_order = !input_order_.empty();
    input_order_ = {};
    warnings_.push_back("the " + scheme_name(scheme) + " scheme refines differently from " + scheme_name(from) +
                        ": its levels start from the base, without the detail");
    if (had_order) warnings_.push_back("the vertex order of the file this mesh was rebuilt from is not kept (its levels are gone)");
  }
  update_.topology = true;
  refresh_state();
  return "Rebuilt with the " + scheme_name(scheme) + " scheme (Ctrl+Z undoes)";
}

void ModelerState::set_level(int level) {
  level = std::clamp(level, 0, session_->finest_level());
  if (level == level_) return;
  level_ = level;
  refresh_compression_net();
  selection_.clear();
  active_ = -1;
  hover_ = -1;
  if (anim_) rebuild_animation_view();  // that level's layer nearest the frame, its ghosts
  update_.topology = true;  // the function keeps its own level
  refresh_state();
}

void ModelerState::subdivide() {
  check_not_animation("subdividing");
  ffd_check_free("subdividing the lattice");
  check_unlocked("subdividing");
  session_->subdivide();
  after_operation();
}

bool ModelerState::undo() {
  if (dragging_) return false;
  check_unlocked("undo");
  if (!session_->can_undo() && !structure_undo_.empty()) {
    ffd_check_free("undoing a change of the hierarchy");
    Snapshot back = std::move(structure_undo_.back());
    structure_undo_.pop_back();
    structure_redo_.push_back(take_snapshot());
    restore(std::move(back));
    structure_redo_.back().resume_position = session_->undo_position();
    structure_redo_.back().resume_history = session_->history().size();
    return true;
  }
  const bool done = session_->undo();
  if (done) after_operation();
  return done;
}

bool ModelerState::redo() {
  if (dragging_) return false;
  check_unlocked("redo");
  if (!session_->can_redo() && !structure_redo_.empty()) {
    // Only from where the undo left this session: an edit since then made a new future.
    const Snapshot& top = structure_redo_.back();
    if (top.resume_position != session_->undo_position() || top.resume_history != session_->history().size()) {
      structure_redo_.clear();
      return false;
    }
    ffd_check_free("redoing a change of the hierarchy");
    Snapshot next = std::move(structure_redo_.back());
    structure_redo_.pop_back();
    structure_undo_.push_back(take_snapshot());
    restore(std::move(next));
    return true;
  }
  const bool done = session_->redo();
  if (done) after_operation();
  return done;
}

void ModelerState::jump_to(std::size_t position) {
  check_unlocked("jumping in the history");
  while (session_->undo_position() > position && undo()) {}
  while (session_->undo_position() < position && redo()) {}
}

void ModelerState::begin_gain(int level) {
  check_unlocked("changing a gain");
  session_->begin_edit("Gain " + std::to_string(level));
}

void ModelerState::set_gain(int level, double factor) {
  check_unlocked("changing a gain");
  session_->set_gain(level, factor);
  after_operation();
}

void ModelerState::end_gain() { session_->end_edit(); }

void ModelerState::set_local_frames(bool local) {
  session_->set_detail_frames(local ? DetailFrames::Local : DetailFrames::World);
}

void ModelerState::begin_drag(const std::string& label) {
  check_unlocked("moving control points");
  if (dragging_) end_drag();
  drag_undo_position_ = session_->undo_position();
  drag_weights_ = selection_weights();
  drag_total_[0] = drag_total_[1] = drag_total_[2] = 0.0;
  session_->begin_edit(label);
  dragging_ = true;
  transform_mode_ = TransformMode::Grab;
}

void ModelerState::drag_to(const double total[3]) {
  if (!dragging_) return;
  const double delta[3] = {total[0] - drag_total_[0], total[1] - drag_total_[1], total[2] - drag_total_[2]};
  if (delta[0] == 0.0 && delta[1] == 0.0 && delta[2] == 0.0) return;
  if (symmetry_[0] || symmetry_[1] || symmetry_[2]) {
    std::vector<double> deltas(3 * drag_weights_.vertices.size());
    for (std::size_t k = 0; k < drag_weights_.vertices.size(); ++k)
      for (int c = 0; c < 3; ++c) deltas[3 * k + c] = drag_weights_.weights[k] * delta[c];
    move_mirrored(drag_weights_.vertices, std::move(deltas));
  } else {
    session_->move(level_, drag_weights_.vertices, drag_weights_.weights, delta);
  }
  for (int c = 0; c < 3; ++c) drag_total_[c] = total[c];
  after_operation();
}

void ModelerState::end_drag() {
  if (!dragging_) return;
  session_->end_edit();
  dragging_ = false;
  if (soft_radius_ > 0.0) refresh_state();
  refresh_basis();  // recomputed once per drag, at its end
}

void ModelerState::cancel_drag() {
  if (!dragging_) return;
  session_->cancel_edit();
  dragging_ = false;
  after_operation();
  drag_total_[0] = drag_total_[1] = drag_total_[2] = 0.0;
}

void ModelerState::set_selection(std::vector<unsigned> selection) {
  std::sort(selection.begin(), selection.end());
  selection.erase(std::unique(selection.begin(), selection.end()), selection.end());
  selection_ = std::move(selection);
  clamp_selection();
  if (selection_.size() == 1) active_ = selection_.front();
  if (active_ >= 0 && !std::binary_search(selection_.begin(), selection_.end(), static_cast<unsigned>(active_))) active_ = -1;
  refresh_state();
  if (selection_.size() == 1) follow_selection();
}

void ModelerState::select_all() {
  std::vector<unsigned> all(session_->num_vertices(level_));
  for (unsigned i = 0; i < all.size(); ++i) all[i] = i;
  selection_ = std::move(all);
  clamp_selection();  // an animation's shown layer only
  refresh_state();
}

void ModelerState::set_hover(long long vertex) {
  if (vertex == hover_) return;
  hover_ = vertex;
  refresh_flags();
}

void ModelerState::set_soft_radius(double radius) {
  soft_radius_ = std::max(radius, 0.0);
  refresh_state();
}

double ModelerState::default_soft_radius() const { return 0.05 * model_size_; }

void ModelerState::clamp_selection() {
  const unsigned n = session_->num_vertices(level_);
  const std::vector<std::uint8_t>* shown = anim_ && anim_->on_layer.size() == n ? &anim_->on_layer : nullptr;
  selection_.erase(std::remove_if(selection_.begin(), selection_.end(),
                                  [&](unsigned v) { return v >= n || (shown && !(*shown)[v]); }),
                   selection_.end());
  if (hover_ >= static_cast<long long>(n) || (shown && hover_ >= 0 && !(*shown)[std::size_t(hover_)])) hover_ = -1;
}

void ModelerState::refresh_state() {
  const std::size_t n = session_->num_vertices(level_);
  net_soft_.assign(n, 0.0f);
  if (soft_radius_ > 0.0 && !selection_.empty()) {
    const SoftWeights w = selection_weights();
    for (std::size_t k = 0; k < w.vertices.size(); ++k) net_soft_[w.vertices[k]] = static_cast<float>(w.weights[k]);
  }
  net_state_.assign(n, 0);
  if (anim_)  // the level's other layers: other times, hidden
    for (std::size_t v = 0; v < n && v < anim_->on_layer.size(); ++v)
      if (!anim_->on_layer[v]) net_state_[v] = 3;
  flagged_.clear();
  refresh_flags();
}

void ModelerState::refresh_flags() {
  const std::size_t n = session_->num_vertices(level_);
  if (net_state_.size() != n) net_state_.assign(n, 0);
  for (const unsigned v : flagged_) {
    if (v < n) net_state_[v] = 0;
  }
  flagged_.clear();
  for (const unsigned v : selection_) net_state_[v] = 2, flagged_.push_back(v);
  if (hover_ >= 0 && static_cast<std::size_t>(hover_) < n) {
    net_state_[static_cast<std::size_t>(hover_)] = 1;
    flagged_.push_back(static_cast<unsigned>(hover_));
  }
  update_.state = true;
}

void ModelerState::set_colour_level(int level) {
  colour_level_ = level < 0 || level >= session_->finest_level() ? -1 : level;
  if (colour_level_ >= 0) colour_channel_ = -1;
  refresh_colour();
}

void ModelerState::set_colour_channel(int channel) {
  if (channel >= int(attribute_names_.size()))
    throw Error("channel " + std::to_string(channel) + ": the model has " + std::to_string(attribute_names_.size()) + " attribute channels");
  check_not_animation("colouring by a channel");
  colour_channel_ = channel < 0 ? -1 : channel;
  if (colour_channel_ >= 0) colour_level_ = -1;
  refresh_colour();
}

void ModelerState::refresh_colour() {
  update_.scalar = true;
  colour_.clear();
  if (colour_channel_ >= 0 && !anim_) {
    colour_ = channel_colour(colour_channel_);
    return;
  }
  if (colour_level_ < 0) return;
  colour_ = wavelet_magnitude_field(session_->hierarchy(), session_->gains(), colour_level_);  // core/analysis/wavelet_colour.h
  if (anim_) {  // the lattice's field on the finest layer nearest the frame shown
    const SpaceTime& st = anim_->anim.st;
    const int J = st.levels(), t = nearest_layer(st, J, anim_->frame);
    const std::uint32_t nvs = st.surface_vertices(J);
    std::vector<float> layer(nvs);
    for (std::uint32_t p = 0; p < nvs; ++p) layer[p] = colour_[st.layer_vertices[std::size_t(J)][std::size_t(t) * nvs + p]];
    colour_ = std::move(layer);
    return;
  }
  colour_.resize(session_->num_vertices(shown_level()));  // level V's vertices come first at every finer level
}

ProjectExtras ModelerState::project_extras() const {
  ProjectExtras extras;
  extras.current_level = level_;
  extras.gains.assign(session_->gains().begin(), session_->gains().end());
  extras.local_frames = session_->detail_frames() == DetailFrames::Local;
  if (!input_order_.empty() && input_order_.level <= session_->finest_level()) extras.input_order = input_order_;
  // (A session never changes level 0; the check keeps a map of another base out of the file.)
  if (fit_source_.base_vertex.size() == session_->num_vertices(0)) extras.fit_source = fit_source_;
  if (anim_) extras.animation = animation_extras(anim_->anim);  // reopens as the animation
  if (uv_refinement_problem(session_->hierarchy().scheme).empty()) extras.uv = base_uv();
  if (!attribute_sets_.empty() && fitted_attributes()) extras.attributes = attribute_names_;
  return extras;
}

void ModelerState::save_project(const std::string& path) {
  std::string why;
  const Hierarchy saved = saved_hierarchy(&why);
  if (!why.empty())
    warnings_.push_back("vertex attributes " + attribute_list() + " not saved: " + why);
  write_project(path, saved, project_extras());
  session_->mark_saved();
  project_path_ = path;
}

void ModelerState::write_recovery(const std::string& path) const { write_project(path, saved_hierarchy(nullptr), project_extras()); }

std::vector<std::string> ModelerState::export_shape(const std::string& path, bool finest) {
  if (anim_) {  // the frame shown, as drawn
    write_surface_with_normals(path, faces_, limit_, normals_);
    return {"the frame shown (" + std::to_string(anim_->frame) + "); 'Export animation' writes every frame"};
  }
  return export_level(path, finest ? -1 : level_);
}

std::vector<std::string> ModelerState::export_level(const std::string& path, int net_level) {
  const Hierarchy& h = session_->hierarchy();
  if (net_level > h.finest_level()) throw Error("level " + std::to_string(net_level) + " is outside 0.." + std::to_string(h.finest_level()));
  const bool finest = net_level < 0;
  const int level = finest ? h.finest_level() : net_level;
  const Complex& c = h.levels[static_cast<std::size_t>(level)];
  // The level's UVs (and the texture they map) where the faces written are the level's own.
  FaceVaryingUV uv = c.dim == 2 ? level_uv(level) : FaceVaryingUV{};
  const SurfaceTexture* texture = texture_.empty() ? nullptr : &texture_;
  // Colours and scalars: the level's net values (a limit export takes the finest net's).
  std::vector<VertexAttribute> attrs = attributes_at(level);
  const std::string ext = file_extension(path);
  const bool gltf = ext == "gltf" || ext == "glb";
  // OBJ and PLY take a net's attributes through write_shape (no normals); glTF through either.
  const bool net_with_attributes = !finest && !attrs.empty() && !gltf && c.dim == 2;
  if (surface_export_supported(path) && c.dim >= 2 && !net_with_attributes) {
    if (finest) {
      // The finest limit (also when the viewport shows a coarser level); UVs where its faces are the level's.
      const LimitSurface coarser = shown_level() == h.finest_level() ? LimitSurface{} : finest_limit_surface(h, session_->positions(h.finest_level()));
      const bool shown = shown_level() == h.finest_level();
      const Csr& faces = shown ? faces_ : coarser.faces;
      return write_surface_with_normals(path, faces, shown ? limit_ : coarser.positions, shown ? normals_ : coarser.normals, attrs,
                                        faces.items == c.faces.items ? &uv : nullptr, texture);
    }
    // The control net of the current level, with area-weighted face normals; a rebuilt mesh's
    // level in the order of its file.
    const bool file_order = level == input_order_.level && input_order_.faces.rows() > 0;
    const std::vector<double> xyz = file_order ? in_input_order(input_order_, session_->positions(level), 3)
                                               : std::vector<double>(session_->positions(level).begin(), session_->positions(level).end());
    // OBJ keeps a net's feature tags (write_shape: no normals); the other formats cannot.
    const FeatureTags tags = c.dim == 2 ? derive_feature_tags(c) : FeatureTags{};
    const bool tagged = !tags.crease_edges.empty() || !tags.corner_vertices.empty();
    if (tagged && file_extension(path) == "obj" && !file_order) return write_shape(path, c, session_->positions(level), attrs, &uv, texture);
    const Csr faces = file_order ? input_order_.faces : boundary_faces(c, xyz);
    if (file_order && !uv.empty()) uv = uv_in_file_order(uv, c);
    if (file_order)
      for (VertexAttribute& a : attrs) a.values = in_input_order(input_order_, a.values, 1);
    const std::vector<double> normals = area_weighted_normals(faces, xyz);
    std::vector<std::string> notes = write_surface_with_normals(path, faces, xyz, normals, attrs, c.dim == 2 ? &uv : nullptr, texture);
    if (tagged)
      notes.push_back("feature tags not written: " + std::to_string(tags.crease_edges.size()) + " crease edges and " +
                      std::to_string(tags.corner_vertices.size()) + " corners (." + file_extension(path) +
                      (file_order ? " in the file's vertex order" : "") + " cannot hold them; export the net as .obj)");
    return notes;
  }
  if (const std::string problem = shape_output_problem(path, c.dim); !problem.empty()) {
    throw Error(path + ": " + problem);
  }
  if (finest) {
    if (shown_level() == h.finest_level()) return write_shape(path, c, limit_, attrs, &uv, texture);
    return write_shape(path, c, finest_limit_surface(h, session_->positions(h.finest_level())).positions, attrs, &uv, texture);
  }
  if (level == input_order_.level) {  // a rebuilt mesh's level: in the order of its file
    if (!uv.empty()) uv = uv_in_file_order(uv, c);
    for (VertexAttribute& a : attrs) a.values = in_input_order(input_order_, a.values, 1);
    return write_shape(path, in_input_order(input_order_, c), in_input_order(input_order_, session_->positions(level), 3), attrs, &uv, texture);
  }
  return write_shape(path, c, session_->positions(level), attrs, &uv, texture);
}

std::vector<LevelStats> ModelerState::level_rows() const {
  const Hierarchy& h = session_->hierarchy();
  std::vector<LevelStats> rows(static_cast<std::size_t>(h.finest_level()) + 1);
  for (int l = 0; l <= h.finest_level(); ++l) {
    rows[static_cast<std::size_t>(l)].level = l;
    rows[static_cast<std::size_t>(l)].vertices = h.num_vertices(l);
  }
  for (const LevelStats& s : level_stats(h)) {
    if (s.level >= 0 && s.level <= h.finest_level()) rows[static_cast<std::size_t>(s.level)] = s;
  }
  return rows;
}

const std::vector<std::uint32_t>& ModelerState::net_edges() const {
  if (anim_) return anim_->net_edges;
  return session_->hierarchy().levels[static_cast<std::size_t>(level_)].edge_verts;
}

std::vector<std::uint8_t> ModelerState::net_edge_features() const {
  if (anim_) return {};
  const Complex& c = session_->hierarchy().levels[static_cast<std::size_t>(level_)];
  std::vector<std::uint8_t> f(c.num_edges(), 0);
  if (c.edge_dim.size() != f.size()) return f;
  for (std::size_t e = 0; e < f.size(); ++e) f[e] = c.edge_dim[e] == 1 && c.dim > 1 ? 1 : (c.edge_dim[e] == 0 ? 2 : 0);
  return f;
}

std::vector<std::uint8_t> ModelerState::net_vertex_features() const {
  if (anim_) return {};
  const Complex& c = session_->hierarchy().levels[static_cast<std::size_t>(level_)];
  std::vector<std::uint8_t> f(c.num_vertices, 0);
  if (c.vertex_dim.size() != f.size()) return f;
  for (std::size_t v = 0; v < f.size(); ++v) f[v] = c.vertex_dim[v] == 0 ? 2 : (c.vertex_dim[v] == 1 && c.dim > 1 ? 1 : 0);
  return f;
}

void ModelerState::basis_off() {
  if (basis_) update_.basis = true;
  basis_.reset();
  basis_settings_.on = false;
}

void ModelerState::set_basis(const BasisSettings& settings_in) {
  if (!settings_in.on || !session_) {
    basis_off();
    return;
  }
  check_not_animation("the basis mode");
  if (shown_level() != session_->finest_level())
    throw Error("the basis mode shows the finest level: set the viewport level to the finest first");
  BasisSettings settings = settings_in;
  if (compress_) compression_off();  // both replace the surface: the newer request wins
  int& j = settings.request.level;
  if (j < 0) j = level_;
  if (j > session_->finest_level()) {
    basis_off();
    throw Error("basis: level " + std::to_string(j) + " does not exist (finest is " +
                std::to_string(session_->finest_level()) + ")");
  }
  if (basis_ && same_function(basis_->settings, settings) && !basis_stale_) {
    basis_->settings = settings;
    basis_settings_ = settings;
    apply_basis_view(*basis_);
    update_.basis = true;
    return;
  }
  try {
    basis_ = std::make_unique<BasisDisplay>(compute_basis_display(*session_, j, settings));
  } catch (...) {
    basis_off();
    throw;
  }
  basis_settings_ = settings;
  basis_stale_ = false;
  update_.basis = true;
}

void ModelerState::pin_basis() {
  if (!basis_) throw Error("basis: nothing to pin (show a function first)");
  pinned_ = std::make_unique<BasisDisplay>(*basis_);
  update_.basis = true;
}

void ModelerState::clear_pin() {
  if (pinned_) update_.basis = true;
  pinned_.reset();
}

void ModelerState::follow_selection() {
  if (!basis_ || !basis_settings_.follow || selection_.empty()) return;
  const auto target = basis_target_at(session_->hierarchy(), level_, basis_settings_.request.kind, selection_.front());
  if (!target) return;
  BasisSettings b = basis_settings_;
  b.request.level = target->level;
  b.request.index = target->index;
  try {
    set_basis(b);
  } catch (const Error&) {
    basis_off();  // K too large for that level: the panel says the mode is off
  }
}

void ModelerState::ffd_check_free(const char* what) const {
  if (ffd_ && ffd_->bound) throw Error(std::string(what) + " is not possible while a model is bound (unbind it first)");
}

void ModelerState::ffd_follow() {
  if (!ffd_ || !ffd_->bound) return;
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<std::uint32_t> moved = update_deformation(ffd_->binding, *session_, ffd_->positions);
  ffd_->last_moved = moved.size();
  if (moved.empty()) return;
  ffd_->normals = model_normals(ffd_->model, ffd_->positions);
  ffd_->last_deform_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  update_.model = true;
}

void ModelerState::load_model(const std::string& path) {
  check_not_animation("free-form deformation");
  const bool lattice = session_ && session_->dim() == 3;
  if (session_ && !lattice && session_->dirty()) {
    throw Error("the open " + std::string(session_->dim() == 2 ? "surface" : "curve") +
                " has unsaved changes: save it first (loading a model replaces it by a box lattice)");
  }
  auto f = std::make_unique<FfdModelState>();
  f->model = import_model(path);
  f->positions = f->model.positions;
  f->normals = f->model.normals;
  if (ffd_) f->outside = ffd_->outside;
  std::unique_ptr<FfdModelState> old = std::move(ffd_);
  ffd_ = std::move(f);
  try {
    if (lattice) {
      bind_model(ffd_->outside);
    } else {
      wrap_model_in_box(4, 4, 4, 0.05);
    }
  } catch (...) {
    ffd_ = std::move(old);  // keep what was there
    throw;
  }
  update_.model_topology = true;
}

void ModelerState::wrap_model_in_box(int nx, int ny, int nz, double margin) {
  if (!ffd_) throw Error("wrap in a box: load a model first");
  Model shape = ffd_->model;
  shape.positions = ffd_->positions;  // around the model as it is now
  const Shape box = box_lattice_around(shape, nx, ny, nz, margin);
  // A box lattice is a volume: sqrt2 (surfaces only) falls back to cubic.
  const Scheme current = session_ ? session_->hierarchy().scheme : Scheme::Cubic;
  const Scheme scheme = scheme_info(current).surfaces_only ? Scheme::Cubic : current;
  Hierarchy h = make_hierarchy(box.base, kDefaultLevels, scheme, 3);
  set_base(h, box.positions);
  install_new_model(std::make_unique<Session>(std::move(h)));
  char name[64];
  std::snprintf(name, sizeof name, "box lattice %dx%dx%d", nx, ny, nz);
  file_path_ = name;
  project_path_.clear();
  warnings_.clear();
  level_ = 0;
  selection_.clear();
  active_ = -1;
  update_.topology = true;
  refresh_state();
  bind_model(ffd_->outside);
}

void ModelerState::bind_model(Outside outside) {
  if (!ffd_) throw Error("bind: load a model first");
  if (!session_ || session_->dim() != 3) throw Error("bind: the open shape is not a lattice (open one or wrap the model in a box)");
  const int J = session_->finest_level();
  ffd_->binding = sublift::bind_model(session_->hierarchy().levels[static_cast<std::size_t>(J)], session_->positions(J),
                                      ffd_->positions, FfdOptions{outside});
  ffd_->outside = outside;
  ffd_->bound = true;
  ffd_->note.clear();
}

void ModelerState::unbind_model() {
  if (ffd_) ffd_->bound = false;
}

void ModelerState::remove_model() {
  if (!ffd_) return;
  ffd_.reset();
  update_.model_topology = true;
}

void ModelerState::export_model(const std::string& path) const {
  if (!ffd_) throw Error("export model: no model loaded");
  sublift::export_model(ffd_->model, ffd_->positions, path);
}

// ---- compression view ---------------------------------------------------------------------------

void ModelerState::check_unlocked(const char* what) const {
  if (compress_)
    throw Error(std::string("the compression view is on: Apply it or turn it Off before ") + what);
}

std::span<const double> ModelerState::net_positions() const {
  if (compress_) return compress_->net;
  return session_->positions(level_);
}

void ModelerState::refresh_compression_net() {
  if (!compress_) return;
  CompressionView& v = *compress_;
  if (v.full) {
    const auto p = session_->positions(level_);
    v.net.assign(p.begin(), p.end());
  } else {
    v.net = synthesize_coefficients(session_->hierarchy(), v.coeffs, session_->gains(), level_);
  }
  update_.topology = true;
}

void ModelerState::set_compression(double fraction) {
  if (!session_) throw Error("compression: no model is open");
  check_not_animation("the compression view (sublift-cli animation --keep compresses an animation)");
  if (shown_level() != session_->finest_level())
    throw Error("the compression view shows the finest level: set the viewport level to the finest first");
  if (!(fraction >= 0.0 && fraction <= 1.0)) throw Error("compression: the kept fraction must be in 0..1");
  if (dragging_) throw Error("compression: finish the drag first");
  const auto t0 = std::chrono::steady_clock::now();
  if (!compress_) {
    CompressOptions options;
    options.gains.assign(session_->gains().begin(), session_->gains().end());
    auto view = std::make_unique<CompressionView>(CompressionView{Compressor(session_->hierarchy(), options), {}, false, {}, {}, {}, {}, {}});
    basis_off();  // the compressed surface replaces the function
    compress_ = std::move(view);
  }
  CompressionView& v = *compress_;
  const std::size_t keep = v.compressor.count_for_fraction(fraction);
  Compression c = v.compressor.evaluate(keep);
  v.full = keep == v.compressor.candidates();
  v.coeffs = std::move(c.coeffs);
  v.finest = std::move(c.finest);
  if (v.full) {  // nothing removed: the session's own shape, bit for bit
    v.limit = limit_;
    v.normals = normals_;
  } else {
    v.limit.assign(limit_.size(), 0.0);
    v.normals.assign(normals_.size(), 0.0);
    eval_limit(stencils_, v.finest.data(), v.limit.data());
    if (faces_.rows() > 0) sublift::limit_normals(stencils_, faces_, v.finest.data(), v.limit.data(), v.normals.data());
  }
  v.readout.fraction = fraction;
  v.readout.kept = c.kept;
  v.readout.total = c.total;
  v.readout.l2_error = c.l2_error;
  v.readout.linf_error = c.linf_error;
  refresh_compression_net();
  v.readout.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

void ModelerState::compression_off() {
  if (!compress_) return;
  compress_.reset();
  update_.topology = true;
}

void ModelerState::apply_compression() {
  if (!compress_) throw Error("compression: nothing to apply (show a compressed shape first)");
  const CompressionView& v = *compress_;
  const int J = session_->finest_level();
  // The finest control net moves onto the compressed one, one axis at a time (a move takes one
  // delta, weighted per vertex); the fold-back then stores the compressed wavelets.
  const auto now = session_->positions(J);
  std::vector<std::uint32_t> vertices[3];
  std::vector<double> weights[3];
  for (std::uint32_t p = 0; p < session_->num_vertices(J); ++p) {
    for (int c = 0; c < 3; ++c) {
      const double d = v.finest[3 * std::size_t(p) + c] - now[3 * std::size_t(p) + c];
      if (d == 0.0) continue;
      vertices[c].push_back(p);
      weights[c].push_back(d);
    }
  }
  char label[64];
  std::snprintf(label, sizeof label, "Compress %.4g%%", 100.0 * v.readout.fraction);
  std::unique_ptr<CompressionView> view = std::move(compress_);  // unlocked for the moves
  session_->begin_edit(label);
  try {
    for (int c = 0; c < 3; ++c) {
      if (vertices[c].empty()) continue;
      double delta[3] = {0.0, 0.0, 0.0};
      delta[c] = 1.0;
      session_->move(J, vertices[c], weights[c], delta);
      after_operation();
    }
  } catch (...) {
    session_->cancel_edit();
    after_operation();
    compress_ = std::move(view);
    throw;
  }
  session_->end_edit();
  update_.topology = true;
}

ViewUpdate ModelerState::take_view_update() {
  ViewUpdate out = std::move(update_);
  update_ = ViewUpdate{};
  return out;
}

}  // namespace sublift
