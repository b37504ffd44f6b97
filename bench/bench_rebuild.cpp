// Rebuilding levels of a mesh subdivided elsewhere (core/multires/rebuild.h) at 0.25 M, 1 M and
// 4 M finest vertices: detection + hierarchy + analysis, against the same hierarchy built and
// analysed when the order is already the engine's (what detection adds) and against
// OpenSubdiv's uniform topology refinement of the same base to the same level (a peer's linear
// topology pass of equal size). Cost per vertex should stay flat; the goal is 1 M
// vertices rebuilt in under 1 s on 2 cores.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <numeric>
#include <random>

#include "bench/bench_timing.h"
#include "core/complex/complex_build.h"
#include "core/multires/rebuild.h"
#include "tests/mesh_fixtures.h"
#include "tests/osd_refiner.h"

namespace {

using namespace sublift;

// Finest levels of the 3 x 5 quad torus (15 quads; each level has 4 times the vertices).
constexpr int kLevels[] = {7, 8, 9};  // 245,760 / 983,040 / 3,932,160 vertices

struct Input {
  std::uint32_t n = 0;
  Csr faces;
  std::vector<double> xyz;
  Complex base;
};

const Input& input(int levels) {
  static std::map<int, Input> cache;
  auto it = cache.find(levels);
  if (it != cache.end()) return it->second;
  const fixtures::Polygons t = fixtures::torus(3, 5);
  Input in;
  in.base = complex_from_polygons(t.num_vertices, t.faces);
  Hierarchy h = make_hierarchy(in.base, levels, Scheme::Cubic, 3);
  set_base(h, t.positions);
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-1e-3, 1e-3);
  for (std::size_t i = t.positions.size(); i < h.coeffs.size(); ++i) h.coeffs[i] = u(rng);
  const std::vector<double> x = synthesize(h, levels);
  const Complex& fine = h.levels.back();
  std::vector<std::uint32_t> perm(fine.num_vertices);
  std::iota(perm.begin(), perm.end(), 0u);
  std::shuffle(perm.begin(), perm.end(), rng);
  std::vector<std::size_t> order(fine.num_faces());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::shuffle(order.begin(), order.end(), rng);
  in.n = fine.num_vertices;
  in.faces.items.reserve(fine.faces.items.size());
  for (std::size_t f : order) {
    for (std::uint32_t v : fine.faces.row(f)) in.faces.items.push_back(perm[v]);
    in.faces.offsets.push_back(static_cast<std::uint32_t>(in.faces.items.size()));
  }
  in.xyz.resize(x.size());
  for (std::uint32_t v = 0; v < fine.num_vertices; ++v)
    for (int k = 0; k < 3; ++k) in.xyz[3 * std::size_t(perm[v]) + k] = x[3 * std::size_t(v) + k];
  return cache.emplace(levels, std::move(in)).first->second;
}

std::string key(const char* what, int levels) { return std::string(what) + "/L" + std::to_string(levels); }

void per_vertex(benchmark::State& st, std::uint32_t n) {
  st.counters["finest_vertices"] = n;
  st.counters["ns_per_vertex"] = benchmark::Counter(n, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_Rebuild(benchmark::State& st) {
  const int L = static_cast<int>(st.range(0));
  const Input& in = input(L);
  for (auto _ : st) {
    const auto t0 = bench::Clock::now();
    Rebuilt r = rebuild_hierarchy(in.n, in.faces, in.xyz, Scheme::Cubic, -1);
    bench::note(key("rebuild", L), bench::since_ms(t0));
    bench::note(key("detect", L), r.detect_ms);
    bench::note(key("build", L), r.build_ms);
    bench::note(key("analyse", L), r.analysis_ms);
    if (r.hierarchy.finest_level() != L) st.SkipWithError("wrong level count");
    benchmark::DoNotOptimize(r);
  }
  per_vertex(st, in.n);
}

// The same hierarchy built and analysed in engine order: all of rebuild but the detection.
void BM_EngineOrder(benchmark::State& st) {
  const int L = static_cast<int>(st.range(0));
  const Input& in = input(L);
  for (auto _ : st) {
    const auto t0 = bench::Clock::now();
    Hierarchy h = make_hierarchy(in.base, L, Scheme::Cubic, 3);
    analyze(h, in.xyz);  // the values' order does not change the work
    bench::note(key("engine", L), bench::since_ms(t0));
    benchmark::DoNotOptimize(h);
  }
  per_vertex(st, in.n);
}

void BM_OsdTopology(benchmark::State& st) {
  const int L = static_cast<int>(st.range(0));
  const fixtures::Polygons t = fixtures::torus(3, 5);
  for (auto _ : st) {
    const auto t0 = bench::Clock::now();
    auto r = fixtures::osd_refiner(t, OpenSubdiv::Sdc::SCHEME_CATMARK, L);
    bench::note(key("osd", L), bench::since_ms(t0));
    benchmark::DoNotOptimize(r);
  }
  per_vertex(st, input(L).n);
}

BENCHMARK(BM_Rebuild)->Arg(7)->Arg(8)->Arg(9)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_EngineOrder)->Arg(7)->Arg(8)->Arg(9)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_OsdTopology)->Arg(7)->Arg(8)->Arg(9)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  auto& b = bench::best_ms();
  if (!b.count(key("rebuild", kLevels[0]))) return 0;
  std::printf("\nrebuild (detect + build + analyse) of a shuffled cubic-refined 3x5 torus, best of 3, ms:\n");
  std::printf("%9s %10s %8s %8s %8s %8s %8s %10s %10s\n", "vertices", "rebuild", "ns/vert", "detect", "build", "analyse", "engine",
              "x engine", "x osd topo");
  for (int L : kLevels) {
    const double n = input(L).n, r = b[key("rebuild", L)];
    std::printf("%9.0f %10.1f %8.1f %8.1f %8.1f %8.1f %8.1f %10.2f %10.2f\n", n, r, 1e6 * r / n, b[key("detect", L)], b[key("build", L)],
                b[key("analyse", L)], b[key("engine", L)], r / b[key("engine", L)], r / b[key("osd", L)]);
  }
  const double one_m = b[key("rebuild", 8)];
  std::printf("1 M vertices (983,040) rebuilt in %.0f ms: %s the 1 s goal\n", one_m, one_m < 1000 ? "within" : "over");
  benchmark::Shutdown();
  return 0;
}
