#include "render/headless_render.h"

#include <string>

#include <epoxy/gl.h>
#include <stb_image.h>

#include "render/background.h"
#include "render/headless_context.h"
#include "render/limit_surface_renderer.h"
#include "render/offscreen_target.h"
#include "render/render_errors.h"
#include "render/viewport_renderer.h"

namespace sublift {

std::optional<Image> decode_image(std::string_view bytes) {
  int w = 0, h = 0, n = 0;
  unsigned char* pixels = stbi_load_from_memory(reinterpret_cast<const unsigned char*>(bytes.data()), int(bytes.size()), &w, &h, &n, 4);
  if (!pixels) return std::nullopt;
  Image image{w, h, std::vector<std::uint8_t>(pixels, pixels + 4 * std::size_t(w) * std::size_t(h))};
  stbi_image_free(pixels);
  return image;
}

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

namespace {

void check_size(int width, int height) {
  constexpr int kMaxSide = 16384;
  if (width < 1 || height < 1 || width > kMaxSide || height > kMaxSide)
    throw RenderError("render size " + std::to_string(width) + "x" + std::to_string(height) + " is outside 1x1.." +
                      std::to_string(kMaxSide) + "x" + std::to_string(kMaxSide));
}

// Frames the surface as the default camera does and draws it on the viewport gradient.
Image draw_surface(LimitSurfaceRenderer& surface, BackgroundRenderer& background, OffscreenTarget& target, int width,
                   int height, const HeadlessRenderSettings& settings, SurfaceStyle style) {
  OrbitCamera camera;
  camera.set_viewport(width, height);
  camera.set_view(settings.view);
  camera.orthographic = settings.orthographic;
  camera.up_axis = settings.up_axis;
  frame_bounds(camera, surface.bounds());
  target.bind();
  glViewport(0, 0, width, height);
  glDepthMask(GL_TRUE);
  glClear(GL_DEPTH_BUFFER_BIT);
  background.draw();
  style.wireframe = settings.display.wireframe;
  style.smooth = settings.smooth;
  surface.draw(camera, style);
  return Image{width, height, target.read_rgba()};
}

}  // namespace

namespace {

// A surface drawn once: its buffers filled by `fill` (scalars, texture) and drawn in `style`.
template <class Fill>
Image render_surface(std::span<const double> xyz, std::span<const double> normals, const Csr& faces, int width, int height,
                     const HeadlessRenderSettings& settings, const SurfaceStyle& style, Fill fill) {
  check_size(width, height);
  HeadlessContext context;
  OffscreenTarget target(width, height, settings.samples);
  BackgroundRenderer background;
  LimitSurfaceRenderer surface;
  surface.set_topology(faces.offsets, faces.items, xyz.size() / 3);
  surface.set_positions_normals(xyz, normals);
  fill(surface);
  return draw_surface(surface, background, target, width, height, settings, style);
}

}  // namespace

Image render_coloured_surface_headless(std::span<const double> xyz, std::span<const double> normals, const Csr& faces,
                                       std::span<const float> scalar01, int width, int height,
                                       const HeadlessRenderSettings& settings) {
  SurfaceStyle style;
  style.color_map = true;
  return render_surface(xyz, normals, faces, width, height, settings, style,
                        [&](LimitSurfaceRenderer& s) { s.set_scalar(scalar01); });
}

Image render_textured_surface_headless(std::span<const double> xyz, std::span<const double> normals, const Csr& faces,
                                       std::span<const float> texcoords, const Image& texture, int width, int height,
                                       const HeadlessRenderSettings& settings, int wrap_s, int wrap_t) {
  SurfaceStyle style;
  style.textured = true;
  return render_surface(xyz, normals, faces, width, height, settings, style, [&](LimitSurfaceRenderer& s) {
    s.set_texcoords(texcoords);
    s.set_texture(texture.rgba, texture.width, texture.height, wrap_s, wrap_t);
  });
}

}  // namespace sublift
