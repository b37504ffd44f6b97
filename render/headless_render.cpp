#include "render/headless_render.h"

#include <string>

#include "render/headless_context.h"
#include "render/offscreen_target.h"
#include "render/render_errors.h"
#include "render/viewport_renderer.h"

namespace sublift {

OrbitCamera headless_camera(const SurfaceMesh& mesh, int width, int height,
                            const HeadlessRenderSettings& settings) {
  OrbitCamera camera;
  camera.set_viewport(width, height);
  camera.set_view(settings.view);
  camera.orthographic = settings.orthographic;
  camera.up_axis = settings.up_axis;
  frame_bounds(camera, drawn_bounds(mesh));
  return camera;
}

Image render_mesh_headless(const SurfaceMesh& mesh, int width, int height) {
  return render_mesh_headless(mesh, width, height, HeadlessRenderSettings{});
}

Image render_mesh_headless(const SurfaceMesh& mesh, int width, int height,
                           const HeadlessRenderSettings& settings) {
  constexpr int kMaxSide = 16384;
  if (width < 1 || height < 1 || width > kMaxSide || height > kMaxSide) {
    throw RenderError("render size " + std::to_string(width) + "x" + std::to_string(height) +
                      " is outside 1x1.." + std::to_string(kMaxSide) + "x" +
                      std::to_string(kMaxSide));
  }
  HeadlessContext context;
  OffscreenTarget target(width, height, settings.samples);
  ViewportRenderer viewport;
  viewport.set_mesh(mesh);
  const OrbitCamera camera = headless_camera(mesh, width, height, settings);
  target.bind();
  viewport.draw(camera, ViewportRect{0, 0, width, height}, settings.display);
  return Image{width, height, target.read_rgba()};
}

}  // namespace sublift
