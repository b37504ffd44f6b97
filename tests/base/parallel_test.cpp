#include <gtest/gtest.h>

#include <atomic>
#include <vector>

#include "core/complex/complex_build.h"
#include "core/multires/hierarchy.h"
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
