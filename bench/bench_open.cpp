// Opening high-valence meshes in the modeler (issue 18's hang: a legal 30 KB OBJ with one
// 1000-sided polygon, or one vertex of valence 1000, froze the modeler in its limit stencils).
// Goal: each opens in under 2 s. Sublift: ModelerState::open (read, kDefaultLevels levels, limit
// stencils and normals: everything before the first frame). Peer, same mesh and levels:
// OpenSubdiv's TopologyRefiner (Catmark) refined uniformly, positions interpolated and
// PrimvarRefiner::Limit positions and tangents at the finest level. The summary prints both and
// the ratio.
#include <benchmark/benchmark.h>
#include <opensubdiv/far/primvarRefiner.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>
#include <vector>

#include "app/modeler/modeler_state.h"
#include "bench/bench_timing.h"
#include "tests/mesh_fixtures.h"
#include "tests/osd_refiner.h"

namespace {
using namespace sublift;
namespace Far = OpenSubdiv::Far;

struct Input {
  std::string name;
  fixtures::Polygons mesh;
  std::string path;
};

void write_obj(const fixtures::Polygons& m, const std::string& path) {
  std::ofstream out(path);
  char line[96];
  for (std::uint32_t v = 0; v < m.num_vertices; ++v) {
    std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", m.positions[3 * v], m.positions[3 * v + 1], m.positions[3 * v + 2]);
    out << line;
  }
  for (std::size_t f = 0; f < m.faces.rows(); ++f) {
    out << 'f';
    for (std::uint32_t x : m.faces.row(f)) out << ' ' << x + 1;
    out << '\n';
  }
}

std::vector<Input>& inputs() {
  static std::vector<Input> all = [] {
    const auto dir = std::filesystem::temp_directory_path() / ("sublift_bench_open_" + std::to_string(getpid()));
    std::filesystem::create_directories(dir);
    std::vector<Input> v;
    v.push_back({"1000-gon prism", fixtures::ngon_prism(1000), (dir / "ngon1000.obj").string()});
    v.push_back({"valence-1000 cone", fixtures::triangle_cone(1000), (dir / "valence1000.obj").string()});
    for (const Input& in : v) write_obj(in.mesh, in.path);
    return v;
  }();
  return all;
}

void BM_OpenInModeler(benchmark::State& st, const Input* in) {
  for (auto _ : st) {
    const auto t0 = bench::Clock::now();
    ModelerState model;
    model.open(in->path);
    benchmark::DoNotOptimize(model.session().finest_level());
    bench::note("sublift|" + in->name, bench::since_ms(t0));
  }
  st.counters["file_KB"] = double(std::filesystem::file_size(in->path)) / 1024.0;
}

struct Xyz {
  float p[3];
  void Clear(void* = nullptr) { p[0] = p[1] = p[2] = 0; }
  void AddWithWeight(const Xyz& s, float w) {
    for (int c = 0; c < 3; ++c) p[c] += w * s.p[c];
  }
};

void BM_OsdLimit(benchmark::State& st, const Input* in) {
  const int levels = ModelerState::kDefaultLevels;
  for (auto _ : st) {
    const auto t0 = bench::Clock::now();
    const auto r = fixtures::osd_refiner(in->mesh, OpenSubdiv::Sdc::SCHEME_CATMARK, levels, /*full_topology=*/true);
    std::vector<Xyz> x(std::size_t(r->GetNumVerticesTotal()));
    for (std::uint32_t v = 0; v < in->mesh.num_vertices; ++v)
      for (int c = 0; c < 3; ++c) x[v].p[c] = float(in->mesh.positions[3 * v + std::size_t(c)]);
    const Far::PrimvarRefiner pr(*r);
    Xyz* src = x.data();
    for (int l = 1; l <= levels; ++l) {
      Xyz* dst = src + r->GetLevel(l - 1).GetNumVertices();
      pr.Interpolate(l, src, dst);
      src = dst;
    }
    const std::size_t nf = std::size_t(r->GetLevel(levels).GetNumVertices());
    std::vector<Xyz> lim(nf), du(nf), dv(nf);
    pr.Limit(src, lim, du, dv);
    benchmark::DoNotOptimize(lim.data());
    bench::note("opensubdiv|" + in->name, bench::since_ms(t0));
  }
}

}  // namespace

int main(int argc, char** argv) {
  for (const Input& in : inputs()) {
    benchmark::RegisterBenchmark(("BM_OpenInModeler/" + in.name).c_str(), BM_OpenInModeler, &in)
        ->Unit(benchmark::kMillisecond)->Iterations(3);
    benchmark::RegisterBenchmark(("BM_OsdLimit/" + in.name).c_str(), BM_OsdLimit, &in)
        ->Unit(benchmark::kMillisecond)->Iterations(3);
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  std::printf("\n%-20s %14s %16s %8s %10s\n", "input", "sublift open", "opensubdiv limit", "ratio", "goal 2 s");
  for (const Input& in : inputs()) {
    const auto& b = bench::best_ms();
    const auto s = b.find("sublift|" + in.name), o = b.find("opensubdiv|" + in.name);
    if (s == b.end() || o == b.end()) continue;
    std::printf("%-20s %11.1f ms %13.1f ms %7.1fx %10s\n", in.name.c_str(), s->second, o->second, s->second / o->second,
                s->second < 2000 ? "met" : "MISSED");
  }
  std::filesystem::remove_all(std::filesystem::path(inputs().front().path).parent_path());
  benchmark::Shutdown();
}
