// core/edit/transform: rotate and scale as per-vertex moves (issue 19), and Session::move_each.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>
#include <vector>

#include "core/base/errors.h"
#include "core/edit/session.h"
#include "core/edit/transform.h"
#include "tests/noisy_hierarchy.h"
#include "tests/test_util.h"

namespace sublift {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(Transform, RotationAboutZByAQuarterTurnAndHalfWeight) {
  // Two points at (1,0,0) and (0,2,5): a quarter turn about +Z through the origin (right-handed:
  // x goes to y) takes them to (0,1,0) and (-2,0,5); at weight 0.5 the first turns by 45 degrees.
  const std::vector<double> pos = {1, 0, 0, 0, 2, 5};
  const std::vector<std::uint32_t> vs = {0, 1};
  std::vector<double> d;
  transform_deltas(pos, pos, vs, {}, glm::dvec3(0.0), {0, 0, 1}, kPi / 2, glm::dvec3(1.0), d);
  ASSERT_EQ(d.size(), 6u);
  const double expect[6] = {-1, 1, 0, -2, -2, 0};
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(d[i], expect[i], 1e-15) << i;

  const std::vector<double> w = {0.5, 1.0};
  transform_deltas(pos, pos, vs, w, glm::dvec3(0.0), {0, 0, 2}, kPi / 2, glm::dvec3(1.0), d);  // axis normalised
  EXPECT_NEAR(d[0], std::sqrt(0.5) - 1.0, 1e-15);
  EXPECT_NEAR(d[1], std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(std::hypot(1.0 + d[0], d[1]), 1.0, 1e-15);  // a partial rotation keeps the length
}

TEST(Transform, ScaleAboutAPivotWithAxisConstraints) {
  EXPECT_EQ(scale_factors(2.0, -1, false), glm::dvec3(2.0));
  EXPECT_EQ(scale_factors(2.0, 1, false), glm::dvec3(1.0, 2.0, 1.0));
  EXPECT_EQ(scale_factors(2.0, 1, true), glm::dvec3(2.0, 1.0, 2.0));
  // (3, 1, 1) scaled by (2, 1, 2) about (1, 1, 1) lands on (5, 1, 1); weight 0.5 scales by 1.5.
  const std::vector<double> pos = {3, 1, 1};
  const std::vector<std::uint32_t> vs = {0};
  std::vector<double> d;
  transform_deltas(pos, pos, vs, {}, glm::dvec3(1.0), {0, 0, 1}, 0.0, glm::dvec3(2, 1, 2), d);
  EXPECT_EQ(d, (std::vector<double>{2, 0, 0}));
  transform_deltas(pos, pos, vs, std::vector<double>{0.5}, glm::dvec3(1.0), {0, 0, 1}, 0.0, glm::dvec3(2, 1, 2), d);
  EXPECT_EQ(d, (std::vector<double>{1, 0, 0}));
  // Deltas are relative to the current positions: from where the first delta put the point, the
  // same transform of the start asks for nothing more.
  const std::vector<double> moved = {4, 1, 1};
  transform_deltas(pos, moved, vs, std::vector<double>{0.5}, glm::dvec3(1.0), {0, 0, 1}, 0.0, glm::dvec3(2, 1, 2), d);
  EXPECT_EQ(d, (std::vector<double>{0, 0, 0}));
}

TEST(Transform, Pivots) {
  const std::vector<double> pos = {0, 0, 0, 2, 0, 0, 2, 4, 0, 9, 9, 9};
  const std::vector<unsigned> sel = {0, 1, 2};
  const glm::dvec3 cursor(1, 2, 3);
  EXPECT_EQ(pivot_point(Pivot::Median, pos, sel, -1, cursor), glm::dvec3(4.0 / 3.0, 4.0 / 3.0, 0.0));
  EXPECT_EQ(pivot_point(Pivot::Active, pos, sel, 2, cursor), glm::dvec3(2, 4, 0));
  EXPECT_EQ(pivot_point(Pivot::Active, pos, sel, -1, cursor), pivot_point(Pivot::Median, pos, sel, -1, cursor));
  EXPECT_EQ(pivot_point(Pivot::Cursor, pos, sel, 2, cursor), cursor);
  EXPECT_EQ(pivot_point(Pivot::Origin, pos, sel, 2, cursor), glm::dvec3(0.0));
  EXPECT_EQ(pivot_point(Pivot::Median, pos, {}, -1, cursor), glm::dvec3(0.0));
  for (const Pivot p : {Pivot::Median, Pivot::Active, Pivot::Cursor, Pivot::Origin}) EXPECT_EQ(parse_pivot(pivot_name(p)), p);
  EXPECT_THROW(parse_pivot("centre"), Error);
}

bool same_bits(std::span<const double> a, std::span<const double> b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

// move_each with one delta per vertex: the local resynthesis equals a fresh synthesis of the
// coefficients, the edit is one undo step, and undo restores every level bit for bit.
TEST(SessionMoveEach, RotationOfABaseRegionKeepsTheHierarchyConsistent) {
  for (const Scheme scheme : {Scheme::Cubic, Scheme::Linear, Scheme::Sqrt2}) {
    SCOPED_TRACE(scheme_name(scheme));
    Session s(testing::noisy_torus(8, 6, scheme == Scheme::Sqrt2 ? 4 : 2, scheme, 3, 0.02));
    const int J = s.finest_level();
    std::vector<std::vector<double>> before;
    for (int l = 0; l <= J; ++l) before.emplace_back(s.positions(l).begin(), s.positions(l).end());
    const std::vector<double> coeffs = s.hierarchy().coeffs;
    const int level = 1;
    const std::vector<std::uint32_t> vs = {0, 1, 2, 3, 9, 10};
    const std::vector<double> w = {1.0, 1.0, 0.5, 0.5, 0.25, 0.1};
    const auto p = s.positions(level);
    std::vector<double> start;
    for (const std::uint32_t v : vs) start.insert(start.end(), p.begin() + 3 * v, p.begin() + 3 * v + 3);
    std::vector<double> d;
    transform_deltas(start, p, vs, w, glm::dvec3(0.1, 0.2, 0.0), {1, 1, 0}, 0.7, glm::dvec3(1.2, 0.9, 1.0), d);
    s.move_each(level, vs, d);
    EXPECT_EQ(s.history().size(), 1u);
    for (std::size_t k = 0; k < vs.size(); ++k)
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(s.positions(level)[3 * vs[k] + c], before[level][3 * vs[k] + c] + d[3 * k + c], 1e-12);
    for (int l = 0; l <= J; ++l)
      EXPECT_LT(testing::max_abs_diff(synthesize(s.hierarchy(), l), s.positions(l)), 1e-11) << "level " << l;
    ASSERT_TRUE(s.undo());
    for (int l = 0; l <= J; ++l) EXPECT_TRUE(same_bits(s.positions(l), before[static_cast<std::size_t>(l)])) << l;
    EXPECT_TRUE(same_bits(s.hierarchy().coeffs, coeffs));
  }
}

TEST(SessionMoveEach, RefusesAMissingOrNonFiniteDelta) {
  Session s(testing::noisy_torus(6, 5, 1, Scheme::Cubic, 1, 0.01));
  const std::vector<std::uint32_t> vs = {0, 1};
  EXPECT_THROW(s.move_each(0, vs, std::vector<double>{1, 2, 3}), Error);
  EXPECT_THROW(s.move_each(0, vs, std::vector<double>{0, 0, 0, 0, NAN, 0}), Error);
  EXPECT_TRUE(s.history().empty());
}

}  // namespace
}  // namespace sublift
