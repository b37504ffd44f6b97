#pragma once
// Small lattices built in code for engine tests: a pyramid cell, a triangular prism, and the
// face loops of a hex block's boundary.
#include <vector>

#include "core/complex/complex_build.h"

namespace sublift::testing {

/// One cell from face loops (each loop one face).
inline Complex single_cell(std::uint32_t nv, const std::vector<std::vector<std::uint32_t>>& faces,
                           const FeatureTags& tags = {}) {
  Csr loops, cells;
  for (const auto& f : faces) {
    loops.items.insert(loops.items.end(), f.begin(), f.end());
    loops.offsets.push_back(static_cast<std::uint32_t>(loops.items.size()));
    cells.items.push_back(static_cast<std::uint32_t>(loops.rows() - 1));
  }
  cells.offsets.push_back(static_cast<std::uint32_t>(cells.items.size()));
  return complex_from_cells(nv, loops, cells, tags);
}

/// Square pyramid: base 0-3, apex 4 (the apex has 4 cell edges: its child is a type-4 cell).
inline Complex pyramid_cell() {
  return single_cell(5, {{0, 3, 2, 1}, {0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}});
}

/// Triangular prism: bottom 0-2, top 3-5.
inline Complex prism_cell() {
  return single_cell(6, {{0, 2, 1}, {3, 4, 5}, {0, 1, 4, 3}, {1, 2, 5, 4}, {2, 0, 3, 5}});
}

/// Tetrahedron.
inline Complex tetra_cell() { return single_cell(4, {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}}); }

}  // namespace sublift::testing
