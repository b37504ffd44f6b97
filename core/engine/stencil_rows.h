#pragma once
// Building the explicit stencil rows of a Weighted step (transition.h): each row's terms added
// in any order, then written with sources increasing and repeated sources summed; rows made in
// parallel chunks and joined in order, so the result does not depend on the thread count.
#include <algorithm>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "core/base/csr.h"
#include "core/base/parallel.h"

namespace sublift {

using StencilTerm = std::pair<std::uint32_t, double>;  // (source, weight)

/// Appends one row made of `terms` to rows/weights: sorted by source, stably, so a repeated
/// source's weights are summed in the order they were added (small meshes repeat vertices, a
/// rule's overlapping rings name them again), and a source whose weights cancel to exactly 0
/// left out. Sorts `terms` in place; n log n, so a vertex of valence 70 000 costs its sort.
void append_stencil_row(std::span<StencilTerm> terms, Csr& rows, std::vector<double>& weights);

/// Accumulates one row; flush() appends it (append_stencil_row) and starts the next.
class RowBuilder {
 public:
  void add(std::uint32_t v, double w) { terms_.emplace_back(v, w); }
  void flush(Csr& rows, std::vector<double>& weights) {
    append_stencil_row(terms_, rows, weights);
    terms_.clear();
  }

 private:
  std::vector<StencilTerm> terms_;
};

/// Appends the rows of `parts` (weights in `part_weights`) to rows/weights in order, each part
/// copied to its place in parallel after the arrays are sized once. Empties the parts.
void join_rows(std::vector<Csr>& parts, std::vector<std::vector<double>>& part_weights, Csr& rows,
               std::vector<double>& weights);

/// Rows 0..n-1 from row(i, builder), built in parallel chunks of 8192 and joined in order (the
/// same rows as one serial pass). `row` must not throw.
template <class RowFn>
void build_rows(std::uint32_t n, Csr& rows, std::vector<double>& weights, RowFn&& row) {
  constexpr std::uint32_t kChunk = 8192;
  const std::uint32_t chunks = (n + kChunk - 1) / kChunk;
  std::vector<Csr> part_rows(chunks);
  std::vector<std::vector<double>> part_weights(chunks);
  parallel_for(chunks, 1, [&](std::uint32_t c0, std::uint32_t c1) {
    RowBuilder b;
    for (std::uint32_t c = c0; c < c1; ++c) {
      const std::uint32_t i0 = c * kChunk, i1 = std::min(n, i0 + kChunk);
      Csr& r = part_rows[c];
      r.offsets.reserve(std::size_t(i1 - i0) + 1);
      r.items.reserve(std::size_t(i1 - i0) * 8);  // the 8-point rule; others fewer or a few more
      part_weights[c].reserve(std::size_t(i1 - i0) * 8);
      for (std::uint32_t i = i0; i < i1; ++i) {
        row(i, b);
        b.flush(r, part_weights[c]);
      }
    }
  });
  join_rows(part_rows, part_weights, rows, weights);
}

}  // namespace sublift
