#pragma once
// ModelerView: the modeler's 3-D viewport on the GPU — backdrop, the finest level's limit
// surface (or a curve's limit polyline) and the control net of the edit level on top. It
// While the basis-function mode is on, the function (colour, optional height field, lattice
// slices and iso-surfaces) replaces the limit surface or curve and its support outline is drawn
// over the net; a pinned function is drawn to the right of it for comparison. A model loaded
// for free-form deformation is drawn shaded inside its lattice's net. It
// mirrors a ModelerState, uploading only what take_view_update() reports as changed.
#include <vector>

#include <glm/vec4.hpp>

#include "app/modeler/modeler_state.h"
#include "render/background.h"
#include "render/camera.h"
#include "render/limit_surface_renderer.h"
#include "render/net_renderer.h"
#include "render/viewport_renderer.h"
#include "ui/modeler_panels.h"

namespace sublift {

class ModelerView {
 public:
  /// Compiles the shaders; throws ShaderError. Needs a current GL 3.3 context.
  ModelerView() = default;

  /// Uploads what changed in `state` since the last call (all of it after a topology change).
  void sync(ModelerState& state);
  /// Draws into `rect` of the bound framebuffer (scissored, own depth clear).
  void draw(const OrbitCamera& camera, const ViewportRect& rect, const ModelerDisplay& display) const;
  /// Bounds of the limit surface (or curve), for framing and the clipping plane.
  Bounds bounds() const;
  /// The clipping plane the display asks for, in world coordinates.
  glm::vec4 clip_plane(const ModelerDisplay& display) const;
  /// Window depth ([0, 1], rows bottom-up, 1 where nothing is drawn) of the surface alone as
  /// `camera` sees it at width x height pixels, drawn into a single-sample offscreen target (the
  /// window's multisampled depth cannot be read back): what picking needs to skip control points
  /// behind the surface. Leaves the previously bound framebuffer and viewport bound. Empty when
  /// there is no surface.
  std::vector<float> surface_depth(const OrbitCamera& camera, int width, int height,
                                   const ModelerDisplay& display) const;

 private:
  BackgroundRenderer background_;
  LimitSurfaceRenderer surface_;
  NetRenderer net_;
  NetRenderer curve_;  // a curve's limit polyline (no points)
  bool has_surface_ = false, has_curve_ = false;
  bool colour_map_ = false;
  // Basis-function mode: the function on the level j+K shape, and its support on the level-j net.
  LimitSurfaceRenderer basis_surface_;
  NetRenderer basis_curve_, basis_support_;
  bool basis_on_ = false, basis_surface_on_ = false;
  // A pinned function for comparison, drawn to the right of what is shown.
  LimitSurfaceRenderer pinned_surface_;
  NetRenderer pinned_curve_;
  bool pinned_on_ = false, pinned_surface_on_ = false;
  Bounds pinned_bounds_;
  // A textured model: the surface split at its UV seams (one GL vertex per vertex and UV), its
  // positions copied from the drawn surface's; the texture decoded once per model.
  LimitSurfaceRenderer textured_surface_;
  UvVertexSplit textured_split_;
  bool textured_on_ = false;
  const void* texture_uploaded_ = nullptr;
  std::size_t texture_bytes_ = 0;
  void upload_textured_positions(const ModelerState& state);
  // Free-form deformation: the model, shaded; a lattice around it shows only its net.
  LimitSurfaceRenderer model_surface_;
  bool model_on_ = false, hide_lattice_surface_ = false;
  // The base a fit would start from (docs/fit.md), drawn over the mesh.
  NetRenderer fit_preview_;
  bool fit_preview_on_ = false;
  // An animation's ghost frames around the current one, as faint wireframes.
  NetRenderer ghosts_;
  bool ghosts_on_ = false;
};

}  // namespace sublift
