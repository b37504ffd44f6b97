#include "app/modeler/basis_view_state.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "core/analysis/boundary_surface.h"
#include "core/base/bounds.h"
#include "core/analysis/cell_contour.h"
#include "core/base/errors.h"

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
  const double d = bbox_diagonal(xyz);
  return d > 0.0 ? d : 1.0;
}

// The plot of a curve function: walk the component of the largest |value| from an end (or, for
// a closed curve, from a vertex where the function is zero), then keep the support and a margin.
std::vector<float> curve_plot(const std::vector<std::uint32_t>& edges, const std::vector<double>& values) {
  const std::size_t n = values.size();
  if (n == 0 || edges.empty()) return {};
  const Csr adj = transpose_pairs(edges, n);
  auto neighbour = [&](std::uint32_t v, std::uint32_t e) {
    return edges[2 * e] == v ? edges[2 * e + 1] : edges[2 * e];
  };
  std::size_t peak = 0;
  for (std::size_t v = 1; v < n; ++v) {
    if (std::abs(values[v]) > std::abs(values[peak])) peak = v;
  }
  // The component of the peak, and a start: an end vertex if any, else a zero, else the peak.
  std::vector<std::uint8_t> seen(n, 0);
  std::vector<std::uint32_t> stack{static_cast<std::uint32_t>(peak)}, component;
  seen[peak] = 1;
  while (!stack.empty()) {
    const std::uint32_t v = stack.back();
    stack.pop_back();
    component.push_back(v);
    for (const std::uint32_t e : adj.row(v)) {
      const std::uint32_t w = neighbour(v, e);
      if (!seen[w]) seen[w] = 1, stack.push_back(w);
    }
  }
  std::uint32_t start = static_cast<std::uint32_t>(peak);
  bool found_end = false;
  for (const std::uint32_t v : component) {
    if (adj.size(v) == 1) {
      start = v, found_end = true;
      break;
    }
  }
  if (!found_end) {
    for (const std::uint32_t v : component) {
      if (values[v] == 0.0) {
        start = v;
        break;
      }
    }
  }
  // Walk (every vertex of a curve has at most two edges; stop at a branch or on return).
  std::vector<double> walk{values[start]};
  std::vector<std::uint8_t> visited(n, 0);
  visited[start] = 1;
  std::uint32_t v = start;
  for (;;) {
    std::uint32_t next = v;
    for (const std::uint32_t e : adj.row(v)) {
      const std::uint32_t w = neighbour(v, e);
      if (!visited[w]) {
        next = w;
        break;
      }
    }
    if (next == v) break;
    visited[next] = 1;
    walk.push_back(values[next]);
    v = next;
  }
  std::size_t first = walk.size(), last = 0;
  for (std::size_t i = 0; i < walk.size(); ++i) {
    if (walk[i] != 0.0) first = std::min(first, i), last = i;
  }
  if (first > last) first = 0, last = walk.size() - 1;
  const std::size_t margin = std::max<std::size_t>(2, (last - first + 1) / 10);
  first = first > margin ? first - margin : 0;
  last = std::min(walk.size() - 1, last + margin);
  return {walk.begin() + static_cast<std::ptrdiff_t>(first), walk.begin() + static_cast<std::ptrdiff_t>(last) + 1};
}

}  // namespace

bool same_function(const BasisSettings& a, const BasisSettings& b) {
  const BasisRequest &p = a.request, &q = b.request;
  return p.kind == q.kind && p.index == q.index && p.dual == q.dual && p.extra_levels == q.extra_levels &&
         p.level == q.level;
}

float basis_colour(const BasisDisplay& d, double v) {
  const double maxabs = std::max(std::abs(d.function.min), std::abs(d.function.max));
  if (!(maxabs > 0.0)) return d.symmetric ? 0.5f : 0.0f;
  const double s = std::clamp(v / maxabs, -1.0, 1.0);
  return static_cast<float>(d.symmetric ? 0.5 + 0.5 * s : s);
}

