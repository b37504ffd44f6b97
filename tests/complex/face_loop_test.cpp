#include <gtest/gtest.h>

#include <random>

#include "core/complex/face_loop.h"

using namespace sublift;

TEST(FaceLoop, RotationsAndReversalsShareOneKey) {
  const std::vector<std::uint32_t> loop{7, 3, 9, 4, 1};
  const std::vector<std::uint32_t> key = canonical_loop(loop);
  EXPECT_EQ(key, (std::vector<std::uint32_t>{1, 4, 9, 3, 7}));  // from 1, towards the smaller neighbour
  std::vector<std::uint32_t> r = loop;
  for (int turn = 0; turn < 5; ++turn) {
    std::rotate(r.begin(), r.begin() + 1, r.end());
    EXPECT_EQ(canonical_loop(r), key);
    std::vector<std::uint32_t> rev(r.rbegin(), r.rend());
    EXPECT_EQ(canonical_loop(rev), key);
  }
  EXPECT_NE(canonical_loop(std::vector<std::uint32_t>{1, 9, 4, 3, 7}), key);  // another polygon, same set
}

TEST(FaceLoop, AppendingFormMatchesTheAllocatingOne) {
  std::mt19937 rng(3);
  std::vector<std::uint32_t> out;
  for (int t = 0; t < 2000; ++t) {
    std::vector<std::uint32_t> f(3 + rng() % 6);
    for (auto& v : f) v = rng() % 12;  // repeats allowed: the key must still agree
    out.clear();
    append_canonical_loop(f, out);
    ASSERT_EQ(out, canonical_loop(f));
  }
}
