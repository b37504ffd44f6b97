// The triangle-mesh wavelet transforms of paper 004 (Lounsbery, DeRose & Warren: linear-tri,
// butterfly, Loop; core/schemes/tri/tri_transform.h) versus Bertram's cubic lifting (1-to-4 quads) at the
// same finest size, in one run:
//   analysis   analyze_transition for j = J-1..0 on one array in place, from the finest
//              positions (the copy that restores them before each iteration is excluded)
//   synthesis  synthesize_transition for j = 0..J-1 in place, from the coefficients that the
//              analysis gave (cubic: base positions plus small nonzero wavelets)
//   setup      make_hierarchy (levels + transitions, once per shape); the triangle schemes cache
//              their wavelet coefficients per neighbourhood type process-wide, so each setup
//              iteration runs in a fresh child process (this binary, --tri-setup-child) that
//              builds twice: "first" pays for solving the types, "second" finds them cached
//   loop parts Loop's analysis split into the sparse solve (the Matrix step, Eigen BiCGSTAB,
//              serial) and the lifting sub-steps (parallel), and its synthesis into the lifting
//              sub-steps and the vertex rule (the Matrix step, serial)
// Input: the scan ../shared/data/scans/bunny_npm_lowres.obj (SUBLIFT_SHARED_DATA) resampled onto
// the octahedron split J times (core/analysis/sphere_resample.h, the order make_hierarchy builds on
// octahedron_complex()); an analytic star-shaped surface when the file is absent (printed).
// Sizes: J = 8 (262,146 finest vertices) and J = 9 (1,048,578). Cubic: closed quad torus 64 x 16
// (1024 quads, make_quad_torus) with L = 4 (262,144) and L = 5 (1,048,576).
// Times are the best over iterations (bench_timing.h); counters: ns per finest vertex and the
// ratio to cubic (same operation and size, measured earlier in the same run).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "bench/bench_timing.h"
#include "core/complex/complex_build.h"
#include "core/multires/hierarchy.h"
#include "core/io/mesh/mesh_import.h"
#include "core/complex/shapes.h"
#include "core/analysis/sphere_resample.h"
#include "core/engine/executor.h"
#include "core/schemes/tri/tri_transform.h"

#ifndef SUBLIFT_SHARED_DATA
#define SUBLIFT_SHARED_DATA "../shared/data"
#endif

