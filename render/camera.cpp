#include "render/camera.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace sublift {
namespace {

constexpr double kHalfPi = std::numbers::pi / 2.0;
constexpr double kFrameMargin = 1.08;  // a little air around the framed box

// Z-up worlds are the Y-up orbit frame turned +90 degrees about X: (x, y, z) -> (x, -z, y).
glm::dvec3 to_world(UpAxis up_axis, const glm::dvec3& v) {
  return up_axis == UpAxis::Z ? glm::dvec3(v.x, -v.z, v.y) : v;
}

}  // namespace

double OrbitCamera::aspect() const {
  return static_cast<double>(viewport_width) / static_cast<double>(viewport_height);
}

void OrbitCamera::set_viewport(int width, int height) {
  viewport_width = std::max(width, 1);
  viewport_height = std::max(height, 1);
}

glm::dvec3 OrbitCamera::world_up() const { return to_world(up_axis, {0.0, 1.0, 0.0}); }

glm::dvec3 OrbitCamera::forward() const {
  const double cp = std::cos(pitch);
  return to_world(up_axis, -glm::dvec3(cp * std::sin(yaw), std::sin(pitch), cp * std::cos(yaw)));
}

glm::dvec3 OrbitCamera::right() const {
  return to_world(up_axis, {std::cos(yaw), 0.0, -std::sin(yaw)});
}

// From yaw/pitch rather than from a world-up vector, so top and bottom views stay well defined.
glm::dvec3 OrbitCamera::up() const { return glm::cross(right(), forward()); }

glm::dvec3 OrbitCamera::eye() const { return target - distance * forward(); }

glm::dmat4 OrbitCamera::view() const {
  const glm::dvec3 r = right(), u = up(), f = forward(), e = eye();
  glm::dmat4 m(1.0);
  m[0][0] = r.x; m[1][0] = r.y; m[2][0] = r.z;
  m[0][1] = u.x; m[1][1] = u.y; m[2][1] = u.z;
  m[0][2] = -f.x; m[1][2] = -f.y; m[2][2] = -f.z;
  m[3][0] = -glm::dot(r, e);
  m[3][1] = -glm::dot(u, e);
  m[3][2] = glm::dot(f, e);
  return m;
}

glm::dmat4 OrbitCamera::projection() const {
  // The scene sphere as seen from the eye bounds the depth range; 1.1 covers rounding.
  const double to_center = glm::length(eye() - scene_center);
  const double reach = 1.1 * scene_radius;
  const double far_plane = std::max(to_center + reach, 1e-6);
  if (orthographic) {
    const double half_h = distance * std::tan(fov_y / 2.0);
    const double half_w = half_h * aspect();
    return glm::ortho(-half_w, half_w, -half_h, half_h, to_center - reach, far_plane);
  }
  const double near_plane = std::max(to_center - reach, 1e-3 * (to_center + reach));
  return glm::perspective(fov_y, aspect(), near_plane, std::max(far_plane, 2.0 * near_plane));
}

void OrbitCamera::frame(const glm::dvec3& bbox_min, const glm::dvec3& bbox_max) {
  const glm::dvec3 center = 0.5 * (bbox_min + bbox_max);
  double radius = 0.5 * glm::length(bbox_max - bbox_min);
  if (!(radius > 0.0) || !std::isfinite(radius)) radius = std::max(1e-3 * glm::length(center), 0.5);
  target = center;
  scene_center = center;
  scene_radius = radius;

  const double tan_y = std::tan(fov_y / 2.0);
  const double tan_x = tan_y * aspect();
  const glm::dvec3 r = right(), u = up(), f = forward();
  double needed = 0.0;
  for (int corner = 0; corner < 8; ++corner) {
    const glm::dvec3 p(corner & 1 ? bbox_max.x : bbox_min.x, corner & 2 ? bbox_max.y : bbox_min.y,
                       corner & 4 ? bbox_max.z : bbox_min.z);
    const glm::dvec3 d = p - center;
    const double x = std::abs(glm::dot(d, r)), y = std::abs(glm::dot(d, u)), z = glm::dot(d, f);
    // Perspective: |x| <= (distance + z) tan_x; orthographic: |x| <= distance tan_x.
    needed = std::max({needed, x / tan_x - z, y / tan_y - z, x / tan_x, y / tan_y});
  }
  distance = std::max(kFrameMargin * needed, 1.01 * radius);
}

void OrbitCamera::orbit(double dx, double dy) {
  yaw = std::remainder(yaw - dx * kOrbitRadiansPerPixel, 2.0 * std::numbers::pi);
  pitch = std::clamp(pitch + dy * kOrbitRadiansPerPixel, -kHalfPi, kHalfPi);
}

double OrbitCamera::world_per_pixel() const {
  return 2.0 * distance * std::tan(fov_y / 2.0) / static_cast<double>(viewport_height);
}

void OrbitCamera::pan(double dx, double dy) {
  const double scale = world_per_pixel();
  target += (-dx * scale) * right() + (dy * scale) * up();
}

void OrbitCamera::zoom(double steps) {
  distance = std::max(distance / std::pow(kZoomFactorPerStep, steps), 1e-6 * scene_radius);
}

void OrbitCamera::set_view(ViewPreset preset) {
  constexpr double pi = std::numbers::pi;
  switch (preset) {
    case ViewPreset::Front: yaw = 0.0; pitch = 0.0; break;
    case ViewPreset::Back: yaw = pi; pitch = 0.0; break;
    case ViewPreset::Right: yaw = kHalfPi; pitch = 0.0; break;
    case ViewPreset::Left: yaw = -kHalfPi; pitch = 0.0; break;
    case ViewPreset::Top: yaw = 0.0; pitch = kHalfPi; break;
    case ViewPreset::Bottom: yaw = 0.0; pitch = -kHalfPi; break;
    case ViewPreset::ThreeQuarter: yaw = 35.0 * pi / 180.0; pitch = 25.0 * pi / 180.0; break;
  }
}

}  // namespace sublift
