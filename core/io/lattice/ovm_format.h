#pragma once
// OpenVolumeMesh's ASCII `.ovm` format (docs/file_formats.md): the polyhedral lattices of the
// volume-mesh community's library.
//
//   OVM ASCII                 header (OpenVolumeMesh also reads files without it)
//   Vertices / n / x y z ...  positions
//   Edges / n / a b ...       edge e runs a -> b; half-edge 2e is a -> b, 2e + 1 is b -> a
//   Faces / n / d h1 .. hd    a face as its cycle of half-edges; half-face 2f runs that way
//   Polyhedra / n / d f1 .. fd  a cell as its half-faces, each pointing into the cell by the
//                             right-hand rule (OpenVolumeMesh's hexahedron kernel takes the
//                             front face 0-1-2-3 as 3-2-1-0; files written by OpenVolumeMesh do so)
//   vprop double "name" ...   optional property blocks: one value per entity and line
//
// The reader is strict (an InputError names file and line), checks every count against the
// bytes left before reserving anything, and accepts cells whose half-faces are not consistently
// oriented (Sublift orients cells from their geometry) with a warning naming them. A vertex
// property of one number per vertex (double, float or an integer type) is a material value and
// becomes an attribute channel; other property blocks are read past and named in the report's
// not-kept list. The writer prints 17 significant digits, gives every cell its inward half-faces,
// writes attributes as `vprop double` blocks and replaces the file atomically.
#include <span>
#include <string>
#include <string_view>

#include "core/complex/shape.h"

namespace sublift {

/// Parses an ASCII `.ovm` text; `file` names it in messages. Throws InputError.
Shape read_ovm(std::string_view bytes, const std::string& file);

/// Writes a volume complex (dim 3) and its positions (3 per vertex). Throws InputError (not a
/// volume) or IoError.
void write_ovm(const std::string& path, const Complex& c, std::span<const double> xyz,
               std::span<const VertexAttribute> attributes = {});

}  // namespace sublift
