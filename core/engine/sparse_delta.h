#pragma once
// A change on the vertices of one level, zero outside a short list: what the executor's sparse
// mode (executor.h) propagates through a transition. Three channels (x, y, z).
#include <cstdint>
#include <vector>

namespace sublift {

struct SparseDelta {
  std::vector<double> x;
  std::vector<std::uint32_t> list;     // vertices where x may be non-zero, no repeats
  std::vector<std::uint8_t> in_list;
  std::vector<std::uint32_t> stamp;    // per vertex: step that last visited it
  std::uint32_t epoch = 0;
  std::vector<std::uint32_t> candidates;

  /// Sizes the buffers for n vertices (kept zero) and empties the list.
  void reset(std::uint32_t n);
  /// Adds v to the list (if new) and returns its 3 values.
  double* at(std::uint32_t v) {
    if (!in_list[v]) {
      in_list[v] = 1;
      list.push_back(v);
    }
    return x.data() + std::size_t(v) * 3;
  }
  /// Zeroes the values on the list and empties it (O(list)).
  void clear();
};

}  // namespace sublift
