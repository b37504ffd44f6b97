#pragma once
// `.lattice`: Sublift's line-based text format for polyhedral lattices (docs/file_formats.md).
//
//   sublift-lattice 1          first line: magic and version
//   v x y z                    vertices, numbered from 0 in file order
//   hex a b c d e f g h        standard cells in VTK vertex order (also wedge, pyramid, tet)
//   cell                       a general polyhedron: its faces as vertex loops ...
//   f a b c d
//   end                        ... up to `end`
//   corner v / crease a b [c ...] / feature_face a b c ...   feature tags
//
// The reader is strict (any fault is an InputError naming file and line); the writer prints 17
// significant digits and replaces the file atomically.
#include <span>
#include <string>
#include <string_view>

#include "core/complex/shape.h"

namespace sublift {

/// Parses a `.lattice` text; `file` names it in messages. Throws InputError.
Shape read_lattice(std::string_view bytes, const std::string& file);

/// Writes a volume complex (dim 3) and its positions (3 per vertex): hexahedra as `hex`, other
/// cells as `cell` blocks with outward loops, and the tags that reproduce its feature dims.
/// Throws InputError (not a volume) or IoError.
void write_lattice(const std::string& path, const Complex& c, std::span<const double> xyz);

}  // namespace sublift
