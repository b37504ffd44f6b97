#pragma once
// The one import layer for surface meshes (OBJ, OFF, PLY ASCII and binary). Every reader here
// is our own bounded parser: counts are checked against the file size before anything is
// allocated, numbers must be finite, indices in range. Structural faults throw InputError
// (file, line, reason). Repairable faults (bad faces, isolated vertices, unknown tags) load and
// are itemised in ImportReport. Vertices are never renumbered: the mesh keeps file order.
#include <cstddef>
#include <string>
#include <vector>

#include "core/surface_mesh.h"

namespace sublift {

/// One kind of repaired or ignored element: what, how many, first few source lines.
struct ImportWarning {
  std::string what;
  std::size_t count = 0;
  std::vector<std::size_t> first_lines;  // at most ImportReport::kMaxLines, 1-based (0 = n/a)
};

struct ImportReport {
  static constexpr std::size_t kMaxLines = 5;
  std::vector<ImportWarning> warnings;
  /// Records one occurrence of `what` at `line` (merged with earlier ones of the same kind).
  void add(const std::string& what, std::size_t line);
  bool empty() const { return warnings.empty(); }
  /// Human-readable, one line per kind: "dropped 2 faces with an index out of range (lines 5, 9)".
  std::string format(const std::string& file) const;
};

struct LoadedMesh {
  SurfaceMesh mesh;
  ImportReport report;
};

/// Limits that keep a hostile file from costing unbounded time or memory.
struct ImportLimits {
  std::size_t max_line_length = 1 << 20;   // bytes; longer lines are an error
  std::size_t max_face_size = 1 << 16;     // corners of one polygon
};

/// Reads OBJ, OFF or PLY, chosen by extension (case-insensitive). Throws InputError or IoError.
LoadedMesh import_surface_mesh(const std::string& path, const ImportLimits& limits = {});

/// The same from memory; `name` is used in messages and to pick the format by extension.
LoadedMesh import_surface_mesh_from_memory(const std::string& name, const std::string& bytes,
                                           const ImportLimits& limits = {});

}  // namespace sublift
