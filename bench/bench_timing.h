#pragma once
// Best-of-runs wall times for the benchmarks' summaries: Google Benchmark reports means over its
// own iterations; the summaries print the best time each named part took, which is what a ratio
// between two implementations in the same run should use.
#include <algorithm>
#include <chrono>
#include <map>
#include <string>

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

}  // namespace sublift::bench
