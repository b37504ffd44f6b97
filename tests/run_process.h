#pragma once
// Runs a child process with a time limit and captures its output, for CLI and GUI tests.
#include <string>
#include <vector>

namespace sublift::testing {

struct ProcessResult {
  int exit_code = -1;       // -1 when killed by a signal or the timeout
  int signal = 0;           // the terminating signal, if any
  bool timed_out = false;
  double seconds = 0.0;
  std::string out, err;
};

/// Runs argv[0] with the arguments; `env_unset` names variables removed from the child's
/// environment. The child is killed after `timeout_s` seconds.
ProcessResult run_process(const std::vector<std::string>& argv, double timeout_s = 30.0,
                          const std::vector<std::string>& env_unset = {});

}  // namespace sublift::testing
