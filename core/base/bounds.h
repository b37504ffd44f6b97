#pragma once
// Axis-aligned bounds of xyz triples (3 doubles per point): the one place the model size behind
// relative errors, soft radii, height fields and box lattices is computed.
#include <array>
#include <cstddef>
#include <span>

namespace sublift {

/// The bounding box of `num_points` points as {lo, hi}; throws Error when there are none.
std::array<std::array<double, 3>, 2> bounding_box(const double* xyz, std::size_t num_points);

/// The length of the bounding-box diagonal; 0 for no points.
double bbox_diagonal(std::span<const double> xyz);

}  // namespace sublift
