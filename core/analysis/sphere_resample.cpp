#include "core/analysis/sphere_resample.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include <glm/geometric.hpp>

#include "core/base/edge_key.h"
#include "core/complex/complex_build.h"
#include "core/base/errors.h"
#include "core/base/parallel.h"
#include "core/complex/refine_tri.h"

namespace sublift {
namespace {

// Relative volume below which a closed mesh is treated as flat (area centroid instead).
constexpr double kFlatVolume = 1e-10;

void check_levels(int levels) {
  if (levels < 0 || levels > kMaxSphereLevels)
    throw Error("sphere levels must be in 0.." + std::to_string(kMaxSphereLevels) + ", got " + std::to_string(levels));
}

// Calls f(a, b, c) for each fan triangle (corner 0, i, i+1) of every face.
template <class F>
void for_each_fan_triangle(const SurfaceMesh& mesh, F&& f) {
  for (std::size_t face = 0; face < mesh.num_faces(); ++face) {
    const auto c = mesh.face(face);
    for (std::size_t i = 1; i + 1 < c.size(); ++i) f(mesh.positions[c[0]], mesh.positions[c[i]], mesh.positions[c[i + 1]]);
  }
}

// Every polygon edge used as often in one direction as in the other: a closed surface whose
// signed volume does not depend on the origin.
bool edges_balanced(const SurfaceMesh& mesh) {
  std::vector<std::pair<std::uint64_t, int>> dir;  // undirected key, +1 (a < b) or -1
  dir.reserve(mesh.face_indices.size());
  for (std::size_t face = 0; face < mesh.num_faces(); ++face) {
    const auto c = mesh.face(face);
    for (std::size_t i = 0; i < c.size(); ++i) {
      const std::uint32_t a = c[i], b = c[(i + 1) % c.size()];
      dir.emplace_back(edge_key(a, b), a < b ? 1 : -1);
    }
  }
  std::sort(dir.begin(), dir.end());
  for (std::size_t i = 0; i < dir.size();) {
    int sum = 0;
    std::size_t j = i;
    for (; j < dir.size() && dir[j].first == dir[i].first; ++j) sum += dir[j].second;
    if (sum != 0) return false;
    i = j;
  }
  return true;
}

// Bounding box of the vertices that faces use.
std::pair<glm::dvec3, glm::dvec3> face_bounds(const SurfaceMesh& mesh) {
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (std::uint32_t v : mesh.face_indices) {
    lo = glm::min(lo, mesh.positions[v]);
    hi = glm::max(hi, mesh.positions[v]);
  }
  return {lo, hi};
}

}  // namespace

std::uint64_t sphere_vertex_count(int levels) {
  return 2 + (std::uint64_t{1} << (2 * (levels + 1)));  // V = 2 + F/2 with F = 8 * 4^levels
}

Complex octahedron_complex() {
  // 0 +x, 1 -x, 2 +y, 3 -y, 4 +z, 5 -z; the upper four around +z, the lower four around -z,
  // each counterclockwise seen from outside.
  static constexpr std::array<std::array<std::uint32_t, 3>, 8> kTris{{
      {0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}}};
  Csr faces;
  for (const auto& t : kTris) {
    faces.items.insert(faces.items.end(), t.begin(), t.end());
    faces.offsets.push_back(static_cast<std::uint32_t>(faces.items.size()));
  }
  return complex_from_polygons(6, faces);
}

GeodesicSphere geodesic_sphere(int levels) {
  check_levels(levels);
  GeodesicSphere s;
  s.base = octahedron_complex();
  s.directions = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  Complex level = s.base;
  for (int j = 1; j <= levels; ++j) {
    // refine_tri: midpoint of coarse edge e is vertex nv + e.
    const std::uint32_t nv = level.num_vertices, ne = level.num_edges();
    s.directions.resize(std::size_t(nv) + ne);
    for (std::uint32_t e = 0; e < ne; ++e)
      s.directions[nv + e] = glm::normalize(s.directions[level.edge_verts[2 * e]] + s.directions[level.edge_verts[2 * e + 1]]);
    level = refine_tri(level, /*adjacency=*/j == levels);
  }
  s.fine = std::move(level);
  return s;
}

const char* centroid_kind_name(CentroidKind kind) { return kind == CentroidKind::Volume ? "volume" : "area"; }

MeshCentroid mesh_centroid(const SurfaceMesh& mesh) {
  if (mesh.num_faces() == 0) throw TopologyError("the mesh has no faces");
  const auto [lo, hi] = face_bounds(mesh);
  const glm::dvec3 o = 0.5 * (lo + hi);  // origin of the tetrahedra, near the mesh: less cancellation
  const double diag = glm::length(hi - lo);
  MeshCentroid result;
  if (edges_balanced(mesh)) {
    double volume = 0.0;
    glm::dvec3 moment(0.0);
    for_each_fan_triangle(mesh, [&](const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
      const glm::dvec3 pa = a - o, pb = b - o, pc = c - o;
      const double v = glm::dot(pa, glm::cross(pb, pc)) / 6.0;  // signed tetrahedron (o, a, b, c)
      volume += v;
      moment += v * (pa + pb + pc) / 4.0;
    });
    if (std::abs(volume) > kFlatVolume * diag * diag * diag) {
      result.point = o + moment / volume;
      result.kind = CentroidKind::Volume;
      return result;
    }
  }
  double area = 0.0;
  glm::dvec3 moment(0.0);
  for_each_fan_triangle(mesh, [&](const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    const double w = 0.5 * glm::length(glm::cross(b - a, c - a));
    area += w;
    moment += w * (a - o + b - o + c - o) / 3.0;
  });
  result.kind = CentroidKind::Area;
  if (area > 0.0) {
    result.point = o + moment / area;
  } else {
    // Every face degenerate: the mean of the used corners.
    glm::dvec3 sum(0.0);
    for (std::uint32_t v : mesh.face_indices) sum += mesh.positions[v] - o;
    result.point = o + sum / double(mesh.face_indices.size());
  }
  return result;
}

SphereResample resample_sphere(const SurfaceMesh& mesh, int levels) {
  check_levels(levels);
  if (mesh.num_faces() == 0) throw TopologyError("the mesh has no faces to cast rays at");
  SphereResample out;
  out.centroid = mesh_centroid(mesh);
  GeodesicSphere sphere = geodesic_sphere(levels);
  const TriangleBvh bvh(mesh);
  const std::uint32_t n = sphere.fine.num_vertices;
  out.rays = n;

  // Per ray: the farthest hit and the number of distinct hits (0 = missed).
  const double same = kSameHitEpsilon * bvh.diagonal();
  const glm::dvec3 c = out.centroid.point;
  std::vector<double> radius(n, 0.0);
  std::vector<std::uint8_t> distinct(n, 0);  // 0, 1 or 2 (= more than one)
  parallel_for(n, 2048, [&](std::uint32_t begin, std::uint32_t end) {
    std::vector<double> hits;
    hits.reserve(16);
    for (std::uint32_t v = begin; v < end; ++v) {
      hits.clear();
      bvh.all_hits(c, sphere.directions[v], hits);
      if (hits.empty()) continue;
      std::sort(hits.begin(), hits.end());
      int count = 1;
      for (std::size_t i = 1; i < hits.size(); ++i)
        if (hits[i] - hits[i - 1] > same) ++count;
      radius[v] = hits.back();  // the farthest: the outer surface
      distinct[v] = static_cast<std::uint8_t>(std::min(count, 2));
    }
  });
  std::vector<std::uint8_t> known(n);
  for (std::uint32_t v = 0; v < n; ++v) {
    known[v] = distinct[v] > 0;
    out.missed += distinct[v] == 0;
    out.multiple_hits += distinct[v] == 2;
  }
  if (out.missed == n) throw TopologyError("no ray from the centroid meets the mesh");

  // Fill the misses ring by ring: each unknown vertex next to known ones takes their mean radius.
  if (out.missed > 0) {
    const Complex& f = sphere.fine;
    std::vector<std::uint32_t> open;  // edges with an unknown end
    for (std::uint32_t e = 0; e < f.num_edges(); ++e)
      if (!known[f.edge_verts[2 * e]] || !known[f.edge_verts[2 * e + 1]]) open.push_back(e);
    std::vector<double> sum(n, 0.0);
    std::vector<std::uint32_t> count(n, 0), touched;
    std::size_t left = out.missed;
    while (left > 0) {
      touched.clear();
      for (std::uint32_t e : open) {
        const std::uint32_t a = f.edge_verts[2 * e], b = f.edge_verts[2 * e + 1];
        if (known[a] == known[b]) continue;
        const std::uint32_t to = known[a] ? b : a, from = known[a] ? a : b;
        if (count[to] == 0) touched.push_back(to);
        sum[to] += radius[from];
        ++count[to];
      }
      if (touched.empty()) throw TopologyError("cannot fill the missed rays: no hit neighbours");  // sphere is connected
      for (std::uint32_t v : touched) {
        radius[v] = sum[v] / count[v];
        known[v] = 1;
        sum[v] = 0.0;
        count[v] = 0;
      }
      left -= touched.size();
      ++out.fill_rounds;
      std::erase_if(open, [&](std::uint32_t e) { return known[f.edge_verts[2 * e]] && known[f.edge_verts[2 * e + 1]]; });
    }
  }

  out.positions.reserve(3 * std::size_t(n));
  for (std::uint32_t v = 0; v < n; ++v) {
    const glm::dvec3 p = c + radius[v] * sphere.directions[v];
    out.positions.insert(out.positions.end(), {p.x, p.y, p.z});
  }
  out.base_positions.assign(out.positions.begin(), out.positions.begin() + 3 * sphere.base.num_vertices);
  out.base = std::move(sphere.base);
  out.fine = std::move(sphere.fine);
  return out;
}

}  // namespace sublift
