#pragma once
// Screen-space picking of control points: pure math, no GL (STYLE.md: "picking is a core
// function"), so ui/ and tests use it without a context.
//
// Conventions. A PickView is the camera's projection * view matrix (OpenGL clip space, NDC depth
// in [-1, 1]) and the viewport size. Screen positions are in pixels with the origin at the
// top-left corner, x right and y down, as ImGui and GLFW report the mouse; a pixel (i, j) covers
// [i, i+1) x [j, j+1). "Linear depth" below is the distance along the view axis (the direction
// through the image centre), in world units: what the eye would call its depth.
//
// PickIndex rationale. With millions of points, projecting all of them on every mouse move is
// too slow; instead build() projects them once into a uniform grid of 8-pixel cells (CSR: cell
// offsets + entries sorted by cell), so nearest() and in_rect() only visit the cells the query
// touches. Rebuild when the camera, the viewport or the positions change; during a drag the
// dragged points move with the mouse, so the index can be rebuilt once the drag ends.
//
// X-ray versus front-most. Points cannot be occluded by the CPU alone, so with xray == false a
// pick is restricted in two ways:
//   1. if build() received the surface's depth buffer (OcclusionDepth), points behind the
//      surface are hidden (they are not drawn either, unless the net is drawn in x-ray);
//   2. among the remaining candidates within the pick radius, only the front-most cluster
//      counts: points whose linear depth is at most the nearest candidate's depth plus the pick
//      radius measured in world units at that depth (the pick disc turned into a ball). So a
//      click on a lattice corner takes the front layer, not a point further back that happens
//      to project a pixel closer to the mouse.
// With xray == true every visible (mask) point counts. in_rect() applies rule 1 only.
#include <cstdint>
#include <span>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace sublift {

/// Camera and viewport for picking: view_proj = projection * view (OpenGL conventions).
struct PickView {
  glm::dmat4 view_proj{1.0};
  int width = 1, height = 1;  // pixels, origin top-left (ImGui/GLFW mouse coordinates)
};

/// Depth of the drawn surface, to hide points behind it in non-x-ray picks. `window_depth`
/// holds width * height values of the PickView, in [0, 1] (glDepthRange default), rows
/// bottom-up as glReadPixels(GL_DEPTH_COMPONENT, GL_FLOAT) returns them; 1 where nothing is
/// drawn. A point is hidden when its window depth exceeds the largest surface depth of the 3x3
/// pixels around it by more than `tolerance` (lenient at silhouettes and for points on the
/// surface).
struct OcclusionDepth {
  std::span<const float> window_depth;
  double tolerance = 1e-4;
};

/// Screen position (x right, y down, pixels) and NDC depth of a world point; false if behind
/// the camera (clip w <= 0) or outside the clip volume. `screen` and `depth` are set whenever
/// w > 0, even when the point is outside.
bool project_point(const PickView& v, const glm::dvec3& p, glm::dvec2& screen, double& depth);

/// World point at screen position (mx, my) and NDC depth `ndc_z` (the inverse of project_point).
glm::dvec3 unproject_point(const PickView& v, double mx, double my, double ndc_z);

/// Ray through the pixel position (mx, my): origin on the near plane, unit direction away from
/// the eye (parallel rays for orthographic views).
void pixel_ray(const PickView& v, double mx, double my, glm::dvec3& origin, glm::dvec3& dir);

/// World-space translation, parallel to the image plane, that moves a point at `anchor` by
/// (dx, dy) pixels on screen (y down). Zero when the anchor is behind the camera.
glm::dvec3 view_plane_delta(const PickView& v, const glm::dvec3& anchor, double dx, double dy);

/// Screen-space grid of projected points for picking; see the rationale at the top.
class PickIndex {
 public:
  static constexpr int kCellPixels = 8;

  /// Projects the points (3 doubles each) into the grid. Points behind the camera, outside the
  /// viewport or the depth range, or with visible[i] == 0 (when `visible` is not empty, it has
  /// one entry per point) are left out. `occlusion`, when given, marks points behind the
  /// surface as hidden. Runs in parallel; O(points + cells).
  void build(const PickView& v, std::span<const double> xyz, std::span<const std::uint8_t> visible = {},
             const OcclusionDepth* occlusion = nullptr);

  /// Index of the point nearest to (mx, my) within `radius_px` pixels (Euclidean); ties by
  /// smaller depth, then smaller index. With !xray, hidden points are skipped and only the
  /// front-most cluster is considered. -1 when there is none.
  std::int64_t nearest(double mx, double my, double radius_px, bool xray) const;

  /// Indices (ascending) of the points inside the rectangle spanned by the two corners (edges
  /// included, corners in any order); with !xray hidden points are left out.
  std::vector<std::uint32_t> in_rect(double x0, double y0, double x1, double y1, bool xray) const;

  /// Indices (ascending) of the points within `radius` pixels of (cx, cy) (circle select); with
  /// !xray hidden points are left out.
  std::vector<std::uint32_t> in_circle(double cx, double cy, double radius, bool xray) const;

  /// Number of points in the index (projected into the viewport and visible).
  std::size_t size() const { return entries_.size(); }
  /// Number of indexed points marked hidden by the occlusion depth.
  std::size_t hidden_count() const { return hidden_count_; }

 private:
  struct Entry {
    float x, y;          // screen pixels
    float depth;         // linear depth relative to the near plane, world units
    std::uint32_t code;  // point index | kHiddenBit
  };
  static constexpr std::uint32_t kHiddenBit = 0x80000000u;

  double world_per_pixel(double depth) const { return wpp0_ + wpp_slope_ * depth; }
  // The points in the rectangle (hidden ones only with xray) for which keep(entry) holds, ascending.
  template <class Keep>
  std::vector<std::uint32_t> in_box(double x0, double y0, double x1, double y1, bool xray, Keep keep) const;

  PickView view_;
  int grid_w_ = 0, grid_h_ = 0;
  std::vector<std::uint32_t> cell_start_;  // grid_w_ * grid_h_ + 1 offsets into entries_
  std::vector<Entry> entries_;
  std::size_t hidden_count_ = 0;
  double wpp0_ = 0.0, wpp_slope_ = 0.0;  // world size of a pixel at linear depth d: wpp0 + slope d
};

}  // namespace sublift
