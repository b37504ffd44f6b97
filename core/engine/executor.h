#pragma once
// The one executor of level transitions (transition.h), for every scheme and every mode:
//   synthesis   the steps forwards                      (coefficients -> level j+1's net)
//   analysis    the steps backwards, each inverted      (the exact inverse, integer mode too)
//   sparse      either direction on a change that is zero outside a few vertices: only the
//               rows that read a changed value are visited, so the cost follows the change
//               (the modeler's drags and fold-back); equal to the dense run of the change
//   adjoint     the transpose of the analysis on one channel (the dual basis functions)
// Centroid and Scale steps read the parent complex's incidences and feature dims, so every
// call takes the level-j complex the transition was built from.
#include <cstdint>
#include <vector>

#include "core/complex/complex.h"
#include "core/base/csr.h"
#include "core/engine/sparse_delta.h"
#include "core/engine/transition.h"

namespace sublift {

/// Synthesis in place on x (level j+1 layout). `new_zero`: the caller knows the new vertices'
/// values (the wavelets) are zero, so steps that read only them are skipped until a step
/// writes them (they would add exact zeros) -- for every scheme the same rule.
void run_synthesis(const Transition& t, const Complex& parent, double* x, int channels, bool integer,
                   bool new_zero = false);
/// Analysis in place: the exact inverse of run_synthesis.
void run_analysis(const Transition& t, const Complex& parent, double* x, int channels, bool integer);

/// The classes (bit 0 v, 1 e, 2 f) whose Scale factors the dense loops apply inside the Centroid
/// step that last writes them, instead of in a pass of their own: bit for bit the same values
/// (executor.cpp, ScaleFold; tested against the unfolded run).
unsigned folded_scale_classes(const Transition& t);

/// The rows each step of one sparse run reached from an input list (executor.cpp, run_sparse).
struct SparsePlan {
  std::vector<std::uint32_t> input;              // the change's list when the run began
  std::vector<std::vector<std::uint32_t>> rows;  // per step: the rows found
  bool valid = false;                            // a run found them all
  std::uint64_t replays = 0;                     // runs that reused them (for tests)
};

/// Per step: the rows that read each vertex (Weighted and Matrix steps; empty for the others,
/// whose reverse incidences the complex has). `plans` (synthesis, analysis) keep the rows the last
/// sparse run found, reused while the next run starts from the same list (a drag): one index
/// serves one thread at a time.
struct SparseIndex {
  std::vector<Csr> readers;
  mutable SparsePlan plans[2];
};
SparseIndex build_sparse_index(const Transition& t);

/// Synthesis / analysis of a change (3 channels, not integer mode), in place.
void run_synthesis_sparse(const Transition& t, const Complex& parent, const SparseIndex& index, SparseDelta& d);
void run_analysis_sparse(const Transition& t, const Complex& parent, const SparseIndex& index, SparseDelta& d);

/// The transpose of run_analysis on one channel, in place: each analysis row x_t -= w x_s
/// becomes x_s -= w x_t, steps in synthesis order.
void run_analysis_adjoint(const Transition& t, const Complex& parent, double* y);

}  // namespace sublift
