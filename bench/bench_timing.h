#pragma once
// Best-of-runs wall times for the benchmarks' summaries: Google Benchmark reports means over its
// own iterations; the summaries print the best time each named part took, which is what a ratio
// between two implementations in the same run should use.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace sublift::bench {

using Clock = std::chrono::steady_clock;

/// The best (smallest) time noted under each name, in ms.
inline std::map<std::string, double>& best_ms() {
  static std::map<std::string, double> m;
  return m;
}

inline void note(const std::string& name, double ms) {
  auto [it, fresh] = best_ms().emplace(name, ms);
  if (!fresh) it->second = std::min(it->second, ms);
}

inline double since_ms(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

/// Runs this binary again as `flag` + `arg` (a fresh process: empty caches, fresh pages) and
/// reads the numbers it prints; empty when it failed or printed fewer than `count`.
inline std::vector<double> numbers_from_child(const std::string& flag, const std::string& arg, std::size_t count) {
  const std::string cmd = std::string("'").append(std::filesystem::read_symlink("/proc/self/exe").string()).append("' ").append(flag).append(arg);
  std::vector<double> out;
  if (FILE* p = popen(cmd.c_str(), "r")) {
    double v;
    while (out.size() < count && std::fscanf(p, "%lf", &v) == 1) out.push_back(v);
    pclose(p);
  }
  if (out.size() != count) out.clear();
  return out;
}

/// main() of a benchmark whose children (numbers_from_child) start with `flag`: a child runs
/// child(the rest of its argument); otherwise the registered benchmarks run, then summary().
inline int main_with_children(int argc, char** argv, const char* flag, int (*child)(const std::string&),
                              void (*register_all)(), void (*summary)()) {
  for (int i = 1; i < argc; ++i)
    if (std::strncmp(argv[i], flag, std::strlen(flag)) == 0) return child(argv[i] + std::strlen(flag));
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  register_all();
  benchmark::RunSpecifiedBenchmarks();
  summary();
  benchmark::Shutdown();
  return 0;
}

}  // namespace sublift::bench
