#include "core/base/bounds.h"

#include <algorithm>
#include <cmath>

#include "core/base/errors.h"

namespace sublift {

std::array<std::array<double, 3>, 2> bounding_box(const double* xyz, std::size_t num_points) {
  if (num_points == 0) throw Error("bounding box of no points");
  std::array<double, 3> lo{xyz[0], xyz[1], xyz[2]}, hi = lo;
  for (std::size_t i = 1; i < num_points; ++i) {
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], xyz[3 * i + a]);
      hi[a] = std::max(hi[a], xyz[3 * i + a]);
    }
  }
  return {lo, hi};
}

double bbox_diagonal(std::span<const double> xyz) {
  if (xyz.size() < 3) return 0.0;
  const auto b = bounding_box(xyz.data(), xyz.size() / 3);
  return std::hypot(b[1][0] - b[0][0], b[1][1] - b[0][1], b[1][2] - b[0][2]);
}

}  // namespace sublift
