#pragma once
// Draws the limit surface of the finest level: clay shading with per-vertex normals (smooth) or
// face normals from screen-space derivatives (flat), an optional wireframe of the polygon edges,
// an optional per-vertex colour map and a clipping plane.
//
// Layout. One GL vertex per surface vertex in three vertex-shared buffers: position (float vec3
// relative to `center`, the bounds centre at set_positions_normals), unit normal (float vec3)
// and scalar (float). Triangles fan each polygon from its first corner; the wireframe is a
// separate element buffer of the unique polygon edges (never fan diagonals). Flat shading needs
// no per-corner copies (the fragment shader takes the face normal from dFdx/dFdy of the view
// position), so update() rewrites just the changed vertices' ranges.
//
// Colour map: viridis (perceptually uniform, colour-blind safe, dark purple at 0 through teal to
// yellow at 1), a degree-6 polynomial fit, shaded more gently than clay so values stay readable.
// The clipping plane keeps dot(plane, (x, 1)) >= 0 in world coordinates (GL_CLIP_DISTANCE0);
// surfaces seen from inside through the cut show their back tint.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "render/camera.h"
#include "render/mesh_buffers.h"

namespace sublift {

class ShaderProgram;

struct SurfaceStyle {
  bool smooth = true;      // per-vertex normals; false: flat faces
  bool wireframe = false;  // polygon edges on top (fades when edges are a few pixels long)
  bool color_map = false;  // per-vertex scalar through viridis instead of clay
  bool textured = false;   // the texture at the per-vertex texture coordinates instead of clay
  bool clip = false;
  glm::vec4 clip_plane{0, 0, 1, 0};  // keeps dot(plane, (x, y, z, 1)) >= 0, world coordinates
};

/// GPU copy of one limit surface; needs a current GL 3.3 context.
class LimitSurfaceRenderer {
 public:
  /// Compiles limit.vert/limit.frag; throws ShaderError.
  LimitSurfaceRenderer();
  ~LimitSurfaceRenderer();
  LimitSurfaceRenderer(const LimitSurfaceRenderer&) = delete;
  LimitSurfaceRenderer& operator=(const LimitSurfaceRenderer&) = delete;

  /// Faces as CSR corner lists: face f has corners face_corners[face_offsets[f] ..
  /// face_offsets[f+1]) (offsets has faces + 1 entries, starting at 0). Faces with fewer than 3
  /// corners are skipped. Resets positions, normals and scalars to zero. Throws TopologyError
  /// on bad offsets or a corner >= num_vertices.
  void set_topology(std::span<const std::uint32_t> face_offsets, std::span<const std::uint32_t> face_corners,
                    std::size_t num_vertices);
  /// Uploads all positions and normals (3 doubles per vertex each; normals need not be unit,
  /// zero ones fall back to the face normal) and recentres; throws Error on a size mismatch.
  void set_positions_normals(std::span<const double> xyz, std::span<const double> normals);
  /// Uploads only vertices `changed` of the full arrays `xyz` and `normals`; keeps the centre
  /// and grows the bounds.
  void update(std::span<const double> xyz, std::span<const double> normals,
              std::span<const std::uint32_t> changed_vertices);
  /// Per-vertex value in [0, 1] for the colour map (clamped in the shader); empty: all 0.
  void set_scalar(std::span<const float> value01);
  /// Per-vertex texture coordinates (u, v with v up, 2 floats per vertex; empty: zeros). Face-
  /// varying UVs need the vertices split at seams first (one vertex per vertex-and-UV pair).
  void set_texcoords(std::span<const float> uv);
  /// The texture drawn when SurfaceStyle::textured: top-down rows of RGBA8, mipmapped; wrap
  /// modes as glTF's sampler numbers them (10497 repeat, 33071 clamp, 33648 mirrored repeat).
  void set_texture(std::span<const std::uint8_t> rgba, int width, int height, int wrap_s = 10497, int wrap_t = 10497);
  /// Draws into the bound framebuffer with depth testing (and writing).
  void draw(const OrbitCamera& camera, const SurfaceStyle& style) const;
  /// Bounds of the positions (set_positions_normals, grown by update), for framing.
  Bounds bounds() const { return bounds_; }

  std::size_t num_vertices() const { return num_vertices_; }
  std::size_t num_triangles() const { return triangle_index_count_ / 3; }
  std::size_t num_edges() const { return edge_index_count_ / 2; }

 private:
  std::unique_ptr<ShaderProgram> program_;
  unsigned fill_vao_ = 0, wire_vao_ = 0;
  unsigned position_vbo_ = 0, normal_vbo_ = 0, scalar_vbo_ = 0, triangle_ebo_ = 0, edge_ebo_ = 0;
  unsigned texcoord_vbo_ = 0, texture_ = 0;
  std::size_t num_vertices_ = 0, triangle_index_count_ = 0, edge_index_count_ = 0;
  glm::dvec3 center_{0.0};
  double mean_edge_length_ = 0.0;  // world units (sampled), for fading dense wireframes
  std::vector<std::uint32_t> edge_sample_;  // up to a few thousand edges (pairs) for that mean
  Bounds bounds_;
};

}  // namespace sublift
