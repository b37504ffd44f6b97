#pragma once
// parallel_for over a persistent pool of worker threads. Work is handed out in chunks from a
// shared counter, so a thread that the OS deschedules does not hold the others up (fixed equal
// splits did, on a loaded machine). Each index is processed by exactly one thread.
#include <cstdint>
#include <functional>

namespace sublift {

/// Runs body(begin, end) over [0, n) in chunks of about `grain` indices on up to
/// parallel_threads() threads (the caller included). Small n runs inline. `body` must not throw.
void parallel_for(std::uint32_t n, std::uint32_t grain, const std::function<void(std::uint32_t, std::uint32_t)>& body);

/// Threads used by parallel_for (default: hardware concurrency, at most 8).
int parallel_threads();
void set_parallel_threads(int n);

}  // namespace sublift
