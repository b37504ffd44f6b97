#pragma once
// The one key of an undirected edge between vertices a and b: the smaller end in the high bits.
#include <algorithm>
#include <cstdint>

namespace sublift {

inline std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
  return std::uint64_t(std::min(a, b)) << 32 | std::max(a, b);
}

}  // namespace sublift
