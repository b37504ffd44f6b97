// Linear time for every scheme (issue 21): setup, synthesis and analysis of all levels, in ns per
// finest vertex, from about 1.6e4 to 4.2e6 finest vertices on one base per scheme, in one run.
//   setup      make_hierarchy, in a fresh child process (this binary, --scaling-setup-child) so the
//              triangle schemes' process-wide cache of wavelet types starts empty and every size
//              pays for fresh pages alike; "first" solves the types, "second" finds them cached
//   synthesis  synthesize_transition j = 0..J-1 in place, from base values plus small wavelets
//   analysis   analyze_transition j = J-1..0 in place, from what that synthesis gave
// Bases: Bertram's linear and cubic and sqrt(2) on the closed 64 x 16 quad torus (1,024 vertices;
// L = 2..6 quad splits, sqrt(2) L = 4..12), cubic also on an 8^3 block of hexahedra (L = 1..4),
// linear-tri, butterfly and Loop on the octahedron (J = 6..10). Default thread count.
// The summary ends with each row's spread: the largest ns per vertex over the smallest, at
// sizes of 1e5 finest vertices and more (the smaller ones fit in cache and are cheaper).
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
#include "core/analysis/sphere_resample.h"
#include "core/complex/complex_build.h"
#include "core/complex/shapes.h"
#include "core/multires/hierarchy.h"
#include "core/schemes/registry.h"

