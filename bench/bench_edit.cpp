// Dragging a control point in the modeler (issue 4, "Performance"): one level-0 point of
//   surface  a quad torus base of 1000 faces, cubic, 5 levels (1,024,000 finest vertices)
//   lattice  a 12^3 and a 16^3 hex block, cubic, 3 levels (912,673 and 2,146,689 finest vertices)
// with non-zero detail at every level, moved as a drag does (Session::move inside one
// begin_edit/end_edit), followed for the surface by the update of the limit positions and limit
// normals of what moved; versus a full synthesis of the same hierarchy (hierarchy.h
// synthesize, all threads) and a full limit and normal evaluation. The summary prints both and
// the ratio. The lattices are larger than the 250,000 vertices because a level-0 cubic
// basis function spans 4 coarse cells in each direction, 33^3 = 35,937 finest vertices at
// level 3: a 250,000-vertex lattice could not be 20x faster to update in part than in full.
// The local cost does not depend on the model's size, the full one grows with it.
// Sculpt brushes (issue 19): one inflate dab (core/edit/brush.h brush_dab + Session::move_each)
// at level 0 and at the finest level of the same surface, versus the same full synthesis.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "bench/bench_timing.h"
#include "core/complex/complex_build.h"
#include "core/base/csr.h"
#include "core/multires/hierarchy.h"
#include "core/multires/limit.h"
#include "core/edit/brush.h"
#include "core/edit/session.h"
#include "core/complex/shapes.h"

