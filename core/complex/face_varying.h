#pragma once
// Face-varying texture coordinates through refinement: the linear rule (OpenSubdiv's
// FVAR_LINEAR_ALL). A child corner's UV is interpolated inside its parent face only: a corner
// keeps the parent corner's UV, an edge point takes the mean of the edge's two corner UVs in that
// face, a face point the mean of the face's corner UVs. Each face reads only its own corners, so
// seams stay where they are and every refined face maps the same part of the texture as the
// piece of its parent it covers; a linear or flat patch is mapped exactly as before.
// (OpenSubdiv's smooth face-varying rules would bend the map with the surface but move texels
// across charts near seams' ends; the linear rule keeps what the artist painted where it was.)
// Edge points are shared where the two faces meeting at an edge use the same UV points at its
// ends, so a level without seams has one UV point per vertex, as its base.
#include <span>
#include <string>
#include <vector>

#include "core/base/surface_mesh.h"
#include "core/complex/complex.h"

namespace sublift {

/// Per-vertex UVs for formats and renderers that have no face-varying data (glTF, GL): one
/// vertex per (vertex, UV point) pair the corners use. Vertex v's first pair keeps number v (so a
/// reader that welds by position numbers the vertices as before); the other pairs follow,
/// numbered in the order first met. A vertex no corner uses keeps UV (0, 0).
struct UvVertexSplit {
  Csr faces;                           // over the split vertices, corner for corner as the input
  std::vector<std::uint32_t> source;   // split vertex -> the input vertex it copies
  std::vector<double> texcoords;       // u, v per split vertex
};
/// Needs uv_problem-free input (one UV index per corner of `faces`, each below the points).
UvVertexSplit split_at_uv_seams(const Csr& faces, const FaceVaryingUV& uv, std::size_t num_vertices);
/// `values` (`width` per input vertex: positions, normals, an attribute) copied to the split vertices.
std::vector<double> at_split_vertices(const UvVertexSplit& split, std::span<const double> values, std::size_t width);

/// `uv`, given per corner of `from` (a surface's faces), carried to `to`: the same faces over the
/// same vertices listed in another order, each perhaps starting at another corner or running the
/// other way (an oriented edge names its face). Throws TopologyError naming the first face of
/// `to` that is not among `from`'s.
FaceVaryingUV uv_for_faces(const Csr& from, const FaceVaryingUV& uv, const Csr& to);

/// "" when `uv` fits the surface `c` (dim 2): one index per face corner, each below the points,
/// points finite; else what is wrong.
std::string uv_problem(const Complex& c, const FaceVaryingUV& uv);

/// The UVs of refine(c) (refine.h: one quad per parent face corner) by the linear rule.
FaceVaryingUV refine_uv_split(const Complex& c, const FaceVaryingUV& uv);

/// The UVs of refine_tri(c) (refine_tri.h: three corner triangles and a middle one per triangle).
FaceVaryingUV refine_uv_tri(const Complex& c, const FaceVaryingUV& uv);

}  // namespace sublift
