#pragma once
// The one weld of a glTF surface: read_shape opens a glTF with it and the animation sampling
// (animation.h) numbers its frames' vertices with it, so both give the same vertices in the same
// order. glTF splits a vertex wherever its normal or UV changes, so a closed surface arrives cut
// along every seam; welding by exact position joins it again.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/base/csr.h"

namespace sublift {

/// Vertices joined where their positions are the same bits, and the triangles over them.
struct PositionWeld {
  std::vector<std::uint32_t> welded;  // input vertex -> welded vertex
  std::vector<std::uint32_t> first;   // welded vertex -> the first input vertex with its position
  Csr faces;                          // the triangles over welded vertices, in input order
  std::vector<std::uint32_t> source;  // faces row -> the input triangle it came from
  std::size_t dropped = 0;            // triangles whose corners welded together (not in faces)
};

/// Welds `positions` (3 per vertex) where x, y and z have the same bits (-0 as +0), numbering the
/// welded vertices in the order their first copy appears, and maps `triangles` (rows of 3) onto
/// them, dropping those that become degenerate.
PositionWeld weld_by_position(std::span<const double> positions, const Csr& triangles);

}  // namespace sublift