namespace {

using namespace sublift;
using bench::best_ms;
using bench::Clock;
using bench::note;
using bench::since_ms;

// Details: the pure subdivision plus a deterministic ripple, analysed.
Hierarchy detailed(Complex base, const std::vector<double>& xyz, int levels) {
  Hierarchy h = make_hierarchy(std::move(base), levels, Scheme::Cubic, 3);
  set_base(h, xyz);
  std::vector<double> fine = synthesize(h, levels);
  for (std::size_t i = 0; i < fine.size(); ++i) fine[i] += 0.002 * std::sin(0.37 * double(i));
  analyze(h, fine);
  return h;
}

struct Fixture {
  std::unique_ptr<Session> session;
  LimitStencils stencils;
  Csr faces, vertex_faces;  // finest surface (surface fixture only)
  std::vector<double> limit, normals;
  std::vector<std::uint32_t> changed_limit;
  std::uint32_t vertex = 0;
  bool surface = false;
};

Fixture& surface_fixture() {
  static Fixture f = [] {
    Fixture x;
    const SurfaceMesh m = make_quad_torus(40, 25);
    x.session = std::make_unique<Session>(detailed(complex_from_surface_mesh(m), flatten_positions(m), 5));
    const Hierarchy& h = x.session->hierarchy();
    x.stencils = build_limit_stencils(h);
    const Complex& fine = h.levels.back();
    x.faces = fine.faces;
    x.vertex_faces = fine.vertex_faces;
    const int J = x.session->finest_level();
    x.limit.resize(x.session->positions(J).size());
    x.normals.resize(x.limit.size());
    eval_limit(x.stencils, x.session->positions(J).data(), x.limit.data());
    limit_normals(x.stencils, x.faces, x.session->positions(J).data(), x.limit.data(), x.normals.data());
    orient_tangents(x.stencils, x.faces, x.session->positions(J).data(), x.limit.data());
    x.vertex = 20 * 25 + 12;  // an interior base vertex
    x.surface = true;
    return x;
  }();
  return f;
}

Fixture make_lattice(int n) {
  Fixture x;
  std::vector<double> xyz;
  Complex c = make_hex_block(n, xyz);
  x.session = std::make_unique<Session>(detailed(std::move(c), xyz, 3));
  const std::uint32_t m = std::uint32_t(n) / 2, side = std::uint32_t(n) + 1;
  x.vertex = (m * side + m) * side + m;  // the block's centre
  return x;
}

Fixture& lattice_fixture() {
  static Fixture f = make_lattice(12);
  return f;
}

Fixture& large_lattice_fixture() {
  static Fixture f = make_lattice(16);
  return f;
}

// One drag: moves back and forth so the shape stays put over many iterations.
void drag(benchmark::State& state, Fixture& f, const std::string& name) {
  Session& s = *f.session;
  const int J = s.finest_level();
  s.begin_edit("Drag");
  int k = 0;
  std::size_t updated = 0;
  for (auto _ : state) {
    const auto t0 = Clock::now();
    const double d = (k++ % 2 ? -1.0 : 1.0) * 0.01;
    const double delta[3] = {d, 0.5 * d, 0.0};
    const OpReport r = s.move(0, std::span<const std::uint32_t>(&f.vertex, 1), {}, delta);
    updated = r.vertices_updated;
    note(name + ": resynthesis only", since_ms(t0));
    if (f.surface) {
      f.changed_limit.clear();
      const auto t1 = Clock::now();
      eval_limit_subset(f.stencils, s.positions(J).data(), s.changed(J), f.limit.data(), f.changed_limit);
      note(name + ": limit positions", since_ms(t1));
      const auto t2 = Clock::now();
      limit_normals_subset(f.stencils, f.faces, f.vertex_faces, s.positions(J).data(), f.limit.data(), f.changed_limit,
                           f.normals.data());
      note(name + ": limit normals", since_ms(t2));
    }
    note(name, since_ms(t0));
  }
  s.end_edit();
  state.counters["vertices_updated"] = double(updated);
  state.counters["finest_vertices"] = double(s.num_vertices(J));
}

void full(benchmark::State& state, Fixture& f, const std::string& name) {
  const Hierarchy& h = f.session->hierarchy();
  const int J = h.finest_level();
  for (auto _ : state) {
    const auto t0 = Clock::now();
    std::vector<double> x = synthesize(h, J);
    benchmark::DoNotOptimize(x.data());
    note(name, since_ms(t0));
    if (f.surface) {
      const auto t1 = Clock::now();
      eval_limit(f.stencils, x.data(), f.limit.data());
      limit_normals(f.stencils, f.faces, x.data(), f.limit.data(), f.normals.data());
      note(name + "+limit", since_ms(t0));
      note("limit+normals (full)", since_ms(t1));
    }
  }
}

// One dab at `level`: the brush scan and the move with its local resynthesis (and, at level 0,
// the fold-back is nothing; at the finest level the fold-back analyses the change down).
void dab(benchmark::State& state, int level, double radius, const std::string& name) {
  Fixture& f = surface_fixture();
  Session& s = *f.session;
  Complex c = s.hierarchy().levels[static_cast<std::size_t>(level)];
  build_adjacency(c);
  const auto p0 = s.positions(level);
  BrushSettings b;
  b.kind = BrushKind::Inflate;
  b.radius = radius;
  b.strength = 0.3;
  b.front_faces_only = false;
  const std::size_t v = 3 * std::size_t(f.vertex);
  Dab d;
  d.center = {p0[v], p0[v + 1], p0[v + 2]};
  std::vector<std::uint32_t> vs;
  std::vector<double> deltas;
  std::size_t moved = 0, updated = 0;
  s.begin_edit("Brush");
  int k = 0;
  for (auto _ : state) {
    b.invert = k++ % 2 != 0;  // in and out: the shape stays put over the iterations
    const auto t0 = Clock::now();
    brush_dab(b, d, c, s.positions(level), vs, deltas);
    note(name + ": brush scan", since_ms(t0));
    const OpReport r = s.move_each(level, vs, deltas);
    note(name, since_ms(t0));
    moved = vs.size(), updated = r.vertices_updated;
  }
  s.end_edit();
  state.counters["points_dabbed"] = double(moved);
  state.counters["vertices_updated"] = double(updated);
}

// Where a sculpt dab lands: the mouse ray's hit on the limit surface, brute force over its faces
// (core/edit/brush.h ray_hit), what the modeler does per mouse move in sculpt mode.
void BM_SurfaceRayHit(benchmark::State& state) {
  Fixture& f = surface_fixture();
  const std::size_t v = 3 * std::size_t(f.vertex);
  const glm::dvec3 target(f.limit[v], f.limit[v + 1], f.limit[v + 2]);
  const glm::dvec3 origin = target + glm::dvec3(0.0, 0.0, 5.0);
  glm::dvec3 hit;
  for (auto _ : state) {
    const auto t0 = Clock::now();
    benchmark::DoNotOptimize(ray_hit(f.limit, f.faces, origin, glm::dvec3(0.0, 0.0, -1.0), hit));
    note("surface ray hit (brute force)", since_ms(t0));
  }
  state.counters["faces"] = double(f.faces.rows());
}
BENCHMARK(BM_SurfaceRayHit)->Unit(benchmark::kMillisecond)->MinTime(1.0);

void BM_SurfaceDabLevel0(benchmark::State& s) { dab(s, 0, 0.35, "surface dab at level 0"); }
void BM_SurfaceDabFinest(benchmark::State& s) { dab(s, 5, 0.05, "surface dab at level 5"); }
BENCHMARK(BM_SurfaceDabLevel0)->Unit(benchmark::kMillisecond)->MinTime(1.0);
BENCHMARK(BM_SurfaceDabFinest)->Unit(benchmark::kMillisecond)->MinTime(1.0);

void BM_SurfaceDragLocal(benchmark::State& s) { drag(s, surface_fixture(), "surface drag (local + limit)"); }
void BM_SurfaceFullSynthesis(benchmark::State& s) { full(s, surface_fixture(), "surface full synthesis"); }
void BM_LatticeDragLocal(benchmark::State& s) { drag(s, lattice_fixture(), "lattice drag (local)"); }
void BM_LatticeFullSynthesis(benchmark::State& s) { full(s, lattice_fixture(), "lattice full synthesis"); }
void BM_LargeLatticeDragLocal(benchmark::State& s) { drag(s, large_lattice_fixture(), "lattice 16^3 drag (local)"); }
void BM_LargeLatticeFullSynthesis(benchmark::State& s) {
  full(s, large_lattice_fixture(), "lattice 16^3 full synthesis");
}

BENCHMARK(BM_SurfaceDragLocal)->Unit(benchmark::kMillisecond)->MinTime(1.0);
BENCHMARK(BM_SurfaceFullSynthesis)->Unit(benchmark::kMillisecond)->MinTime(1.0);
BENCHMARK(BM_LatticeDragLocal)->Unit(benchmark::kMillisecond)->MinTime(1.0);
BENCHMARK(BM_LatticeFullSynthesis)->Unit(benchmark::kMillisecond)->MinTime(1.0);
BENCHMARK(BM_LargeLatticeDragLocal)->Unit(benchmark::kMillisecond)->MinTime(1.0);
BENCHMARK(BM_LargeLatticeFullSynthesis)->Unit(benchmark::kMillisecond)->MinTime(1.0);

void print_summary() {
  auto& m = best_ms();
  auto get = [&](const std::string& k) { return m.count(k) ? m[k] : 0.0; };
  std::printf("\nSummary (best of the iterations, ms)\n");
  for (const auto& [k, v] : m) std::printf("  %-40s %10.3f\n", k.c_str(), v);
  const double sl = get("surface drag (local + limit)"), sf = get("surface full synthesis"),
               sfl = get("surface full synthesis+limit");
  const double ll = get("lattice drag (local)"), lf = get("lattice full synthesis");
  const double sr = get("surface drag (local + limit): resynthesis only");
  if (sl > 0 && sf > 0) {
    std::printf("surface: drag %.3f ms (60 Hz frame: 16.7 ms), full synthesis %.1f ms: %.1fx; with limit+normals %.1f ms: %.1fx\n",
                sl, sf, sf / sl, sfl, sfl / sl);
    if (sr > 0) std::printf("surface: local resynthesis alone %.3f ms vs full synthesis %.1f ms: %.1fx\n", sr, sf, sf / sr);
  }
  if (ll > 0 && lf > 0) std::printf("lattice 12^3: drag %.3f ms, full synthesis %.1f ms: %.1fx\n", ll, lf, lf / ll);
  for (const char* k : {"surface dab at level 0", "surface dab at level 5"})
    if (get(k) > 0 && sf > 0)
      std::printf("%s: %.3f ms (brush scan %.3f ms), full synthesis %.1f ms: %.1fx\n", k, get(k),
                  get(std::string(k) + ": brush scan"), sf, sf / get(k));
  const double Ll = get("lattice 16^3 drag (local)"), Lf = get("lattice 16^3 full synthesis");
  if (Ll > 0 && Lf > 0) std::printf("lattice 16^3: drag %.3f ms, full synthesis %.1f ms: %.1fx\n", Ll, Lf, Lf / Ll);
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  print_summary();
  return 0;
}
