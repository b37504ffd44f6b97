#include "core/base/temp_files.h"

#include <signal.h>
#include <sys/types.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <system_error>

namespace sublift {
namespace fs = std::filesystem;

namespace {

constexpr int kSlots = 64;              // saves in flight at once
constexpr std::size_t kPathBytes = 4096;  // PATH_MAX on Linux

enum SlotState : int { kFree = 0, kFilling = 1, kInUse = 2 };

struct Slot {
  std::atomic<int> state{kFree};
  char path[kPathBytes];
};

Slot g_slots[kSlots];
struct sigaction g_previous[2];  // SIGINT, SIGTERM as they were before ours
constexpr int kSignals[2] = {SIGINT, SIGTERM};

extern "C" void on_interrupt(int sig) {
  const int saved_errno = errno;
  for (Slot& s : g_slots)
    if (s.state.load(std::memory_order_acquire) == kInUse) unlink(s.path);
  const int k = sig == SIGINT ? 0 : 1;
  const struct sigaction& prev = g_previous[k];
  if (!(prev.sa_flags & SA_SIGINFO) && prev.sa_handler != SIG_DFL && prev.sa_handler != SIG_IGN) {
    errno = saved_errno;
    prev.sa_handler(sig);  // a handler the program had before: it decides what happens next
    return;
  }
  // The default action: restore it and raise again, so the parent sees death by this signal.
  struct sigaction dfl {};
  dfl.sa_handler = SIG_DFL;
  sigemptyset(&dfl.sa_mask);
  sigaction(sig, &dfl, nullptr);
  raise(sig);
}

}  // namespace

void install_interrupt_cleanup() {
  static std::once_flag once;
  std::call_once(once, [] {
    for (int k = 0; k < 2; ++k) {
      struct sigaction cur {};
      if (sigaction(kSignals[k], nullptr, &cur) != 0) continue;
      if (!(cur.sa_flags & SA_SIGINFO) && cur.sa_handler == SIG_IGN) continue;  // ignored stays ignored
      if (cur.sa_flags & SA_SIGINFO) continue;  // a siginfo handler is the program's business
      g_previous[k] = cur;
      struct sigaction act {};
      act.sa_handler = on_interrupt;
      sigemptyset(&act.sa_mask);
      for (int sig : kSignals) sigaddset(&act.sa_mask, sig);  // one cleanup at a time
      act.sa_flags = SA_RESTART;
      sigaction(kSignals[k], &act, nullptr);
    }
  });
}

int register_temp_file(const std::string& path) {
  if (path.size() >= kPathBytes) return -1;
  for (int i = 0; i < kSlots; ++i) {
    int expected = kFree;
    if (!g_slots[i].state.compare_exchange_strong(expected, kFilling, std::memory_order_acq_rel)) continue;
    std::memcpy(g_slots[i].path, path.c_str(), path.size() + 1);
    g_slots[i].state.store(kInUse, std::memory_order_release);
    return i;
  }
  return -1;
}

void unregister_temp_file(int slot) {
  if (slot >= 0 && slot < kSlots) g_slots[slot].state.store(kFree, std::memory_order_release);
}

bool is_registered_temp_file(const std::string& path) {
  for (const Slot& s : g_slots)
    if (s.state.load(std::memory_order_acquire) == kInUse && path == s.path) return true;
  return false;
}

std::string temp_file_name(const std::string& name, unsigned long n) {
  return name + ".tmp-" + std::to_string(static_cast<long>(getpid())) + "-" + std::to_string(n);
}

std::size_t remove_stale_temp_files(const std::string& target) {
  const fs::path t(target);
  fs::path dir = t.parent_path();
  if (dir.empty()) dir = ".";
  const std::string prefix = t.filename().string() + ".tmp-";
  const auto now = fs::file_time_type::clock::now();
  std::size_t removed = 0;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string_view rest = std::string_view(name).substr(prefix.size());
    // "PID-N" (this format) or anything else (older Sublift wrote "tmp-NNNNNN", no PID).
    long pid = 0;
    const auto [p, err] = std::from_chars(rest.data(), rest.data() + rest.size(), pid);
    const bool has_pid = err == std::errc() && p != rest.data() + rest.size() && *p == '-' && pid > 0;
    bool stale;
    if (has_pid) {
      const bool alive = pid == static_cast<long>(getpid()) ? is_registered_temp_file(it->path().string())
                                                           : (kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM);
      stale = !alive;
    } else {
      std::error_code tec;
      const auto when = fs::last_write_time(it->path(), tec);
      stale = !tec && when < now;
    }
    std::error_code rec;
    if (stale && fs::remove(it->path(), rec)) ++removed;
  }
  return removed;
}

}  // namespace sublift
