#include "core/base/parallel.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>
#include <vector>

namespace sublift {
namespace {

// A job's chunks are claimed through one 64-bit ticket, its generation above the next chunk's
// index: a claim names the job it belongs to, so a worker that wakes late cannot take a chunk of
// the next job for the last one. The caller returns once every chunk is finished, not once every
// worker has checked in: a drag runs dozens of small jobs, and waiting for sleeping workers to
// wake and report made two threads slower than one (bench_edit: local resynthesis 0.63 ms on
// one thread, 0.92-1.14 ms on two). Workers spin a little after a job before they sleep, so the
// next small job usually finds them awake.
class Pool {
 public:
  static Pool& instance() {
    static Pool pool;
    return pool;
  }

  int threads() const { return threads_; }
  void set_threads(int n) { threads_ = std::clamp(n, 1, 8); }

  void run(std::uint32_t n, std::uint32_t grain, const std::function<void(std::uint32_t, std::uint32_t)>& body) {
    const std::uint32_t chunks = (n + grain - 1) / grain;
    const int helpers = std::min<int>(threads_ - 1, static_cast<int>(chunks) - 1);
    // A parallel_for inside a body runs inline: the pool is busy with the outer one (waiting for
    // it would never end).
    if (helpers <= 0 || in_body_) {
      body(0, n);
      return;
    }
    std::unique_lock<std::mutex> job_lock(job_mutex_);  // one parallel_for at a time
    ensure_workers(helpers);
    const std::uint64_t generation = ++generation_count_;
    // First the new generation with nothing to claim: a worker late from the last job, which
    // read its ticket before, can no longer claim with it (the fields below are about to change).
    ticket_.store(generation << 32 | kNoChunk);
    body_ = &body;
    n_ = n;
    grain_ = grain;
    chunks_ = chunks;
    wanted_.store(helpers);
    finished_.store(0);
    ticket_.store(generation << 32);  // publishes the job (its fields above) to any claim
    generation_.store(generation);
    if (sleeping_.load() > 0) {  // seq_cst with the sleepers' count and check (see worker_loop)
      std::lock_guard<std::mutex> g(mutex_);
      wake_.notify_all();
    }
    work(generation);
    // Every chunk is claimed; wait for the ones still running on workers.
    if (!spin_until([&] { return finished_.load(std::memory_order_acquire) == chunks; })) {
      std::unique_lock<std::mutex> g(mutex_);
      done_.wait(g, [&] { return finished_.load() == chunks; });
    }
    body_ = nullptr;
  }

 private:
  static constexpr std::uint64_t kNoChunk = 0xffffffffu;
  // Spins up to 50 microseconds for `done`: longer than the gaps between a drag's jobs, short
  // against a frame. False if it is not done by then.
  template <class Done>
  static bool spin_until(Done done) {
    const auto start = std::chrono::steady_clock::now();
    for (std::uint32_t i = 0;; ++i) {
      if (done()) return true;
#if defined(__x86_64__) || defined(__i386__)
      __builtin_ia32_pause();
#endif
      if ((i & 63) == 63 && std::chrono::steady_clock::now() - start > std::chrono::microseconds(50)) return false;
    }
  }

  Pool() : threads_(std::clamp(static_cast<int>(std::thread::hardware_concurrency()), 1, 8)) {}
  ~Pool() {
    stop_.store(true);
    {
      std::lock_guard<std::mutex> g(mutex_);
      wake_.notify_all();
    }
    for (auto& t : workers_) t.join();
  }

  // Claims and runs chunks of job `generation` until none is left (or another job is on).
  void work(std::uint64_t generation) {
    in_body_ = true;
    for (;;) {
      std::uint64_t t = ticket_.load(std::memory_order_acquire);
      if ((t >> 32) != generation || static_cast<std::uint32_t>(t) >= chunks_.load(std::memory_order_relaxed)) break;
      if (!ticket_.compare_exchange_weak(t, t + 1, std::memory_order_acq_rel)) continue;
      // Claimed: the job's fields stay until every chunk, this one too, is finished.
      const std::uint32_t b = static_cast<std::uint32_t>(t) * grain_;
      (*body_)(b, std::min(n_, b + grain_));
      if (finished_.fetch_add(1, std::memory_order_acq_rel) + 1 == chunks_.load(std::memory_order_relaxed)) {
        std::lock_guard<std::mutex> g(mutex_);
        done_.notify_one();
      }
    }
    in_body_ = false;
  }
  static thread_local bool in_body_;

  void ensure_workers(int count) {
    while (static_cast<int>(workers_.size()) < count) {
      const int id = static_cast<int>(workers_.size());
      workers_.emplace_back([this, id] { worker_loop(id); });
    }
  }

  void worker_loop(int id) {
    std::uint64_t seen = generation_.load();
    for (;;) {
      if (!spin_until([&] { return generation_.load(std::memory_order_acquire) != seen || stop_.load(); })) {
        std::unique_lock<std::mutex> g(mutex_);
        ++sleeping_;  // before the check below, so a caller that publishes after it notifies
        wake_.wait(g, [&] { return stop_.load() || generation_.load() != seen; });
        --sleeping_;
      }
      if (stop_.load()) return;
      seen = generation_.load();
      if (id < wanted_.load()) work(seen);  // else not needed for this job
    }
  }

  int threads_;
  std::vector<std::thread> workers_;
  std::mutex job_mutex_, mutex_;
  std::condition_variable wake_, done_;
  // The current job; written by the caller before its ticket is published.
  const std::function<void(std::uint32_t, std::uint32_t)>* body_ = nullptr;
  std::uint32_t n_ = 0, grain_ = 1;
  std::atomic<std::uint32_t> chunks_{0};  // also read before a claim, by a worker that may be late
  std::atomic<int> wanted_{0};
  std::atomic<std::uint64_t> ticket_{0};
  std::atomic<std::uint32_t> finished_{0};
  std::atomic<std::uint64_t> generation_{0};
  std::uint64_t generation_count_ = 0;  // the caller's, under job_mutex_
  std::atomic<int> sleeping_{0};
  std::atomic<bool> stop_{false};
};

thread_local bool Pool::in_body_ = false;

}  // namespace

void parallel_for(std::uint32_t n, std::uint32_t grain, const std::function<void(std::uint32_t, std::uint32_t)>& body) {
  if (n == 0) return;
  grain = std::max<std::uint32_t>(grain, 1);
  Pool::instance().run(n, grain, body);
}

int parallel_threads() { return Pool::instance().threads(); }
void set_parallel_threads(int n) { Pool::instance().set_threads(n); }

}  // namespace sublift
