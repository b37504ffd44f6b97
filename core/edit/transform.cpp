#include "core/edit/transform.h"

#include <cmath>

#include <glm/geometric.hpp>

#include "core/base/errors.h"

namespace sublift {

const char* pivot_name(Pivot p) {
  switch (p) {
    case Pivot::Median: return "median";
    case Pivot::Active: return "active";
    case Pivot::Cursor: return "cursor";
    case Pivot::Origin: return "origin";
  }
  return "median";
}

Pivot parse_pivot(const std::string& name) {
  for (const Pivot p : {Pivot::Median, Pivot::Active, Pivot::Cursor, Pivot::Origin})
    if (name == pivot_name(p)) return p;
  throw Error("unknown pivot '" + name + "' (median, active, cursor or origin)");
}

glm::dvec3 pivot_point(Pivot p, std::span<const double> positions, std::span<const unsigned> selection, long long active,
                       const glm::dvec3& cursor) {
  const std::size_t n = positions.size() / 3;
  if (p == Pivot::Origin) return glm::dvec3(0.0);
  if (p == Pivot::Cursor) return cursor;
  if (p == Pivot::Active && active >= 0 && static_cast<std::size_t>(active) < n) {
    const double* a = &positions[3 * static_cast<std::size_t>(active)];
    return {a[0], a[1], a[2]};
  }
  glm::dvec3 sum(0.0);
  std::size_t count = 0;
  for (const unsigned v : selection) {
    if (v >= n) continue;
    sum += glm::dvec3(positions[3 * std::size_t(v)], positions[3 * std::size_t(v) + 1], positions[3 * std::size_t(v) + 2]);
    ++count;
  }
  return count ? sum / static_cast<double>(count) : glm::dvec3(0.0);
}

glm::dvec3 scale_factors(double s, int axis, bool exclude) {
  if (axis < 0 || axis > 2) return glm::dvec3(s);
  glm::dvec3 f(exclude ? s : 1.0);
  f[axis] = exclude ? 1.0 : s;
  return f;
}

namespace {

// Rodrigues' rotation of r about the unit axis k.
glm::dvec3 rotate(const glm::dvec3& r, const glm::dvec3& k, double angle) {
  if (angle == 0.0) return r;
  const double c = std::cos(angle), s = std::sin(angle);
  return r * c + glm::cross(k, r) * s + k * (glm::dot(k, r) * (1.0 - c));
}

}  // namespace

void transform_deltas(std::span<const double> start, std::span<const double> current,
                      std::span<const std::uint32_t> vertices, std::span<const double> weights, const glm::dvec3& pivot,
                      const glm::dvec3& axis, double angle, const glm::dvec3& factors, std::vector<double>& out) {
  out.assign(3 * vertices.size(), 0.0);
  const double len = glm::length(axis);
  const glm::dvec3 k = len > 0.0 ? axis / len : glm::dvec3(0.0, 0.0, 1.0);
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    const std::size_t v = vertices[i];
    const double w = weights.empty() ? 1.0 : weights[i];
    const glm::dvec3 p0(start[3 * i], start[3 * i + 1], start[3 * i + 2]);
    glm::dvec3 r = rotate(p0 - pivot, k, w * angle);
    r *= glm::dvec3(1.0) + w * (factors - glm::dvec3(1.0));
    const glm::dvec3 target = pivot + r;
    for (int c = 0; c < 3; ++c) out[3 * i + c] = target[c] - current[3 * v + c];
  }
}

}  // namespace sublift
