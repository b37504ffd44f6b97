#include "core/engine/stencil_rows.h"

#include <algorithm>
#include <cstdint>

#include "core/base/small_sort.h"

namespace sublift {

namespace {

// Sorts 8 keys with the 19 compare-exchanges of Knuth's optimal network, branch-free (rows'
// sources come in rule order, so an insertion sort's branches mispredicted).
void sort8(std::uint64_t* k) {
  constexpr int kPairs[19][2] = {{0, 2}, {1, 3}, {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}, {0, 1}, {2, 3},
                                 {4, 5}, {6, 7}, {2, 4}, {3, 5}, {1, 4}, {3, 6}, {1, 2}, {3, 4}, {5, 6}};
  for (const auto& [a, b] : kPairs) {
    const std::uint64_t x = k[a], y = k[b];
    k[a] = std::min(x, y);
    k[b] = std::max(x, y);
  }
}

}  // namespace

void append_stencil_row(std::span<StencilTerm> terms, Csr& rows, std::vector<double>& weights) {
  const auto by_source = [](const StencilTerm& x, const StencilTerm& y) { return x.first < y.first; };
  if (terms.size() >= 5 && terms.size() <= 8) {
    // Keys (source, place) are distinct, so their one sorted order is the stable one. (Rows of
    // 4 terms or fewer sort faster by insertion: a handful of compares.)
    std::uint64_t k[8];
    StencilTerm copy[8];
    const std::size_t n = terms.size();
    for (std::size_t i = 0; i < 8; ++i) k[i] = i < n ? std::uint64_t(terms[i].first) << 32 | i : UINT64_MAX;
    std::copy(terms.begin(), terms.end(), copy);
    sort8(k);
    for (std::size_t i = 0; i < n; ++i) terms[i] = copy[k[i] & 0xffffffffu];
  } else {
    stable_sort_small(terms.begin(), terms.end(), by_source);
  }
  for (std::size_t i = 0; i < terms.size();) {
    const std::uint32_t v = terms[i].first;
    double w = 0;
    for (; i < terms.size() && terms[i].first == v; ++i) w += terms[i].second;
    if (w != 0.0) rows.items.push_back(v), weights.push_back(w);
  }
  rows.offsets.push_back(static_cast<std::uint32_t>(rows.items.size()));
}

void join_rows(std::vector<Csr>& parts, std::vector<std::vector<double>>& part_weights, Csr& rows,
               std::vector<double>& weights) {
  const std::size_t n = parts.size();
  std::vector<std::size_t> row_at(n + 1), item_at(n + 1);
  row_at[0] = rows.rows(), item_at[0] = rows.items.size();
  for (std::size_t c = 0; c < n; ++c) {
    row_at[c + 1] = row_at[c] + parts[c].rows();
    item_at[c + 1] = item_at[c] + parts[c].items.size();
  }
  rows.offsets.resize(row_at.back() + 1);
  rows.items.resize(item_at.back());
  weights.resize(item_at.back());
  parallel_for(static_cast<std::uint32_t>(n), 1, [&](std::uint32_t c0, std::uint32_t c1) {
    for (std::uint32_t c = c0; c < c1; ++c) {
      const Csr& r = parts[c];
      const auto base = static_cast<std::uint32_t>(item_at[c]);
      for (std::size_t k = 1; k < r.offsets.size(); ++k) rows.offsets[row_at[c] + k] = base + r.offsets[k];
      std::copy(r.items.begin(), r.items.end(), rows.items.begin() + std::ptrdiff_t(item_at[c]));
      std::copy(part_weights[c].begin(), part_weights[c].end(), weights.begin() + std::ptrdiff_t(item_at[c]));
      parts[c] = Csr{};
      part_weights[c] = {};
    }
  });
}

}  // namespace sublift
