#pragma once
// Counts and topology facts of a SurfaceMesh, as `sublift-cli info` and the GUI panel show them.
#include <cstddef>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "core/base/import_report.h"
#include "core/base/surface_mesh.h"
#include "core/complex/complex.h"

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
  // The first kFirstElements of each (vertices ascending, edges by their vertex pair), for
  // warnings that name them.
  static constexpr std::size_t kFirstElements = 5;
  std::vector<std::uint32_t> first_non_manifold_vertices;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> first_non_manifold_edges;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> first_misoriented_edges;
  std::size_t isolated_vertices = 0;  // used by no face and no polyline
  std::size_t polylines = 0;         // OBJ `l` lines
  std::size_t closed_polylines = 0;  // first vertex == last vertex
  std::size_t polyline_segments = 0;
  std::size_t components = 0;        // connected components of the faces
  long long euler_characteristic = 0;  // used_vertices - edges + faces
  glm::dvec3 bbox_min{0.0}, bbox_max{0.0};  // over used vertices (else polyline vertices, else all)
};

/// Computes the stats in O(corners log corners); never throws on a valid SurfaceMesh.
MeshStats compute_mesh_stats(const SurfaceMesh& mesh);

/// The one text of the topology warnings (non-manifold vertices and edges, inconsistent
/// orientation), as import warnings: `count` elements, `what` naming the first few, e.g.
/// "non-manifold vertex: its faces do not form one fan (vertex 4)". Empty for a clean mesh.
/// Commands that subdivide or edit print them and list them in --json `warnings`; the modeler
/// shows them with the import warnings.
std::vector<ImportWarning> topology_warnings(const MeshStats& s);

/// topology_warnings of a surface complex's faces as it holds them (file vertex numbers, file
/// orientation); empty for curves and lattices.
std::vector<ImportWarning> topology_warnings(const Complex& c);

/// Appends the topology warnings of `c` (or of `mesh`) to `report`, after its import warnings.
void add_topology_warnings(ImportReport& report, const Complex& c);
void add_topology_warnings(ImportReport& report, const SurfaceMesh& mesh);

}  // namespace sublift
