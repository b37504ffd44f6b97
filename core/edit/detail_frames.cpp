#include "core/edit/detail_frames.h"

#include <algorithm>
#include <cmath>

#include "core/complex/polygon_normal.h"

namespace sublift {
namespace {

struct V3 {
  double x = 0, y = 0, z = 0;
};
V3 sub(const V3& a, const V3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
V3 add(const V3& a, const V3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
V3 scale(const V3& a, double s) { return {a.x * s, a.y * s, a.z * s}; }
double dot(const V3& a, const V3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
V3 cross(const V3& a, const V3& b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
V3 at(const double* p, std::uint32_t v) { return {p[3 * std::size_t(v)], p[3 * std::size_t(v) + 1], p[3 * std::size_t(v) + 2]}; }

// Relative to the element's size, below this a direction is degenerate.
constexpr double kTiny = 1e-12;

bool normalize(V3& v, double ref) {
  const double n = std::sqrt(dot(v, v));
  if (!(n > kTiny * ref)) return false;
  v = scale(v, 1.0 / n);
  return true;
}

// The face's area vector (core/complex/polygon_normal.h) and its longest edge, the size that says
// when the normal is degenerate.
V3 newell(const Complex& c, const double* p, std::uint32_t f, double& size) {
  const auto row = c.faces.row(f);
  size = 0;
  for (std::size_t i = 0; i < row.size(); ++i) {
    const V3 e = sub(at(p, row[(i + 1) % row.size()]), at(p, row[i]));
    size = std::max(size, std::sqrt(dot(e, e)));
  }
  double n[3];
  polygon_area_vector(row, p, n);
  return {n[0], n[1], n[2]};
}

void set_identity(double f[9]) {
  for (int i = 0; i < 9; ++i) f[i] = (i % 4 == 0) ? 1.0 : 0.0;
}

void store(double f[9], const V3& t, const V3& b, const V3& n) {
  f[0] = t.x, f[1] = t.y, f[2] = t.z;
  f[3] = b.x, f[4] = b.y, f[5] = b.z;
  f[6] = n.x, f[7] = n.y, f[8] = n.z;
}

}  // namespace

void wavelet_frame(const Complex& c, const double* p, std::uint32_t child, double f[9], const ChildSites* sites) {
  const std::uint32_t nv = c.num_vertices, ne = c.num_edges();
  if (sites) {  // map the child to the 1-to-4 index of its site
    if (child < nv || child - nv >= sites->site.size()) return set_identity(f);
    child = nv + sites->site[child - nv];
  }
  if (child >= nv && child < nv + ne) {
    const std::uint32_t e = child - nv;
    const V3 a = at(p, c.edge_verts[2 * std::size_t(e)]), b = at(p, c.edge_verts[2 * std::size_t(e) + 1]);
    V3 t = sub(b, a);
    const double len = std::sqrt(dot(t, t));
    if (!normalize(t, 1.0) || len == 0.0) return set_identity(f);
    V3 n;
    for (const std::uint32_t face : c.edge_faces.row(e)) {
      double size;
      V3 fn = newell(c, p, face, size);
      if (normalize(fn, size * size)) n = add(n, fn);
    }
    n = sub(n, scale(t, dot(n, t)));
    if (!normalize(n, 1.0)) return set_identity(f);
    store(f, t, cross(n, t), n);
    return;
  }
  if (child >= nv + ne && child < nv + ne + c.num_faces()) {
    const std::uint32_t face = child - nv - ne;
    double size;
    V3 n = newell(c, p, face, size);
    if (!normalize(n, size * size)) return set_identity(f);
    const auto row = c.faces.row(face);
    V3 t = sub(at(p, row[1]), at(p, row[0]));
    t = sub(t, scale(n, dot(n, t)));
    if (!normalize(t, size)) return set_identity(f);
    store(f, t, cross(n, t), n);
    return;
  }
  set_identity(f);
}

void frames_reading(const Complex& c, std::span<const std::uint32_t> changed, std::vector<std::uint32_t>& out,
                    std::vector<std::uint32_t>& stamp, std::uint32_t epoch, const ChildSites* sites) {
  const std::uint32_t nv = c.num_vertices, ne = c.num_edges();
  auto add_child = [&](std::uint32_t u) {
    if (sites) {  // u is the 1-to-4 index of a site: its sqrt(2) child, if it has one
      u = u < nv + ne ? sites->edge_child[u - nv] : sites->face_child[u - nv - ne];
      if (u == UINT32_MAX) return;
    }
    if (stamp[u] != epoch) {
      stamp[u] = epoch;
      out.push_back(u);
    }
  };
  for (const std::uint32_t v : changed) {
    if (v >= nv) continue;
    for (const std::uint32_t e : c.vertex_edges.row(v)) add_child(nv + e);
    for (const std::uint32_t face : c.vertex_faces.row(v)) {
      add_child(nv + ne + face);
      // Edge frames read the normals of their faces.
      for (const std::uint32_t e : c.face_edges.row(face)) add_child(nv + e);
    }
  }
}

}  // namespace sublift
