#pragma once
// Points of flat position arrays (3 doubles per vertex) as glm vectors.
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

namespace sublift {

inline glm::dvec3 at(std::span<const double> x, std::uint32_t v) {
  return {x[3 * std::size_t(v)], x[3 * std::size_t(v) + 1], x[3 * std::size_t(v) + 2]};
}

inline void put(std::vector<double>& x, std::uint32_t v, const glm::dvec3& p) {
  for (int k = 0; k < 3; ++k) x[3 * std::size_t(v) + k] = p[k];
}

}  // namespace sublift
