#pragma once
// Writing surface meshes: OBJ (with `l` polylines and `t` tags), OFF and ASCII PLY (faces only),
// chosen by extension.
// Coordinates use 17 significant digits so that a write/read round trip is exact; the file is
// replaced atomically, so a failed save leaves the previous file intact.
#include <iosfwd>
#include <string>

#include "core/base/surface_mesh.h"

namespace sublift {

/// Writes `mesh` to `path` in the format of its extension. Throws IoError or InputError
/// (unsupported extension, or a curve without faces to .off/.ply). OFF and PLY keep faces only.
void write_surface_mesh(const std::string& path, const SurfaceMesh& mesh);

/// Formats a double with 17 significant digits (shortest exact form is not required).
std::string format_double(double v);

/// Writes `prefix`, then p[0] p[1] p[2] by format_double, then a newline.
void write_xyz_line(std::ostream& out, const char* prefix, const double* p);

}  // namespace sublift
