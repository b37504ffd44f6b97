#pragma once
// A table of one number per index (a vertex's label, a slot), cleared by bumping an epoch
// instead of by value: hot loops take millions of small neighbourhoods of a big mesh, each
// touching a few hundred of its vertices. Keep one per thread (thread_local); it grows to the
// largest index asked for and stays that size.
#include <algorithm>
#include <cstdint>
#include <vector>

namespace sublift {

struct EpochTable {
  std::vector<std::uint32_t> value, stamp;
  std::uint32_t epoch = 0;

  /// Starts an empty table over indices 0..n-1.
  void begin(std::uint32_t n) {
    if (stamp.size() < n) {
      value.resize(n);
      stamp.assign(n, 0);
      epoch = 0;
    }
    if (++epoch == 0) {  // wrapped: every old stamp could match again
      std::fill(stamp.begin(), stamp.end(), 0);
      epoch = 1;
    }
  }
  bool has(std::uint32_t i) const { return stamp[i] == epoch; }
  /// The value set for i since begin(), or UINT32_MAX.
  std::uint32_t get(std::uint32_t i) const { return stamp[i] == epoch ? value[i] : UINT32_MAX; }
  void mark(std::uint32_t i) { stamp[i] = epoch; }  // has(i) from now on, with no value
  void set(std::uint32_t i, std::uint32_t v) {
    stamp[i] = epoch;
    value[i] = v;
  }
};

}  // namespace sublift
