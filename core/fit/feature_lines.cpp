#include "core/fit/feature_lines.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "core/base/points.h"

namespace sublift {

namespace {

glm::dvec3 closest_on_segment(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b) {
  const glm::dvec3 d = b - a;
  const double l2 = glm::dot(d, d);
  if (l2 == 0.0) return a;
  return a + std::clamp(glm::dot(p - a, d) / l2, 0.0, 1.0) * d;
}

}  // namespace

FeatureLines::FeatureLines(std::span<const double> x, std::span<const std::uint32_t> edges) {
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi = -lo;
  double length = 0;
  for (std::size_t e = 0; e + 1 < edges.size(); e += 2) {
    a_.push_back(at(x, edges[e]));
    b_.push_back(at(x, edges[e + 1]));
    lo = glm::min(lo, glm::min(a_.back(), b_.back()));
    hi = glm::max(hi, glm::max(a_.back(), b_.back()));
    length += glm::distance(a_.back(), b_.back());
  }
  if (a_.empty()) return;
  // Cells about two segments long, at most 2^21 of them.
  const glm::dvec3 extent = hi - lo;
  cell_ = std::max({2.0 * length / double(a_.size()), std::max({extent.x, extent.y, extent.z}) / 128.0, 1e-300});
  for (int k = 0; k < 3; ++k) dims_[k] = std::clamp(static_cast<int>(extent[k] / cell_) + 1, 1, 128);
  lo_ = lo;
  const auto index = [&](const glm::dvec3& p, int k) { return std::clamp(static_cast<int>((p[k] - lo_[k]) / cell_), 0, dims_[k] - 1); };
  // Counting sort of (cell, segment) pairs over each segment's box.
  const std::size_t cells = std::size_t(dims_[0]) * dims_[1] * dims_[2];
  offsets_.assign(cells + 1, 0);
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<std::uint32_t> fill;
    if (pass == 1) {
      for (std::size_t c = 0; c < cells; ++c) offsets_[c + 1] += offsets_[c];
      items_.resize(offsets_[cells]);
      fill.assign(offsets_.begin(), offsets_.end() - 1);
    }
    for (std::uint32_t s = 0; s < a_.size(); ++s) {
      const glm::dvec3 l = glm::min(a_[s], b_[s]), h = glm::max(a_[s], b_[s]);
      for (int z = index(l, 2); z <= index(h, 2); ++z)
        for (int y = index(l, 1); y <= index(h, 1); ++y)
          for (int xx = index(l, 0); xx <= index(h, 0); ++xx) {
            const std::uint32_t c = cell_of(xx, y, z);
            if (pass == 0) ++offsets_[c + 1];
            else items_[fill[c]++] = s;
          }
    }
  }
}

glm::dvec3 FeatureLines::closest(const glm::dvec3& p) const {
  if (a_.empty()) return p;
  int c[3];
  for (int k = 0; k < 3; ++k) c[k] = std::clamp(static_cast<int>(std::floor((p[k] - lo_[k]) / cell_)), 0, dims_[k] - 1);
  // Outside the grid, every cell is at least this much farther than its index distance says.
  double outside = 0;
  for (int k = 0; k < 3; ++k) {
    const double d = std::max({lo_[k] - p[k], p[k] - (lo_[k] + dims_[k] * cell_), 0.0});
    outside += d * d;
  }
  outside = std::sqrt(outside);
  glm::dvec3 best = a_[0];
  double best_d = std::numeric_limits<double>::infinity();
  const int max_r = std::max({dims_[0], dims_[1], dims_[2]});
  for (int r = 0; r <= max_r; ++r) {
    for (int z = c[2] - r; z <= c[2] + r; ++z)
      for (int y = c[1] - r; y <= c[1] + r; ++y)
        for (int x = c[0] - r; x <= c[0] + r; ++x) {
          if (std::max({std::abs(x - c[0]), std::abs(y - c[1]), std::abs(z - c[2])}) != r) continue;  // the shell only
          if (x < 0 || y < 0 || z < 0 || x >= dims_[0] || y >= dims_[1] || z >= dims_[2]) continue;
          const std::uint32_t cell = cell_of(x, y, z);
          for (std::uint32_t i = offsets_[cell]; i < offsets_[cell + 1]; ++i) {
            const std::uint32_t s = items_[i];
            const glm::dvec3 q = closest_on_segment(p, a_[s], b_[s]);
            const double d = glm::distance(p, q);
            if (d < best_d) best_d = d, best = q;
          }
        }
    // Cells r + 1 or more away (in index) lie at least r cells away.
    if (best_d <= std::max(outside, r * cell_)) break;
  }
  return best;
}

}  // namespace sublift
