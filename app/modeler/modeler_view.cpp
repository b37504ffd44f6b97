#include "app/modeler/modeler_view.h"

#include <epoxy/gl.h>

#include <algorithm>

#include "render/offscreen_target.h"

#include "render/headless_render.h"

namespace sublift {
namespace {

Bounds bounds_of(const std::vector<double>& xyz) {
  Bounds b;
  for (std::size_t i = 0; i + 2 < xyz.size(); i += 3) {
    const glm::dvec3 p(xyz[i], xyz[i + 1], xyz[i + 2]);
    b.min = b.empty ? p : glm::min(b.min, p);
    b.max = b.empty ? p : glm::max(b.max, p);
    b.empty = false;
  }
  return b;
}

// Uploads a function's drawn shape at `positions`; true when it is a surface.
bool upload_basis(const BasisDisplay& b, const std::vector<double>& positions, LimitSurfaceRenderer& surface,
                  NetRenderer& curve) {
  const std::size_t n = positions.size() / 3;
  if (b.faces.rows() > 0) {
    surface.set_topology(b.faces.offsets, b.faces.items, n);
    surface.set_positions_normals(positions, b.normals);
    surface.set_scalar(b.colour);
    return true;
  }
  curve.set_topology(b.curve_edges, {}, {}, n);
  curve.set_positions(positions);
  return false;
}

}  // namespace

void ModelerView::sync(ModelerState& state) {
  ViewUpdate u = state.take_view_update();
  if (!state.has_session()) return;
  if (u.topology) {
    const Csr& faces = state.surface_faces();
    const std::size_t n = state.limit_positions().size() / 3;
    has_surface_ = faces.rows() > 0;
    has_curve_ = !has_surface_;
    if (has_surface_) {
      surface_.set_topology(faces.offsets, faces.items, n);
      surface_.set_positions_normals(state.limit_positions(), state.limit_normals());
    } else {
      const Complex& shown = state.shown_complex();  // the finest unless a viewport level is set
      curve_.set_topology(shown.edge_verts, {}, {}, n);
      curve_.set_positions(state.limit_positions());
    }
    net_.set_topology(state.net_edges(), state.net_edge_features(), state.net_vertex_features(),
                      state.session().num_vertices(state.level()));
    net_.set_positions(state.net_positions());  // compressed while the compression view is on
    u.state = u.scalar = true;
    // The texture's surface, when the shown level has UVs and the model a texture.
    textured_split_ = has_surface_ ? state.shown_uv_split() : UvVertexSplit{};
    const UvVertexSplit& split = textured_split_;
    textured_on_ = !split.source.empty();
    if (textured_on_) {
      textured_surface_.set_topology(split.faces.offsets, split.faces.items, split.source.size());
      textured_surface_.set_texcoords(std::vector<float>(split.texcoords.begin(), split.texcoords.end()));
      const SurfaceTexture& t = state.texture();
      if (texture_uploaded_ != t.bytes.data() || texture_bytes_ != t.bytes.size()) {
        if (const std::optional<Image> image = decode_image(t.bytes)) {
          textured_surface_.set_texture(image->rgba, image->width, image->height, t.wrap_s, t.wrap_t);
          texture_uploaded_ = t.bytes.data();
          texture_bytes_ = t.bytes.size();
        } else {
          textured_on_ = false;  // an image that does not decode: clay, as before
        }
      }
      if (textured_on_) upload_textured_positions(state);
    }
  } else {
    if (!u.surface.empty()) {
      if (has_surface_) {
        surface_.update(state.limit_positions(), state.limit_normals(), u.surface);
        if (textured_on_) upload_textured_positions(state);  // all of them: a seam vertex has copies
      } else {
        curve_.update_positions(state.limit_positions(), u.surface);
      }
    }
    if (!u.net.empty()) net_.update_positions(state.net_positions(), u.net);
  }
  if (u.state) net_.set_state(state.net_state(), state.net_soft());
  if (u.basis || (u.topology && state.basis_on()) || (state.basis_on() && !u.net.empty())) {
    basis_on_ = state.basis_on();
    basis_surface_on_ = false;
    if (basis_on_) {
      const BasisDisplay& b = state.basis();
      basis_surface_on_ = upload_basis(b, b.positions, basis_surface_, basis_curve_);
      // The outline follows a drag live when the function's level is the one being edited.
      const bool live = b.level == state.level();
      const auto net = live ? state.session().positions(state.level()) : std::span<const double>(b.net_positions);
      basis_support_.set_topology(b.support_edges, {}, {}, net.size() / 3);
      basis_support_.set_positions(net);
    }
    pinned_on_ = state.pinned() != nullptr;
    if (pinned_on_) {
      // Beside what is shown now, to the right (+x), a tenth of the wider extent apart.
      const BasisDisplay& p = *state.pinned();
      const std::vector<double>& shown = basis_on_ ? state.basis().positions : state.limit_positions();
      const Bounds a = bounds_of(shown), c = bounds_of(p.positions);
      const double gap = 0.1 * std::max(a.max.x - a.min.x, c.max.x - c.min.x) + 1e-9;
      const double dx = a.max.x + gap - c.min.x;
      std::vector<double> moved = p.positions;
      for (std::size_t i = 0; i < moved.size(); i += 3) moved[i] += dx;
      pinned_surface_on_ = upload_basis(p, moved, pinned_surface_, pinned_curve_);
      pinned_bounds_ = bounds_of(moved);
    }
  }
  if (u.model_topology) {
    const FfdModelState* f = state.ffd();
    model_on_ = f != nullptr && f->model.faces.rows() > 0;
    if (model_on_) {
      model_surface_.set_topology(f->model.faces.offsets, f->model.faces.items, f->positions.size() / 3);
      u.model = true;
    }
  }
  if (u.model && model_on_ && state.ffd() != nullptr) {
    model_surface_.set_positions_normals(state.ffd()->positions, state.ffd()->normals);
  }
  // A lattice with a model inside shows its net only: its boundary would hide the model.
  hide_lattice_surface_ = model_on_ && state.dim() == 3;
  if (u.fit_preview || u.topology) {
    const ModelerState::FitPreview* p = state.fit_preview();
    fit_preview_on_ = p != nullptr;
    if (p) {
      fit_preview_.set_topology(p->edges, {}, {}, p->positions.size() / 3);
      fit_preview_.set_positions(p->positions);
    }
  }
  if (u.ghosts || u.topology) {
    const AnimationViewState* a = state.animation();
    ghosts_on_ = a != nullptr && !a->ghost_edges.empty();
    if (ghosts_on_) {
      ghosts_.set_topology(a->ghost_edges, {}, {}, a->ghost_positions.size() / 3);
      ghosts_.set_positions(a->ghost_positions);
    }
  }
  if (u.scalar && has_surface_) {
    colour_map_ = !state.colour_values().empty();
    surface_.set_scalar(state.colour_values());
  }
}

void ModelerView::upload_textured_positions(const ModelerState& state) {
  textured_surface_.set_positions_normals(at_split_vertices(textured_split_, state.limit_positions(), 3),
                                         at_split_vertices(textured_split_, state.limit_normals(), 3));
}

Bounds ModelerView::bounds() const {
  Bounds b = has_surface_ ? surface_.bounds() : curve_.bounds();
  if (model_on_) {
    const Bounds m = model_surface_.bounds();
    if (b.empty) {
      b = m;
    } else if (!m.empty) {
      b.min = glm::min(b.min, m.min);
      b.max = glm::max(b.max, m.max);
    }
  }
  if (pinned_on_ && !pinned_bounds_.empty && !b.empty) {
    b.min = glm::min(b.min, pinned_bounds_.min);
    b.max = glm::max(b.max, pinned_bounds_.max);
  }
  const Bounds& n = net_.bounds();
  if (b.empty) return n;
  if (!n.empty) {
    b.min = glm::min(b.min, n.min);
    b.max = glm::max(b.max, n.max);
  }
  return b;
}

glm::vec4 ModelerView::clip_plane(const ModelerDisplay& d) const {
  const Bounds b = bounds();
  const int a = std::clamp(d.clip_axis, 0, 2);
  const double lo = b.empty ? -1.0 : b.min[a], hi = b.empty ? 1.0 : b.max[a];
  const double at = lo + (hi - lo) * static_cast<double>(std::clamp(d.clip_offset, 0.0f, 1.0f));
  // Keeps dot(plane, (x, 1)) >= 0: the side below the offset (above with clip_flip).
  glm::vec4 plane(0.0f);
  const float s = d.clip_flip ? 1.0f : -1.0f;
  plane[a] = s;
  plane.w = static_cast<float>(-s * at);
  return plane;
}

void ModelerView::draw(const OrbitCamera& camera, const ViewportRect& rect, const ModelerDisplay& d) const {
  glViewport(rect.x, rect.y, rect.width, rect.height);
  glEnable(GL_SCISSOR_TEST);
  glScissor(rect.x, rect.y, rect.width, rect.height);
  glDepthMask(GL_TRUE);
  glClear(GL_DEPTH_BUFFER_BIT);
  background_.draw();
  const glm::vec4 plane = clip_plane(d);
  // The surface and curve styles every branch shares: display switches and the clipping plane.
  auto surface_style = [&](bool colour) {
    SurfaceStyle style;
    style.smooth = d.smooth;
    style.wireframe = d.wireframe;
    style.color_map = colour;
    style.clip = d.clip;
    style.clip_plane = plane;
    return style;
  };
  auto curve_style = [&](const glm::vec4& colour) {
    NetStyle style;
    style.points = false;
    style.clip = d.clip;
    style.clip_plane = plane;
    style.colors.edge = colour;
    return style;
  };
  const glm::vec4 curve_colour(0.80f, 0.45f, 0.20f, 1.0f);
  if (basis_on_ && basis_surface_on_) {
    basis_surface_.draw(camera, surface_style(true));
  } else if (basis_on_) {
    basis_curve_.draw(camera, curve_style(glm::vec4(0.10f, 0.55f, 0.75f, 1.0f)));
    // The curve itself, thin and faint, as the zero line.
    if (has_curve_) curve_.draw(camera, curve_style(glm::vec4(0.80f, 0.45f, 0.20f, 0.35f)));
  } else if (has_surface_ && !hide_lattice_surface_ && textured_on_ && d.texture && !colour_map_) {
    SurfaceStyle style = surface_style(false);
    style.textured = true;
    textured_surface_.draw(camera, style);
  } else if (has_surface_ && !hide_lattice_surface_) {
    surface_.draw(camera, surface_style(colour_map_));
  } else if (has_curve_) {
    curve_.draw(camera, curve_style(curve_colour));
  }
  if (model_on_) model_surface_.draw(camera, surface_style(false));
  if (pinned_on_ && pinned_surface_on_) {
    pinned_surface_.draw(camera, surface_style(true));
  } else if (pinned_on_) {
    pinned_curve_.draw(camera, curve_style(glm::vec4(0.55f, 0.30f, 0.75f, 1.0f)));
  }
  if (d.net) {
    NetStyle style;
    style.depth_cue = d.depth_cue;
    style.xray = d.xray;
    style.clip = d.clip;
    style.clip_plane = plane;
    net_.draw(camera, style);
  }
  if (basis_on_) {  // the support outline, over the net and through the surface
    NetStyle style;
    style.points = false;
    style.xray = true;
    style.clip = d.clip;
    style.clip_plane = plane;
    style.colors.edge = glm::vec4(0.95f, 0.15f, 0.45f, 1.0f);
    basis_support_.draw(camera, style);
  }
  if (ghosts_on_) {  // the frames around the current one, faint and behind nothing
    NetStyle style;
    style.points = false;
    style.clip = d.clip;
    style.clip_plane = plane;
    style.colors.edge = glm::vec4(0.25f, 0.45f, 0.85f, 0.35f);
    ghosts_.draw(camera, style);
  }
  if (fit_preview_on_) {  // the base a fit would start from, over the mesh and through it
    NetStyle style;
    style.xray = true;
    style.clip = d.clip;
    style.clip_plane = plane;
    style.point_size = 5;
    style.colors.edge = glm::vec4(1.0f, 0.55f, 0.05f, 1.0f);
    fit_preview_.draw(camera, style);
  }
  glDisable(GL_SCISSOR_TEST);
}

std::vector<float> ModelerView::surface_depth(const OrbitCamera& camera, int width, int height,
                                             const ModelerDisplay& d) const {
  if ((!has_surface_ && !model_on_) || width <= 0 || height <= 0) return {};
  GLint previous_fbo = 0, previous_viewport[4] = {0, 0, 0, 0};
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &previous_fbo);
  glGetIntegerv(GL_VIEWPORT, previous_viewport);
  std::vector<float> depth(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), 1.0f);
  {
    OffscreenTarget target(width, height, 0);
    target.bind();
    glDepthMask(GL_TRUE);
    glClear(GL_DEPTH_BUFFER_BIT | GL_COLOR_BUFFER_BIT);
    SurfaceStyle style;
    style.clip = d.clip;
    style.clip_plane = clip_plane(d);
    if (has_surface_ && !hide_lattice_surface_) surface_.draw(camera, style);
    if (model_on_) model_surface_.draw(camera, style);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, width, height, GL_DEPTH_COMPONENT, GL_FLOAT, depth.data());
  }
  glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(previous_fbo));
  glViewport(previous_viewport[0], previous_viewport[1], previous_viewport[2], previous_viewport[3]);
  return depth;
}

}  // namespace sublift
