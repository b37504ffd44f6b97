#pragma once
// Legacy VTK unstructured grids (`.vtk`, what ParaView users have), both ways.
//
// Reading (ASCII and BINARY; classic `CELLS n size` records of versions 2-4 and the
// OFFSETS/CONNECTIVITY layout of version 5): VTK_TETRA(10), VTK_VOXEL(11), VTK_HEXAHEDRON(12),
// VTK_WEDGE(13), VTK_PYRAMID(14) and VTK_POLYHEDRON(42, face stream) are cells, converted to
// face loops with VTK's vertex orderings. The highest-dimensional cells present make the
// shape; lower-dimensional ones tag its features (Gmsh writes a model's points, curves and
// surfaces that way): VTK_VERTEX/POLY_VERTEX are corners, VTK_LINE/POLY_LINE creases,
// VTK_TRIANGLE/QUAD/PIXEL/POLYGON feature faces. Without volume cells the polygons are a
// surface, without those the lines a curve. Other cell types are refused (cell index, type,
// line). Counts are checked against the file size before anything is allocated. POINT_DATA
// become vertex attributes (SCALARS, a channel per component; VECTORS as NAME_x, _y, _z;
// COLOR_SCALARS as red, green, blue, alpha; FIELD arrays of one tuple per point): a lattice's
// material values, carried as channels. Normals, texture coordinates, tensors, lookup tables and
// every CELL_DATA array are read past and named as not kept.
//
// Writing (ASCII, version 4.2 layout): hexahedral cells (6 quads forming a topological cube)
// as VTK_HEXAHEDRON in VTK order with positive orientation, other cells as VTK_POLYHEDRON
// with outward faces, surfaces as polygons, curves as lines; features as the lower-dimensional
// cells above, so reading back gives the same feature dims; attributes as POINT_DATA SCALARS
// (double).
#include <span>
#include <string>
#include <string_view>

#include "core/complex/shape.h"

namespace sublift {

/// Parses a legacy VTK unstructured grid; `file` names it in messages. Throws InputError.
Shape read_vtk(std::string_view bytes, const std::string& file);

/// Writes a complex of any dimension and its positions (3 per vertex). Throws InputError or
/// IoError.
void write_vtk(const std::string& path, const Complex& c, std::span<const double> xyz,
               std::span<const VertexAttribute> attributes = {});

}  // namespace sublift
