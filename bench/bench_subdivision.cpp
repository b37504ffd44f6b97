// Sublift's hierarchy versus OpenSubdiv (Far) and OpenMesh (CatmullClarkT) on the same bases and
// levels, in one run (issue 3, "Performance"):
//   topology   complex_from_* + make_hierarchy   vs  TopologyRefinerFactory::Create + RefineUniform
//   synthesis  cubic lifting of all levels       vs  PrimvarRefiner::Interpolate (float xyz)
//   analysis   cubic inverse lifting             (Sublift only; goal: within 1.2x of synthesis)
//   openmesh   CatmullClarkT, topology and positions together (smaller size of each input only)
//   stencils   OpenSubdiv's StencilTable, base -> finest in one step (smaller sizes only; the table
//              takes seconds to build and cannot carry details: shown for context, not a goal)
// plus cubic synthesis cost per finest vertex on one thread from ~5e3 to ~5e6 vertices (linear
// time; expect steps where the working set leaves L2 and then L3, for OpenSubdiv as well).
// Memory is the heap still allocated after construction (glibc mallinfo2, all arenas, before
// minus after), so both libraries are measured the same way; Hierarchy::bytes() is shown too.
// Times are the minimum over --benchmark_repetitions (default 1) of the mean per iteration.
// A summary table with ns per finest vertex and the ratios Sublift / peer ends the run.
#include <benchmark/benchmark.h>
#include <malloc.h>

#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/stencilTable.h>
#include <opensubdiv/far/stencilTableFactory.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/CatmullClarkT.hh>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "core/complex/complex_build.h"
#include "core/multires/hierarchy.h"
#include "core/engine/executor.h"
#include "core/base/parallel.h"
#include "tests/mesh_fixtures.h"
#include "tests/osd_refiner.h"

