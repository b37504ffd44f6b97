#pragma once
// A flat quad grid for the editing tools' tests (selection, symmetry, brushes).
#include <cstdint>
#include <vector>

#include "core/complex/complex_build.h"

namespace sublift::testing {

/// An nx x ny grid of unit quads in z = 0: vertex (i, j) is j * (nx + 1) + i, at (i, j, 0) plus
/// `offset` in x and y; its upward rows built.
inline Complex quad_grid(int nx, int ny, std::vector<double>& positions, double offset = 0.0) {
  Csr faces;
  auto v = [&](int i, int j) { return static_cast<std::uint32_t>(j * (nx + 1) + i); };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      for (const std::uint32_t c : {v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)}) faces.items.push_back(c);
      faces.offsets.push_back(static_cast<std::uint32_t>(faces.items.size()));
    }
  positions.clear();
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) positions.insert(positions.end(), {i + offset, j + offset, 0.0});
  return complex_from_polygons(static_cast<std::uint32_t>((nx + 1) * (ny + 1)), faces);
}

}  // namespace sublift::testing
