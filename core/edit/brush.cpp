#include "core/edit/brush.h"

#include <algorithm>
#include <cmath>
#include <mutex>

#include <glm/geometric.hpp>

#include "core/base/errors.h"
#include "core/base/parallel.h"
#include "core/base/points.h"
#include "core/complex/polygon_normal.h"

namespace sublift {
namespace {

constexpr BrushKind kKinds[] = {BrushKind::Draw, BrushKind::Inflate, BrushKind::Smooth,
                                BrushKind::Grab, BrushKind::Flatten, BrushKind::Pinch};
constexpr Falloff kFalloffs[] = {Falloff::Smooth, Falloff::Linear, Falloff::Sharp, Falloff::Constant};

}  // namespace

const char* brush_name(BrushKind k) {
  switch (k) {
    case BrushKind::Draw: return "draw";
    case BrushKind::Inflate: return "inflate";
    case BrushKind::Smooth: return "smooth";
    case BrushKind::Grab: return "grab";
    case BrushKind::Flatten: return "flatten";
    case BrushKind::Pinch: return "pinch";
  }
  return "draw";
}

BrushKind parse_brush(const std::string& name) {
  for (const BrushKind k : kKinds)
    if (name == brush_name(k)) return k;
  throw Error("unknown brush '" + name + "' (draw, inflate, smooth, grab, flatten or pinch)");
}

const char* falloff_name(Falloff f) {
  switch (f) {
    case Falloff::Smooth: return "smooth";
    case Falloff::Linear: return "linear";
    case Falloff::Sharp: return "sharp";
    case Falloff::Constant: return "constant";
  }
  return "smooth";
}

Falloff parse_falloff(const std::string& name) {
  for (const Falloff f : kFalloffs)
    if (name == falloff_name(f)) return f;
  throw Error("unknown falloff '" + name + "' (smooth, linear, sharp or constant)");
}

double falloff_weight(Falloff f, double t) {
  if (!(t < 1.0)) return 0.0;
  t = std::max(t, 0.0);
  switch (f) {
    case Falloff::Smooth: return 1.0 - t * t * (3.0 - 2.0 * t);
    case Falloff::Linear: return 1.0 - t;
    case Falloff::Sharp: return (1.0 - t) * (1.0 - t);
    case Falloff::Constant: return 1.0;
  }
  return 0.0;
}

bool brush_needs_normals(BrushKind k) {
  return k == BrushKind::Draw || k == BrushKind::Inflate || k == BrushKind::Flatten;
}

void brush_dab(const BrushSettings& b, const Dab& dab, const Complex& c, std::span<const double> positions,
               std::vector<std::uint32_t>& vertices, std::vector<double>& deltas) {
  if (!(b.radius > 0.0) || !std::isfinite(b.radius)) throw Error("the brush radius must be a positive distance");
  if (!(b.strength >= 0.0 && b.strength <= 1.0)) throw Error("the brush strength must be in 0..1");
  const std::size_t n = positions.size() / 3;
  if (c.num_vertices != n || c.vertex_edges.rows() != n) throw Error("internal: the brush needs the level's adjacency");
  const bool have_normals = c.dim == 2 && c.vertex_faces.rows() == n;
  if (brush_needs_normals(b.kind) && !have_normals)
    throw Error(std::string("the ") + brush_name(b.kind) + " brush moves along the surface normal and needs a surface");
  vertices.clear();
  deltas.clear();
  const double r2 = b.radius * b.radius;
  std::vector<double> w, normals;  // normals: 3 per entry of `vertices`
  for (std::size_t v = 0; v < n; ++v) {
    const glm::dvec3 d = at(positions, v) - dab.center;
    const double d2 = glm::dot(d, d);
    if (d2 >= r2) continue;
    glm::dvec3 nv(0.0);
    if (have_normals) {
      for (const std::uint32_t f : c.vertex_faces.row(v)) {
        double a[3];
        polygon_area_vector(c.faces.row(f), positions.data(), a);
        nv += glm::dvec3(a[0], a[1], a[2]);
      }
      if (glm::length(nv) > 0.0) nv = glm::normalize(nv);
      if (b.front_faces_only && glm::dot(nv, dab.view_dir) > 0.0) continue;
    }
    const double weight = b.strength * falloff_weight(b.falloff, std::sqrt(d2) / b.radius);
    if (weight <= 0.0) continue;
    vertices.push_back(static_cast<std::uint32_t>(v));
    w.push_back(weight);
    normals.insert(normals.end(), {nv.x, nv.y, nv.z});
  }
  if (vertices.empty()) return;
  // The area's mean point and normal (Draw, Flatten).
  glm::dvec3 mean(0.0), normal(0.0);
  for (std::size_t k = 0; k < vertices.size(); ++k) {
    mean += at(positions, vertices[k]);
    normal += at(normals, k);
  }
  mean /= static_cast<double>(vertices.size());
  if (glm::length(normal) > 0.0) normal = glm::normalize(normal);
  const double sign = b.invert ? -1.0 : 1.0;
  deltas.resize(3 * vertices.size());
  for (std::size_t k = 0; k < vertices.size(); ++k) {
    const std::uint32_t v = vertices[k];
    const glm::dvec3 p = at(positions, v);
    glm::dvec3 d(0.0);
    switch (b.kind) {
      case BrushKind::Draw: d = normal * (sign * w[k] * 0.25 * b.radius); break;
      case BrushKind::Inflate: d = at(normals, k) * (sign * w[k] * 0.25 * b.radius); break;
      case BrushKind::Smooth: {
        const auto edges = c.vertex_edges.row(v);
        if (edges.empty()) break;
        glm::dvec3 avg(0.0);
        for (const std::uint32_t e : edges) avg += at(positions, edge_other_end(c, e, v));
        d = (avg / static_cast<double>(edges.size()) - p) * w[k];
        break;
      }
      case BrushKind::Grab: d = dab.motion * w[k]; break;
      case BrushKind::Flatten: {
        const double h = have_normals ? glm::dot(p - mean, normal) : 0.0;
        d = -normal * (sign * h * w[k]);
        break;
      }
      case BrushKind::Pinch: {
        glm::dvec3 to = dab.center - p;
        const glm::dvec3 nv = at(normals, k);
        to -= nv * glm::dot(to, nv);  // zero on curves and lattices: no projection
        d = to * (sign * 0.5 * w[k]);
        break;
      }
    }
    for (int i = 0; i < 3; ++i) deltas[3 * k + i] = d[i];
  }
}

std::vector<glm::dvec3> dab_centres_along(const glm::dvec3& from, const glm::dvec3& to, double spacing, std::size_t most) {
  std::vector<glm::dvec3> out;
  const double length = glm::length(to - from);
  if (!(spacing > 0.0) || !(length >= spacing)) return out;
  const auto n = std::min(static_cast<std::size_t>(length / spacing), most);
  for (std::size_t k = 1; k <= n; ++k) out.push_back(from + (to - from) * (double(k) * spacing / length));
  return out;
}

bool ray_hit(std::span<const double> positions, const Csr& faces, const glm::dvec3& origin, const glm::dvec3& dir,
             glm::dvec3& hit) {
  // Each chunk of faces keeps its nearest t; chunks run on the pool (a million faces: ~7 ms on
  // 2 cores, bench_edit BM_SurfaceRayHit).
  constexpr std::uint32_t kGrain = 8192;
  const auto nf = static_cast<std::uint32_t>(faces.rows());
  double best = INFINITY;
  std::mutex best_mutex;  // taken once per chunk
  parallel_for(nf, kGrain, [&](std::uint32_t begin, std::uint32_t end) {
    double t_best = INFINITY;
    for (std::uint32_t f = begin; f < end; ++f) {
      const auto corners = faces.row(f);
      if (corners.size() < 3) continue;
      const glm::dvec3 a = at(positions, corners[0]);
      for (std::size_t i = 1; i + 1 < corners.size(); ++i) {
        // Moller-Trumbore on the fan triangle (a, b, c).
        const glm::dvec3 e1 = at(positions, corners[i]) - a, e2 = at(positions, corners[i + 1]) - a;
        const glm::dvec3 pv = glm::cross(dir, e2);
        const double det = glm::dot(e1, pv);
        if (std::abs(det) < 1e-300) continue;
        const glm::dvec3 tv = origin - a;
        const double u = glm::dot(tv, pv) / det;
        if (u < 0.0 || u > 1.0) continue;
        const glm::dvec3 qv = glm::cross(tv, e1);
        const double vv = glm::dot(dir, qv) / det;
        if (vv < 0.0 || u + vv > 1.0) continue;
        const double t = glm::dot(e2, qv) / det;
        if (t > 0.0 && t < t_best) t_best = t;
      }
    }
    const std::lock_guard<std::mutex> lock(best_mutex);
    best = std::min(best, t_best);
  });
  const double t = best;
  if (!std::isfinite(t)) return false;
  hit = origin + dir * t;
  return true;
}

}  // namespace sublift
