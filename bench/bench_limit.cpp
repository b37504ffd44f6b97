// Cost of a limit stencil against the valence (issue 18's hang: opening builds the limit stencils
// of the finest level, where an n-gon has become a valence-n face point). Two configurations:
//   fan    the centre of n quads (the face point of an n-gon one level down), the costly case
//   prism  a vertex on the n-gon cap of a prism (the n-gon itself in the star)
// Each run solves one configuration (probe_limit_stencil: the same solve build_limit_stencils
// caches per configuration). The goal is valence 1000 in well under 2 s (docs/limit_stencils.md:
// the dense eigen-analysis grew as n^3; stars above kLimitDenseStar now take the structured
// solve, about linear). bench_open measures whole opens in the modeler against OpenSubdiv.
#include <benchmark/benchmark.h>

#include "core/complex/complex_build.h"
#include "core/multires/limit.h"

namespace {
using namespace sublift;

Complex quad_fan(std::uint32_t n) {  // centre 0, edge vertices 1..n, corners n+1..2n
  Csr f;
  f.offsets = {0};
  for (std::uint32_t i = 0; i < n; ++i) {
    f.items.insert(f.items.end(), {0u, 1 + i, n + 1 + i, 1 + (i + 1) % n});
    f.offsets.push_back(static_cast<std::uint32_t>(f.items.size()));
  }
  return complex_from_polygons(2 * n + 1, f);
}

Complex ngon_prism(std::uint32_t n) {  // top ring 0..n-1, bottom n..2n-1
  Csr f;
  f.offsets = {0};
  for (std::uint32_t i = 0; i < n; ++i) f.items.push_back(i);
  f.offsets.push_back(static_cast<std::uint32_t>(f.items.size()));
  for (std::uint32_t i = n; i-- > 0;) f.items.push_back(n + i);
  f.offsets.push_back(static_cast<std::uint32_t>(f.items.size()));
  for (std::uint32_t i = 0; i < n; ++i) {
    f.items.insert(f.items.end(), {(i + 1) % n, i, n + i, n + (i + 1) % n});
    f.offsets.push_back(static_cast<std::uint32_t>(f.items.size()));
  }
  return complex_from_polygons(2 * n, f);
}

void run(benchmark::State& state, const Complex& c) {
  bool ok = true;
  for (auto _ : state) {
    const ProbedStencil p = probe_limit_stencil(c, 0);
    ok = ok && p.ok && !p.du.empty();
    benchmark::DoNotOptimize(p.weights.data());
  }
  if (!ok) state.SkipWithError("no stencil with tangents");
}

void BM_LimitStencilFan(benchmark::State& state) { run(state, quad_fan(static_cast<std::uint32_t>(state.range(0)))); }
void BM_LimitStencilPrismCap(benchmark::State& state) {
  run(state, ngon_prism(static_cast<std::uint32_t>(state.range(0))));
}

BENCHMARK(BM_LimitStencilFan)->Arg(8)->Arg(25)->Arg(50)->Arg(100)->Arg(200)->Arg(400)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LimitStencilPrismCap)->Arg(25)->Arg(100)->Arg(400)->Arg(1000)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
