#pragma once
// Internal to the lifting loops (lifting.cpp dense, lifting_sparse.cpp sparse): the source
// groups of a gather sub-step and their weights, shared so both compute the same numbers.
#include <array>
#include <cmath>
#include <cstdint>

#include "core/complex.h"
#include "core/lifting.h"

namespace sublift::lifting_detail {

// Regular-grid neighbour count: a t-dim primitive inside an m-dim regular grid touches
// C(m-t, k-t) 2^(k-t) primitives of dim k (000 eq. 3.16-3.17: 6/12/8, 4/4, 2).
inline double grid_count(int m, int t, int k) {
  if (k > m || t > m) return 0.0;
  const int n = m - t, r = k - t;
  double binom = 1;
  for (int i = 0; i < r; ++i) binom = binom * (n - i) / (i + 1);
  return binom * std::ldexp(1.0, r);
}

// One source group of a gather sub-step: rows of source indices (local to their class) with
// the weight per feature dim m of the target (already multiplied by a^(k-t)).
struct Group {
  const std::uint32_t* offsets = nullptr;
  const std::uint32_t* items = nullptr;
  std::uint32_t stride = 0;     // rows of fixed size (edge_verts) when offsets == nullptr
  std::uint32_t source_base = 0;
  double weight[4] = {0, 0, 0, 0};
};

// 1/n for small n without a division in the hot loop.
constexpr int kInvTable = 64;
inline const std::array<double, kInvTable> kInv = [] {
  std::array<double, kInvTable> t{};
  for (int i = 1; i < kInvTable; ++i) t[i] = 1.0 / double(i);
  return t;
}();

inline double inv(std::uint32_t n) { return n < kInvTable ? kInv[n] : 1.0 / double(n); }

inline Group group_of(const Csr& rows, std::uint32_t source_base) {
  Group g;
  g.offsets = rows.offsets.data();
  g.items = rows.items.data();
  g.source_base = source_base;
  return g;
}

// Weights of a source class k for a target class t: w-lift ignores features (topological
// counts of the target primitive, 000 eq. 3.16); s-lift uses the target's feature dim m.
inline void set_wlift_weight(Group& g, int t, int k, double a) {
  // Number of k-faces of a regular t-cube: C(t, k) 2^(t-k).
  double binom = 1;
  for (int i = 0; i < t - k; ++i) binom = binom * (t - i) / (i + 1);
  const double count = binom * std::ldexp(1.0, t - k);
  const double v = count * std::pow(a, t - k);
  for (double& x : g.weight) x = v;
}

inline void set_slift_weight(Group& g, int t, int k, double a) {
  for (int m = 0; m < 4; ++m) g.weight[m] = grid_count(m, t, k) * std::pow(a, k - t);
}

struct Classes {
  std::uint32_t nv, ne, nf, nc, E0, F0, C0;
  explicit Classes(const Complex& p)
      : nv(p.num_vertices), ne(p.num_edges()), nf(p.num_faces()), nc(p.num_cells()),
        E0(nv), F0(nv + ne), C0(nv + ne + nf) {}
};

// Sum of the rows' source values (C channels) into s.
template <int C>
inline void sum_sources(const double* x, const std::uint32_t* idx, std::uint32_t n, std::uint32_t base, int ch,
                        double* s) {
  const int cc = C > 0 ? C : ch;
  for (int c = 0; c < cc; ++c) s[c] = 0.0;
  for (std::uint32_t k = 0; k < n; ++k) {
    const double* p = x + std::size_t(base + idx[k]) * cc;
    for (int c = 0; c < cc; ++c) s[c] += p[c];
  }
}

// Row i of a group: items [b, b + len).
inline void group_row(const Group& gr, std::uint32_t i, std::uint32_t& b, std::uint32_t& len) {
  if (gr.offsets) {
    b = gr.offsets[i];
    len = gr.offsets[i + 1] - b;
  } else {
    b = i * gr.stride;
    len = gr.stride;
  }
}

// acc += sum over groups of weight_g(m) times the centroid of row i of group g (C channels, 0 =
// `ch` at run time; `sum` is scratch of ch values). False when no group has a row for i. The
// dense and the sparse loops evaluate a row through this one function, so they agree.
template <int C, int G>
inline bool accumulate_row(const Group* groups, std::uint32_t i, int m, const double* x, int ch, double* sum,
                           double* acc) {
  const int cc = C > 0 ? C : ch;
  bool any = false;
  for (int g = 0; g < G; ++g) {
    const Group& gr = groups[g];
    const double wm = gr.weight[m];
    std::uint32_t b, len;
    group_row(gr, i, b, len);
    if (len == 0 || wm == 0.0) continue;
    any = true;
    sum_sources<C>(x, gr.items + b, len, gr.source_base, cc, sum);
    const double w = wm * inv(len);
    for (int c = 0; c < cc; ++c) acc[c] += w * sum[c];
  }
  return any;
}

inline const Csr& pick(bool own, const Csr& owned, const Csr& complex_rows) { return own ? owned : complex_rows; }

}  // namespace sublift::lifting_detail
