// The 1-D filters that the lifting programs imply equal paper 003's Table 1, digit for digit.
// Filters are read off the transform itself: synthesis of a unit coefficient gives l~ and h~;
// analysis of a unit fine value gives l and h.
#include <gtest/gtest.h>

#include <map>

#include "core/multires/hierarchy.h"
#include "core/complex/shapes.h"

using namespace sublift;

namespace {

constexpr int kN = 16;  // closed curve: fine position 2i is vertex i, 2i+1 is the edge (i, i+1)

int fine_index(int k) {  // fine 1-D position -> level-1 vertex index
  k = ((k % (2 * kN)) + 2 * kN) % (2 * kN);
  return k % 2 == 0 ? k / 2 : kN + (k - 1) / 2;
}

Hierarchy curve(Scheme s) {
  std::vector<double> pos;
  Complex c = make_curve_loop(kN, pos);
  return make_hierarchy(std::move(c), 1, s, 1);
}

// Synthesis of a unit coefficient at level-1 index `unit`, read at fine offsets from `center`.
std::map<int, double> synthesis_filter(Scheme s, int unit, int center) {
  Hierarchy h = curve(s);
  h.coeffs.assign(h.coeffs.size(), 0.0);
  h.coeffs[unit] = 1.0;
  const std::vector<double> x = synthesize(h, 1);
  std::map<int, double> f;
  for (int d = -4; d <= 4; ++d) f[d] = x[fine_index(center + d)];
  return f;
}

// Analysis row: the weight of fine position center+d in the coefficient at level-1 index `out`.
std::map<int, double> analysis_filter(Scheme s, int out, int center) {
  std::map<int, double> f;
  for (int d = -4; d <= 4; ++d) {
    Hierarchy h = curve(s);
    std::vector<double> fine(h.coeffs.size(), 0.0);
    fine[fine_index(center + d)] = 1.0;
    analyze(h, fine);
    f[d] = h.coeffs[out];
  }
  return f;
}

void expect_symmetric(const std::map<int, double>& f, const std::vector<double>& taps, const char* what) {
  for (int d = -4; d <= 4; ++d) {
    const std::size_t a = static_cast<std::size_t>(std::abs(d));
    const double want = a < taps.size() ? taps[a] : 0.0;
    EXPECT_EQ(f.at(d), want) << what << " tap " << d;
  }
}

}  // namespace

// Paper 003, Table 1 (decomposition l, h; reconstruction l~, h~), linear degree.
TEST(Table1, LinearFilters) {
  const int i = 5;  // any coarse vertex; its fine position is 2i, its wavelet sits at 2i+1
  expect_symmetric(synthesis_filter(Scheme::Linear, i, 2 * i), {1.0, 0.5}, "l~");
  expect_symmetric(synthesis_filter(Scheme::Linear, kN + i, 2 * i + 1), {0.75, -0.25, -0.125}, "h~");
  expect_symmetric(analysis_filter(Scheme::Linear, i, 2 * i), {0.75, 0.25, -0.125}, "l");
  expect_symmetric(analysis_filter(Scheme::Linear, kN + i, 2 * i + 1), {1.0, -0.5}, "h");
}

// Paper 003, Table 1, cubic degree.
TEST(Table1, CubicFilters) {
  const int i = 5;
  expect_symmetric(synthesis_filter(Scheme::Cubic, i, 2 * i), {0.75, 0.5, 0.125}, "l~");
  expect_symmetric(synthesis_filter(Scheme::Cubic, kN + i, 2 * i + 1), {5.0 / 8, -5.0 / 64, -3.0 / 16, -3.0 / 64}, "h~");
  expect_symmetric(analysis_filter(Scheme::Cubic, i, 2 * i), {5.0 / 4, 5.0 / 32, -3.0 / 8, 3.0 / 32}, "l");
  expect_symmetric(analysis_filter(Scheme::Cubic, kN + i, 2 * i + 1), {1.5, -1.0, 0.25}, "h");
}
