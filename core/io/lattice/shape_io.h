#pragma once
// Reading and writing any supported shape by extension: surfaces (.obj/.off/.ply through the
// import layer), curves (.obj holding only `l` polylines), lattices (.lattice, .ovm, .vtk; .vtk may
// also hold a surface or curve). Output vertices are in the complex's order, which for a
// refined level is refine.h's numbering.
#include <span>
#include <string>
#include <vector>

#include "core/complex/shape.h"

namespace sublift {

/// Reads `path` by extension into a base complex and positions. A .gltf/.glb opens as one
/// surface: its triangles in world space, vertices welded by position (import_model's sandbox
/// and checks apply). Throws InputError or IoError.
Shape read_shape(const std::string& path);

/// The same from memory; `name` picks the format by extension and names it in messages.
Shape read_shape_from_memory(const std::string& name, const std::string& bytes);

/// Writes complex `c` with positions `xyz` (3 per vertex) in the format of path's extension:
/// dim 2 to .obj (faces, `t crease`/`t corner` tags that reproduce its features), .off or .ply
/// (faces only); dim 1 to .obj (`l` polylines, `t corner` tags); dim 3 to .lattice; any dim to
/// .vtk. `attributes` (one value per vertex each) go to .ply as properties, and red, green and
/// blue to .obj as `v x y z r g b`. `uv` (per corner of c.faces, a surface's) goes to .obj as
/// `vt` and to .gltf/.glb as TEXCOORD_0; `texture` (the image the UVs map) to .gltf/.glb as the
/// material, to .obj as a material library and the image file beside it (OUT.mtl,
/// OUT_<image name>). Returns notes on what the format could not hold (empty when nothing was
/// lost). Throws InputError (extension that cannot hold this dimension, UVs that do not fit the
/// faces) or IoError.
std::vector<std::string> write_shape(const std::string& path, const Complex& c, std::span<const double> xyz,
                                     std::span<const VertexAttribute> attributes = {}, const FaceVaryingUV* uv = nullptr,
                                     const SurfaceTexture* texture = nullptr);

/// Empty when write_shape can write a complex of dimension `dim` to `path`; else the reason.
std::string shape_output_problem(const std::string& path, int dim);

}  // namespace sublift
