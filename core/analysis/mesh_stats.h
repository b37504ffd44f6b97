#pragma once
// Counts and topology facts of a SurfaceMesh, as `sublift-cli info` and the GUI panel show them.
#include <cstddef>
#include <map>

#include <glm/vec3.hpp>

#include "core/base/surface_mesh.h"

namespace sublift {

struct MeshStats {
  std::size_t vertices = 0;          // all vertices in the file
  std::size_t used_vertices = 0;     // referenced by at least one face
  std::size_t edges = 0;             // undirected edges of the faces
  std::size_t faces = 0;
  std::map<std::size_t, std::size_t> face_sizes;  // corners -> number of faces
  std::map<std::size_t, std::size_t> valences;    // edges at a used vertex -> number of vertices
  std::size_t boundary_edges = 0;    // edges with exactly one face
  std::size_t boundary_loops = 0;    // connected components of the boundary-edge graph
  std::size_t non_manifold_edges = 0;     // edges with more than two faces
  std::size_t non_manifold_vertices = 0;  // used vertices whose face fan is not one disc/half-disc
  std::size_t misoriented_edges = 0;      // edges used twice in the same direction
  std::size_t isolated_vertices = 0;  // used by no face and no polyline
  std::size_t polylines = 0;         // OBJ `l` lines
  std::size_t closed_polylines = 0;  // first vertex == last vertex
  std::size_t polyline_segments = 0;
  std::size_t polyline_vertices = 0;  // distinct vertices on polylines
  std::size_t components = 0;        // connected components of the faces
  long long euler_characteristic = 0;  // used_vertices - edges + faces
  glm::dvec3 bbox_min{0.0}, bbox_max{0.0};  // over used vertices (else polyline vertices, else all)
};

/// Computes the stats in O(corners log corners); never throws on a valid SurfaceMesh.
MeshStats compute_mesh_stats(const SurfaceMesh& mesh);

}  // namespace sublift