std::optional<BasisTarget> basis_target_at(const Hierarchy& h, int edit_level, BasisKind kind, std::uint32_t vertex) {
  if (edit_level < 0 || edit_level > h.finest_level() || vertex >= h.num_vertices(edit_level)) return std::nullopt;
  if (kind == BasisKind::Scaling) return BasisTarget{edit_level, vertex};
  if (edit_level >= 1 && vertex >= h.num_vertices(edit_level - 1)) return BasisTarget{edit_level - 1, vertex};
  const long long w = edge_wavelet_at(h.levels[static_cast<std::size_t>(edit_level)], vertex);
  if (w < 0) return std::nullopt;
  return BasisTarget{edit_level, static_cast<std::uint32_t>(w)};
}

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
  BasisRequest r = settings.request;
  r.level = level;
  // The modeler's default K stops at a million finest vertices (about a third of a second here),
  // so that a click with Follow answers at once; a K typed in the panel may go to core's cap.
  if (r.extra_levels < 0) r.extra_levels = default_extra_levels(cj, kModelerBasisVertices, h.scheme, level);
  d.function = basis_function(cj, h.scheme, r, session.positions(level), &d.base_positions);
  const BasisFunction& f = d.function;
  d.model_size = diagonal(d.base_positions);

  // Colour.
  const double maxabs = std::max(std::abs(f.min), std::abs(f.max));
  d.symmetric = r.kind == BasisKind::Wavelet || r.dual || f.min < -1e-9 * maxabs;
  d.vertex_colour.resize(f.values.size());
  for (std::size_t v = 0; v < f.values.size(); ++v) d.vertex_colour[v] = basis_colour(d, f.values[v]);

  // What to draw.
  if (f.finest.dim >= 2) {
    d.boundary = boundary_faces(f.finest, d.base_positions);
  } else {
    d.curve_edges = f.finest.edge_verts;
    d.plot.clear();
    for (const float x : curve_plot(d.curve_edges, f.values)) d.plot.push_back(x);
  }
  const auto net = session.positions(level);
  d.net_positions.assign(net.begin(), net.end());

  // Support outline on the level-j net.
  std::vector<std::uint8_t> nonzero(f.values.size(), 0);
  for (const std::uint32_t v : f.support) nonzero[v] = 1;
  const std::uint32_t nv = cj.num_vertices;
  for (std::uint32_t e = 0; e < cj.num_edges(); ++e) {
    const std::uint32_t a = cj.edge_verts[2 * e], b = cj.edge_verts[2 * e + 1];
    const bool mid = f.extra_levels >= 1 && nv + e < nonzero.size() && nonzero[nv + e];
    if (nonzero[a] || nonzero[b] || mid) d.support_edges.insert(d.support_edges.end(), {a, b});
  }
  apply_basis_view(d);
  return d;
}

namespace {

// Lattices: the boundary in colour, or the slice plane and iso-surfaces.
void lattice_view(BasisDisplay& d) {
  const BasisFunction& f = d.function;
  const BasisSettings& s = d.settings;
  if (s.slice_axis < 0 && !s.iso) {
    d.faces = d.boundary;
    d.positions = d.base_positions;
    d.normals = face_normals(d.faces, d.positions);
    d.colour = d.vertex_colour;
    return;
  }
  ContourMesh m;
  if (s.slice_axis >= 0 && s.slice_axis < 3) {
    const int k = s.slice_axis;
    double lo = 1e300, hi = -1e300;
    for (std::size_t v = 0; v < d.base_positions.size() / 3; ++v) {
      lo = std::min(lo, d.base_positions[3 * v + static_cast<std::size_t>(k)]);
      hi = std::max(hi, d.base_positions[3 * v + static_cast<std::size_t>(k)]);
    }
    double normal[3] = {0, 0, 0};
    normal[k] = 1.0;
    slice_cells(f.finest, d.base_positions, normal, lo + std::clamp(s.slice_pos, 0.0, 1.0) * (hi - lo), f.values, m);
  }
  const double maxabs = std::max(std::abs(f.min), std::abs(f.max));
  if (s.iso && maxabs > 0.0) {
    const double level = std::clamp(s.iso_level, 1e-6, 1.0) * maxabs;
    contour_cells(f.finest, d.base_positions, f.values, level, f.values, m);
    if (f.min < -level) {  // the negative lobes, normals out of them as well
      std::vector<double> negated(f.values.size());
      for (std::size_t v = 0; v < negated.size(); ++v) negated[v] = -f.values[v];
      contour_cells(f.finest, d.base_positions, negated, level, f.values, m);
    }
  }
  const std::size_t n = m.value.size();
  d.faces.offsets.resize(n / 3 + 1);
  d.faces.items.resize(n);
  for (std::size_t t = 0; t <= n / 3; ++t) d.faces.offsets[t] = static_cast<std::uint32_t>(3 * t);
  for (std::size_t v = 0; v < n; ++v) d.faces.items[v] = static_cast<std::uint32_t>(v);
  d.positions = std::move(m.xyz);
  d.normals = std::move(m.normals);
  d.colour.resize(n);
  for (std::size_t v = 0; v < n; ++v) d.colour[v] = basis_colour(d, m.value[v]);
}

}  // namespace

void apply_basis_view(BasisDisplay& d) {
  const BasisFunction& f = d.function;
  if (f.finest.dim == 3) {
    lattice_view(d);
    return;
  }
  d.colour = d.vertex_colour;
  if (f.finest.dim == 2) d.faces = d.boundary;
  const bool surface = d.faces.rows() > 0;
  const bool can_displace = true;
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
