#pragma once
// Draws a SurfaceMesh: flat-shaded clay fill plus a wireframe of the polygon edges on top.
#include <memory>

#include "core/base/surface_mesh.h"
#include "render/camera.h"
#include "render/mesh_buffers.h"

namespace sublift {

class ShaderProgram;

/// What the viewport shows. The wireframe fades as edges get shorter than about ten pixels on
/// screen, so a dense scan shows its shape rather than a black mesh of lines.
struct DisplayOptions {
  bool shaded = true;
  bool wireframe = true;
};

/// GPU copy of one mesh and the programs to draw it; needs a current GL 3.3 context.
class MeshRenderer {
 public:
  /// Compiles the mesh and line shaders; throws ShaderError.
  MeshRenderer();
  ~MeshRenderer();
  MeshRenderer(const MeshRenderer&) = delete;
  MeshRenderer& operator=(const MeshRenderer&) = delete;

  /// Replaces the drawn mesh (triangulates, computes normals and edges, uploads).
  void upload(const SurfaceMesh& mesh);
  /// Draws into the current framebuffer and viewport with depth testing.
  void draw(const OrbitCamera& camera, const DisplayOptions& options) const;
  /// Bounds of the uploaded mesh, for framing.
  const Bounds& bounds() const { return bounds_; }

 private:
  std::unique_ptr<ShaderProgram> fill_program_, line_program_;
  unsigned fill_vao_ = 0, fill_vbo_ = 0, fill_ebo_ = 0;
  unsigned line_vao_ = 0, line_vbo_ = 0, line_ebo_ = 0;
  unsigned curve_vao_ = 0, curve_ebo_ = 0;  // polylines; shares line_vbo_
  int triangle_index_count_ = 0, edge_index_count_ = 0, curve_index_count_ = 0;
  glm::dvec3 center_{0.0};
  double mean_edge_length_ = 0.0;  // world units, for fading dense wireframes
  Bounds bounds_;
};

}  // namespace sublift
