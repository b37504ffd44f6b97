// Fitting any mesh (core/fit, issue 17, docs/fit.md) at 100 k and 1 M input vertices: a bumpy
// triangulated torus with no subdivision connectivity, fitted with the defaults (a base of 1/64
// of the vertices, the levels that bring it to about the input's count) by Loop, Bertram's
// cubic and sqrt(2) (the default scheme; the polygon schemes from quad-dominant bases), every
// stage timed. The goals: 100 k in under 10 s, 1 M in under 60 s, on this machine's 2
// cores. The "base" column is OpenMesh's decimater alone: the peer's own cost of that stage.
#include <benchmark/benchmark.h>

#include <cstdio>

#include "bench/bench_timing.h"
#include "bench/bumpy_torus.h"
#include "core/fit/base_mesh.h"
#include "core/fit/fit_levels.h"
#include "core/schemes/registry.h"

namespace {

using namespace sublift;

using Input = bench::BumpyTorus;
const Input& torus(std::uint32_t nu) { return bench::bumpy_torus(nu); }

constexpr std::uint32_t kSizes[] = {448, 1414};  // 100,352 and 999,698 vertices

constexpr Scheme kSchemes[] = {Scheme::Loop, Scheme::Cubic, Scheme::Sqrt2};

std::string key(const char* what, std::uint32_t nu, Scheme s) { return std::string(what) + "/" + std::to_string(nu) + "/" + scheme_name(s); }

void BM_Fit(benchmark::State& st) {
  const auto nu = static_cast<std::uint32_t>(st.range(0));
  const Scheme scheme = static_cast<Scheme>(st.range(1));
  const Input& in = torus(nu);
  st.SetLabel(scheme_name(scheme));
  for (auto _ : st) {
    const auto t0 = bench::Clock::now();
    BaseMeshOptions bo;
    bo.quads = fit_base_quads(scheme);
    FitOptions o;
    o.scheme = scheme;
    o.levels = -1;  // default_fit_levels
    const MeshFit m = fit_mesh(in.n, in.faces, in.xyz, bo, o);
    const Fitted& f = m.fitted;
    bench::note(key("base", nu, scheme), m.base_ms);
    bench::note(key("fit", nu, scheme), bench::since_ms(t0));
    for (const auto& [stage, ms] : f.stage_ms) bench::note(key(stage.c_str(), nu, scheme), ms);
    bench::note(key("limit_max_ppm", nu, scheme), 1e6 * std::max(f.limit_max, f.limit_back_max));
    bench::note(key("folded", nu, scheme), f.limit_folded + f.levels.back().folded);
    st.counters["input_vertices"] = in.n;
    st.counters["finest_vertices"] = f.hierarchy.num_vertices(f.hierarchy.finest_level());
  }
}

BENCHMARK(BM_Fit)
    ->ArgsProduct({{kSizes[0], kSizes[1]}, {int(kSchemes[0]), int(kSchemes[1]), int(kSchemes[2])}})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  auto& b = bench::best_ms();
  std::printf("\nfit of a bumpy torus (defaults: base 1/64, levels to about the input's count), ms per stage:\n");
  std::printf("%9s %7s %9s %9s %9s %9s %9s %9s %9s %11s %7s %6s\n", "vertices", "scheme", "total", "base", "indexing", "hierarchy",
              "levels", "analysis", "report", "max dist %", "folded", "goal");
  for (std::uint32_t nu : kSizes)
    for (Scheme s : kSchemes) {
      if (!b.count(key("fit", nu, s))) continue;
      const double total = b[key("fit", nu, s)], goal = nu < 1000 ? 10000 : 60000;
      std::printf("%9u %7s %9.0f %9.0f %9.0f %9.0f %9.0f %9.0f %9.0f %11.4f %7.0f %5.2fx\n", torus(nu).n, scheme_name(s).c_str(), total,
                  b[key("base", nu, s)], b[key("indexing", nu, s)], b[key("hierarchy", nu, s)], b[key("levels", nu, s)],
                  b[key("analysis", nu, s)], b[key("report", nu, s)], 1e-4 * b[key("limit_max_ppm", nu, s)], b[key("folded", nu, s)],
                  total / goal);
    }
  std::printf("goal: 100 k vertices in under 10 s, 1 M in under 60 s (the last column: time over the goal; folded: net + limit)\n");
  benchmark::Shutdown();
  return 0;
}
