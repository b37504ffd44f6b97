#include "core/complex/polygon_normal.h"

#include <cmath>

namespace sublift {

void accumulate_face_normals(const Csr& faces, const double* xyz, double* out) {
  for (std::size_t f = 0; f < faces.rows(); ++f) {
    double n[3];
    polygon_area_vector(faces.row(f), xyz, n);
    for (const std::uint32_t v : faces.row(f))
      for (int c = 0; c < 3; ++c) out[3 * std::size_t(v) + c] += n[c];
  }
}

std::vector<double> area_weighted_normals(const Csr& faces, std::span<const double> xyz) {
  std::vector<double> n(xyz.size(), 0.0);
  accumulate_face_normals(faces, xyz.data(), n.data());
  for (std::size_t v = 0; v + 2 < n.size(); v += 3) {
    const double len = std::sqrt(n[v] * n[v] + n[v + 1] * n[v + 1] + n[v + 2] * n[v + 2]);
    if (len > 0)
      for (int c = 0; c < 3; ++c) n[v + c] /= len;
  }
  return n;
}

}  // namespace sublift
