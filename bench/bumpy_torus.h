#pragma once
// The input of the fitting benchmarks (bench_fit, bench_bvh): a triangulated torus of nu x nu/2
// vertices, major radius 1, minor radius 0.3 with bumps of 0.01 (7 x 5 of them), each grid cell
// split into two triangles; no subdivision connectivity. Made once per size.
#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <vector>

#include "core/base/csr.h"

namespace sublift::bench {

struct BumpyTorus {
  std::uint32_t n = 0;  // vertices
  Csr faces;
  std::vector<double> xyz;
};

inline const BumpyTorus& bumpy_torus(std::uint32_t nu) {
  static std::map<std::uint32_t, BumpyTorus> cache;
  if (auto it = cache.find(nu); it != cache.end()) return it->second;
  const std::uint32_t nv = nu / 2;
  BumpyTorus t;
  t.n = nu * nv;
  for (std::uint32_t j = 0; j < nv; ++j)
    for (std::uint32_t i = 0; i < nu; ++i) {
      const double u = 2 * std::numbers::pi * i / nu, v = 2 * std::numbers::pi * j / nv;
      const double r = 0.3 + 0.01 * std::sin(7 * u) * std::sin(5 * v);
      t.xyz.insert(t.xyz.end(), {(1 + r * std::cos(v)) * std::cos(u), (1 + r * std::cos(v)) * std::sin(u), r * std::sin(v)});
    }
  const auto id = [&](std::uint32_t i, std::uint32_t j) { return (i % nu) + nu * (j % nv); };
  for (std::uint32_t j = 0; j < nv; ++j)
    for (std::uint32_t i = 0; i < nu; ++i) {
      for (std::uint32_t v : {id(i, j), id(i + 1, j), id(i + 1, j + 1)}) t.faces.items.push_back(v);
      t.faces.offsets.push_back(static_cast<std::uint32_t>(t.faces.items.size()));
      for (std::uint32_t v : {id(i, j), id(i + 1, j + 1), id(i, j + 1)}) t.faces.items.push_back(v);
      t.faces.offsets.push_back(static_cast<std::uint32_t>(t.faces.items.size()));
    }
  return cache.emplace(nu, std::move(t)).first->second;
}

}  // namespace sublift::bench
