#pragma once
// The boundary surface of a volume lattice: the faces that bound exactly one cell, oriented
// outward, for display and export of a lattice level as a polygon surface.
//
// Orientation. Each cell is a closed polyhedron, so its faces can be oriented consistently from
// the topology alone: two faces of the cell that share an edge must run it in opposite
// directions. Walking the cell's faces that way gives one of the two consistent orientations;
// the sign of the cell's volume (divergence theorem over the faces, fan-triangulated) picks the
// outward one. This holds for non-convex cells as well (any closed cell whose faces do not
// intersect each other), unlike a comparison with the cell centroid, which assumes convex cells.
// A degenerate cell of zero volume keeps the orientation the walk gives.
#include <cstdint>
#include <span>
#include <vector>

#include "core/complex/complex.h"

namespace sublift {

/// Faces of a dim-3 complex that bound exactly one cell, each oriented so its normal (Newell,
/// right-hand rule over the corner order) points out of its cell, given positions (3 per
/// vertex); `face_ids` receives the complex face index of each output face (ascending). For
/// dim 2 (and 1) returns the complex's own faces unchanged (face_ids = 0..F-1). A reversed face
/// keeps its first corner. Throws Error when xyz holds fewer than 3 values per vertex and
/// TopologyError for a cell that is not closed.
Csr boundary_faces(const Complex& c, std::span<const double> xyz, std::vector<std::uint32_t>* face_ids = nullptr);

}  // namespace sublift
