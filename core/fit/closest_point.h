#pragma once
// Closest points on a triangle mesh (fitting attracts each level to the input, and measures the
// distance both ways): a bounding-volume hierarchy over the triangles, split at the median of
// the longest axis, queried depth first with boxes pruned by their distance.
#include <cstdint>
#include <span>
#include <vector>

#include "core/base/csr.h"

namespace sublift {

class TriangleIndex {
 public:
  /// `faces`: triangles (other polygons are fanned) over `positions` (3 per vertex), both kept
  /// by reference: they must outlive the index.
  TriangleIndex(std::span<const double> positions, const Csr& faces);

  struct Hit {
    double point[3] = {0, 0, 0};
    double distance = 0;
    std::uint32_t triangle = 0;  // index into the fanned triangles
  };
  Hit closest(const double p[3]) const;
  /// Unit normal of fanned triangle t (zero when degenerate).
  void normal(std::uint32_t t, double n[3]) const;

 private:
  struct Node {
    double lo[3], hi[3];
    std::uint32_t first, count;  // leaves: triangles [first, first + count) of order_; else children first, first+1
    bool leaf;
  };
  void build(std::uint32_t node, std::uint32_t begin, std::uint32_t end);
  std::span<const double> p_;
  std::vector<std::uint32_t> tri_;    // 3 vertex indices per triangle
  std::vector<std::uint32_t> order_;  // triangles in leaf order
  std::vector<double> centre_;
  std::vector<Node> nodes_;
};

}  // namespace sublift
