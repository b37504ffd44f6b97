#pragma once
// Helpers for engine tests: edge lookup by end vertices, random values.
#include <map>
#include <random>
#include <utility>
#include <vector>

#include "core/complex.h"

namespace sublift::testing {

/// Edge index by its (unordered) end vertices.
inline std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> edge_map(const Complex& c) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> m;
  for (std::uint32_t e = 0; e < c.num_edges(); ++e) {
    const std::uint32_t a = c.edge_verts[2 * e], b = c.edge_verts[2 * e + 1];
    m[{std::min(a, b), std::max(a, b)}] = e;
  }
  return m;
}

inline std::uint32_t edge_of(const std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t>& m,
                             std::uint32_t a, std::uint32_t b) {
  return m.at({std::min(a, b), std::max(a, b)});
}

inline std::vector<double> random_values(std::size_t n, std::uint64_t seed, double lo = -1.0, double hi = 1.0) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(lo, hi);
  std::vector<double> v(n);
  for (double& x : v) x = u(rng);
  return v;
}

}  // namespace sublift::testing
