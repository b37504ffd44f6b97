#pragma once
// Memory refused up front (issue 18): work whose size is known before it starts (levels of a
// hierarchy, a fit, an FFD lattice) predicts its bytes and is refused with that number when it
// would not fit, instead of dying "out of memory" after the fact.
#include <string>

namespace sublift {

struct MemoryBudget {
  double bytes = 0;
  std::string source;  // where the number came from, for messages
};

/// What the process may plan to use: the environment variable SUBLIFT_MEMORY_BUDGET when set
/// (bytes, or a number with K, M, G or T: "6G", "512M"), else the memory the machine has
/// available now (MemAvailable in /proc/meminfo; the physical memory where that is missing).
/// A malformed SUBLIFT_MEMORY_BUDGET throws Error naming it.
MemoryBudget memory_budget();

/// Work below this size is never checked: asking for the budget reads /proc/meminfo, which would
/// cost more than the small builds (limit stencils build hundreds of patch hierarchies).
inline constexpr double kUncheckedBytes = 64.0 * 1024 * 1024;

/// Throws Error "<what> needs about X GB, more than the memory budget of Y GB (source)" when
/// need_bytes exceeds kUncheckedBytes and memory_budget().
void check_memory(double need_bytes, const std::string& what);

/// "1.5 GB", "320 MB", "12 KB", "512 bytes" (powers of 1024).
std::string format_bytes(double bytes);

}  // namespace sublift
