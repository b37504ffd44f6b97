#pragma once
// Shapes made in code, for tests, benchmarks and samples: regular grids whose subdivision has a
// known tensor-product answer.
#include <cstdint>
#include <vector>

#include "core/complex/complex.h"
#include "core/base/surface_mesh.h"

namespace sublift {

/// Regular n x m quad torus (radii R, r); vertex (i, j) has index i * m + j.
SurfaceMesh make_quad_torus(int n, int m, double R = 1.0, double r = 0.4);

/// Closed polyline loop of n vertices on a circle of radius 1 (edge i joins i and i+1 mod n).
Complex make_curve_loop(int n, std::vector<double>& positions);

/// n x n x n block of unit hexahedra; vertex (i, j, k) has index (k * (n+1) + j) * (n+1) + i.
/// Each cell lists its 6 faces as quads; shared faces are merged.
Complex make_hex_block(int n, std::vector<double>& positions);

/// Flattens mesh positions to xyz doubles.
std::vector<double> flatten_positions(const SurfaceMesh& mesh);

}  // namespace sublift
