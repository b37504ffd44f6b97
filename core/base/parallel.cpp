#include "core/base/parallel.h"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <mutex>
#include <thread>
#include <vector>

namespace sublift {
namespace {

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
    {
      std::lock_guard<std::mutex> g(mutex_);
      body_ = &body;
      n_ = n;
      grain_ = grain;
      next_.store(0);
      wanted_ = helpers;
      active_ = helpers;
      ++generation_;
    }
    wake_.notify_all();
    work();
    std::unique_lock<std::mutex> g(mutex_);
    done_.wait(g, [&] { return active_ == 0; });
    body_ = nullptr;
  }

 private:
  Pool() : threads_(std::clamp(static_cast<int>(std::thread::hardware_concurrency()), 1, 8)) {}
  ~Pool() {
    {
      std::lock_guard<std::mutex> g(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    for (auto& t : workers_) t.join();
  }

  void work() {
    in_body_ = true;
    for (;;) {
      const std::uint32_t b = next_.fetch_add(grain_);
      if (b >= n_) break;
      (*body_)(b, std::min(n_, b + grain_));
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
    std::uint64_t seen = 0;
    for (;;) {
      {
        std::unique_lock<std::mutex> g(mutex_);
        wake_.wait(g, [&] { return stop_ || generation_ != seen; });
        if (stop_) return;
        seen = generation_;
        if (id >= wanted_) continue;  // not needed for this job
      }
      work();
      std::lock_guard<std::mutex> g(mutex_);
      if (--active_ == 0) done_.notify_one();
    }
  }

  int threads_;
  std::vector<std::thread> workers_;
  std::mutex job_mutex_, mutex_;
  std::condition_variable wake_, done_;
  const std::function<void(std::uint32_t, std::uint32_t)>* body_ = nullptr;
  std::uint32_t n_ = 0, grain_ = 1;
  std::atomic<std::uint32_t> next_{0};
  int wanted_ = 0, active_ = 0;
  std::uint64_t generation_ = 0;
  bool stop_ = false;
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
