// sublift-cli basis --png: the basis function as a coloured picture (see cli_basis_png.h).
#ifdef SUBLIFT_HAVE_RENDER
#include "app/cli/cli_basis_png.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "core/analysis/boundary_surface.h"
#include "core/complex/polygon_normal.h"
#include "render/background.h"
#include "render/camera.h"
#include "render/headless_context.h"
#include "render/limit_surface_renderer.h"
#include "render/offscreen_target.h"
#include "render/viewport_renderer.h"

namespace sublift::cli {
namespace {

constexpr double kDegree = 0.017453292519943295;

// A drawable: CSR faces over its own vertex arrays.
struct Drawn {
  std::vector<std::uint32_t> offsets{0}, corners;
  std::vector<double> xyz, normals;
  std::vector<float> scalar;
  void add_face(std::span<const std::uint32_t> f) {
    corners.insert(corners.end(), f.begin(), f.end());
    offsets.push_back(static_cast<std::uint32_t>(corners.size()));
  }
};

glm::dvec3 at(std::span<const double> a, std::size_t v) { return {a[3 * v], a[3 * v + 1], a[3 * v + 2]}; }
void put(std::vector<double>& a, const glm::dvec3& p) { a.insert(a.end(), {p.x, p.y, p.z}); }

std::vector<float> to_unit(std::span<const double> values, bool symmetric) {
  double lo = 0, hi = 0;
  for (double v : values) lo = std::min(lo, v), hi = std::max(hi, v);
  if (symmetric) hi = std::max(hi, -lo), lo = -hi;
  const double span = hi > lo ? hi - lo : 1.0;
  std::vector<float> s;
  for (double v : values) s.push_back(static_cast<float>((v - lo) / span));
  return s;
}

// Area-weighted unit vertex normals (core/complex/polygon_normal.h) as vectors.
std::vector<glm::dvec3> vertex_normals(const Csr& faces, std::span<const double> xyz) {
  const std::vector<double> flat = area_weighted_normals(faces, xyz);
  std::vector<glm::dvec3> n(flat.size() / 3);
  for (std::size_t v = 0; v < n.size(); ++v) n[v] = glm::dvec3(flat[3 * v], flat[3 * v + 1], flat[3 * v + 2]);
  return n;
}

// Rows of a rotation taking unit `up` to +Y (a proper rotation; +Z up maps +X to +X).
struct Frame {
  glm::dvec3 x, y, z;
  glm::dvec3 operator()(const glm::dvec3& p) const { return {glm::dot(p, x), glm::dot(p, y), glm::dot(p, z)}; }
};
Frame frame_up(glm::dvec3 up) {
  if (glm::length(up) == 0) up = glm::dvec3(0, 0, 1);
  up = glm::normalize(up);
  const glm::dvec3 ref = std::abs(up.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(0, 0, -1);
  const glm::dvec3 x = glm::normalize(glm::cross(ref, up));
  return {x, up, glm::cross(x, up)};
}

Bounds bounds_of(std::span<const double> xyz, std::span<const std::uint32_t> only = {}) {
  Bounds b;
  auto grow = [&](std::size_t v) {
    const glm::dvec3 p = at(xyz, v);
    b.min = b.empty ? p : glm::min(b.min, p);
    b.max = b.empty ? p : glm::max(b.max, p);
    b.empty = false;
  };
  if (only.empty())
    for (std::size_t v = 0; v < xyz.size() / 3; ++v) grow(v);
  else
    for (std::uint32_t v : only) grow(v);
  return b;
}

double peak_abs(std::span<const double> values) {
  double m = 0;
  for (double v : values) m = std::max(m, std::abs(v));
  return m;
}

// Surface: displaced, turned so the support's mean normal is up, cropped to support + margin.
Drawn surface_scene(const BasisFunction& b, std::span<const double> xyz, bool symmetric) {
  const std::vector<glm::dvec3> n = vertex_normals(b.finest.faces, xyz);
  const double peak = peak_abs(b.values);
  std::vector<std::uint32_t> big;  // where |value| is at least 2% of the peak: framed
  for (std::uint32_t v : b.support)
    if (std::abs(b.values[v]) >= 0.02 * peak) big.push_back(v);
  const Bounds sb = bounds_of(xyz, big);
  const double diag = sb.empty ? 1.0 : glm::length(sb.max - sb.min);
  const double scale = peak > 0 ? 0.3 * diag / peak : 0.0;
  glm::dvec3 up(0.0);
  for (std::uint32_t v : b.support) up += std::abs(b.values[v]) * n[v];
  const Frame r = frame_up(up);
  Drawn d;
  for (std::size_t v = 0; v < n.size(); ++v) {
    put(d.xyz, r(at(xyz, v) + scale * b.values[v] * n[v]));
    put(d.normals, r(n[v]));
  }
  Bounds box = bounds_of(d.xyz, big);
  if (box.empty) box = bounds_of(d.xyz);
  const glm::dvec3 margin(0.15 * glm::length(box.max - box.min));
  box.min -= margin, box.max += margin;
  auto inside = [&](std::uint32_t v) {
    const glm::dvec3 p = at(d.xyz, v);
    return glm::all(glm::greaterThanEqual(p, box.min)) && glm::all(glm::lessThanEqual(p, box.max));
  };
  for (std::size_t f = 0; f < b.finest.faces.rows(); ++f) {
    const auto row = b.finest.faces.row(f);
    if (std::any_of(row.begin(), row.end(), inside)) d.add_face(row);
  }
  d.scalar = to_unit(b.values, symmetric);
  return d;
}

// Curve: the displaced curve and the curve itself as ribbons facing the view direction `fwd`
// (in the turned frame), one quad per edge.
Drawn curve_scene(const BasisFunction& b, std::span<const double> xyz, bool symmetric, const glm::dvec3& fwd) {
  const Bounds all = bounds_of(xyz);
  const double diag = all.empty ? 1.0 : glm::length(all.max - all.min);
  const double peak = peak_abs(b.values), scale = peak > 0 ? 0.2 * diag / peak : 0.0;
  const Frame r = frame_up(glm::dvec3(0, 0, 1));
  const std::vector<float> s = to_unit(b.values, symmetric);
  const float zero = to_unit(std::vector<double>{b.min, b.max, 0.0}, symmetric)[2];
  Drawn d;
  auto ribbon = [&](double lift, double half_width, bool colour) {
    for (std::uint32_t e = 0; e < b.finest.num_edges(); ++e) {
      const std::uint32_t ends[2] = {b.finest.edge_verts[2 * e], b.finest.edge_verts[2 * e + 1]};
      glm::dvec3 p[2];
      for (int i = 0; i < 2; ++i) p[i] = r(at(xyz, ends[i]) + glm::dvec3(0, 0, lift * scale * b.values[ends[i]]));
      glm::dvec3 side = glm::cross(p[1] - p[0], fwd);
      if (glm::length(side) == 0) continue;
      side = half_width * glm::normalize(side);
      const std::uint32_t base = static_cast<std::uint32_t>(d.scalar.size());
      const glm::dvec3 q[4] = {p[0] - side, p[1] - side, p[1] + side, p[0] + side};
      const std::uint32_t w[4] = {ends[0], ends[1], ends[1], ends[0]};
      for (int i = 0; i < 4; ++i) {
        put(d.xyz, q[i]);
        put(d.normals, -fwd);
        d.scalar.push_back(colour ? s[w[i]] : zero);
      }
      const std::uint32_t quad[4] = {base, base + 1, base + 2, base + 3};
      d.add_face(quad);
    }
  };
  ribbon(0.0, 0.002 * diag, false);
  ribbon(1.0, 0.005 * diag, true);
  return d;
}

// Lattice: its boundary (drawn clipped to z <= zp) and the finest faces on the plane z = zp.
void lattice_scenes(const BasisFunction& b, std::span<const double> xyz, bool symmetric, Drawn& boundary, Drawn& slice,
                    double& zp) {
  std::size_t top = 0;
  for (std::size_t v = 0; v < b.values.size(); ++v)
    if (std::abs(b.values[v]) > std::abs(b.values[top])) top = v;
  zp = xyz[3 * top + 2];
  const Csr outer = boundary_faces(b.finest, xyz);
  const std::vector<glm::dvec3> n = vertex_normals(outer, xyz);
  boundary.xyz.assign(xyz.begin(), xyz.end());
  slice.xyz = boundary.xyz;
  for (const glm::dvec3& d : n) put(boundary.normals, d), put(slice.normals, glm::dvec3(0, 0, 1));
  for (std::size_t f = 0; f < outer.rows(); ++f) boundary.add_face(outer.row(f));
  const Csr& faces = b.finest.faces;
  for (std::size_t f = 0; f < faces.rows(); ++f) {
    const auto row = faces.row(f);
    if (std::all_of(row.begin(), row.end(), [&](std::uint32_t v) { return std::abs(xyz[3 * v + 2] - zp) <= 1e-9; }))
      slice.add_face(row);
  }
  boundary.scalar = slice.scalar = to_unit(b.values, symmetric);
}

void upload(LimitSurfaceRenderer& r, const Drawn& d) {
  r.set_topology(d.offsets, d.corners, d.xyz.size() / 3);
  r.set_positions_normals(d.xyz, d.normals);
  r.set_scalar(d.scalar);
}

OrbitCamera camera_for(int width, int height, double yaw_deg, double pitch_deg) {
  OrbitCamera c;
  c.set_viewport(width, height);
  c.yaw = yaw_deg * kDegree;
  c.pitch = pitch_deg * kDegree;
  return c;
}

Bounds drawn_bounds_of(const Drawn& d) { return bounds_of(d.xyz, d.corners); }

}  // namespace

void write_basis_png(const std::string& path, const BasisFunction& b, std::span<const double> xyz, bool symmetric,
                     int width, int height) {
  HeadlessContext context;
  OffscreenTarget target(width, height, 4);
  LimitSurfaceRenderer first, second;
  SurfaceStyle style;
  style.color_map = true;
  OrbitCamera camera = camera_for(width, height, 30, 35);
  bool two = false;
  SurfaceStyle second_style = style;
  if (b.finest.dim == 2) {
    const Drawn d = surface_scene(b, xyz, symmetric);
    upload(first, d);
    frame_bounds(camera, drawn_bounds_of(d));
  } else if (b.finest.dim == 1) {
    camera = camera_for(width, height, 0, 30);
    const Drawn d = curve_scene(b, xyz, symmetric, camera.forward());
    upload(first, d);
    frame_bounds(camera, drawn_bounds_of(d));
  } else {
    Drawn boundary, slice;
    double zp = 0;
    lattice_scenes(b, xyz, symmetric, boundary, slice, zp);
    camera = camera_for(width, height, 35, 30);
    const Bounds all = bounds_of(xyz);
    style.clip = true;
    style.clip_plane = glm::vec4(0, 0, -1, static_cast<float>(zp + 1e-6 * glm::length(all.max - all.min)));
    upload(first, boundary);
    upload(second, slice);
    two = true;
    camera.up_axis = UpAxis::Y;
    frame_bounds(camera, all);
  }
  target.bind();
  clear_framebuffer(width, height, BackgroundRenderer::kBottomColor);
  BackgroundRenderer background;
  background.draw();
  first.draw(camera, style);
  if (two) second.draw(camera, second_style);
  write_png(path, width, height, target.read_rgba());
}

}  // namespace sublift::cli
#endif
