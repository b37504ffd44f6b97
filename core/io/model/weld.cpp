#include "core/io/model/weld.h"

#include <array>
#include <bit>
#include <map>

namespace sublift {

PositionWeld weld_by_position(std::span<const double> positions, const Csr& triangles) {
  PositionWeld w;
  const std::size_t nv = positions.size() / 3;
  std::map<std::array<std::uint64_t, 3>, std::uint32_t> first;
  w.welded.resize(nv);
  for (std::size_t v = 0; v < nv; ++v) {
    const double* p = &positions[3 * v];
    const std::array<std::uint64_t, 3> key{std::bit_cast<std::uint64_t>(p[0] + 0.0), std::bit_cast<std::uint64_t>(p[1] + 0.0),
                                           std::bit_cast<std::uint64_t>(p[2] + 0.0)};  // + 0.0: -0 and 0 weld
    const auto [it, fresh] = first.emplace(key, static_cast<std::uint32_t>(w.first.size()));
    if (fresh) w.first.push_back(static_cast<std::uint32_t>(v));
    w.welded[v] = it->second;
  }
  for (std::size_t f = 0; f < triangles.rows(); ++f) {
    const auto row = triangles.row(f);
    const std::uint32_t tri[3] = {w.welded[row[0]], w.welded[row[1]], w.welded[row[2]]};
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) {
      ++w.dropped;
      continue;
    }
    w.faces.items.insert(w.faces.items.end(), tri, tri + 3);
    w.source.push_back(static_cast<std::uint32_t>(f));
    w.faces.offsets.push_back(static_cast<std::uint32_t>(w.faces.items.size()));
  }
  return w;
}

}  // namespace sublift
