#pragma once
// Milliseconds since a steady-clock time point: the one form of the stage times reports carry.
#include <chrono>

namespace sublift {

inline double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace sublift
