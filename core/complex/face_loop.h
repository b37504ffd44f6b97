#pragma once
// The canonical form of a face's vertex loop: rotated to start at its smallest vertex, in the
// direction whose second vertex is smaller. A face and its reversed copy get the same key, so
// shared faces of two cells, duplicate faces and tags naming a face by its loop all match.
#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

namespace sublift {

namespace detail {
template <class Int>
std::vector<std::uint32_t> canonical_loop_of(std::span<const Int> f) {
  const std::size_t n = f.size();
  if (n == 0) return {};
  const std::size_t m = static_cast<std::size_t>(std::min_element(f.begin(), f.end()) - f.begin());
  std::vector<std::uint32_t> fwd(n), bwd(n);
  for (std::size_t i = 0; i < n; ++i) {
    fwd[i] = static_cast<std::uint32_t>(f[(m + i) % n]);
    bwd[i] = static_cast<std::uint32_t>(f[(m + n - i) % n]);
  }
  return std::min(fwd, bwd);
}
}  // namespace detail

/// Canonical loop of 32-bit vertex indices.
inline std::vector<std::uint32_t> canonical_loop(std::span<const std::uint32_t> f) { return detail::canonical_loop_of(f); }
/// Canonical loop of raw (already range-checked) 64-bit indices.
inline std::vector<std::uint32_t> canonical_loop(std::span<const std::int64_t> f) { return detail::canonical_loop_of(f); }

/// Appends the canonical loop of `f` to `out` without temporary allocations (hot in importers).
inline void append_canonical_loop(std::span<const std::uint32_t> f, std::vector<std::uint32_t>& out) {
  const std::size_t n = f.size();
  if (n == 0) return;
  const std::size_t m = static_cast<std::size_t>(std::min_element(f.begin(), f.end()) - f.begin());
  bool forward = true;  // compare the forward and backward walks from m
  for (std::size_t i = 1; i < n; ++i) {
    const std::uint32_t a = f[(m + i) % n], b = f[(m + n - i) % n];
    if (a != b) {
      forward = a < b;
      break;
    }
  }
  for (std::size_t i = 0; i < n; ++i) out.push_back(forward ? f[(m + i) % n] : f[(m + n - i) % n]);
}

}  // namespace sublift
