#include "core/base/surface_mesh.h"

#include <cmath>

namespace sublift {

std::string uv_problem(std::size_t face_corners, const FaceVaryingUV& uv) {
  if (uv.corners.size() != face_corners)
    return std::to_string(uv.corners.size()) + " UV corners for " + std::to_string(face_corners) + " face corners";
  if (uv.points.size() % 2) return "an odd number of UV coordinates";
  for (std::uint32_t k : uv.corners)
    if (k >= uv.num_points()) return "UV index " + std::to_string(k) + " beyond the " + std::to_string(uv.num_points()) + " UV points";
  for (double x : uv.points)
    if (!std::isfinite(x)) return "a UV coordinate that is not finite";
  return "";
}

}  // namespace sublift
