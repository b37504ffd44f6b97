#pragma once
// A level's new neighbourhood signatures, each kept once (core/schemes/tri/tri_transform.cpp).
#include <algorithm>
#include <array>
#include <cstdint>
#include <mutex>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/schemes/tri/tri_local.h"

namespace sublift {

// The signatures (keys) a triangle level meets that are not cached (build_tri_transition), each
// kept once whichever thread meets it first: a fitted base's 1 M level has 750 k irregular edges
// but 127 k new neighbourhoods, and copying one signature per edge was a third of its hierarchy
// stage (perf: page faults on fresh memory). An entry remembers the lowest edge that has it, so
// the order they are solved in, and their results, do not depend on the threads.
class NewSignatures {
 public:
  struct Entry {
    std::uint32_t first = UINT32_MAX;  // lowest edge (index into the level's irregular edges)
    std::uint32_t place = 0;           // in in_order()
  };
  /// Notes that edge k has `signature`; the entry stays where it is.
  Entry* add(const std::string& signature, std::uint32_t k) {
    const std::size_t h = SignatureHash{}(signature);
    Shard& sh = shards_[(h >> 7) % kShards];
    const std::lock_guard<std::mutex> lock(sh.mutex);
    Entry& e = sh.map[signature];
    e.first = std::min(e.first, k);
    return &e;
  }
  using Map = std::unordered_map<std::string, Entry, SignatureHash>;
  /// Every signature with its entry, taken out of the maps (so the keys may be moved from; the
  /// entries stay where add() put them), by first edge; numbers the entries' places.
  std::vector<Map::node_type> in_order() {
    std::vector<Map::node_type> out;
    for (Shard& sh : shards_)
      while (!sh.map.empty()) out.push_back(sh.map.extract(sh.map.begin()));
    std::sort(out.begin(), out.end(), [](const auto& x, const auto& y) { return x.mapped().first < y.mapped().first; });
    for (std::size_t i = 0; i < out.size(); ++i) out[i].mapped().place = static_cast<std::uint32_t>(i);
    return out;
  }

 private:
  static constexpr std::size_t kShards = 64;
  struct Shard {
    std::mutex mutex;
    Map map;
  };
  std::array<Shard, kShards> shards_;
};

}  // namespace sublift
