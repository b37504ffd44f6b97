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
/// OBJ writes `mesh.uv` as `vt` lines and `f v/vt` corners, and, with `mtllib` given, refers to
/// that material library and uses its material "texture" for every face.
void write_surface_mesh(const std::string& path, const SurfaceMesh& mesh, const std::string& mtllib = "");

/// Formats a double with 17 significant digits (shortest exact form is not required).
std::string format_double(double v);

/// The names of `attributes` a file of extension `ext` cannot hold, comma-separated ("" when
/// it holds them all): .ply, .gltf/.glb, .vtk (POINT_DATA) and .ovm (vertex properties) every
/// one, .obj red, green and blue together (`v x y z r g b`, as 0..1), other formats none. write_surface_mesh writes what it can and leaves the rest.
std::string attributes_not_written(const std::string& ext, std::span<const VertexAttribute> attributes);

/// Writes `prefix`, then p[0] p[1] p[2] by format_double, then a newline.
void write_xyz_line(std::ostream& out, const char* prefix, const double* p);

}  // namespace sublift
