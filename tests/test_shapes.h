#pragma once
// Helpers for engine tests: edge lookup by end vertices, random values.
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <span>
#include <utility>
#include <vector>

#include "core/complex/complex.h"

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

/// Uniform values in [-1, 1] (integer: rounded multiples of 1/1000 of them, times 1000).
inline std::vector<double> random_coefficients(std::size_t n, unsigned seed, bool integer) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> x(n);
  // + 0.0: round() of a small negative value is -0; keep every zero +0.
  for (double& v : x) v = integer ? std::round(1000.0 * u(rng)) + 0.0 : u(rng);
  return x;
}

/// Largest |a[i] - b[i]|; infinite when the sizes differ, so any tolerance check fails.
inline double max_abs_diff(std::span<const double> a, std::span<const double> b) {
  if (a.size() != b.size()) return std::numeric_limits<double>::infinity();
  double m = 0;
  for (std::size_t i = 0; i < a.size(); ++i) m = std::max(m, std::abs(a[i] - b[i]));
  return m;
}

}  // namespace sublift::testing
