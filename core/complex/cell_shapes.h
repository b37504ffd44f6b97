#pragma once
// The standard cell shapes of VTK (tetrahedron, hexahedron, wedge, pyramid) as face loops in
// VTK's vertex numbering, and the inverse question for writers: the outward face loops of a
// complex's cell, and its VTK_HEXAHEDRON vertex order when it is a topological cube.
//
// VTK numbering (VTK file formats, "Linear cell types"): hexahedron 0-1-2-3 one quad, 4-5-6-7
// the opposite one with i+4 above i; wedge 0-1-2 and 3-4-5 triangles with i+3 above i; pyramid
// 0-1-2-3 base and apex 4; tetrahedron 0-1-2 and apex 3. Face tables are VTK's (vtkHexahedron,
// vtkWedge, vtkPyramid, vtkTetra), outward for a positively oriented cell.
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/complex/complex.h"

namespace sublift {

enum class CellShape : std::uint8_t { Tetrahedron, Hexahedron, Wedge, Pyramid };

/// Number of vertices of a standard shape (4, 8, 6, 5).
int cell_shape_vertex_count(CellShape s);

/// Lower-case name ("tetrahedron", ...).
std::string cell_shape_name(CellShape s);

/// Faces of a standard shape as loops of local vertex numbers (VTK order and orientation).
const std::vector<std::vector<int>>& cell_shape_faces(CellShape s);

/// The face loops of cell k oriented consistently across its edges and outward (positive
/// signed volume) under `xyz` (3 doubles per vertex; empty: orientation of the first face kept).
/// Needs nothing but the downward connectivity of `c`.
std::vector<std::vector<std::uint32_t>> oriented_cell_loops(const Complex& c, std::span<const double> xyz,
                                                            std::uint32_t k);

/// The face loops of every cell, oriented consistently across each cell's edges and across
/// the faces its neighbours share (a shared face runs opposite ways in its two cells), each
/// connected component outward by its total signed volume under `xyz`. Writers use this, so
/// a lattice Sublift writes is consistently oriented even where some cells are inverted.
std::vector<std::vector<std::vector<std::uint32_t>>> oriented_lattice_loops(const Complex& c,
                                                                            std::span<const double> xyz);

/// The 8 vertices of a cell given by outward loops in VTK_HEXAHEDRON order when the loops
/// are 6 quads forming a topological cube; nullopt otherwise.
std::optional<std::array<std::uint32_t, 8>> hexahedron_vertices(const std::vector<std::vector<std::uint32_t>>& loops);

}  // namespace sublift
