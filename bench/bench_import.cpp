// Sublift's validating OBJ reader versus OpenMesh's read_mesh on the same generated quad grid
// (in memory for Sublift, from the same temp file for both). Prints ns per vertex and, at the
// end, the ratio Sublift / OpenMesh for each size.
#include <benchmark/benchmark.h>

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>

#include "core/io/mesh/mesh_import.h"

namespace {

using OmMesh = OpenMesh::PolyMesh_ArrayKernelT<>;

std::string grid_obj_path(int n) {
  const auto path = std::filesystem::temp_directory_path() / ("sublift_bench_grid_" + std::to_string(n) + ".obj");
  if (!std::filesystem::exists(path)) {
    std::ofstream out(path);
    for (int y = 0; y <= n; ++y)
      for (int x = 0; x <= n; ++x) out << "v " << x * 0.1 << ' ' << y * 0.1 << ' ' << (x * y % 7) * 0.01 << '\n';
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const int a = y * (n + 1) + x + 1;
        out << "f " << a << ' ' << a + 1 << ' ' << a + n + 2 << ' ' << a + n + 1 << '\n';
      }
  }
  return path.string();
}

std::map<int, double> g_sublift_ns, g_openmesh_ns;

void BM_SubliftObj(benchmark::State& st) {
  const int n = static_cast<int>(st.range(0));
  const std::string path = grid_obj_path(n);
  for (auto _ : st) benchmark::DoNotOptimize(sublift::import_surface_mesh(path));
  const double verts = double(n + 1) * (n + 1);
  st.counters["ns_per_vertex"] = benchmark::Counter(verts, benchmark::Counter::kIsIterationInvariantRate |
                                                               benchmark::Counter::kInvert);
}

void BM_OpenMeshObj(benchmark::State& st) {
  const int n = static_cast<int>(st.range(0));
  const std::string path = grid_obj_path(n);
  for (auto _ : st) {
    OmMesh m;
    benchmark::DoNotOptimize(OpenMesh::IO::read_mesh(m, path));
  }
  const double verts = double(n + 1) * (n + 1);
  st.counters["ns_per_vertex"] = benchmark::Counter(verts, benchmark::Counter::kIsIterationInvariantRate |
                                                               benchmark::Counter::kInvert);
}

BENCHMARK(BM_SubliftObj)->Arg(100)->Arg(400)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OpenMeshObj)->Arg(100)->Arg(400)->Unit(benchmark::kMillisecond);

// Collects per-run times so main() can print the ratios after all benchmarks ran.
class RatioReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& r : runs) {
      const std::string name = r.benchmark_name();
      const int n = std::stoi(name.substr(name.find('/') + 1));
      (name.rfind("BM_SubliftObj", 0) == 0 ? g_sublift_ns : g_openmesh_ns)[n] = r.GetAdjustedRealTime();
    }
    ConsoleReporter::ReportRuns(runs);
  }
};

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  std::printf("\nOBJ import, Sublift / OpenMesh time ratio (lower is better):\n");
  for (auto [n, t] : g_sublift_ns)
    if (g_openmesh_ns.count(n))
      std::printf("  grid %dx%d (%d vertices): %.2f\n", n, n, (n + 1) * (n + 1), t / g_openmesh_ns[n]);
  benchmark::Shutdown();
  return 0;
}
