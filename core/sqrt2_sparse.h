#pragma once
// The sqrt(2) transform's sub-steps (core/sqrt2_transform.h) run one at a time, on a sparse
// change (the session's local resynthesis, as lifting_sparse.h does for the 1-to-4 schemes) and
// as the adjoint of the analysis (the basis explorer's dual functions).
#include <cstdint>
#include <vector>

#include "core/csr.h"
#include "core/lifting_sparse.h"
#include "core/sqrt2_transform.h"

namespace sublift {

/// Runs one sub-step on dense values: x[target] += sign * row (integer: the rounded row).
void sqrt2_run_step(const Sqrt2Substep& s, double* x, int channels, double sign, bool integer);

/// Per sub-step of one transition: the rows that read each fine vertex (source -> rows).
struct Sqrt2SparseIndex {
  std::vector<Csr> rows_of_source;
};
Sqrt2SparseIndex build_sqrt2_sparse_index(const Sqrt2Transition& t);

/// Synthesis of a change laid out like the fine level (3 channels), visiting only the rows
/// that read a changed value; equal to the dense synthesis of the change.
void sqrt2_synthesize_sparse(const Sqrt2Transition& t, const Sqrt2SparseIndex& index, SparseDelta& d);
/// Analysis of a change of the fine level's values, in place (the inverse of the above).
void sqrt2_analyze_sparse(const Sqrt2Transition& t, const Sqrt2SparseIndex& index, SparseDelta& d);

/// The transpose of sqrt2_analyze on one channel, in place: each analysis row x_t -= w x_s
/// becomes x_s -= w x_t, sub-steps in synthesis order.
void sqrt2_analyze_adjoint(const Sqrt2Transition& t, double* y);

}  // namespace sublift
