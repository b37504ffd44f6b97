#pragma once
// Level sets inside a volume lattice, for looking at a scalar field given at the lattice's
// vertices: slice planes (the zero set of a plane's signed distance, coloured by the field) and
// iso-surfaces (the set where the field equals a level).
//
// Interpolation. Every cell is split into tetrahedra (cell centroid, face centroid, and the two
// ends of each face edge), with values at the centroids the mean of the cell's or face's
// vertex values; both fields are linear on each tetrahedron, and each tetrahedron crossed by the
// level set gives one triangle (one vertex sign differs) or two (two and two). This works for
// any polyhedral cell, convex or not, and the pieces of neighbouring cells meet along their
// shared faces, since a face's split depends only on that face.
//
// Output: triangles with their own three vertices (not shared, flat shading), positions and
// unit normals 3 doubles per vertex, and the carried value at each vertex. Normals point from
// where `field` is above the level to where it is below (a slice's normals point against the
// plane normal), and each triangle winds counter-clockwise about its normal.
#include <cstdint>
#include <span>
#include <vector>

#include "core/complex/complex.h"

namespace sublift {

struct ContourMesh {
  std::vector<double> xyz, normals;  // 3 per vertex, 3 vertices per triangle
  std::vector<double> value;         // the carried value per vertex
  std::size_t triangles() const { return xyz.size() / 9; }
};

/// Appends to `out` the triangles of {field = level} inside the cells of `c` (dim 3; faces and
/// cell_faces are enough), carrying `carried` (one value per vertex) by the same linear
/// interpolation. `xyz` has 3 values per vertex; `field` and `carried` one. Throws Error on
/// sizes that do not match or a complex that is not a volume.
void contour_cells(const Complex& c, std::span<const double> xyz, std::span<const double> field, double level,
                   std::span<const double> carried, ContourMesh& out);

/// The slice of `c` by the plane {p : dot(normal, p) = offset}: contour_cells of the signed
/// distance at 0, carrying `values`.
void slice_cells(const Complex& c, std::span<const double> xyz, const double normal[3], double offset,
                 std::span<const double> values, ContourMesh& out);

}  // namespace sublift
