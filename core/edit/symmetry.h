#pragma once
// Mirror editing (issue 19; Blender's X/Y/Z mirror with topology mirror): which control point
// of a level is the mirror image of which across the world planes x = 0, y = 0, z = 0.
//
// Found once per level and axis: first by position (the reflected point within `tolerance`,
// nearest first, each vertex taken once), then by topology where positions are not exact: an
// unmatched vertex whose matched neighbours' mirrors share exactly one unmatched neighbour is
// paired with it (repeated while pairs are found), so a mesh made symmetric by hand with a
// small error still mirrors everywhere its connectivity is symmetric. Vertices on the plane
// mirror onto themselves. What stays unmatched is reported (count and the first few).
//
// A symmetric edit moves the selection's mirror images by the reflected moves (mirror_deltas):
// additive, so asymmetric detail stays as it was, and a vertex on the plane keeps its
// coordinate across the plane.
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/complex/complex.h"

namespace sublift {

struct MirrorMap {
  int axis = 0;
  std::vector<std::int64_t> mirror;  // per vertex: its mirror image, -1 when none was found
  std::size_t by_position = 0, by_topology = 0, unmatched = 0;
  std::vector<std::uint32_t> first_unmatched;  // up to 8
  /// "X mirror: 4 of 96 control points have no mirror image (first: 3, 17, 40, 41)", or "".
  std::string problem() const;
};

/// The mirror map of a level's net across the plane through the origin across `axis` (0..2).
/// `tolerance` <= 0 picks 1e-4 of the bounding-box diagonal.
MirrorMap find_mirror(const Complex& c, std::span<const double> positions, int axis, double tolerance = 0.0);

/// Appends to (vertices, deltas) the mirror images of the moves already there (3 deltas per
/// vertex): for every enabled combination of the axes in `maps` (x, y, z, xy, ...), each moved
/// vertex's image under it gets the move with those components negated, unless that image
/// moves already. A moved vertex that is its own image across an axis has that component
/// zeroed (it stays on the plane).
void mirror_deltas(std::span<const MirrorMap* const> maps, std::vector<std::uint32_t>& vertices,
                   std::vector<double>& deltas);

}  // namespace sublift
