#pragma once
// Polygon normals by Newell's formula, the one implementation the frames, limit normals,
// exports and pictures share.
#include <cstdint>
#include <span>
#include <vector>

#include "core/base/csr.h"

namespace sublift {

/// Twice the area vector of the polygon `corners` over xyz (3 doubles per vertex): its length is
/// twice the area, its direction the normal by the right-hand rule. Coordinates are taken
/// relative to the first corner, so a polygon far from the origin keeps its precision.
inline void polygon_area_vector(std::span<const std::uint32_t> corners, const double* xyz, double n[3]) {
  n[0] = n[1] = n[2] = 0.0;
  if (corners.empty()) return;
  const double* o = xyz + 3 * std::size_t(corners[0]);
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const double* pa = xyz + 3 * std::size_t(corners[i]);
    const double* pb = xyz + 3 * std::size_t(corners[(i + 1) % corners.size()]);
    const double a[3] = {pa[0] - o[0], pa[1] - o[1], pa[2] - o[2]};
    const double b[3] = {pb[0] - o[0], pb[1] - o[1], pb[2] - o[2]};
    n[0] += (a[1] - b[1]) * (a[2] + b[2]);
    n[1] += (a[2] - b[2]) * (a[0] + b[0]);
    n[2] += (a[0] - b[0]) * (a[1] + b[1]);
  }
}

/// Adds every face's area vector to its corners: out holds 3 doubles per vertex (not zeroed).
void accumulate_face_normals(const Csr& faces, const double* xyz, double* out);

/// Area-weighted unit vertex normals (3 per vertex, (0, 0, 0) on no face) of `faces` over xyz.
std::vector<double> area_weighted_normals(const Csr& faces, std::span<const double> xyz);

}  // namespace sublift
