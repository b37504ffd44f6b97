#pragma once
// Runs sublift-cli (SUBLIFT_CLI, set for every test by tests/CMakeLists.txt) with arguments, and
// small helpers the CLI round-trip tests share.
#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "tests/run_process.h"

namespace sublift::testing {

inline ProcessResult run_cli(const std::vector<std::string>& args, double timeout_s = 60.0) {
  std::vector<std::string> argv{SUBLIFT_CLI};
  argv.insert(argv.end(), args.begin(), args.end());
  return run_process(argv, timeout_s);
}

/// OBJ `text` with the x coordinate of its k-th `v` line moved by dx.
inline std::string move_vertex(const std::string& text, std::size_t k, double dx) {
  std::istringstream in(text);
  std::string out, line;
  std::size_t seen = 0;
  while (std::getline(in, line)) {
    if (line.rfind("v ", 0) == 0 && seen++ == k) {
      std::istringstream l(line.substr(2));
      double x, y, z;
      l >> x >> y >> z;
      line = "v " + std::to_string(x + dx) + " " + std::to_string(y) + " " + std::to_string(z);
    }
    out += line + "\n";
  }
  return out;
}

/// Largest |a - b| relative to the largest |a|; infinite when the sizes differ, so that a
/// comparison with a tolerance fails.
inline double relative_error(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return HUGE_VAL;
  double err = 0, scale = 0;
  for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) {
    err = std::max(err, std::abs(a[i] - b[i]));
    scale = std::max(scale, std::abs(a[i]));
  }
  return err / scale;
}

}  // namespace sublift::testing
