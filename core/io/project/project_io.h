#pragma once
// `.sublift` projects (docs/file_formats.md): a hierarchy saved exactly — base complex with
// every feature dim, scheme, integer flag, levels, channels and all coefficients, bit for bit.
//
// Layout: line 1 `sublift-project 2` (version 1 files are read too); line 2 a one-line JSON
// header (counts, scheme, ...); then a little-endian binary payload whose size the header fixes
// (checked against the file size before anything is read): u32 edge_verts[2E],
// face_offsets[F+1], face_verts[SF], face_edges[SF], cell_offsets[C+1], cell_faces[CF]; u8
// vertex_dim[V], edge_dim[E], face_dim[F]; the N coefficients in hierarchy.h's layout, encoded as
// the header's `encoding` says (dense f64 in version 1; coefficient_codec.h).
// Optional header keys (files without them read with the defaults):
// `current_level`, `gains` and `local_frames`, the modeler's session state (ProjectExtras), and
// `input_order` {level, vertices, faces, face_corners}: then the payload ends with u32
// engine_vertex[vertices] face_offsets[faces+1] face_verts[face_corners] (InputOrder);
// `fit_source` {mesh, mesh_vertices, base_vertex[base vertices]} (FitSource).
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/base/csr.h"
#include "core/base/surface_mesh.h"
#include "core/complex/complex.h"

#include "core/multires/hierarchy.h"

namespace sublift {

/// The vertex and face order of the file a project was rebuilt from (sublift-cli rebuild,
/// docs/rebuild.md): level `level` written through it gives that file back. Empty (level -1)
/// for projects made in Sublift's own order.
struct InputOrder {
  int level = -1;
  std::vector<std::uint32_t> engine_vertex;  // the engine vertex of each file vertex
  Csr faces;                                 // the file's faces, in file vertex numbers; no
                                             // rows for lattices (their vertex order only)
  bool empty() const { return level < 0; }
};

/// The mesh a fitted project was fitted to (sublift-cli fit, the modeler's Fit; docs/fit.md):
/// its file, its vertex count, and the mesh vertex each base vertex was decimated from
/// (BaseMesh::input_vertex), so the fit can be compared with the mesh and fitted again. Empty
/// for projects not fitted.
struct FitSource {
  std::string mesh;                          // the path the mesh was read from
  std::uint32_t mesh_vertices = 0;
  std::vector<std::uint32_t> base_vertex;    // the mesh vertex of each base vertex
  bool empty() const { return base_vertex.empty(); }
};

/// Session state a project keeps beside the hierarchy. Defaults are what a version-1 file
/// without the optional header keys means.
/// A space-time lattice's animation (core/anim/spacetime.h; docs/animation.md): the lattice is the
/// base surface (the lattice's first `surface_vertices` vertices and first `surface_faces` faces,
/// as sweep_lattice numbers them) swept over `base_steps` steps; the frames' times in seconds.
struct AnimationExtras {
  int base_steps = 0;  // 0: not an animation
  bool cyclic = false;
  std::uint32_t surface_vertices = 0, surface_faces = 0;
  std::vector<double> times;  // one per finest layer, increasing
  double loop_end = 0;        // cyclic: when the loop returns to frame 0
  bool empty() const { return base_steps == 0; }
};

struct ProjectExtras {
  int current_level = 0;      // edit level the modeler shows, 0..J
  std::vector<double> gains;  // detail gain per level 0..J-1; empty means all 1
  bool local_frames = false;  // detail kept in local frames (session.h DetailFrames::Local)
  InputOrder input_order;     // header key `input_order` and a payload tail when not empty
  FitSource fit_source;       // header key `fit_source` when not empty
  /// What channels 3.. hold beyond x, y, z (a file's colours and scalars): name and PLY type
  /// each, `values` empty. Header key `attributes`; as many as the channels after the third.
  std::vector<VertexAttribute> attributes = {};
  /// Header key `animation` when the hierarchy is a swept space-time lattice.
  AnimationExtras animation = {};
  /// The base's face-varying texture coordinates (per corner of levels[0].faces), header key
  /// `uv`; every level's follow by the linear rule (core/multires/level_uv.h).
  FaceVaryingUV uv = {};
};

/// Level `order.level`'s complex numbered as the file: a surface with the file's faces (in the
/// file's order), a lattice with the engine's cells and the file's vertex numbers.
Complex in_input_order(const InputOrder& order, const Complex& level);

/// The values of level `order.level` (channels per engine vertex) in the file's vertex order.
std::vector<double> in_input_order(const InputOrder& order, std::span<const double> level_values, int channels);

/// Empty when `order` fits `level` (a permutation of its vertices whose faces are the level's
/// faces); else what is wrong, for messages.
std::string input_order_problem(const InputOrder& order, const Complex& level);

/// What a save wrote: the coefficients' encoding (core/io/project/coefficient_codec.h), the
/// file's size, and for a quantized save the largest change of a coefficient.
struct SavedProject {
  std::string encoding;
  std::uint64_t bytes = 0;
  double max_quantization_error = 0.0;
};

/// Writes `h` and the session `extras` to `path` atomically: lossless (zero wavelets stored as a
/// bit each where that is smaller), or with `quantize_bits` 8, 16 or 32 quantized (lossy).
/// Throws Error (current_level outside 0..J, gains neither empty nor J finite values, bits
/// other than those, an integer-mode hierarchy quantized) or IoError.
SavedProject write_project(const std::string& path, const Hierarchy& h, const ProjectExtras& extras = {}, int quantize_bits = 0);

/// Reads a project and rebuilds its hierarchy (levels, tables, coefficients). Throws
/// InputError (bad magic or version, malformed header, truncated or oversized payload,
/// inconsistent counts, invalid base complex, non-finite coefficients) or IoError.
/// Fills `*extras` (if not null) from the optional header keys; its gains always hold J values
/// (all 1 when the file has none). Throws InputError naming line 2 for current_level outside
/// 0..J or gains that are not J finite numbers.
Hierarchy read_project(const std::string& path, ProjectExtras* extras = nullptr);

/// The same from memory; `name` is used in messages.
Hierarchy read_project_from_memory(const std::string& name, const std::string& bytes, ProjectExtras* extras = nullptr);

// The level limits are the scheme registry's (kMaxLevels, max_levels in core/schemes/registry.h).

}  // namespace sublift
