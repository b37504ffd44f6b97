#include "core/sqrt2_sparse.h"

#include <cmath>

#include "core/parallel.h"
#include "core/tri_transform.h"

namespace sublift {

void sqrt2_run_step(const Sqrt2Substep& s, double* x, int ch, double sign, bool integer) {
  const std::uint32_t rows = static_cast<std::uint32_t>(s.target.size());
  parallel_for(rows, 512, [&](std::uint32_t begin, std::uint32_t end) {
    double acc[64];  // channels are at most 64 (project_io.h)
    std::vector<double> big(ch > 64 ? ch : 0);
    double* a = ch > 64 ? big.data() : acc;
    for (std::uint32_t r = begin; r < end; ++r) {
      for (int c = 0; c < ch; ++c) a[c] = 0.0;
      for (std::uint32_t k = s.sources.offsets[r]; k < s.sources.offsets[r + 1]; ++k) {
        const double w = s.weights[k];
        const double* src = x + std::size_t(s.sources.items[k]) * ch;
        for (int c = 0; c < ch; ++c) a[c] += w * src[c];
      }
      double* dst = x + std::size_t(s.target[r]) * ch;
      // Integer mode: the same rounded increment both ways, as core/lifting.cpp.
      for (int c = 0; c < ch; ++c) dst[c] += sign * (integer ? std::floor(a[c] + 0.5) : a[c]);
    }
  });
}

Sqrt2SparseIndex build_sqrt2_sparse_index(const Sqrt2Transition& t) {
  Sqrt2SparseIndex idx;
  for (const Sqrt2Substep& s : t.steps) idx.rows_of_source.push_back(transpose(s.sources, t.num_fine));
  return idx;
}

namespace {

// Rows of step s reading a listed vertex are evaluated on the change; their targets are never
// sources of the same step, so the order of the rows does not matter.
void sparse_step(const Sqrt2Substep& s, const Csr& rev, double sign, SparseDelta& d) {
  const std::uint32_t epoch = ++d.epoch;
  d.candidates.clear();
  for (const std::uint32_t v : d.list)
    for (const std::uint32_t r : rev.row(v)) {
      std::uint32_t& st = d.stamp[s.target[r]];
      if (st != epoch) {
        st = epoch;
        d.candidates.push_back(r);
      }
    }
  for (const std::uint32_t r : d.candidates) {
    double acc[3] = {0, 0, 0};
    for (std::uint32_t k = s.sources.offsets[r]; k < s.sources.offsets[r + 1]; ++k) {
      const double* src = d.x.data() + std::size_t(s.sources.items[k]) * 3;
      for (int c = 0; c < 3; ++c) acc[c] += s.weights[k] * src[c];
    }
    double* dst = d.at(s.target[r]);
    for (int c = 0; c < 3; ++c) dst[c] += sign * acc[c];
  }
}

}  // namespace

void sqrt2_synthesize_sparse(const Sqrt2Transition& t, const Sqrt2SparseIndex& index, SparseDelta& d) {
  for (std::size_t k = 0; k < t.steps.size(); ++k) sparse_step(t.steps[k], index.rows_of_source[k], 1.0, d);
  if (t.smooth) loop_smooth_sparse(*t.smooth, d);
}

void sqrt2_analyze_sparse(const Sqrt2Transition& t, const Sqrt2SparseIndex& index, SparseDelta& d) {
  if (t.smooth) loop_unsmooth_sparse(*t.smooth, d);
  for (std::size_t k = t.steps.size(); k-- > 0;) sparse_step(t.steps[k], index.rows_of_source[k], -1.0, d);
}

void sqrt2_analyze_adjoint(const Sqrt2Transition& t, double* y) {
  for (const Sqrt2Substep& s : t.steps)
    for (std::uint32_t r = 0; r < s.target.size(); ++r) {
      const double yt = y[s.target[r]];
      if (yt == 0.0) continue;
      for (std::uint32_t k = s.sources.offsets[r]; k < s.sources.offsets[r + 1]; ++k) y[s.sources.items[k]] -= s.weights[k] * yt;
    }
  // Analysis starts with Loop's solve, so its adjoint comes last.
  if (t.smooth) loop_unsmooth_adjoint(*t.smooth, y);
}

}  // namespace sublift
