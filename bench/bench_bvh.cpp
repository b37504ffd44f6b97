// The closest-point queries fitting makes (core/base/triangle_bvh.h; issue 17: a third of a
// 1 M fit's levels stage): a bumpy triangulated torus of 200 k and 2 M triangles, queried from
// points a little off the surface, once from the root and once with the hint a fitting round
// has (the face found for the point's position one round earlier), any side and one side.
// Prints ns per query. One thread: the queries are independent, fitting runs them on the pool.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <chrono>
#include <map>
#include <memory>
#include <random>

#include <glm/geometric.hpp>

#include "bench/bumpy_torus.h"
#include "core/base/parallel.h"
#include "core/base/triangle_bvh.h"

namespace {

using namespace sublift;

struct Case {
  std::unique_ptr<TriangleBvh> bvh;
  std::vector<glm::dvec3> points, normals;
  std::vector<std::uint32_t> hints;
};

// bench_fit's torus (bench/bumpy_torus.h); the query points are 100 k vertices moved off the
// surface by up to 0.002, their hints the faces found from 0.0005 away (where the point was a
// round earlier).
const Case& torus(std::uint32_t nu) {
  static std::map<std::uint32_t, Case> cache;
  if (auto it = cache.find(nu); it != cache.end()) return it->second;
  const bench::BumpyTorus& t = bench::bumpy_torus(nu);
  Case c;
  c.bvh = std::make_unique<TriangleBvh>(t.xyz, t.faces);
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const std::uint32_t step = std::max(1u, t.n / 100000);
  for (std::uint32_t v = 0; v < t.n; v += step) {
    const glm::dvec3 d(u(rng), u(rng), u(rng)), p(t.xyz[3 * v], t.xyz[3 * v + 1], t.xyz[3 * v + 2]);
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
