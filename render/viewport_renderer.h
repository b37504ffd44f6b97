#pragma once
// The 3-D viewport as the GUI and the headless renderer both draw it: gradient backdrop, then
// the mesh, inside a rectangle of the current framebuffer.
#include <glm/vec3.hpp>

#include "core/base/surface_mesh.h"
#include "render/background.h"
#include "render/camera.h"
#include "render/mesh_renderer.h"

namespace sublift {

/// A rectangle of the framebuffer in GL pixel coordinates (origin bottom-left).
struct ViewportRect {
  int x = 0, y = 0, width = 1, height = 1;
};

/// Owns the background and mesh renderers; needs a current GL 3.3 context.
class ViewportRenderer {
 public:
  /// Compiles all shaders up front so a broken one fails at start-up; throws ShaderError.
  ViewportRenderer() = default;

  /// Replaces the drawn mesh.
  void set_mesh(const SurfaceMesh& mesh) { mesh_.upload(mesh); }
  /// Bounds of the drawn mesh, for framing.
  const Bounds& bounds() const { return mesh_.bounds(); }
  /// Draws backdrop and mesh into `rect` of the bound framebuffer (scissored, own depth clear).
  void draw(const OrbitCamera& camera, const ViewportRect& rect,
            const DisplayOptions& options) const;

 private:
  BackgroundRenderer background_;
  MeshRenderer mesh_;
};

/// Clears the whole bound framebuffer (colour and depth) to `color`.
void clear_framebuffer(int width, int height, const glm::vec3& color);

/// Frames `camera` on `bounds` (a unit box around the origin when empty).
void frame_bounds(OrbitCamera& camera, const Bounds& bounds);

}  // namespace sublift
