#pragma once
// `.sublift` projects (docs/file_formats.md): a hierarchy saved exactly — base complex with
// every feature dim, scheme, integer flag, levels, channels and all coefficients, bit for bit.
//
// Layout: line 1 `sublift-project 1`; line 2 a one-line JSON header (counts, scheme, ...);
// then a little-endian binary payload whose size the header fixes (checked against the file
// size before anything is read): u32 edge_verts[2E], face_offsets[F+1], face_verts[SF],
// face_edges[SF], cell_offsets[C+1], cell_faces[CF]; u8 vertex_dim[V], edge_dim[E],
// face_dim[F]; f64 coefficients[N] in hierarchy.h's layout.
#include <string>

#include "core/hierarchy.h"

namespace sublift {

/// Writes `h` to `path` atomically. Throws IoError.
void write_project(const std::string& path, const Hierarchy& h);

/// Reads a project and rebuilds its hierarchy (levels, tables, coefficients). Throws
/// InputError (bad magic or version, malformed header, truncated or oversized payload,
/// inconsistent counts, invalid base complex, non-finite coefficients) or IoError.
Hierarchy read_project(const std::string& path);

/// The same from memory; `name` is used in messages.
Hierarchy read_project_from_memory(const std::string& name, const std::string& bytes);

/// Largest number of levels a project or command accepts.
inline constexpr int kMaxLevels = 12;

}  // namespace sublift
