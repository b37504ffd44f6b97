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
  // A stamp and its value side by side: a look-up touches one cache line, not two.
  struct Slot {
    std::uint32_t stamp = 0, value = 0;
  };
  std::vector<Slot> slot;
  std::uint32_t epoch = 0;

  /// Starts an empty table over indices 0..n-1.
  void begin(std::uint32_t n) {
    if (slot.size() < n) {
      slot.assign(n, Slot{});
      epoch = 0;
    }
    if (++epoch == 0) {  // wrapped: every old stamp could match again
      std::fill(slot.begin(), slot.end(), Slot{});
      epoch = 1;
    }
  }
  bool has(std::uint32_t i) const { return slot[i].stamp == epoch; }
  /// The value set for i since begin(), or UINT32_MAX.
  std::uint32_t get(std::uint32_t i) const { return slot[i].stamp == epoch ? slot[i].value : UINT32_MAX; }
  void mark(std::uint32_t i) { slot[i].stamp = epoch; }  // has(i) from now on, with no value
  void set(std::uint32_t i, std::uint32_t v) { slot[i] = {epoch, v}; }
};

}  // namespace sublift