namespace {

using namespace sublift;
namespace Far = OpenSubdiv::Far;
namespace Sdc = OpenSubdiv::Sdc;
using Clock = std::chrono::steady_clock;

// ---- Inputs --------------------------------------------------------------------------------

struct Input {
  std::string name;
  int levels = 0;
  bool openmesh = false;  // also run OpenMesh (slow: only the smaller size of each input)
  std::optional<fixtures::Polygons> surface;
  std::optional<fixtures::Cells> volume;
  const std::vector<double>& positions() const { return surface ? surface->positions : volume->positions; }
};

Complex base_complex(const Input& in) {
  return in.surface ? complex_from_polygons(in.surface->num_vertices, in.surface->faces)
                    : complex_from_cells(in.volume->num_vertices, in.volume->face_loops, in.volume->cell_faces);
}

const std::vector<Input>& inputs() {
  static const std::vector<Input> all = [] {
    std::vector<Input> v;
    const auto torus = fixtures::torus(48, 24);
    const auto cube = fixtures::cube();
    v.push_back({"torus48x24/L5", 5, true, torus, std::nullopt});
    v.push_back({"torus48x24/L6", 6, false, torus, std::nullopt});
    v.push_back({"cube/L9", 9, true, cube, std::nullopt});
    v.push_back({"cube/L10", 10, false, cube, std::nullopt});
    v.push_back({"hex16^3/L3", 3, false, std::nullopt, fixtures::hex_block(16)});
    return v;
  }();
  return all;
}

// ---- Results collected for the summary ----------------------------------------------------

std::map<std::string, double> g_ms;             // "op|who|input" -> min time per iteration, ms
std::map<std::string, double> g_bytes;          // "who|input" -> retained heap bytes
std::map<std::string, double> g_hier_bytes;     // input -> Hierarchy::bytes()
std::map<std::string, double> g_finest;         // input -> finest vertex count

std::size_t heap_in_use() {
  const struct mallinfo2 m = mallinfo2();
  return m.uordblks + m.hblkhd;
}

void set_per_vertex(benchmark::State& st, double finest) {
  st.counters["finest_vertices"] = finest;
  st.counters["ns_per_vertex"] =
      benchmark::Counter(finest, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

// ---- OpenSubdiv -----------------------------------------------------------------------------

struct OsdVertex {
  float p[3];
  void Clear(void* = nullptr) { p[0] = p[1] = p[2] = 0; }
  void AddWithWeight(const OsdVertex& s, float w) {
    p[0] += w * s.p[0];
    p[1] += w * s.p[1];
    p[2] += w * s.p[2];
  }
};

std::unique_ptr<Far::TopologyRefiner> osd_refine(const fixtures::Polygons& m, int levels) {
  return fixtures::osd_refiner(m, Sdc::SCHEME_CATMARK, levels);
}

void BM_OsdTopology(benchmark::State& st, const Input* in) {
  for (auto _ : st) {
    auto r = osd_refine(*in->surface, in->levels);
    benchmark::DoNotOptimize(r.get());
  }
  const std::size_t before = heap_in_use();
  auto r = osd_refine(*in->surface, in->levels);
  g_bytes["osd|" + in->name] = double(heap_in_use() - before);
  g_finest[in->name] = r->GetLevel(in->levels).GetNumVertices();
  set_per_vertex(st, g_finest[in->name]);
}

void BM_OsdSynthesis(benchmark::State& st, const Input* in) {
  const auto r = osd_refine(*in->surface, in->levels);
  std::vector<OsdVertex> buf(static_cast<std::size_t>(r->GetNumVerticesTotal()));
  const auto& base = in->surface->positions;
  for (std::size_t v = 0; v < base.size() / 3; ++v)
    buf[v] = {{float(base[3 * v]), float(base[3 * v + 1]), float(base[3 * v + 2])}};
  const Far::PrimvarRefiner pr(*r);
  for (auto _ : st) {
    OsdVertex* src = buf.data();
    for (int l = 1; l <= in->levels; ++l) {
      OsdVertex* dst = src + r->GetLevel(l - 1).GetNumVertices();
      pr.Interpolate(l, src, dst);
      src = dst;
    }
    benchmark::ClobberMemory();
  }
  g_bytes["osd_positions|" + in->name] = double(buf.size() * sizeof(OsdVertex));
  set_per_vertex(st, r->GetLevel(in->levels).GetNumVertices());
}

/// OpenSubdiv's fastest CPU path for re-posing a fixed mesh: a stencil table from the base
/// straight to the finest level (no intermediate levels, no details), built once (timed
/// separately: it is slow) and evaluated per iteration.
void BM_OsdStencils(benchmark::State& st, const Input* in) {
  const auto r = osd_refine(*in->surface, in->levels);
  const auto t0 = Clock::now();
  Far::StencilTableFactory::Options opts;
  opts.generateIntermediateLevels = false;
  opts.generateOffsets = true;
  const std::size_t before = heap_in_use();
  const std::unique_ptr<const Far::StencilTable> table(Far::StencilTableFactory::Create(*r, opts));
  g_bytes["osd_stencils|" + in->name] = double(heap_in_use() - before);
  g_ms["stencil_build/opensubdiv/" + in->name] = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  std::vector<OsdVertex> base(in->surface->num_vertices), out(static_cast<std::size_t>(table->GetNumStencils()));
  const auto& p = in->surface->positions;
  for (std::size_t v = 0; v < base.size(); ++v) base[v] = {{float(p[3 * v]), float(p[3 * v + 1]), float(p[3 * v + 2])}};
  for (auto _ : st) {
    table->UpdateValues(base.data(), out.data());
    benchmark::ClobberMemory();
  }
  set_per_vertex(st, double(out.size()));
}

// ---- Sublift --------------------------------------------------------------------------------

/// A hierarchy of `in` with the base positions and small deterministic wavelets (so no code path
/// can profit from zeros).
Hierarchy make_shape(const Input& in) {
  Hierarchy h = make_hierarchy(base_complex(in), in.levels, Scheme::Cubic, 3);
  set_base(h, in.positions());
  std::uint64_t s = 88172645463325252ull;
  for (std::size_t i = in.positions().size(); i < h.coeffs.size(); ++i) {
    s ^= s << 13, s ^= s >> 7, s ^= s << 17;
    h.coeffs[i] = 1e-3 * (double(s >> 11) * 0x1.0p-53 - 0.5);
  }
  return h;
}

void BM_SubliftTopology(benchmark::State& st, const Input* in) {
  for (auto _ : st) {
    Hierarchy h = make_hierarchy(base_complex(*in), in->levels, Scheme::Cubic, 3);
    benchmark::DoNotOptimize(h.coeffs.data());
  }
  const std::size_t before = heap_in_use();
  Hierarchy h = make_hierarchy(base_complex(*in), in->levels, Scheme::Cubic, 3);
  g_bytes["sublift|" + in->name] = double(heap_in_use() - before);
  g_hier_bytes[in->name] = double(h.bytes());
  g_finest[in->name] = h.num_vertices(in->levels);
  set_per_vertex(st, h.num_vertices(in->levels));
}

/// Runs `body` on a fresh copy of `init` each iteration, timing only `body` (manual time).
template <class Body>
void time_in_place(benchmark::State& st, const std::vector<double>& init, Body body) {
  std::vector<double> buf(init.size());
  for (auto _ : st) {
    std::copy(init.begin(), init.end(), buf.begin());
    const auto t0 = Clock::now();
    body(buf.data());
    st.SetIterationTime(std::chrono::duration<double>(Clock::now() - t0).count());
    benchmark::ClobberMemory();
  }
}

void BM_SubliftSynthesis(benchmark::State& st, const Input* in, int threads) {
  const Hierarchy h = make_shape(*in);
  if (threads > 0) set_parallel_threads(threads);
  time_in_place(st, h.coeffs, [&](double* x) {
    for (int j = 0; j < in->levels; ++j) run_synthesis(h.transitions[j], h.levels[j], x, 3, false);
  });
  if (threads > 0) set_parallel_threads(static_cast<int>(std::clamp(std::thread::hardware_concurrency(), 1u, 8u)));
  set_per_vertex(st, h.num_vertices(in->levels));
}

void BM_SubliftSynthesizeApi(benchmark::State& st, const Input* in) {
  const Hierarchy h = make_shape(*in);
  for (auto _ : st) benchmark::DoNotOptimize(synthesize(h, in->levels).data());
  set_per_vertex(st, h.num_vertices(in->levels));
}

void BM_SubliftAnalysis(benchmark::State& st, const Input* in) {
  const Hierarchy h = make_shape(*in);
  const std::vector<double> fine = synthesize(h, in->levels);
  time_in_place(st, fine, [&](double* x) {
    for (int j = in->levels - 1; j >= 0; --j) run_analysis(h.transitions[j], h.levels[j], x, 3, false);
  });
  set_per_vertex(st, h.num_vertices(in->levels));
}

void BM_SubliftAnalyzeApi(benchmark::State& st, const Input* in) {
  Hierarchy h = make_shape(*in);
  const std::vector<double> fine = synthesize(h, in->levels);
  for (auto _ : st) {
    analyze(h, fine);
    benchmark::DoNotOptimize(h.coeffs.data());
  }
  set_per_vertex(st, h.num_vertices(in->levels));
}

// ---- OpenMesh -------------------------------------------------------------------------------

using OmMesh = OpenMesh::PolyMesh_ArrayKernelT<>;

void BM_OpenMesh(benchmark::State& st, const Input* in) {
  const fixtures::Polygons& m = *in->surface;
  OmMesh base;
  for (std::uint32_t v = 0; v < m.num_vertices; ++v)
    base.add_vertex(OmMesh::Point(float(m.positions[3 * v]), float(m.positions[3 * v + 1]), float(m.positions[3 * v + 2])));
  for (std::size_t f = 0; f < m.faces.rows(); ++f) {
    std::vector<OmMesh::VertexHandle> corners;
    for (std::uint32_t v : m.faces.row(f)) corners.emplace_back(static_cast<int>(v));
    base.add_face(corners);
  }
  std::size_t finest = 0;
  for (auto _ : st) {
    OmMesh om = base;
    const auto t0 = Clock::now();
    OpenMesh::Subdivider::Uniform::CatmullClarkT<OmMesh> cc;
    cc.attach(om);
    cc(static_cast<std::size_t>(in->levels));
    cc.detach();
    st.SetIterationTime(std::chrono::duration<double>(Clock::now() - t0).count());
    finest = om.n_vertices();
  }
  {
    const std::size_t before = heap_in_use();
    auto om = std::make_unique<OmMesh>(base);
    OpenMesh::Subdivider::Uniform::CatmullClarkT<OmMesh> cc;
    cc.attach(*om);
    cc(static_cast<std::size_t>(in->levels));
    cc.detach();
    g_bytes["openmesh|" + in->name] = double(heap_in_use() - before);
  }
  set_per_vertex(st, double(finest));
}

// ---- Summary ---------------------------------------------------------------------------------

class SummaryReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& r : runs) {
      if (r.run_type != Run::RT_Iteration || r.error_occurred) continue;
      const std::string key = r.run_name.function_name;
      const double ms = r.GetAdjustedRealTime();  // every benchmark here is in milliseconds
      auto it = g_ms.find(key);
      if (it == g_ms.end() || ms < it->second) g_ms[key] = ms;
    }
    ConsoleReporter::ReportRuns(runs);
  }
};

