#pragma once
// Internal to the import layer: collects faces as raw (already 0-based, possibly invalid)
// indices with their source lines, then validates them all at once against the final vertex
// count. One place decides what is dropped or repaired, so OBJ, OFF and PLY behave alike.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/base/import_report.h"

namespace sublift {

class FaceBuilder {
 public:
  /// Records one face; indices are 0-based (invalid ones are caught in finish()). `uvs`, when
  /// not empty, gives each corner's 0-based texture-coordinate index (-1: the corner has none);
  /// pass it empty when no corner has one.
  void add(std::span<const std::int64_t> corners, std::size_t line, std::span<const std::int64_t> uvs = {});
  /// Records a face that could not even be parsed (dropped with `reason`).
  void add_unreadable(std::size_t line, ImportReport& report, const char* reason);
  /// Faces that use vertex v are dropped (v stands for an unreadable vertex line).
  void mark_unusable_vertex(std::size_t v) { unusable_.push_back(v); }
  std::size_t size() const { return lines_.size(); }
  /// Validates every face against `mesh.num_vertices()` and appends the good ones to `mesh`:
  /// out-of-range indices, fewer than 3 corners, repeated vertices and duplicate faces are
  /// dropped (consecutive repeats are collapsed first), each itemised in `report`.
  /// When `mesh.uv.points` is not empty the kept faces' UV indices go to `mesh.uv.corners`; if a
  /// kept face has a corner without one, or one beyond the points, the UVs are dropped and named
  /// in `report` with that face's line (a UV set must cover every corner).
  void finish(SurfaceMesh& mesh, ImportReport& report) const;
  /// Vertices marked with mark_unusable_vertex().
  std::span<const std::size_t> unusable() const { return unusable_; }

 private:
  std::vector<std::int64_t> indices_;
  std::vector<std::int64_t> uvs_;  // parallel to indices_ (-1: no UV), empty until a corner has one
  std::vector<std::size_t> offsets_{0};
  std::vector<std::size_t> lines_;
  std::vector<std::size_t> unusable_;
};

/// Collects polylines (OBJ `l` lines) like FaceBuilder collects faces, validated at the end.
class PolylineBuilder {
 public:
  /// Records one polyline; indices are 0-based (invalid ones are caught in finish()).
  void add(std::span<const std::int64_t> vertices, std::size_t line);
  std::size_t size() const { return lines_.size(); }
  /// Appends the good polylines to `mesh`: out-of-range or unreadable-vertex indices, fewer
  /// than 2 distinct vertices and segments used twice drop the polyline; consecutive repeats
  /// are collapsed. Each case is itemised in `report`. `unusable` as in FaceBuilder.
  void finish(SurfaceMesh& mesh, std::span<const std::size_t> unusable, ImportReport& report) const;

 private:
  std::vector<std::int64_t> indices_;
  std::vector<std::size_t> offsets_{0};
  std::vector<std::size_t> lines_;
};

/// Post-import checks shared by all readers: refuses a mesh without faces and polylines
/// (naming what was dropped) and reports vertices no face or polyline uses.
/// `vertex_lines[v]` is the source line of vertex v (may be empty when unknown).
void check_imported_mesh(const std::string& file, const SurfaceMesh& mesh,
                         std::span<const std::size_t> vertex_lines, ImportReport& report);

}  // namespace sublift
