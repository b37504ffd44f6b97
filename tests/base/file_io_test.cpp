// Atomic saves and clean interruption (issue 18): a save killed by SIGTERM or SIGINT leaves no
// temporary file; a leftover from a hard kill (SIGKILL) is removed by the next save of the same
// target, and only leftovers of that target whose process is gone.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "core/base/file_io.h"
#include "core/base/temp_files.h"
#include "tests/io_test_util.h"

namespace fs = std::filesystem;
using sublift::testing::TempDir;

namespace {

std::vector<std::string> names_in(const fs::path& dir) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) out.push_back(e.path().filename().string());
  std::sort(out.begin(), out.end());
  return out;
}

// Forks a child that saves `path` slowly (a large file in 1 MB pieces); returns its pid once
// the first piece is in the temporary file.
pid_t start_slow_save(const std::string& path) {
  int fds[2];
  if (pipe(fds) != 0) return -1;
  const pid_t pid = fork();
  if (pid == 0) {
    close(fds[0]);
    const std::string piece(1 << 20, 'x');
    try {
      sublift::write_file_atomic(path, [&](std::ostream& out) {
        for (int i = 0; i < 600; ++i) {  // at most 600 MB over 60 s: the parent kills it long before
          out << piece;
          out.flush();
          if (i == 0 && write(fds[1], "1", 1) != 1) _exit(3);
          std::this_thread::sleep_for(std::chrono::milliseconds(100));
        }
      });
    } catch (...) {
      _exit(2);
    }
    _exit(0);
  }
  close(fds[1]);
  char c = 0;
  const bool started = read(fds[0], &c, 1) == 1;
  close(fds[0]);
  return started ? pid : -1;
}

// Kills the child with `sig` and returns how it ended.
int kill_and_wait(pid_t pid, int sig) {
  kill(pid, sig);
  int status = 0;
  waitpid(pid, &status, 0);
  return status;
}

// A pid that is certainly not alive: a child that has exited and been reaped.
long dead_pid() {
  const pid_t pid = fork();
  if (pid == 0) _exit(0);
  int status = 0;
  waitpid(pid, &status, 0);
  return pid;
}

}  // namespace

TEST(FileIo, TempFileIsNamedForItsProcess) {
  EXPECT_EQ(sublift::temp_file_name("a.obj", 7), "a.obj.tmp-" + std::to_string(getpid()) + "-7");
}

TEST(FileIo, SaveInterruptedBySigtermOrSigintLeavesNoTempFile) {
  for (int sig : {SIGTERM, SIGINT}) {
    SCOPED_TRACE(sig == SIGTERM ? "SIGTERM" : "SIGINT");
    TempDir dir("sublift_interrupted_save");
    const std::string path = dir.file("big.obj");
    const pid_t pid = start_slow_save(path);
    ASSERT_GT(pid, 0);
    const std::vector<std::string> during = names_in(dir.path());
    ASSERT_EQ(during.size(), 1u);  // the save is under way: its temp file is there
    EXPECT_EQ(during[0], "big.obj.tmp-" + std::to_string(pid) + "-0");
    const int status = kill_and_wait(pid, sig);
    EXPECT_TRUE(WIFSIGNALED(status)) << status;  // died of the signal, as without the cleanup
    if (WIFSIGNALED(status)) {
      EXPECT_EQ(WTERMSIG(status), sig);
    }
    EXPECT_EQ(names_in(dir.path()), std::vector<std::string>{});
  }
}

TEST(FileIo, LeftoverOfAHardKillIsRemovedByTheNextSave) {
  TempDir dir("sublift_hard_killed_save");
  const std::string path = dir.file("big.obj");
  const pid_t pid = start_slow_save(path);
  ASSERT_GT(pid, 0);
  const int status = kill_and_wait(pid, SIGKILL);  // no handler runs
  ASSERT_TRUE(WIFSIGNALED(status));
  const std::string leftover = "big.obj.tmp-" + std::to_string(pid) + "-0";
  ASSERT_EQ(names_in(dir.path()), std::vector<std::string>{leftover});
  // Planted too: an older Sublift's name (no PID, older than this save), another dead process's,
  // a live process's (pid 1: another save under way), and another target's.
  const std::string old_style = "big.obj.tmp-123456", dead = "big.obj.tmp-" + std::to_string(dead_pid()) + "-3";
  const std::string live = "big.obj.tmp-1-0", other = "other.obj.tmp-" + std::to_string(dead_pid()) + "-0";
  for (const std::string& n : {old_style, dead, live, other}) std::ofstream(dir.file(n)) << "stale";
  fs::last_write_time(dir.file(old_style), fs::file_time_type::clock::now() - std::chrono::hours(1));
  sublift::write_file_atomic(path, [](std::ostream& out) { out << "v 0 0 0\n"; });
  EXPECT_EQ(names_in(dir.path()), (std::vector<std::string>{"big.obj", live, other}));
  EXPECT_EQ(sublift::read_file_bytes(path), "v 0 0 0\n");
}

TEST(FileIo, ASaveInFlightInThisProcessIsNotStale) {
  TempDir dir("sublift_in_flight_save");
  const std::string path = dir.file("a.obj");
  // While a.obj is being written, a save of the same target from inside the writer (another
  // thread would do the same) must leave the first one's temp file alone.
  sublift::write_file_atomic(path, [&](std::ostream& out) {
    out << "first\n";
    const std::vector<std::string> before = names_in(dir.path());
    ASSERT_EQ(before.size(), 1u);
    sublift::write_file_atomic(path, [](std::ostream& o) { o << "second\n"; });
    EXPECT_EQ(names_in(dir.path()), (std::vector<std::string>{"a.obj", before[0]}));
  });
  EXPECT_EQ(sublift::read_file_bytes(path), "first\n");  // the outer save renamed last
  EXPECT_EQ(names_in(dir.path()), std::vector<std::string>{"a.obj"});
}
