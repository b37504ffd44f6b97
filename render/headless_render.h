#pragma once
// One-call offscreen rendering of a mesh to pixels, without any window system
// (what `sublift-cli render` uses).
#include <cstdint>
#include <optional>
#include <string_view>
#include <span>
#include <vector>

#include "core/base/csr.h"
#include "core/base/surface_mesh.h"
#include "render/camera.h"
#include "render/mesh_renderer.h"

namespace sublift {

/// Pixels as top-down rows of RGBA8, width * height * 4 bytes.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;
};

struct HeadlessRenderSettings {
  ViewPreset view = ViewPreset::ThreeQuarter;
  bool orthographic = false;
  UpAxis up_axis = UpAxis::Y;
  DisplayOptions display;
  int samples = 4;  // MSAA samples (0 = none)
  bool smooth = true;  // surfaces: per-vertex normals; false: flat faces (coloured and textured renders)
};

/// Renders `mesh` shaded with wireframe from the default 3/4 view, framed to fit, on the
/// viewport gradient. Creates its own EGL context; throws RenderError if headless GL is
/// unavailable or the size is out of range.
Image render_mesh_headless(const SurfaceMesh& mesh, int width, int height);

/// The same with a chosen view, projection and display options.
Image render_mesh_headless(const SurfaceMesh& mesh, int width, int height,
                           const HeadlessRenderSettings& settings);

/// A limit surface (3 doubles per vertex of positions and normals, CSR faces) coloured through
/// viridis by `scalar01` (one value per vertex in 0..1), from the same default view: what
/// `sublift-cli render --colour L` draws (the modeler's "Colour by |w| of level").
Image render_coloured_surface_headless(std::span<const double> xyz, std::span<const double> normals, const Csr& faces,
                                       std::span<const float> scalar01, int width, int height,
                                       const HeadlessRenderSettings& settings = {});

/// A surface with a texture (`texcoords`: u, v per vertex, v up; `texture`: the decoded image,
/// top-down RGBA8) from the same default view, lit as the colour map: what `sublift-cli render
/// --textured` draws. Face-varying UVs need the vertices split at seams first. `wrap_s`/`wrap_t`
/// as glTF's sampler numbers them.
Image render_textured_surface_headless(std::span<const double> xyz, std::span<const double> normals, const Csr& faces,
                                       std::span<const float> texcoords, const Image& texture, int width, int height,
                                       const HeadlessRenderSettings& settings = {}, int wrap_s = 10497, int wrap_t = 10497);

/// An encoded image (PNG, JPEG: what stb_image reads) decoded to RGBA8; nullopt when it does not
/// decode.
std::optional<Image> decode_image(std::string_view bytes);

/// The camera render_mesh_headless uses for these arguments (no GL needed).
OrbitCamera headless_camera(const SurfaceMesh& mesh, int width, int height,
                            const HeadlessRenderSettings& settings = {});

}  // namespace sublift