namespace {

using namespace sublift;
using namespace sublift::bench;  // best_ms, Clock, note, since_ms, numbers_from_child

constexpr const char* kChildFlag = "--scaling-setup-child=";

struct Case {
  Scheme scheme;
  std::string base;  // "torus", "hex", "octahedron"
  std::vector<int> levels;
  std::string name() const { return scheme_name(scheme) + "/" + base; }
};

const std::vector<Case>& cases() {
  static const std::vector<Case> all = {
      {Scheme::Linear, "torus", {2, 3, 4, 5, 6}},         {Scheme::Cubic, "torus", {2, 3, 4, 5, 6}},
      {Scheme::Cubic, "hex", {1, 2, 3, 4}},               {Scheme::Sqrt2, "torus", {4, 6, 8, 10, 12}},
      {Scheme::LinearTri, "octahedron", {6, 7, 8, 9, 10}}, {Scheme::Butterfly, "octahedron", {6, 7, 8, 9, 10}},
      {Scheme::Loop, "octahedron", {6, 7, 8, 9, 10}},
  };
  return all;
}

Complex base_complex(const std::string& base, std::vector<double>& positions) {
  if (base == "torus") {
    const SurfaceMesh t = make_quad_torus(64, 16);
    positions = flatten_positions(t);
    return complex_from_surface_mesh(t);
  }
  if (base == "hex") return make_hex_block(8, positions);
  Complex c = octahedron_complex();
  positions.clear();
  positions.assign(3 * std::size_t(c.num_vertices), 0.0);
  return c;
}

/// Small deterministic values (xorshift) in [-amp, amp] from index `from` on.
void fill(std::vector<double>& x, std::size_t from, double amp) {
  std::uint64_t s = 88172645463325252ull;
  for (std::size_t i = from; i < x.size(); ++i) {
    s ^= s << 13, s ^= s >> 7, s ^= s << 17;
    x[i] += amp * (2 * (double(s >> 11) * 0x1.0p-53) - 1);
  }
}

std::string key(const Case& c, int L) { return c.name() + "/L" + std::to_string(L); }

// ---- Setup, in a child process ------------------------------------------------------------

int setup_child(const std::string& arg) {  // "scheme base L"
  char scheme[32], base[32];
  int L = 0;
  if (std::sscanf(arg.c_str(), "%31[^:]:%31[^:]:%d", scheme, base, &L) != 3) return 2;
  std::vector<double> pos;
  const Complex c = base_complex(base, pos);
  double ms[2], bytes = 0, vertices = 0;
  for (double& m : ms) {
    const auto t0 = Clock::now();
    Hierarchy h = make_hierarchy(c, L, parse_scheme(scheme), 3);
    m = since_ms(t0);
    bytes = double(h.bytes());
    vertices = h.num_vertices(h.finest_level());
    benchmark::DoNotOptimize(h.coeffs.data());
  }
  std::printf("%.6f %.6f %.0f %.0f\n", ms[0], ms[1], bytes, vertices);
  return 0;
}

std::map<std::string, double> g_vertices, g_bytes;  // by key

void BM_Setup(benchmark::State& st, const Case* c, int L) {
  const std::string k = key(*c, L);
  for (auto _ : st) {
    const std::vector<double> r =
        numbers_from_child(kChildFlag, scheme_name(c->scheme) + ":" + c->base + ":" + std::to_string(L), 4);
    if (r.empty()) {
      st.SkipWithError("setup child failed");
      return;
    }
    st.SetIterationTime(r[0] * 1e-3);
    note("setup first " + k, r[0]);
    note("setup second " + k, r[1]);
    g_bytes[k] = r[2];
    g_vertices[k] = r[3];
  }
  st.counters["finest_vertices"] = g_vertices[k];
  st.counters["ns_per_vertex"] = best_ms()["setup first " + k] * 1e6 / g_vertices[k];
  st.counters["bytes_per_vertex"] = g_bytes[k] / g_vertices[k];
}

// ---- Synthesis and analysis, in process ------------------------------------------------------

struct Data {
  std::string key;
  Hierarchy h;
  std::vector<double> coeffs, finest;
};
std::unique_ptr<Data> g_data;  // one at a time: the 4 M-vertex ones are large

const Data& data(const Case& c, int L) {
  const std::string k = key(c, L);
  if (g_data && g_data->key == k) return *g_data;
  g_data.reset();
  auto d = std::make_unique<Data>();
  d->key = k;
  std::vector<double> pos;
  d->h = make_hierarchy(base_complex(c.base, pos), L, c.scheme, 3);
  set_base(d->h, pos);
  fill(d->h.coeffs, 0, 1e-3);  // the octahedron's base is all zero: give every value something
  d->coeffs = d->h.coeffs;
  d->finest = synthesize(d->h, L);
  g_vertices[k] = d->h.num_vertices(L);
  g_data = std::move(d);
  return *g_data;
}

void BM_Transform(benchmark::State& st, const Case* c, int L, bool synthesis) {
  const Data& d = data(*c, L);
  const std::string k = (synthesis ? "synthesis " : "analysis ") + d.key;
  std::vector<double> x(d.coeffs.size());
  for (auto _ : st) {
    std::copy((synthesis ? d.coeffs : d.finest).begin(), (synthesis ? d.coeffs : d.finest).end(), x.begin());
    const auto t0 = Clock::now();
    if (synthesis)
      for (int j = 0; j < L; ++j) synthesize_transition(d.h, j, x.data(), 3, false);
    else
      for (int j = L - 1; j >= 0; --j) analyze_transition(d.h, j, x.data(), 3, false);
    const double ms = since_ms(t0);
    benchmark::ClobberMemory();
    st.SetIterationTime(ms * 1e-3);
    note(k, ms);
  }
  st.counters["finest_vertices"] = g_vertices[d.key];
  st.counters["ns_per_vertex"] = best_ms()[k] * 1e6 / g_vertices[d.key];
}

// ---- Summary --------------------------------------------------------------------------------

// Least squares ms = fixed + marginal * n over the points, each weighted by 1 / ms^2 (relative
// misses count alike at every size); the worst |relative miss|.
struct Affine {
  double fixed_ms = 0, marginal_ns = 0, worst = 0;
};
Affine affine_fit(const std::vector<std::pair<double, double>>& pts) {  // (n, ms)
  Affine a;
  if (pts.size() < 2) return a;
  double s = 0, sn = 0, sm = 0, snn = 0, snm = 0;
  for (const auto& [n, ms] : pts) {
    const double w = 1 / (ms * ms);
    s += w, sn += w * n, sm += w * ms, snn += w * n * n, snm += w * n * ms;
  }
  const double slope = (s * snm - sn * sm) / (s * snn - sn * sn);
  a.fixed_ms = (sm - slope * sn) / s;
  a.marginal_ns = slope * 1e6;
  for (const auto& [n, ms] : pts) a.worst = std::max(a.worst, std::abs(a.fixed_ms + slope * n - ms) / ms);
  return a;
}

void print_summary() {
  std::printf("\n=== ns per finest vertex against size (best over iterations; default threads) ===\n");
  std::printf("%-22s %-13s", "scheme/base", "operation");
  for (int i = 0; i < 5; ++i) std::printf(" %16s", "");
  std::printf(" %7s %9s %8s %6s\n", "spread", "fixed ms", "ns/v", "worst");
  for (const Case& c : cases())
    for (const char* op : {"setup first", "setup second", "synthesis", "analysis", "bytes"}) {
      const bool bytes = std::string(op) == "bytes";
      std::printf("%-22s %-13s", c.name().c_str(), op);
      double lo = 0, hi = 0;
      std::vector<std::pair<double, double>> pts;
      for (int L : c.levels) {
        const std::string k = key(c, L), t = std::string(op) + " " + k;
        const double v = g_vertices.count(k) ? g_vertices[k] : 0;
        const double ms = bytes || !best_ms().count(t) ? 0 : best_ms()[t];
        const double per = bytes ? (g_bytes.count(k) && v > 0 ? g_bytes[k] / v : 0) : (v > 0 ? ms * 1e6 / v : 0);
        char cell[40];
        std::snprintf(cell, sizeof cell, "%.0fk:%.1f", v / 1e3, per);
        std::printf(" %16s", per > 0 ? cell : "-");
        if (per > 0 && v >= 1e5) {
          lo = lo == 0 ? per : std::min(lo, per), hi = std::max(hi, per);
          if (!bytes) pts.emplace_back(v, ms);
        }
      }
      for (std::size_t i = c.levels.size(); i < 5; ++i) std::printf(" %16s", "");
      if (lo > 0) std::printf(" %6.2fx", hi / lo);
      if (pts.size() >= 2) {
        const Affine a = affine_fit(pts);
        std::printf(" %9.1f %8.1f %5.0f%%", a.fixed_ms, a.marginal_ns, 100 * a.worst);
      }
      std::printf("\n");
    }
  std::printf("cells: finest vertices (thousands):ns per vertex (bytes: Hierarchy::bytes per vertex)\n"
              "spread: the largest ns per vertex over the smallest at 1e5 vertices and more; fixed ms, ns/v:\n"
              "the least-squares line ms = fixed + ns/v * vertices over those sizes, worst: its largest\n"
              "relative miss (a fixed part is the triangle schemes' neighbourhood types, solved once)\n");
}

template <class... Args>
benchmark::internal::Benchmark* reg(const std::string& name, void (*fn)(benchmark::State&, Args...), Args... args) {
  return benchmark::RegisterBenchmark(name.c_str(), fn, args...)->Unit(benchmark::kMillisecond)->UseManualTime();
}

void register_all() {
  for (const Case& c : cases())
    for (int L : c.levels) {
      reg("setup/" + key(c, L), BM_Setup, &c, L)->Iterations(2);
      reg("synthesis/" + key(c, L), BM_Transform, &c, L, true)->Iterations(3);
      reg("analysis/" + key(c, L), BM_Transform, &c, L, false)->Iterations(3);
    }
}

}  // namespace

int main(int argc, char** argv) {
  return main_with_children(argc, argv, kChildFlag, setup_child, register_all, print_summary);
}
