#pragma once
// Quad-dominant bases for the schemes that refine polygons (Bertram's 1-to-4 split, sqrt(2)):
// the decimated triangle base's triangles are paired, two across an edge, into quads where the
// pair makes a convex quad with corners near 90 degrees. Crease and boundary edges are never
// removed, so the base keeps its feature tags; a triangle with no good partner stays a triangle.
#include <cstddef>

#include "core/fit/base_mesh.h"

namespace sublift {

/// The largest corner angle deviation from 90 degrees a paired quad may have: corners between 30
/// and 150 degrees. A decimated base's triangles vary too much for 45 (a third of them would
/// stay triangles on the rocker arm, against a sixth).
constexpr double kMaxQuadCornerDeviationDeg = 60.0;

/// Pairs `base`'s triangles into quads in place, best-shaped quads first (greedy matching);
/// returns the number of quads made. Genus, boundaries and tags are unchanged.
std::size_t pair_into_quads(BaseMesh& base, double max_corner_deviation_deg = kMaxQuadCornerDeviationDeg);

}  // namespace sublift
