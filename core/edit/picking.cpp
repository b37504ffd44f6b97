#include "core/edit/picking.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>
#include <glm/vec4.hpp>

#include "core/base/errors.h"
#include "core/base/parallel.h"

namespace sublift {
namespace {

constexpr std::uint32_t kSkipped = std::numeric_limits<std::uint32_t>::max();

glm::dvec2 ndc_to_screen(const PickView& v, double nx, double ny) {
  return {(nx + 1.0) * 0.5 * v.width, (1.0 - ny) * 0.5 * v.height};
}

glm::dvec3 unproject_with(const glm::dmat4& inverse, const PickView& v, double mx, double my,
                          double ndc_z) {
  const glm::dvec4 ndc(2.0 * mx / v.width - 1.0, 1.0 - 2.0 * my / v.height, ndc_z, 1.0);
  const glm::dvec4 w = inverse * ndc;
  return glm::dvec3(w) / w.w;
}

}  // namespace

bool project_point(const PickView& v, const glm::dvec3& p, glm::dvec2& screen, double& depth) {
  const glm::dvec4 clip = v.view_proj * glm::dvec4(p, 1.0);
  if (!(clip.w > 0.0)) return false;
  const glm::dvec3 ndc = glm::dvec3(clip) / clip.w;
  screen = ndc_to_screen(v, ndc.x, ndc.y);
  depth = ndc.z;
  return std::abs(ndc.x) <= 1.0 && std::abs(ndc.y) <= 1.0 && std::abs(ndc.z) <= 1.0;
}

glm::dvec3 unproject_point(const PickView& v, double mx, double my, double ndc_z) {
  return unproject_with(glm::inverse(v.view_proj), v, mx, my, ndc_z);
}

void pixel_ray(const PickView& v, double mx, double my, glm::dvec3& origin, glm::dvec3& dir) {
  const glm::dmat4 inverse = glm::inverse(v.view_proj);
  origin = unproject_with(inverse, v, mx, my, -1.0);
  dir = glm::normalize(unproject_with(inverse, v, mx, my, 1.0) - origin);
}

glm::dvec3 view_plane_delta(const PickView& v, const glm::dvec3& anchor, double dx, double dy) {
  const glm::dvec4 clip = v.view_proj * glm::dvec4(anchor, 1.0);
  if (!(clip.w > 0.0)) return glm::dvec3(0.0);
  const glm::dvec3 ndc = glm::dvec3(clip) / clip.w;
  // Same NDC depth = same eye depth: the moved point stays in the view plane of the anchor.
  // The offset is unprojected as a difference of homogeneous points (linear in the offset), so
  // the anchor's large coordinates do not cancel.
  const glm::dmat4 inverse = glm::inverse(v.view_proj);
  const glm::dvec4 h0 = inverse * glm::dvec4(ndc, 1.0);
  const glm::dvec4 dh = inverse * glm::dvec4(2.0 * dx / v.width, -2.0 * dy / v.height, 0.0, 0.0);
  const glm::dvec4 h1 = h0 + dh;
  // p1 - p0 = h1.xyz/h1.w - h0.xyz/h0.w = (dh.xyz * h0.w - h0.xyz * dh.w) / (h0.w * h1.w)
  return (glm::dvec3(dh) * h0.w - glm::dvec3(h0) * dh.w) / (h0.w * h1.w);
}

void PickIndex::build(const PickView& v, std::span<const double> xyz,
                      std::span<const std::uint8_t> visible, const OcclusionDepth* occlusion) {
  if (v.width < 1 || v.height < 1) throw Error("PickIndex::build: empty viewport");
  if (xyz.size() % 3 != 0) throw Error("PickIndex::build: positions are not 3 per point");
  const std::size_t n = xyz.size() / 3;
  if (n >= kHiddenBit) throw Error("PickIndex::build: too many points");
  if (!visible.empty() && visible.size() != n) {
    throw Error("PickIndex::build: visibility mask size does not match the points");
  }
  const std::size_t pixels = static_cast<std::size_t>(v.width) * static_cast<std::size_t>(v.height);
  if (occlusion != nullptr && occlusion->window_depth.size() != pixels) {
    throw Error("PickIndex::build: occlusion depth is not width * height values");
  }
  view_ = v;
  grid_w_ = (v.width + kCellPixels - 1) / kCellPixels;
  grid_h_ = (v.height + kCellPixels - 1) / kCellPixels;

  // Linear depth: along the central ray, from its point on the near plane.
  const glm::dmat4 inverse = glm::inverse(v.view_proj);
  const double cx = 0.5 * v.width, cy = 0.5 * v.height;
  const glm::dvec3 near_center = unproject_with(inverse, v, cx, cy, -1.0);
  const glm::dvec3 far_center = unproject_with(inverse, v, cx, cy, 1.0);
  const glm::dvec3 forward = glm::normalize(far_center - near_center);
  const double depth_origin = glm::dot(near_center, forward);
  // Pixel size is affine in linear depth (constant for orthographic views).
  const double wpp_near = glm::distance(unproject_with(inverse, v, cx + 1.0, cy, -1.0), near_center);
  const double wpp_far = glm::distance(unproject_with(inverse, v, cx + 1.0, cy, 1.0), far_center);
  const double far_depth = glm::dot(far_center, forward) - depth_origin;
  wpp0_ = wpp_near;
  wpp_slope_ = far_depth > 0.0 ? (wpp_far - wpp_near) / far_depth : 0.0;

  std::vector<std::uint32_t> cell_of(n);
  std::vector<Entry> projected(n);
  const glm::dmat4 m = v.view_proj;
  const int w = v.width, h = v.height, gw = grid_w_;
  parallel_for(static_cast<std::uint32_t>(n), 16384, [&](std::uint32_t begin, std::uint32_t end) {
    for (std::uint32_t i = begin; i < end; ++i) {
      cell_of[i] = kSkipped;
      if (!visible.empty() && visible[i] == 0) continue;
      const glm::dvec3 p(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
      const glm::dvec4 clip = m * glm::dvec4(p, 1.0);
      if (!(clip.w > 0.0)) continue;
      const glm::dvec3 ndc = glm::dvec3(clip) / clip.w;
      if (!(std::abs(ndc.x) <= 1.0 && std::abs(ndc.y) <= 1.0 && std::abs(ndc.z) <= 1.0)) continue;
      const double sx = (ndc.x + 1.0) * 0.5 * w, sy = (1.0 - ndc.y) * 0.5 * h;
      const int px = std::min(static_cast<int>(sx), w - 1), py = std::min(static_cast<int>(sy), h - 1);
      std::uint32_t code = i;
      if (occlusion != nullptr) {
        const double point_depth = 0.5 * ndc.z + 0.5;
        float surface = 0.0f;
        const int gl_row = h - 1 - py;  // the depth rows are bottom-up
        for (int yy = std::max(gl_row - 1, 0); yy <= std::min(gl_row + 1, h - 1); ++yy) {
          for (int xx = std::max(px - 1, 0); xx <= std::min(px + 1, w - 1); ++xx) {
            surface = std::max(surface, occlusion->window_depth[static_cast<std::size_t>(yy) * w + xx]);
          }
        }
        if (point_depth > surface + occlusion->tolerance) code |= kHiddenBit;
      }
      projected[i] = {static_cast<float>(sx), static_cast<float>(sy),
                      static_cast<float>(glm::dot(p, forward) - depth_origin), code};
      cell_of[i] = static_cast<std::uint32_t>((py / kCellPixels) * gw + px / kCellPixels);
    }
  });

  // Counting sort by cell; entries of a cell keep ascending point order.
  cell_start_.assign(static_cast<std::size_t>(grid_w_) * grid_h_ + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    if (cell_of[i] != kSkipped) ++cell_start_[cell_of[i] + 1];
  }
  for (std::size_t c = 1; c < cell_start_.size(); ++c) cell_start_[c] += cell_start_[c - 1];
  entries_.resize(cell_start_.back());
  std::vector<std::uint32_t> fill(cell_start_.begin(), cell_start_.end() - 1);
  hidden_count_ = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (cell_of[i] == kSkipped) continue;
    entries_[fill[cell_of[i]]++] = projected[i];
    hidden_count_ += (projected[i].code & kHiddenBit) != 0;
  }
}

std::int64_t PickIndex::nearest(double mx, double my, double radius_px, bool xray) const {
  if (entries_.empty() || !(radius_px >= 0.0)) return -1;
  const int cx0 = std::max(static_cast<int>(std::floor((mx - radius_px) / kCellPixels)), 0);
  const int cy0 = std::max(static_cast<int>(std::floor((my - radius_px) / kCellPixels)), 0);
  const int cx1 = std::min(static_cast<int>(std::floor((mx + radius_px) / kCellPixels)), grid_w_ - 1);
  const int cy1 = std::min(static_cast<int>(std::floor((my + radius_px) / kCellPixels)), grid_h_ - 1);
  if (cx0 > cx1 || cy0 > cy1) return -1;
  const double r2 = radius_px * radius_px;

  struct Candidate {
    double d2, depth;
    std::uint32_t index;
  };
  std::vector<Candidate> candidates;
  double front = std::numeric_limits<double>::infinity();
  for (int cy = cy0; cy <= cy1; ++cy) {
    for (int cx = cx0; cx <= cx1; ++cx) {
      const std::size_t cell = static_cast<std::size_t>(cy) * grid_w_ + cx;
      for (std::uint32_t k = cell_start_[cell]; k < cell_start_[cell + 1]; ++k) {
        const Entry& e = entries_[k];
        if (!xray && (e.code & kHiddenBit) != 0) continue;
        const double ddx = e.x - mx, ddy = e.y - my;
        const double d2 = ddx * ddx + ddy * ddy;
        if (d2 > r2) continue;
        candidates.push_back({d2, e.depth, e.code & ~kHiddenBit});
        front = std::min(front, static_cast<double>(e.depth));
      }
    }
  }
  if (candidates.empty()) return -1;
  // The front-most cluster: within the pick radius (as a world distance) behind the nearest.
  const double depth_limit =
      xray ? std::numeric_limits<double>::infinity() : front + radius_px * world_per_pixel(front);
  const Candidate* best = nullptr;
  for (const Candidate& c : candidates) {
    if (c.depth > depth_limit) continue;
    if (best == nullptr || c.d2 < best->d2 ||
        (c.d2 == best->d2 && (c.depth < best->depth || (c.depth == best->depth && c.index < best->index)))) {
      best = &c;
    }
  }
  return best->index;
}

template <class Keep>
std::vector<std::uint32_t> PickIndex::in_box(double x0, double y0, double x1, double y1, bool xray, Keep keep) const {
  std::vector<std::uint32_t> out;
  if (entries_.empty()) return out;
  if (x0 > x1) std::swap(x0, x1);
  if (y0 > y1) std::swap(y0, y1);
  const int cx0 = std::max(static_cast<int>(std::floor(x0 / kCellPixels)), 0);
  const int cy0 = std::max(static_cast<int>(std::floor(y0 / kCellPixels)), 0);
  const int cx1 = std::min(static_cast<int>(std::floor(x1 / kCellPixels)), grid_w_ - 1);
  const int cy1 = std::min(static_cast<int>(std::floor(y1 / kCellPixels)), grid_h_ - 1);
  for (int cy = cy0; cy <= cy1; ++cy) {
    for (int cx = cx0; cx <= cx1; ++cx) {
      const std::size_t cell = static_cast<std::size_t>(cy) * grid_w_ + cx;
      for (std::uint32_t k = cell_start_[cell]; k < cell_start_[cell + 1]; ++k) {
        const Entry& e = entries_[k];
        if (!xray && (e.code & kHiddenBit) != 0) continue;
        if (e.x >= x0 && e.x <= x1 && e.y >= y0 && e.y <= y1 && keep(e)) out.push_back(e.code & ~kHiddenBit);
      }
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<std::uint32_t> PickIndex::in_rect(double x0, double y0, double x1, double y1, bool xray) const {
  return in_box(x0, y0, x1, y1, xray, [](const Entry&) { return true; });
}

std::vector<std::uint32_t> PickIndex::in_circle(double cx, double cy, double radius, bool xray) const {
  if (!(radius >= 0.0)) return {};
  const double r2 = radius * radius;
  return in_box(cx - radius, cy - radius, cx + radius, cy + radius, xray, [&](const Entry& e) {
    const double dx = e.x - cx, dy = e.y - cy;
    return dx * dx + dy * dy <= r2;
  });
}

}  // namespace sublift