double ms_of(const std::string& key) {
  auto it = g_ms.find(key);
  return it == g_ms.end() ? 0 : it->second;
}

void print_summary() {
  std::printf("\n=== Sublift vs OpenSubdiv 3.5 (Far, serial) and OpenMesh 9 (CatmullClarkT) ===\n");
  std::printf("time: min over repetitions of the mean per iteration; ns/v: per finest vertex; "
              "Sublift lifting on %s thread(s) unless noted.\n", "default (hardware, <= 8)");
  std::printf("%-15s %9s | %-28s | %-28s | %-22s | %-16s\n", "input", "finest V", "topology ms (ns/v)",
              "cubic synthesis ms (ns/v)", "analysis ms  / synth", "retained B/v");
  std::printf("%-15s %9s | %8s %8s %9s | %8s %8s %9s | %8s %5s %7s | %5s %5s %5s\n", "", "", "Sublift", "OSD",
              "S/OSD", "Sublift", "OSD", "S/OSD", "Sublift", "1thr", "S/synth", "Subl", "OSD", "OSD+p");
  for (const Input& in : inputs()) {
    const double n = g_finest[in.name];
    if (n == 0) continue;
    const double tt = ms_of("topology/sublift/" + in.name), to = ms_of("topology/opensubdiv/" + in.name);
    const double ts = ms_of("synthesis/sublift/" + in.name), tso = ms_of("synthesis/opensubdiv/" + in.name);
    const double ts1 = ms_of("synthesis/sublift_1thread/" + in.name);
    const double ta = ms_of("analysis/sublift/" + in.name);
    auto ratio = [](double a, double b) { return b > 0 ? a / b : 0.0; };
    const double bs = g_bytes["sublift|" + in.name] / n, bo = g_bytes["osd|" + in.name] / n;
    const double bop = (g_bytes["osd|" + in.name] + g_bytes["osd_positions|" + in.name]) / n;
    std::printf("%-15s %9.0f | %8.1f %8.1f %8.2fx | %8.2f %8.2f %8.2fx | %8.2f %5.2f %6.2fx | %5.0f %5.0f %5.0f\n",
                in.name.c_str(), n, tt, to, ratio(tt, to), ts, tso, ratio(ts, tso), ta, ratio(ts1, tso),
                ratio(ta, ts), bs, bo, bop);
    std::printf("%-15s %9s | %8.1f %8.1f %9s | %8.1f %8.1f %9s | %8.1f %5s %7s |\n", "  ns/vertex", "",
                tt * 1e6 / n, to * 1e6 / n, "", ts * 1e6 / n, tso * 1e6 / n, "", ta * 1e6 / n, "", "");
  }
  std::printf("'1thr' = Sublift synthesis on one thread / OpenSubdiv. Retained B/v: heap kept after\n"
              "construction (mallinfo2); Subl = hierarchy incl. its coefficients (doubles), OSD = refiner\n"
              "only, OSD+p = refiner plus float xyz of all levels. Hierarchy::bytes() per finest vertex:");
  for (const Input& in : inputs())
    if (g_finest[in.name] > 0) std::printf(" %s %.0f;", in.name.c_str(), g_hier_bytes[in.name] / g_finest[in.name]);
  std::printf("\n\nAPI calls (allocate and copy included): synthesize(h, J) / analyze(h, fine), ms\n");
  for (const Input& in : inputs())
    if (g_finest[in.name] > 0)
      std::printf("  %-15s synthesize %8.1f   analyze %8.1f\n", in.name.c_str(),
                  ms_of("synthesize_api/sublift/" + in.name), ms_of("analyze_api/sublift/" + in.name));
  std::printf("\nOpenMesh CatmullClarkT (topology + positions) vs Sublift topology + synthesis:\n");
  for (const Input& in : inputs()) {
    const double tom = ms_of("openmesh/catmullclark/" + in.name);
    if (tom == 0 || g_finest[in.name] == 0) continue;
    const double ours = ms_of("topology/sublift/" + in.name) + ms_of("synthesis/sublift/" + in.name);
    std::printf("  %-15s OpenMesh %9.1f ms (%6.0f B/v)  Sublift %8.1f ms  OpenMesh / Sublift %5.1fx\n",
                in.name.c_str(), tom, g_bytes["openmesh|" + in.name] / g_finest[in.name], ours, ours > 0 ? tom / ours : 0);
  }
  std::printf("\nOpenSubdiv stencil table, base -> finest in one step (no intermediate levels, no details;\n"
              "the fastest way OpenSubdiv re-poses a fixed mesh) vs Sublift cubic synthesis of all levels:\n");
  for (const Input& in : inputs()) {
    const double te = ms_of("stencils/opensubdiv/" + in.name);
    if (te == 0 || g_finest[in.name] == 0) continue;
    const double n = g_finest[in.name], ts = ms_of("synthesis/sublift/" + in.name);
    std::printf("  %-15s build %8.0f ms, %5.0f B/v; evaluate %7.2f ms (%5.1f ns/v); Sublift / stencils %5.2fx\n",
                in.name.c_str(), ms_of("stencil_build/opensubdiv/" + in.name), g_bytes["osd_stencils|" + in.name] / n, te,
                te * 1e6 / n, ts / te);
  }
  std::printf("\nLinear time: cubic synthesis ns per finest vertex, one thread (torus 48x24, Sublift / OpenSubdiv):\n");
  double lo = 1e300, hi = 0;
  for (int l = 1; l <= 6; ++l) {
    const std::string key = "torus48x24/L" + std::to_string(l);
    const double s = ms_of("lineartime/sublift/" + key), o = ms_of("lineartime/opensubdiv/" + key);
    if (s == 0) continue;
    const double n = 1152.0 * double(1 << (2 * l));
    std::printf("  L%d %9.0f vertices  Sublift %6.2f ns/v   OpenSubdiv %6.2f ns/v\n", l, n, s * 1e6 / n, o * 1e6 / n);
    if (n >= 1e4) lo = std::min(lo, s * 1e6 / n), hi = std::max(hi, s * 1e6 / n);
  }
  if (hi > 0) std::printf("  max/min ns per vertex over >= 1e4 vertices: %.2f\n", hi / lo);
}

