#pragma once
// Internal to the lattice and VTK readers: collects cells (as face loops), polygons, polylines
// and feature tags with their source lines, checks each element on its own so that an error
// names the line it came from, then builds the Complex with complex_build.h. The highest-
// dimensional elements present are the shape (cells: a lattice; else polygons: a surface; else
// polylines: a curve); tags name its vertices, edges and faces.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/complex/shape.h"

namespace sublift {

/// What to do with a tag that names no vertex, edge or face of the shape.
enum class TagPolicy : std::uint8_t { Strict, Warn };

class ShapeBuilder {
 public:
  /// Starts a cell (ended by the next begin_cell or by build); `label` names it in messages
  /// ("cell 3", "cell 17 (VTK_WEDGE)").
  void begin_cell(std::size_t line, std::string label);
  /// Adds one face loop (0-based indices, checked in build) to the current cell.
  void add_cell_face(std::span<const std::int64_t> loop, std::size_t line);
  /// Adds a polygon (a face of a surface, or a feature-face tag when cells are present).
  void add_polygon(std::span<const std::int64_t> loop, std::size_t line, std::string label);
  /// Adds a polyline (a curve, or crease tags when polygons or cells are present).
  void add_polyline(std::span<const std::int64_t> chain, std::size_t line, std::string label);
  /// Tags vertex v as a corner (cusp).
  void add_corner(std::int64_t v, std::size_t line);
  /// Tags a chain of crease edges v0-v1, v1-v2, ...
  void add_crease(std::span<const std::int64_t> chain, std::size_t line);
  /// Tags the face with this vertex loop (either orientation) as a surface feature.
  void add_feature_face(std::span<const std::int64_t> loop, std::size_t line);
  /// Cells begun so far.
  std::size_t num_cells() const { return cells_.size(); }

  /// Validates everything against `num_vertices` and builds the complex into `shape.base`
  /// (positions are the caller's). Throws InputError(file, line, reason); tags that name
  /// nothing are errors under Strict and itemised in shape.report under Warn. Vertices no
  /// element uses are reported (`vertex_lines[v]` is v's source line, may be empty).
  void build(const std::string& file, std::uint32_t num_vertices, std::span<const std::size_t> vertex_lines,
             TagPolicy policy, Shape& shape) const;

 private:
  struct Element {
    std::size_t first_loop = 0, end_loop = 0;  // loops [first, end) of loop_*
    std::size_t line = 0;
    std::string label;
  };
  struct Tag {
    std::size_t first = 0, end = 0;  // into tag_items_
    std::size_t line = 0;
  };
  std::size_t add_loop(std::span<const std::int64_t> loop, std::size_t line);

  std::vector<std::int64_t> loop_items_;
  std::vector<std::size_t> loop_offsets_{0};
  std::vector<std::size_t> loop_lines_;
  std::vector<Element> cells_, polygons_, polylines_;
  std::vector<std::int64_t> tag_items_;
  std::vector<Tag> corners_, creases_, feature_faces_;
};

}  // namespace sublift
