#pragma once
// Resampling a closed, roughly star-shaped surface onto a subdivided octahedron, the way paper
// 004 prepared its examples (sec. 7.4-7.5: a head scan sampled onto an octahedron split 1-to-4
// six times). A ray leaves the surface's centroid towards every vertex of the geodesic sphere
// (the octahedron refined J times by refine_tri, each new vertex's direction the normalised sum
// of its edge's end directions); the vertex is placed where the ray leaves the surface.
//
// Choices (docs/resample_sphere.md):
//   centroid   the volume centroid (signed tetrahedra) when every polygon edge is used equally
//              often in both directions (closed, consistently oriented) and the enclosed volume
//              is not ~0; otherwise the area-weighted centroid of the polygons.
//   hit        the farthest intersection along the ray (the outer surface). Intersections whose
//              ray parameters differ by less than kSameHitEpsilon * (bounding-box diagonal) are
//              one hit (a ray through an edge or vertex shared by several triangles).
//   misses     rays that meet nothing (open meshes, holes, a centroid outside the surface) get
//              the mean radius of their already-known neighbours on the sphere mesh, ring by ring
//              inwards from the hit region (`fill_rounds` rings).
//
// Vertex order: the fine vertices are in refine_tri's (the engine's) order, old vertices first,
// so the base octahedron's six vertices are the first six fine ones, and `sublift-cli analyze
// FINE --base BASE` refines BASE to exactly this numbering.
//
// The rays are cast through core/base/triangle_bvh.h (all intersections of each ray).
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "core/complex/complex.h"
#include "core/base/surface_mesh.h"
#include "core/base/triangle_bvh.h"

namespace sublift {

/// Largest number of 1-to-4 splits resample_sphere accepts (4 194 306 vertices).
inline constexpr int kMaxSphereLevels = 10;

/// Two intersections closer than this times the mesh's bounding-box diagonal along a ray are one.
inline constexpr double kSameHitEpsilon = 1e-9;

/// Vertices of the octahedron refined `levels` times: 2 + 4^(levels+1) (levels >= 0).
std::uint64_t sphere_vertex_count(int levels);

/// The octahedron: vertices +x, -x, +y, -y, +z, -z (0..5), 8 triangles counterclockwise seen
/// from outside, built by complex_from_polygons (so a written and re-read copy has its edges).
Complex octahedron_complex();

/// The base octahedron, its `levels`-times refine_tri refinement and the unit direction of every
/// fine vertex (base: the axes; a midpoint: normalize(dir_a + dir_b), level by level).
struct GeodesicSphere {
  Complex base;
  Complex fine;                           // with adjacency
  std::vector<glm::dvec3> directions;     // one per fine vertex, engine order
};

/// Builds the geodesic sphere of `levels` splits. Throws Error for levels outside
/// 0..kMaxSphereLevels.
GeodesicSphere geodesic_sphere(int levels);

/// Which centroid the rays start from.
enum class CentroidKind : std::uint8_t { Volume, Area };
const char* centroid_kind_name(CentroidKind kind);

struct MeshCentroid {
  glm::dvec3 point{0.0};
  CentroidKind kind = CentroidKind::Area;
};

/// The volume centroid of a closed mesh with non-negligible volume, else the area-weighted
/// centroid of its (fan-triangulated) polygons. Throws TopologyError for a mesh without faces.
MeshCentroid mesh_centroid(const SurfaceMesh& mesh);

/// What resample_sphere returns.
struct SphereResample {
  Complex base;                        // the octahedron (octahedron_complex())
  Complex fine;                        // base refined `levels` times by refine_tri, with adjacency
  std::vector<double> positions;       // x, y, z per fine vertex, engine order
  std::vector<double> base_positions;  // x, y, z of the 6 base vertices (= first 18 of positions)
  MeshCentroid centroid;
  std::size_t rays = 0;                // one per fine vertex
  std::size_t missed = 0;              // rays that met no triangle (filled from neighbours)
  std::size_t multiple_hits = 0;       // rays with more than one distinct intersection
  int fill_rounds = 0;                 // rings of neighbour averaging needed to fill the misses
};

/// Samples `mesh` onto the octahedron refined `levels` times by rays from its centroid: each
/// fine vertex goes to centroid + r * direction, r the farthest hit (misses filled from their
/// neighbours). Parallel over rays. Throws TopologyError for a mesh without faces or when no ray
/// meets the mesh, Error for levels outside 0..kMaxSphereLevels.
SphereResample resample_sphere(const SurfaceMesh& mesh, int levels);

}  // namespace sublift
