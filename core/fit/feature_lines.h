#pragma once
// The input's feature lines (its sharp and boundary edges, as the base's decimation marks them,
// core/fit/base_mesh.h) as segments, with a closest-point query: fitting puts the net's crease
// vertices on them, so a fitted crease runs along the input's (issue 17, docs/fit.md).
// A uniform grid of cells about a segment long; a query searches shells of cells outwards and
// stops once no unsearched cell can hold a nearer point.
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

namespace sublift {

class FeatureLines {
 public:
  /// `edges`: 2 input vertex numbers per segment; `positions`: 3 per input vertex.
  FeatureLines(std::span<const double> positions, std::span<const std::uint32_t> edges);
  bool empty() const { return a_.empty(); }
  std::size_t size() const { return a_.size(); }
  /// The closest point of the lines to p (p itself when there are none).
  glm::dvec3 closest(const glm::dvec3& p) const;

 private:
  std::uint32_t cell_of(int x, int y, int z) const { return static_cast<std::uint32_t>(x + dims_[0] * (y + dims_[1] * z)); }
  std::vector<glm::dvec3> a_, b_;
  glm::dvec3 lo_{0.0};
  double cell_ = 1.0;
  int dims_[3] = {1, 1, 1};
  std::vector<std::uint32_t> offsets_, items_;  // segments per cell
};

}  // namespace sublift
