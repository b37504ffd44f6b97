#pragma once
// Runs sublift-cli (SUBLIFT_CLI, set for every test by tests/CMakeLists.txt) with arguments.
#include <string>
#include <vector>

#include "tests/run_process.h"

namespace sublift::testing {

inline ProcessResult run_cli(const std::vector<std::string>& args, double timeout_s = 60.0) {
  std::vector<std::string> argv{SUBLIFT_CLI};
  argv.insert(argv.end(), args.begin(), args.end());
  return run_process(argv, timeout_s);
}

}  // namespace sublift::testing
