#pragma once
// Box lattices for free-form deformation (issue 6): an nx x ny x nz block of hexahedra around an
// axis-aligned box.
//
// Conventions. Vertex (i, j, k), 0 <= i <= nx etc., has index (k * (ny+1) + j) * (nx+1) + i and
// sits at lo + (i/nx, j/ny, k/nz) * (hi - lo) of the padded box; every cell lists its 6 quads
// (shared faces merged), so the complex is valid per validate() and its boundary gets the usual
// feature dims (faces 2, edges 1, corners 0: docs/features.md).
// Padding. An extent below 1e-12 of the box diagonal (a flat or linear model) is widened to 10%
// of the diagonal, centred; a box that is a single point becomes the unit cube around it. Then
// `margin` times the (padded) diagonal is added on every side of every axis.
#include <array>
#include <cstddef>

#include "core/base/bounds.h"
#include "core/complex/shape.h"

namespace sublift {

/// Hexahedral lattice of nx * ny * nz cells around [lo, hi] (lo <= hi per axis) with `margin`
/// (a fraction of the box diagonal, >= 0) on every side. Throws Error for non-finite bounds or
/// margin, lo > hi, a count < 1, or nx * ny * nz >= 1e6 cells.
Shape make_box_lattice(const std::array<double, 3>& lo, const std::array<double, 3>& hi, int nx, int ny, int nz,
                       double margin);

}  // namespace sublift