namespace {

using namespace sublift;
using bench::best_ms;
using bench::Clock;
using bench::note;
using bench::since_ms;

constexpr int kTorusU = 64, kTorusV = 16;  // cubic base: 1024 quads
constexpr const char* kChildFlag = "--tri-setup-child=";

struct Size {
  std::string name;
  int J;  // triangle splits of the octahedron
  int L;  // cubic levels on the 64 x 16 torus
};

const std::vector<Size>& sizes() {
  static const std::vector<Size> all = {{"262k", 8, 4}, {"1M", 9, 5}};
  return all;
}

std::string scan_path() { return std::string(SUBLIFT_SHARED_DATA) + "/scans/bunny_npm_lowres.obj"; }

// ---- Input: the scan resampled onto the split octahedron ---------------------------------------

struct Input {
  std::vector<double> finest;  // x, y, z per fine vertex, engine order
  std::string source;
};

std::map<int, Input> g_input;  // by J

const Input& input(int J) {
  auto it = g_input.find(J);
  if (it != g_input.end()) return it->second;
  Input in;
  const std::string path = scan_path();
  if (std::filesystem::exists(path)) {
    const LoadedMesh m = import_surface_mesh(path);
    const auto t0 = Clock::now();
    SphereResample r = resample_sphere(m.mesh, J);
    const double ms = since_ms(t0);
    in.finest = std::move(r.positions);
    in.source = "bunny_npm_lowres.obj (" + std::to_string(m.mesh.num_vertices()) + " vertices, " +
                std::to_string(m.mesh.num_faces()) + " faces), " + std::to_string(r.missed) + " missed rays";
    std::printf("input J=%d: %s resampled in %.0f ms\n", J, in.source.c_str(), ms);
  } else {
    // Fallback: r(d) = 1 + 0.15 sin(3 x) cos(5 y) + 0.1 z^2 on the geodesic sphere's directions.
    const GeodesicSphere s = geodesic_sphere(J);
    for (const glm::dvec3& d : s.directions) {
      const double r = 1.0 + 0.15 * std::sin(3 * d.x) * std::cos(5 * d.y) + 0.1 * d.z * d.z;
      in.finest.insert(in.finest.end(), {r * d.x, r * d.y, r * d.z});
    }
    in.source = "analytic star-shaped surface (" + path + " absent)";
    std::printf("input J=%d: FALLBACK to an %s\n", J, in.source.c_str());
  }
  return g_input.emplace(J, std::move(in)).first->second;
}

// ---- Hierarchies ----------------------------------------------------------------------------

/// Small deterministic nonzero wavelets after the first `keep` values (as bench_sqrt2).
void fill_wavelets(std::vector<double>& x, std::size_t keep) {
  std::uint64_t s = 88172645463325252ull;
  for (std::size_t i = keep; i < x.size(); ++i) {
    s ^= s << 13, s ^= s >> 7, s ^= s << 17;
    x[i] = 1e-3 * (double(s >> 11) * 0x1.0p-53 - 0.5);
  }
}

struct Data {
  Hierarchy h;
  std::vector<double> finest;  // analysis input
  std::vector<double> coeffs;  // synthesis input (the analysis of `finest`)
  double max_error = 0;        // |synthesize(analyze(finest)) - finest|_inf
  double update_entries = 0, predict_entries = 0;  // triangle schemes: sparse terms, all levels
  int levels() const { return h.finest_level(); }
  double vertices() const { return h.num_vertices(h.finest_level()); }
};

std::map<std::string, std::unique_ptr<Data>> g_data;  // by "<scheme> <size>"

std::string key(Scheme s, const Size& sz) { return scheme_name(s) + " " + sz.name; }

const Data& data(Scheme s, const Size& sz) {
  auto it = g_data.find(key(s, sz));
  if (it != g_data.end()) return *it->second;
  auto d = std::make_unique<Data>();
  if (s == Scheme::Cubic) {
    const SurfaceMesh torus = make_quad_torus(kTorusU, kTorusV);
    d->h = make_hierarchy(complex_from_surface_mesh(torus), sz.L, Scheme::Cubic, 3);
    const std::vector<double> base = flatten_positions(torus);
    set_base(d->h, base);
    fill_wavelets(d->h.coeffs, base.size());
    d->coeffs = d->h.coeffs;
    d->finest = synthesize(d->h, sz.L);
  } else {
    const Input& in = input(sz.J);
    d->h = make_hierarchy(octahedron_complex(), sz.J, s, 3);
    if (d->h.coeffs.size() != in.finest.size()) throw std::logic_error("bench_tri: resampled size differs from the hierarchy");
    d->finest = in.finest;
    analyze(d->h, d->finest);
    d->coeffs = d->h.coeffs;
    for (const Transition& t : d->h.transitions) {
      d->update_entries += double(std::get<WeightedStep>(t.steps[0].op).sources.items.size());
      d->predict_entries += double(std::get<WeightedStep>(t.steps[1].op).sources.items.size());
    }
  }
  const std::vector<double> back = synthesize(d->h, d->h.finest_level());
  for (std::size_t i = 0; i < back.size(); ++i) d->max_error = std::max(d->max_error, std::abs(back[i] - d->finest[i]));
  return *g_data.emplace(key(s, sz), std::move(d)).first->second;
}

double ms_of(const std::string& k) {
  auto it = best_ms().find(k);
  return it == best_ms().end() ? 0.0 : it->second;
}

// ---- Transform benchmarks -------------------------------------------------------------------

void counters(benchmark::State& st, const std::string& op, Scheme s, const Size& sz, const Data& d) {
  const double ms = ms_of(op + " " + key(s, sz));
  st.counters["finest_vertices"] = d.vertices();
  st.counters["ns_per_vertex"] = ms * 1e6 / d.vertices();
  st.counters["max_error"] = d.max_error;
  if (s != Scheme::Cubic) {
    const double c = ms_of(op + " " + key(Scheme::Cubic, sz));
    const double cv = g_data.count(key(Scheme::Cubic, sz)) ? g_data[key(Scheme::Cubic, sz)]->vertices() : 0;
    // Per vertex (the sizes differ by 2 vertices).
    if (c > 0 && cv > 0) st.counters["x_cubic"] = (ms / d.vertices()) / (c / cv);
  }
}

void BM_Analysis(benchmark::State& st, Scheme s, const Size* sz) {
  const Data& d = data(s, *sz);
  const std::string k = "analysis " + key(s, *sz);
  std::vector<double> x(d.finest.size());
  for (auto _ : st) {
    std::copy(d.finest.begin(), d.finest.end(), x.begin());
    double total = 0;
    for (int j = d.levels() - 1; j >= 0; --j) {
      const auto t0 = Clock::now();
      analyze_transition(d.h, j, x.data(), 3, false);
      const double ms = since_ms(t0);
      note(k + " level " + std::to_string(j), ms);
      total += ms;
    }
    st.SetIterationTime(total * 1e-3);
    benchmark::ClobberMemory();
    note(k, total);
  }
  counters(st, "analysis", s, *sz, d);
}

void BM_Synthesis(benchmark::State& st, Scheme s, const Size* sz) {
  const Data& d = data(s, *sz);
  const std::string k = "synthesis " + key(s, *sz);
  std::vector<double> x(d.coeffs.size());
  for (auto _ : st) {
    std::copy(d.coeffs.begin(), d.coeffs.end(), x.begin());
    double total = 0;
    for (int j = 0; j < d.levels(); ++j) {
      const auto t0 = Clock::now();
      synthesize_transition(d.h, j, x.data(), 3, false, false);
      const double ms = since_ms(t0);
      note(k + " level " + std::to_string(j), ms);
      total += ms;
    }
    st.SetIterationTime(total * 1e-3);
    benchmark::ClobberMemory();
    note(k, total);
  }
  counters(st, "synthesis", s, *sz, d);
}

/// The steps of one transition of one kind (Matrix or not), to time Loop's parts apart.
Transition part(const Transition& t, bool matrix) {
  Transition p;
  p.num_coarse = t.num_coarse;
  p.num_fine = t.num_fine;
  for (const Step& s : t.steps)
    if (std::holds_alternative<MatrixStep>(s.op) == matrix) p.steps.push_back(s);
  return p;
}

/// Loop's transitions split as the executor runs them: the solve (analysis) or vertex rule
/// (synthesis), serial, and the lifting steps, parallel. Manual time: both.
void BM_LoopParts(benchmark::State& st, const Size* sz) {
  const Data& d = data(Scheme::Loop, *sz);
  std::vector<Transition> rule, lifting;
  for (const Transition& t : d.h.transitions) rule.push_back(part(t, true)), lifting.push_back(part(t, false));
  const std::string k = "loop parts " + sz->name;
  std::vector<double> x(d.finest.size());
  double err = 0;
  for (auto _ : st) {
    double solve = 0, alift = 0, slift = 0, smooth = 0;
    std::copy(d.finest.begin(), d.finest.end(), x.begin());
    for (int j = d.levels() - 1; j >= 0; --j) {
      const auto J = std::size_t(j);
      auto t0 = Clock::now();
      run_analysis(rule[J], d.h.levels[J], x.data(), 3, false);
      const double ms = since_ms(t0);
      note(k + " solve level " + std::to_string(j), ms);
      solve += ms;
      t0 = Clock::now();
      run_analysis(lifting[J], d.h.levels[J], x.data(), 3, false);
      alift += since_ms(t0);
    }
    for (std::size_t i = 0; i < x.size(); ++i) err = std::max(err, std::abs(x[i] - d.coeffs[i]));
    for (int j = 0; j < d.levels(); ++j) {
      const auto J = std::size_t(j);
      auto t0 = Clock::now();
      run_synthesis(lifting[J], d.h.levels[J], x.data(), 3, false);
      slift += since_ms(t0);
      t0 = Clock::now();
      run_synthesis(rule[J], d.h.levels[J], x.data(), 3, false);
      smooth += since_ms(t0);
    }
    st.SetIterationTime((solve + alift + slift + smooth) * 1e-3);
    note(k + " analysis solve", solve);
    note(k + " analysis lifting", alift);
    note(k + " synthesis lifting", slift);
    note(k + " synthesis smooth", smooth);
  }
  st.counters["solve_ms"] = ms_of(k + " analysis solve");
  st.counters["alift_ms"] = ms_of(k + " analysis lifting");
  st.counters["slift_ms"] = ms_of(k + " synthesis lifting");
  st.counters["smooth_ms"] = ms_of(k + " synthesis smooth");
  st.counters["coeff_diff"] = err;  // against analyze(): the same operations, so ~0
}

// ---- Setup ----------------------------------------------------------------------------------

/// Child mode: builds the hierarchy twice in this fresh process and prints both times (ms).
int setup_child(const std::string& s) {
  const auto colon = s.find(':');
  const Scheme scheme = parse_scheme(s.substr(0, colon));
  const int J = std::stoi(s.substr(colon + 1));
  double ms[2];
  for (double& m : ms) {
    const auto t0 = Clock::now();
    Hierarchy h = make_hierarchy(octahedron_complex(), J, scheme, 3);
    m = since_ms(t0);
    benchmark::DoNotOptimize(h.coeffs.data());
  }
  std::printf("%.6f %.6f\n", ms[0], ms[1]);
  return 0;
}

void BM_TriSetup(benchmark::State& st, Scheme s, const Size* sz) {
  const std::string k = "setup " + key(s, *sz);
  for (auto _ : st) {
    const std::vector<double> r = bench::numbers_from_child(kChildFlag, scheme_name(s) + ":" + std::to_string(sz->J), 2);
    if (r.empty()) {
      st.SkipWithError("setup child failed");
      return;
    }
    st.SetIterationTime(r[0] * 1e-3);
    note(k + " first", r[0]);
    note(k + " second", r[1]);
  }
  st.counters["first_ms"] = ms_of(k + " first");
  st.counters["second_ms"] = ms_of(k + " second");
  st.counters["first/second"] = ms_of(k + " first") / ms_of(k + " second");
}

void BM_CubicSetup(benchmark::State& st, const Size* sz) {
  const Complex base = complex_from_surface_mesh(make_quad_torus(kTorusU, kTorusV));
  const std::string k = "setup " + key(Scheme::Cubic, *sz);
  for (auto _ : st) {
    const auto t0 = Clock::now();
    Hierarchy h = make_hierarchy(base, sz->L, Scheme::Cubic, 3);
    const double ms = since_ms(t0);
    st.SetIterationTime(ms * 1e-3);
    note(k, ms);
    benchmark::DoNotOptimize(h.coeffs.data());
  }
}

// ---- Summary --------------------------------------------------------------------------------

void print_summary() {
  std::printf("\n=== paper 004 triangle wavelets (octahedron split J times, scan resampled) vs Bertram cubic "
              "(64x16 quad torus) ===\n");
  if (!g_input.empty()) std::printf("input: %s\n", g_input.begin()->second.source.c_str());
  std::printf("best over iterations; all levels in place on one array; default threads; ns per finest vertex;\n"
              "x cubic = (ns/vertex) / (cubic's ns/vertex, same operation and size)\n\n");
  std::printf("%-10s %-9s %-5s %9s %10s %9s %8s %10s\n", "scheme", "operation", "size", "vertices", "ms", "ns/vert", "x cubic",
              "max err");
  const Scheme order[] = {Scheme::Cubic, Scheme::Butterfly, Scheme::LinearTri, Scheme::Loop};
  for (const Size& sz : sizes())
    for (const char* op : {"analysis", "synthesis"})
      for (Scheme s : order) {
        const auto it = g_data.find(key(s, sz));
        const double ms = ms_of(std::string(op) + " " + key(s, sz));
        if (it == g_data.end() || ms == 0) continue;
        const double v = it->second->vertices();
        const double c = ms_of(std::string(op) + " " + key(Scheme::Cubic, sz));
        const auto ci = g_data.find(key(Scheme::Cubic, sz));
        char ratio[32] = "-";
        if (s != Scheme::Cubic && c > 0 && ci != g_data.end())
          std::snprintf(ratio, sizeof ratio, "%.2fx", (ms / v) / (c / ci->second->vertices()));
        std::printf("%-10s %-9s %-5s %9.0f %10.2f %9.1f %8s %10.1e\n", scheme_name(s).c_str(), op, sz.name.c_str(), v, ms,
                    ms * 1e6 / v, ratio, it->second->max_error);
      }
  std::printf("\nsparse terms per finest vertex (all levels; each term is 3 multiply-adds on a gathered vertex):\n");
  for (const Size& sz : sizes())
    for (Scheme s : {Scheme::Butterfly, Scheme::LinearTri, Scheme::Loop}) {
      const auto it = g_data.find(key(s, sz));
      if (it == g_data.end()) continue;
      const Data& d = *it->second;
      std::printf("  %-10s %-5s update %5.1f  predict %5.1f\n", scheme_name(s).c_str(), sz.name.c_str(),
                  d.update_entries / d.vertices(), d.predict_entries / d.vertices());
    }
  for (const Size& sz : sizes()) {
    const std::string k = "loop parts " + sz.name;
    const double solve = ms_of(k + " analysis solve");
    if (solve == 0) continue;
    std::printf("\nloop %s: analysis = solve %.1f ms + lifting %.1f ms; synthesis = lifting %.1f ms + vertex rule %.1f ms\n",
                sz.name.c_str(), solve, ms_of(k + " analysis lifting"), ms_of(k + " synthesis lifting"),
                ms_of(k + " synthesis smooth"));
    std::printf("  solve per level (ms):");
    for (int j = 0; j < sz.J; ++j) std::printf(" %d:%.1f", j, ms_of(k + " solve level " + std::to_string(j)));
    std::printf("\n");
  }
  std::printf("\nsetup, make_hierarchy (ms): first build in a fresh process (types solved) / second build (cached)\n");
  for (const Size& sz : sizes()) {
    for (Scheme s : {Scheme::Butterfly, Scheme::Loop}) {
      const double f = ms_of("setup " + key(s, sz) + " first"), c = ms_of("setup " + key(s, sz) + " second");
      if (f > 0)
        std::printf("  %-9s J=%d %-5s first %9.1f  second %9.1f  (%.2fx)\n", scheme_name(s).c_str(), sz.J, sz.name.c_str(), f,
                    c, f / c);
    }
    const double cu = ms_of("setup " + key(Scheme::Cubic, sz));
    if (cu > 0) std::printf("  %-9s L=%d %-5s       %9.1f  (no cache)\n", "cubic", sz.L, sz.name.c_str(), cu);
  }
}

template <class... Args>
benchmark::internal::Benchmark* reg(const std::string& name, void (*fn)(benchmark::State&, Args...), Args... args) {
  return benchmark::RegisterBenchmark(name.c_str(), fn, args...)->Unit(benchmark::kMillisecond)->UseManualTime();
}

void register_all() {
  for (const Size& sz : sizes()) {
    const Size* p = &sz;
    reg("setup/butterfly/" + sz.name, BM_TriSetup, Scheme::Butterfly, p)->Iterations(2);
    reg("setup/loop/" + sz.name, BM_TriSetup, Scheme::Loop, p)->Iterations(2);
    reg("setup/cubic/" + sz.name, BM_CubicSetup, p)->Iterations(2);
  }
  for (const Size& sz : sizes()) {
    const Size* p = &sz;
    // Cubic first: the others' x_cubic counters read its times.
    for (Scheme s : {Scheme::Cubic, Scheme::Butterfly, Scheme::LinearTri, Scheme::Loop}) {
      reg("analysis/" + scheme_name(s) + "/" + sz.name, BM_Analysis, s, p)->Iterations(3);
      reg("synthesis/" + scheme_name(s) + "/" + sz.name, BM_Synthesis, s, p)->Iterations(3);
    }
    reg("loop_parts/" + sz.name, BM_LoopParts, p)->Iterations(2);
  }
}

}  // namespace

int main(int argc, char** argv) {
  return sublift::bench::main_with_children(argc, argv, kChildFlag, setup_child, register_all, print_summary);
}
