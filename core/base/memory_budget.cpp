#include "core/base/memory_budget.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "core/base/errors.h"

namespace sublift {
namespace {

constexpr const char* kVariable = "SUBLIFT_MEMORY_BUDGET";

double parse_size(const std::string& text) {
  std::size_t used = 0;
  double value = 0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  std::string unit = text.substr(used);
  if (!unit.empty() && (unit.back() == 'B' || unit.back() == 'b') && unit.size() > 1) unit.pop_back();
  double scale = 0;
  if (unit.empty()) scale = 1;
  else if (unit == "K" || unit == "k") scale = 1024.0;
  else if (unit == "M" || unit == "m") scale = 1024.0 * 1024;
  else if (unit == "G" || unit == "g") scale = 1024.0 * 1024 * 1024;
  else if (unit == "T" || unit == "t") scale = 1024.0 * 1024 * 1024 * 1024;
  if (used == 0 || scale == 0 || !std::isfinite(value) || value <= 0)
    throw Error(std::string(kVariable) + " must be a positive size such as 6G, 512M or 1000000 (bytes); got '" + text + "'");
  return value * scale;
}

// MemAvailable from /proc/meminfo, in bytes; 0 when absent.
double available_memory() {
  std::ifstream in("/proc/meminfo");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("MemAvailable:", 0) != 0) continue;
    std::istringstream s(line.substr(13));
    double kb = 0;
    if (s >> kb) return kb * 1024.0;
  }
  return 0;
}

}  // namespace

MemoryBudget memory_budget() {
  if (const char* env = std::getenv(kVariable); env && *env) return {parse_size(env), std::string(kVariable) + "=" + env};
  if (const double a = available_memory(); a > 0) return {a, "the memory available now; set " + std::string(kVariable) + " to choose"};
  const double pages = double(sysconf(_SC_PHYS_PAGES)), page = double(sysconf(_SC_PAGE_SIZE));
  return {pages * page, "the physical memory; set " + std::string(kVariable) + " to choose"};
}

void check_memory(double need_bytes, const std::string& what) {
  if (need_bytes <= kUncheckedBytes) return;
  const MemoryBudget b = memory_budget();
  if (need_bytes > b.bytes)
    throw Error(what + " needs about " + format_bytes(need_bytes) + ", more than the memory budget of " + format_bytes(b.bytes) +
                " (" + b.source + ")");
}

std::string format_bytes(double bytes) {
  const char* units[] = {"bytes", "KB", "MB", "GB", "TB", "PB"};
  int u = 0;
  while (bytes >= 1024.0 && u < 5) bytes /= 1024.0, ++u;
  char buf[48];
  if (u == 0) std::snprintf(buf, sizeof buf, "%.0f bytes", bytes);
  else std::snprintf(buf, sizeof buf, bytes < 10 ? "%.1f %s" : "%.0f %s", bytes, units[u]);
  return buf;
}

}  // namespace sublift
