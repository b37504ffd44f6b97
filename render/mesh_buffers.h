#pragma once
// CPU side of mesh drawing, no GL: what MeshRenderer uploads. Kept apart so tests can check the
// triangulation, normals and edge list without a context.
//
// Layout: fill geometry has one vertex per face corner (face order, then corner order) carrying
// the face's Newell normal, so shading is flat; `triangles` fans each polygon from its first
// corner. Line geometry has one vertex per mesh vertex; `edges` holds each undirected polygon
// edge once (never a fan diagonal), sorted, and `polyline_segments` the segments of the mesh's
// polylines (curves), which are drawn whatever the wireframe toggle says. Positions are floats
// relative to `center`, the centre of the drawn bounds, so large coordinates keep their
// precision near the model.
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "core/base/surface_mesh.h"

namespace sublift {

struct Bounds {
  glm::dvec3 min{0.0}, max{0.0};
  bool empty = true;  // no vertex at all
};

struct CornerVertex {
  glm::vec3 position;
  glm::vec3 normal;  // unit face normal; zero for a degenerate face
};

struct MeshBuffers {
  glm::dvec3 center{0.0};
  std::vector<CornerVertex> corners;
  std::vector<std::uint32_t> triangles;       // 3 indices into `corners` per triangle
  std::vector<glm::vec3> vertex_positions;    // one per mesh vertex
  std::vector<std::uint32_t> edges;           // 2 indices into `vertex_positions` per edge
  std::vector<std::uint32_t> polyline_segments;  // 2 indices per segment, in polyline order
};

/// Bounds of the vertices used by faces or polylines; of all vertices when none is used.
Bounds drawn_bounds(const SurfaceMesh& mesh);

/// Newell's normal of polygon `corners` (not normalised; its length is twice the area of a
/// planar polygon), robust for non-convex and slightly non-planar polygons.
glm::dvec3 newell_normal(const SurfaceMesh& mesh, std::span<const std::uint32_t> corners);

/// Builds the fill and line geometry described above. O(corners log corners).
MeshBuffers build_mesh_buffers(const SurfaceMesh& mesh);

}  // namespace sublift
