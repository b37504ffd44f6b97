#pragma once
// Sparse lifting: the synthesis or analysis of one transition applied to a *change* that is zero
// outside a few vertices. Lifting is linear, so synthesising the change and adding it equals
// resynthesising everything (up to round-off); only the rows whose sources changed are visited,
// so the cost follows the size of the change, not of the level (issue 4, local resynthesis).
//
// Each gather sub-step finds its rows through the reverse connectivity of its sources (a changed
// edge reaches the faces and cells around it, ...) and evaluates them with the same weights as
// the dense loops in lifting.cpp (lifting_detail.h). Three channels (x, y, z); not for integer
// mode, whose rounding is not linear.
#include <cstdint>
#include <vector>

#include "core/complex.h"
#include "core/lifting.h"

namespace sublift {

/// A change on the vertices of one level: x (3 per vertex) is zero outside `list`.
struct SparseDelta {
  std::vector<double> x;
  std::vector<std::uint32_t> list;     // vertices where x may be non-zero, no repeats
  std::vector<std::uint8_t> in_list;
  std::vector<std::uint32_t> stamp;    // per vertex: sub-step that last visited it
  std::uint32_t epoch = 0;
  std::vector<std::uint32_t> candidates;

  /// Sizes the buffers for n vertices (kept zero) and empties the list.
  void reset(std::uint32_t n);
  /// Adds v to the list (if new) and returns its 3 values.
  double* at(std::uint32_t v) {
    if (!in_list[v]) {
      in_list[v] = 1;
      list.push_back(v);
    }
    return x.data() + std::size_t(v) * 3;
  }
  /// Zeroes the values on the list and empties it (O(list)).
  void clear();
};

/// Synthesis of transition parent -> child on a change laid out like the child level
/// ([v | e | f | c], v part = change of the parent's control points, e/f/c = change of its wavelets).
void lift_synthesize_sparse(const Complex& parent, const LiftTables& t, const LiftProgram& program, SparseDelta& d);

/// Analysis of a change of the child level's control points, in place (the inverse of the above).
void lift_analyze_sparse(const Complex& parent, const LiftTables& t, const LiftProgram& program, SparseDelta& d);

}  // namespace sublift
