#include "render/mesh_buffers.h"

#include <algorithm>
#include <utility>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "core/complex/polygon_normal.h"

namespace sublift {

Bounds drawn_bounds(const SurfaceMesh& mesh) {
  Bounds bounds;
  auto include = [&bounds](const glm::dvec3& p) {
    if (bounds.empty) {
      bounds.min = bounds.max = p;
      bounds.empty = false;
    } else {
      bounds.min = glm::min(bounds.min, p);
      bounds.max = glm::max(bounds.max, p);
    }
  };
  for (const std::uint32_t v : mesh.face_indices) include(mesh.positions[v]);
  for (const std::uint32_t v : mesh.line_indices) include(mesh.positions[v]);
  if (bounds.empty) {
    for (const glm::dvec3& p : mesh.positions) include(p);
  }
  return bounds;
}

glm::dvec3 newell_normal(const SurfaceMesh& mesh, std::span<const std::uint32_t> corners) {
  // glm::dvec3 holds three packed doubles: the positions are a flat xyz array.
  static_assert(sizeof(glm::dvec3) == 3 * sizeof(double));
  double n[3];
  polygon_area_vector(corners, &mesh.positions.data()->x, n);
  return {n[0], n[1], n[2]};
}

MeshBuffers build_mesh_buffers(const SurfaceMesh& mesh) {
  MeshBuffers out;
  const Bounds bounds = drawn_bounds(mesh);
  if (!bounds.empty) out.center = 0.5 * (bounds.min + bounds.max);
  auto local = [&out](const glm::dvec3& p) { return glm::vec3(p - out.center); };

  out.corners.reserve(mesh.face_indices.size());
  // A k-gon fans into k - 2 triangles.
  if (mesh.face_indices.size() >= 2 * mesh.num_faces()) {
    out.triangles.reserve(3 * (mesh.face_indices.size() - 2 * mesh.num_faces()));
  }
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
  edges.reserve(mesh.face_indices.size());
  for (std::size_t f = 0; f < mesh.num_faces(); ++f) {
    const auto corners = mesh.face(f);
    const glm::dvec3 n = newell_normal(mesh, corners);
    const double length = glm::length(n);
    const glm::vec3 normal = length > 0.0 ? glm::vec3(n / length) : glm::vec3(0.0f);
    const auto first = static_cast<std::uint32_t>(out.corners.size());
    for (std::size_t i = 0; i < corners.size(); ++i) {
      out.corners.push_back({local(mesh.positions[corners[i]]), normal});
      const std::uint32_t a = corners[i], b = corners[(i + 1) % corners.size()];
      edges.emplace_back(std::min(a, b), std::max(a, b));
    }
    for (std::uint32_t i = 1; i + 1 < corners.size(); ++i) {
      out.triangles.insert(out.triangles.end(), {first, first + i, first + i + 1});
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  out.edges.reserve(2 * edges.size());
  for (const auto& [a, b] : edges) out.edges.insert(out.edges.end(), {a, b});

  for (std::size_t l = 0; l < mesh.num_polylines(); ++l) {
    const auto vertices = mesh.polyline(l);
    for (std::size_t i = 0; i + 1 < vertices.size(); ++i) {
      out.polyline_segments.insert(out.polyline_segments.end(), {vertices[i], vertices[i + 1]});
    }
  }

  out.vertex_positions.reserve(mesh.num_vertices());
  for (const glm::dvec3& p : mesh.positions) out.vertex_positions.push_back(local(p));
  return out;
}

}  // namespace sublift