/// Registers `fn(state, args...)` under `name`, in milliseconds (the summary relies on it).
template <class... Args>
benchmark::internal::Benchmark* reg(const std::string& name, void (*fn)(benchmark::State&, Args...), Args... args) {
  return benchmark::RegisterBenchmark(name.c_str(), fn, args...)->Unit(benchmark::kMillisecond);
}

void register_all() {
  for (const Input& in : inputs()) {
    const Input* p = &in;
    reg("topology/sublift/" + in.name, BM_SubliftTopology, p);
    if (in.surface) reg("topology/opensubdiv/" + in.name, BM_OsdTopology, p);
    reg("synthesis/sublift/" + in.name, BM_SubliftSynthesis, p, 0)->UseManualTime();
    reg("synthesis/sublift_1thread/" + in.name, BM_SubliftSynthesis, p, 1)
        ->UseManualTime();
    if (in.surface) reg("synthesis/opensubdiv/" + in.name, BM_OsdSynthesis, p);
    reg("analysis/sublift/" + in.name, BM_SubliftAnalysis, p)->UseManualTime();
    reg("synthesize_api/sublift/" + in.name, BM_SubliftSynthesizeApi, p);
    reg("analyze_api/sublift/" + in.name, BM_SubliftAnalyzeApi, p);
    if (in.surface && in.openmesh) {
      reg("openmesh/catmullclark/" + in.name, BM_OpenMesh, p)->UseManualTime();
      reg("stencils/opensubdiv/" + in.name, BM_OsdStencils, p)->Iterations(10);  // table built once
    }
  }
  static std::vector<Input> sizes;
  for (int l = 1; l <= 6; ++l)
    sizes.push_back({"torus48x24/L" + std::to_string(l), l, false, fixtures::torus(48, 24), std::nullopt});
  for (const Input& in : sizes) {
    reg("lineartime/sublift/" + in.name, BM_SubliftSynthesis, &in, 1)
        ->UseManualTime();
    reg("lineartime/opensubdiv/" + in.name, BM_OsdSynthesis, &in);
  }
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  register_all();
  SummaryReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  print_summary();
  benchmark::Shutdown();
  return 0;
}
