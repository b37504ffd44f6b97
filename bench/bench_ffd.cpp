// Free-form deformation (issue 6, "Performance"): a 100,000-vertex model (points on a sphere of
// radius 1, Fibonacci spiral) in a 4x4x4 box lattice (margin 0.1) refined 3 levels with the cubic
// scheme (32^3 = 32,768 finest hexahedra, 35,937 finest vertices).
//   BM_FfdBind               bind_model against the finest level (arg 1: one thread, 0: all;
//                            target < 1 s)
//   BM_FfdDeformLevel0Edit   Session::move of one level-0 lattice point (arg 0: the centre,
//                            arg 1: a corner), then deform_changed with session.changed(finest)
//                            (target < 10 ms for the vertices that move)
// The summary prints the best times of each part and the counts.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "bench/bench_timing.h"
#include "core/ffd/box_lattice.h"
#include "core/ffd/ffd.h"
#include "core/multires/hierarchy.h"
#include "core/base/parallel.h"
#include "core/edit/session.h"

namespace {

using namespace sublift;
using bench::best_ms;
using bench::Clock;
using bench::note;
using bench::since_ms;

std::map<std::string, double>& counts() {
  static std::map<std::string, double> m;
  return m;
}

struct Fixture {
  std::vector<double> model;
  std::unique_ptr<Session> session;
  FfdBinding binding;
  std::vector<double> out;
};

Fixture& fixture() {
  static Fixture f = [] {
    Fixture x;
    const std::uint32_t n = 100000;
    const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
    for (std::uint32_t i = 0; i < n; ++i) {
      const double z = 1.0 - 2.0 * (i + 0.5) / n, r = std::sqrt(1.0 - z * z), t = golden * i;
      x.model.insert(x.model.end(), {r * std::cos(t), r * std::sin(t), z});
    }
    const auto bb = bounding_box(x.model.data(), n);
    const Shape box = make_box_lattice(bb[0], bb[1], 4, 4, 4, 0.1);
    Hierarchy h = make_hierarchy(box.base, 3, Scheme::Cubic, 3);
    set_base(h, box.positions);
    x.session = std::make_unique<Session>(std::move(h));
    return x;
  }();
  return f;
}

void BM_FfdBind(benchmark::State& state) {
  Fixture& f = fixture();
  Session& s = *f.session;
  const int J = s.finest_level();
  const Complex& fine = s.hierarchy().levels[static_cast<std::size_t>(J)];
  const int threads = parallel_threads();
  if (state.range(0) == 1) set_parallel_threads(1);
  const std::string name = state.range(0) == 1 ? "bind, one thread" : "bind, all threads";
  for (auto _ : state) {
    const auto t0 = Clock::now();
    f.binding = bind_model(fine, s.positions(J), f.model);
    note(name, since_ms(t0));
  }
  set_parallel_threads(threads);
  state.counters["model_vertices"] = double(f.binding.num_model_vertices());
  state.counters["bound"] = double(f.binding.report.bound);
  state.counters["outside"] = double(f.binding.report.outside);
  state.counters["finest_cells"] = double(fine.num_cells());
  counts()["finest cells"] = fine.num_cells();
  counts()["bound"] = double(f.binding.report.bound);
  counts()["outside"] = double(f.binding.report.outside);
  f.out.resize(f.model.size());
  deform(f.binding, s.positions(J), f.out);
}
BENCHMARK(BM_FfdBind)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->Iterations(5);

void BM_FfdDeformLevel0Edit(benchmark::State& state) {
  Fixture& f = fixture();
  if (f.binding.num_model_vertices() == 0) {
    Session& s = *f.session;
    f.binding = bind_model(s.hierarchy().levels.back(), s.positions(s.finest_level()), f.model);
    f.out.resize(f.model.size());
    deform(f.binding, s.positions(s.finest_level()), f.out);
  }
  Session& s = *f.session;
  const int J = s.finest_level();
  const std::uint32_t vertex = state.range(0) == 0 ? (2 * 5 + 2) * 5 + 2 : 0;  // centre or corner of 5^3
  const std::string name = state.range(0) == 0 ? "centre" : "corner";
  std::vector<std::uint32_t> touched;
  std::size_t changed = 0;
  int k = 0;
  s.begin_edit("Drag");
  for (auto _ : state) {
    const double d = (k++ % 2 ? -1.0 : 1.0) * 0.05;
    const double delta[3] = {d, 0.5 * d, -0.25 * d};
    const auto t0 = Clock::now();
    s.move(0, std::span<const std::uint32_t>(&vertex, 1), {}, delta);
    const auto t1 = Clock::now();
    deform_changed(f.binding, s.positions(J), s.changed(J), f.out, &touched);
    note(name + ": deform_changed", since_ms(t1));
    note(name + ": session move", std::chrono::duration<double, std::milli>(t1 - t0).count());
    changed = s.changed(J).size();
  }
  s.end_edit();
  state.counters["model_vertices_moved"] = double(touched.size());
  state.counters["lattice_vertices_changed"] = double(changed);
  counts()[name + ": model vertices moved"] = double(touched.size());
  counts()[name + ": finest lattice vertices changed"] = double(changed);
}
BENCHMARK(BM_FfdDeformLevel0Edit)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  std::printf("\nFFD summary (best of the runs, ms; targets: bind < 1000, deform_changed < 10)\n");
  for (const auto& [name, ms] : best_ms()) std::printf("  %-40s %10.3f\n", name.c_str(), ms);
  for (const auto& [name, n] : counts()) std::printf("  %-40s %10.0f\n", name.c_str(), n);
  return 0;
}
