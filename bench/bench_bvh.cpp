// The closest-point queries fitting makes (core/base/triangle_bvh.h; issue 17: a third of a
// 1 M fit's levels stage): a bumpy triangulated torus of 200 k and 2 M triangles, queried from
// points a little off the surface, once from the root and once with the hint a fitting round
// has (the face found for the point's position one round earlier), any side and one side.
// Prints ns per query. One thread: the queries are independent, fitting runs them on the pool.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <chrono>
#include <map>
#include <memory>
#include <numbers>
#include <random>

#include <glm/geometric.hpp>

#include "core/base/parallel.h"
#include "core/base/triangle_bvh.h"

namespace {

using namespace sublift;

struct Case {
  std::vector<double> xyz;
  Csr faces;
  std::unique_ptr<TriangleBvh> bvh;
  std::vector<glm::dvec3> points, normals;
  std::vector<std::uint32_t> hints;
};

// nu x nu/2 vertices, minor radius 0.3 with bumps of 0.01 (bench_fit's torus); the query points
// are 100 k vertices moved off the surface by up to 0.002, their hints the faces found from
// 0.0005 away (where the point was a round earlier).
const Case& torus(std::uint32_t nu) {
  static std::map<std::uint32_t, Case> cache;
  if (auto it = cache.find(nu); it != cache.end()) return it->second;
  Case c;
  const std::uint32_t nv = nu / 2;
  for (std::uint32_t j = 0; j < nv; ++j)
    for (std::uint32_t i = 0; i < nu; ++i) {
      const double u = 2 * std::numbers::pi * i / nu, v = 2 * std::numbers::pi * j / nv;
      const double r = 0.3 + 0.01 * std::sin(7 * u) * std::sin(5 * v);
      c.xyz.insert(c.xyz.end(), {(1 + r * std::cos(v)) * std::cos(u), (1 + r * std::cos(v)) * std::sin(u), r * std::sin(v)});
    }
  const auto id = [&](std::uint32_t i, std::uint32_t j) { return (i % nu) + nu * (j % nv); };
  for (std::uint32_t j = 0; j < nv; ++j)
    for (std::uint32_t i = 0; i < nu; ++i) {
      for (std::uint32_t v : {id(i, j), id(i + 1, j), id(i + 1, j + 1)}) c.faces.items.push_back(v);
      c.faces.offsets.push_back(static_cast<std::uint32_t>(c.faces.items.size()));
      for (std::uint32_t v : {id(i, j), id(i + 1, j + 1), id(i, j + 1)}) c.faces.items.push_back(v);
      c.faces.offsets.push_back(static_cast<std::uint32_t>(c.faces.items.size()));
    }
  c.bvh = std::make_unique<TriangleBvh>(c.xyz, c.faces);
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const std::uint32_t n = nu * nv, step = std::max(1u, n / 100000);
  for (std::uint32_t v = 0; v < n; v += step) {
    const glm::dvec3 d(u(rng), u(rng), u(rng)), p(c.xyz[3 * v], c.xyz[3 * v + 1], c.xyz[3 * v + 2]);
    const glm::dvec3 q = p + 0.002 * d;
    c.points.push_back(q);
    c.normals.push_back(glm::normalize(p - glm::normalize(glm::dvec3(p.x, p.y, 0.0))));  // outwards
    c.hints.push_back(c.bvh->closest(q + 0.0005 * glm::dvec3(u(rng), u(rng), u(rng))).face);
  }
  return cache.emplace(nu, std::move(c)).first->second;
}

// range(0): nu; range(1): 1 with hints; range(2): 1 facing the outward normal.
void BM_Closest(benchmark::State& st) {
  const Case& c = torus(static_cast<std::uint32_t>(st.range(0)));
  const bool hinted = st.range(1) != 0, facing = st.range(2) != 0;
  const int threads = parallel_threads();
  set_parallel_threads(1);
  double sum = 0, seconds = 0;
  for (auto _ : st) {
    const auto t0 = std::chrono::steady_clock::now();
    for (std::size_t i = 0; i < c.points.size(); ++i)
      sum += c.bvh->closest(c.points[i], facing ? &c.normals[i] : nullptr, hinted ? c.hints[i] : UINT32_MAX).distance;
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  benchmark::DoNotOptimize(sum);
  set_parallel_threads(threads);
  st.counters["ns/query"] = 1e9 * seconds / (double(c.points.size()) * double(st.iterations()));
  st.counters["triangles"] = double(c.bvh->num_triangles());
}

BENCHMARK(BM_Closest)->ArgsProduct({{448, 1414}, {0, 1}, {0, 1}})->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
