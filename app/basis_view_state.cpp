#include "app/basis_view_state.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "core/boundary_surface.h"
#include "core/errors.h"

namespace sublift {
namespace {

glm::dvec3 at(const std::vector<double>& xyz, std::size_t v) { return {xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]}; }

// Area-weighted vertex normals of polygon faces (Newell normals), unit length (0 when unused).
std::vector<double> face_normals(const Csr& faces, const std::vector<double>& xyz) {
  std::vector<glm::dvec3> n(xyz.size() / 3, glm::dvec3(0.0));
  for (std::size_t f = 0; f < faces.rows(); ++f) {
    const auto c = faces.row(f);
    glm::dvec3 fn(0.0);
    for (std::size_t i = 0; i < c.size(); ++i) fn += glm::cross(at(xyz, c[i]), at(xyz, c[(i + 1) % c.size()]));
    for (const std::uint32_t v : c) n[v] += fn;
  }
  std::vector<double> out(xyz.size(), 0.0);
  for (std::size_t v = 0; v < n.size(); ++v) {
    const double len = glm::length(n[v]);
    if (len > 0.0) {
      for (int k = 0; k < 3; ++k) out[3 * v + k] = n[v][k] / len;
    }
  }
  return out;
}

// In-plane normals of a polyline: tangent (sum of incident edge directions) x Z, or x Y when the
// tangent runs along Z.
std::vector<double> curve_normals(const std::vector<std::uint32_t>& edges, const std::vector<double>& xyz) {
  std::vector<glm::dvec3> t(xyz.size() / 3, glm::dvec3(0.0));
  for (std::size_t e = 0; 2 * e + 1 < edges.size(); ++e) {
    const glm::dvec3 d = at(xyz, edges[2 * e + 1]) - at(xyz, edges[2 * e]);
    const double len = glm::length(d);
    if (len <= 0.0) continue;
    t[edges[2 * e]] += d / len;
    t[edges[2 * e + 1]] += d / len;
  }
  std::vector<double> out(xyz.size(), 0.0);
  for (std::size_t v = 0; v < t.size(); ++v) {
    const double len = glm::length(t[v]);
    if (len <= 0.0) continue;
    const glm::dvec3 u = t[v] / len;
    glm::dvec3 n = glm::cross(u, glm::dvec3(0, 0, 1));
    if (glm::length(n) < 0.3) n = glm::cross(u, glm::dvec3(0, 1, 0));
    n = glm::normalize(n);
    for (int k = 0; k < 3; ++k) out[3 * v + k] = n[k];
  }
  return out;
}

double diagonal(const std::vector<double>& xyz) {
  if (xyz.empty()) return 1.0;
  glm::dvec3 lo(1e300), hi(-1e300);
  for (std::size_t v = 0; v < xyz.size() / 3; ++v) lo = glm::min(lo, at(xyz, v)), hi = glm::max(hi, at(xyz, v));
  const double d = glm::length(hi - lo);
  return d > 0.0 ? d : 1.0;
}

}  // namespace

long long edge_wavelet_at(const Complex& c, std::uint32_t v) {
  for (std::uint32_t e = 0; e < c.num_edges(); ++e) {
    if (c.edge_verts[2 * e] == v || c.edge_verts[2 * e + 1] == v) return static_cast<long long>(c.num_vertices) + e;
  }
  return -1;
}

BasisDisplay compute_basis_display(const Session& session, int level, const BasisSettings& settings) {
  const Hierarchy& h = session.hierarchy();
  if (level < 0 || level > h.finest_level()) throw Error("basis: level " + std::to_string(level) + " does not exist");
  const Complex& cj = h.levels[static_cast<std::size_t>(level)];
  BasisDisplay d;
  d.settings = settings;
  d.level = level;
  BasisRequest r;
  r.level = level;
  r.kind = settings.kind;
  r.index = settings.index;
  r.dual = settings.dual;
  r.extra_levels = settings.extra_levels;
  d.function = basis_function(cj, h.scheme, r, session.positions(level), &d.base_positions);
  const BasisFunction& f = d.function;
  d.model_size = diagonal(d.base_positions);

  // Colour.
  const double maxabs = std::max(std::abs(f.min), std::abs(f.max));
  d.symmetric = settings.kind == BasisKind::Wavelet || settings.dual || f.min < -1e-9 * maxabs;
  d.colour.assign(f.values.size(), d.symmetric ? 0.5f : 0.0f);
  if (maxabs > 0.0) {
    for (std::size_t v = 0; v < f.values.size(); ++v) {
      const double s = f.values[v] / maxabs;
      d.colour[v] = static_cast<float>(d.symmetric ? 0.5 + 0.5 * s : s);
    }
  }

  // What to draw.
  if (f.finest.dim >= 2) {
    d.faces = boundary_faces(f.finest, d.base_positions);
  } else {
    d.curve_edges = f.finest.edge_verts;
  }

  // Support outline on the level-j net.
  std::vector<std::uint8_t> nonzero(f.values.size(), 0);
  for (const std::uint32_t v : f.support) nonzero[v] = 1;
  const std::uint32_t nv = cj.num_vertices;
  for (std::uint32_t e = 0; e < cj.num_edges(); ++e) {
    const std::uint32_t a = cj.edge_verts[2 * e], b = cj.edge_verts[2 * e + 1];
    const bool mid = f.extra_levels >= 1 && nv + e < nonzero.size() && nonzero[nv + e];
    if (nonzero[a] || nonzero[b] || mid) d.support_edges.insert(d.support_edges.end(), {a, b});
  }
  apply_basis_height(d);
  return d;
}

void apply_basis_height(BasisDisplay& d) {
  const BasisFunction& f = d.function;
  const bool surface = d.faces.rows() > 0;
  const bool can_displace = surface ? f.finest.dim == 2 : true;
  const std::vector<double> base_normals =
      surface ? face_normals(d.faces, d.base_positions) : curve_normals(d.curve_edges, d.base_positions);
  d.positions = d.base_positions;
  const double maxabs = std::max(std::abs(f.min), std::abs(f.max));
  if (d.settings.height && can_displace && maxabs > 0.0) {
    const double s = d.settings.height_scale * d.model_size / maxabs;
    for (std::size_t v = 0; v < f.values.size(); ++v) {
      for (int k = 0; k < 3; ++k) d.positions[3 * v + k] += base_normals[3 * v + k] * f.values[v] * s;
    }
    d.normals = surface ? face_normals(d.faces, d.positions) : std::vector<double>(d.positions.size(), 0.0);
  } else {
    d.normals = surface ? base_normals : std::vector<double>(d.positions.size(), 0.0);
  }
}

}  // namespace sublift
