#pragma once
// Exporting a surface with per-vertex normals (a level's limit surface or control net, or the
// boundary of a lattice) as OBJ, PLY, glTF or GLB, chosen by extension.
//
// Formats: .obj `v` and `vn` lines with 17 significant digits and `f a//a b//b ...` corners;
// .ply binary little endian with float64 x y z nx ny nz and faces as `list uchar uint32`
// (`list uint uint32` when a face has more than 255 corners); .gltf (JSON, the buffer embedded
// as a base64 data URI) and .glb through tinygltf: one scene, node, mesh and TRIANGLES primitive
// with float32 POSITION (with min/max), float32 unit NORMAL and uint32 indices, polygons
// triangulated as fans from their first corner, asset.generator "Sublift". Every file is
// replaced atomically (file_io.h), so a failed save leaves the previous file intact.
#include <span>
#include <string>
#include <vector>

#include "core/base/csr.h"
#include "core/base/surface_mesh.h"

namespace sublift {

/// Writes a polygon surface (faces as CSR corner lists, positions and unit normals 3 doubles
/// per vertex) to path by extension (.obj, .ply, .gltf, .glb). Normals off unit length by more
/// than 1e-12 are renormalised, a zero normal is written as (0, 0, 1). Throws InputError
/// (unknown extension, sizes that do not match, a face of fewer than 3 corners or naming a
/// missing vertex, no face at all, values not finite or beyond the supported magnitude) or IoError (write failure).
/// glTF also takes per-vertex `attributes`: red, green, blue (and alpha) as COLOR_0 (float VEC4;
/// uchar values / 255, everything clamped to 0..1, alpha 1 when absent), every other attribute
/// as an application-specific float SCALAR attribute "_NAME" (upper case, other characters '_').
/// OBJ and PLY ignore them (core/io/mesh writes a level's attributes).
/// `uv` (one index per corner of `faces`), when given, goes to OBJ as `vt` and `f v/vt/vn` and to
/// glTF as TEXCOORD_0 (t = 1 - v), the glTF vertices split wherever a vertex has corners with
/// different UVs (normals, colours and attributes copied to each part); PLY ignores it. `texture`
/// (glTF only, with uv) becomes the primitive's material: the image embedded in the buffer, its
/// sampler and factors as read. Returns what the format could not hold, named (OBJ and PLY:
/// the attributes; PLY: the UVs; OBJ and PLY: the texture); empty when nothing was left out.
std::vector<std::string> write_surface_with_normals(const std::string& path, const Csr& faces, std::span<const double> xyz,
                                std::span<const double> normals, std::span<const VertexAttribute> attributes = {},
                                const FaceVaryingUV* uv = nullptr, const SurfaceTexture* texture = nullptr);

/// True for the extensions write_surface_with_normals accepts (".obj", ".ply", ".gltf", ".glb",
/// any case).
bool surface_export_supported(const std::string& path);

}  // namespace sublift
