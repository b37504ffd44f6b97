#pragma once
// What an importer says about a file beside the data: repaired or ignored elements by kind,
// with their first source lines. Plain data, shared by every reader and by the complex
// builders that repair on import.
#include <cstddef>
#include <string>
#include <vector>

#include "core/base/surface_mesh.h"

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
  /// Per-corner or per-vertex data the file carries and the surface mesh does not keep (OBJ
  /// texture coordinates `vt`, normals `vn`, materials `usemtl`), by name and count. Not
  /// warnings for reading; commands that promise to give the file back (rebuild) name them.
  std::vector<ImportWarning> not_kept;
  void note_not_kept(const std::string& what, std::size_t line);
  /// Names `attributes` as not kept, for commands that carry positions only (rebuild, fit, the
  /// modeler): "4 values of the vertex attributes red, green, blue".
  void note_attributes_not_kept(const std::vector<VertexAttribute>& attributes);
  /// "4 texture coordinates (vt), 1 normals (vn)"; empty when nothing.
  std::string not_kept_summary() const;
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

}  // namespace sublift
