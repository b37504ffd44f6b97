#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <vector>

#include "core/complex/complex_build.h"
#include "core/multires/hierarchy.h"
#include "core/base/csr.h"
#include "core/base/parallel.h"
#include "core/complex/shapes.h"
#include "tests/test_shapes.h"

using namespace sublift;

TEST(ParallelFor, VisitsEveryIndexExactlyOnce) {
  const int before = parallel_threads();
  for (int threads : {1, 2, 4}) {
    set_parallel_threads(threads);
    for (std::uint32_t n : {0u, 1u, 100u, 8191u, 8192u, 100000u}) {
      std::vector<std::atomic<int>> hits(n);
      parallel_for(n, 1000, [&](std::uint32_t b, std::uint32_t e) {
        for (std::uint32_t i = b; i < e; ++i) hits[i].fetch_add(1);
      });
      for (std::uint32_t i = 0; i < n; ++i) ASSERT_EQ(hits[i].load(), 1) << "n " << n << " threads " << threads;
    }
  }
  set_parallel_threads(before);
}

// A drag runs many small jobs back to back, and the caller no longer waits for every worker to
// check in (core/base/parallel.cpp): each job must still be run whole, once, and end. Job sizes
// and chunk counts vary from job to job. (The window for a late worker's stale claim is a few
// instructions wide and this rarely meets it: a first version of the pool passed it, and a
// ThreadSanitizer stress of 20,000 jobs, yet hung once in bench_edit, before the pool closed
// the old ticket first.)
TEST(ParallelFor, ManySmallJobsInARowEachVisitEveryIndexOnce) {
  const int before = parallel_threads();
  std::vector<int> hits(5000);
  for (int threads : {2, 3}) {
    set_parallel_threads(threads);
    for (std::uint32_t job = 0; job < 10000; ++job) {
      const std::uint32_t n = job % 3 ? (job * 7919u) % 5000u : job % 300u;
      const std::uint32_t grain = 1 + (job % 7) * 150;
      std::fill(hits.begin(), hits.begin() + n, 0);
      parallel_for(n, grain, [&](std::uint32_t b, std::uint32_t e) {
        for (std::uint32_t i = b; i < e; ++i) ++hits[i];  // plain writes: each index has one owner
      });
      for (std::uint32_t i = 0; i < n; ++i) ASSERT_EQ(hits[i], 1) << "job " << job << " index " << i << " threads " << threads;
    }
  }
  set_parallel_threads(before);
}

TEST(ParallelFor, LiftingIsBitIdenticalForAnyThreadCount) {
  Hierarchy h = make_hierarchy(complex_from_surface_mesh(make_quad_torus(48, 24)), 3, Scheme::Cubic, 3);
  const std::vector<double> fine = sublift::testing::random_values(h.coeffs.size(), 5);
  const int before = parallel_threads();
  std::vector<std::vector<double>> results;
  for (int threads : {1, 2, 3}) {
    set_parallel_threads(threads);
    analyze(h, fine);
    std::vector<double> r = h.coeffs;
    const std::vector<double> back = synthesize(h, 3);
    r.insert(r.end(), back.begin(), back.end());
    results.push_back(std::move(r));
  }
  set_parallel_threads(before);
  EXPECT_EQ(results[0], results[1]);
  EXPECT_EQ(results[0], results[2]);
}

TEST(ParallelFor, ANestedLoopRunsInlineAndVisitsEveryIndex) {
  const int before = parallel_threads();
  set_parallel_threads(2);
  constexpr std::uint32_t kOuter = 64, kInner = 5000;
  std::vector<std::atomic<int>> hits(kOuter * kInner);
  parallel_for(kOuter, 1, [&](std::uint32_t b, std::uint32_t e) {
    for (std::uint32_t o = b; o < e; ++o)
      parallel_for(kInner, 100, [&](std::uint32_t ib, std::uint32_t ie) {
        for (std::uint32_t i = ib; i < ie; ++i) hits[o * kInner + i].fetch_add(1);
      });
  });
  set_parallel_threads(before);
  for (std::size_t i = 0; i < hits.size(); ++i) ASSERT_EQ(hits[i].load(), 1) << i;
}

// The transposes count and place in blocks of rows on large inputs; the upward rows must list
// their rows in increasing order exactly as one serial pass does, for any thread count.
TEST(ParallelFor, TransposeEqualsTheSerialCountingSort) {
  const std::uint32_t lower = 30000, rows = 120000;
  Csr down;
  std::uint32_t state = 12345;
  const auto next = [&] { return state = state * 1664525u + 1013904223u; };
  std::vector<std::uint32_t> pairs;
  for (std::uint32_t r = 0; r < rows; ++r) {
    const std::uint32_t n = next() % 5;
    for (std::uint32_t k = 0; k < n; ++k) down.items.push_back(next() % lower);
    down.offsets.push_back(static_cast<std::uint32_t>(down.items.size()));
    pairs.push_back(next() % lower);
    pairs.push_back(next() % lower);
  }
  // The reference: every (item, row) in row order, stably by item.
  Csr expect;
  expect.offsets.assign(lower + 1, 0);
  std::vector<std::vector<std::uint32_t>> by(lower);
  for (std::uint32_t r = 0; r < rows; ++r)
    for (std::uint32_t x : down.row(r)) by[x].push_back(r);
  for (std::uint32_t x = 0; x < lower; ++x) {
    expect.items.insert(expect.items.end(), by[x].begin(), by[x].end());
    expect.offsets[x + 1] = static_cast<std::uint32_t>(expect.items.size());
  }
  const int before = parallel_threads();
  for (int threads : {1, 2, 3}) {
    set_parallel_threads(threads);
    const Csr up = transpose(down, lower);
    EXPECT_EQ(up.offsets, expect.offsets) << threads << " threads";
    EXPECT_EQ(up.items, expect.items) << threads << " threads";
    const Csr up_pairs = transpose_pairs(pairs, lower);
    ASSERT_EQ(up_pairs.offsets.size(), std::size_t(lower) + 1);
    for (std::uint32_t x = 0; x < lower; ++x) {
      const auto row = up_pairs.row(x);
      ASSERT_TRUE(std::is_sorted(row.begin(), row.end())) << x;
      for (std::uint32_t r : row) ASSERT_TRUE(pairs[2 * r] == x || pairs[2 * r + 1] == x);
    }
    EXPECT_EQ(up_pairs.items.size(), pairs.size());
  }
  set_parallel_threads(before);
}
