#include "core/edit/selection.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sublift {
namespace {

std::vector<std::uint8_t> mask_of(std::uint32_t n, std::span<const unsigned> selection) {
  std::vector<std::uint8_t> m(n, 0);
  for (const unsigned v : selection)
    if (v < n) m[v] = 1;
  return m;
}

std::vector<unsigned> from_mask(const std::vector<std::uint8_t>& m) {
  std::vector<unsigned> out;
  for (std::uint32_t v = 0; v < m.size(); ++v)
    if (m[v]) out.push_back(v);
  return out;
}

bool share_a_face(const Complex& c, std::uint32_t a, std::uint32_t b) {
  const auto fa = c.edge_faces.row(a), fb = c.edge_faces.row(b);
  std::size_t i = 0, j = 0;  // rows ascend
  while (i < fa.size() && j < fb.size()) {
    if (fa[i] == fb[j]) return true;
    fa[i] < fb[j] ? ++i : ++j;
  }
  return false;
}

// The loop's next edge at v after `e`: the only edge of v sharing no face with e.
std::int64_t straight_on(const Complex& c, std::uint32_t e, std::uint32_t v) {
  std::int64_t found = -1;
  for (const std::uint32_t f : c.vertex_edges.row(v)) {
    if (f == e || share_a_face(c, e, f)) continue;
    if (found >= 0) return -1;  // two or more: an irregular vertex
    found = f;
  }
  return found;
}

// The edge of quad face f opposite to edge e, or -1 when f is not a quad.
std::int64_t opposite_in_face(const Complex& c, std::uint32_t f, std::uint32_t e) {
  const auto edges = c.face_edges.row(f);
  if (edges.size() != 4) return -1;
  for (std::size_t i = 0; i < 4; ++i)
    if (edges[i] == e) return edges[(i + 2) % 4];
  return -1;
}

}  // namespace

std::vector<unsigned> select_linked(const Complex& c, std::span<const unsigned> selection) {
  std::vector<std::uint8_t> m = mask_of(c.num_vertices, selection);
  std::vector<unsigned> stack = from_mask(m);
  while (!stack.empty()) {
    const unsigned v = stack.back();
    stack.pop_back();
    for (const std::uint32_t e : c.vertex_edges.row(v)) {
      const std::uint32_t w = edge_other_end(c, e, v);
      if (!m[w]) m[w] = 1, stack.push_back(w);
    }
  }
  return from_mask(m);
}

std::vector<unsigned> grow_selection(const Complex& c, std::span<const unsigned> selection) {
  std::vector<std::uint8_t> m = mask_of(c.num_vertices, selection);
  for (const unsigned v : from_mask(m))
    for (const std::uint32_t e : c.vertex_edges.row(v)) m[edge_other_end(c, e, v)] = 1;
  return from_mask(m);
}

std::vector<unsigned> shrink_selection(const Complex& c, std::span<const unsigned> selection) {
  const std::vector<std::uint8_t> m = mask_of(c.num_vertices, selection);
  std::vector<unsigned> out;
  for (const unsigned v : from_mask(m)) {
    bool inner = true;
    for (const std::uint32_t e : c.vertex_edges.row(v)) inner = inner && m[edge_other_end(c, e, v)];
    if (inner) out.push_back(v);
  }
  return out;
}

std::vector<unsigned> invert_selection(std::uint32_t num_vertices, std::span<const unsigned> selection) {
  std::vector<std::uint8_t> m = mask_of(num_vertices, selection);
  for (auto& b : m) b = !b;
  return from_mask(m);
}

std::vector<std::uint32_t> edge_loop(const Complex& c, std::uint32_t start) {
  std::vector<std::uint32_t> out{start};
  if (start >= c.num_edges()) return {};
  std::vector<std::uint8_t> seen(c.num_edges(), 0);
  seen[start] = 1;
  for (int side = 0; side < 2; ++side) {
    std::uint32_t e = start, v = c.edge_verts[2 * std::size_t(start) + side];
    for (;;) {
      const std::int64_t next = straight_on(c, e, v);
      if (next < 0 || seen[static_cast<std::size_t>(next)]) break;
      e = static_cast<std::uint32_t>(next);
      seen[e] = 1;
      out.push_back(e);
      v = edge_other_end(c, e, v);
    }
  }
  return out;
}

std::vector<std::uint32_t> edge_ring(const Complex& c, std::uint32_t start) {
  if (start >= c.num_edges()) return {};
  std::vector<std::uint32_t> out{start};
  if (c.dim != 2) return out;
  std::vector<std::uint8_t> seen(c.num_edges(), 0);
  seen[start] = 1;
  const auto first_faces = c.edge_faces.row(start);
  for (const std::uint32_t f0 : std::vector<std::uint32_t>(first_faces.begin(), first_faces.end())) {
    std::uint32_t e = start, f = f0;
    for (;;) {
      const std::int64_t opp = opposite_in_face(c, f, e);
      if (opp < 0 || seen[static_cast<std::size_t>(opp)]) break;
      e = static_cast<std::uint32_t>(opp);
      seen[e] = 1;
      out.push_back(e);
      const auto faces = c.edge_faces.row(e);
      if (faces.size() != 2) break;  // a boundary (or a non-manifold edge)
      f = faces[0] == f ? faces[1] : faces[0];
    }
  }
  return out;
}

std::vector<unsigned> edge_vertices(const Complex& c, std::span<const std::uint32_t> edges) {
  std::vector<unsigned> out;
  for (const std::uint32_t e : edges) {
    out.push_back(c.edge_verts[2 * std::size_t(e)]);
    out.push_back(c.edge_verts[2 * std::size_t(e) + 1]);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

std::int64_t find_edge(const Complex& c, std::uint32_t a, std::uint32_t b) {
  if (a >= c.num_vertices || b >= c.num_vertices) return -1;
  for (const std::uint32_t e : c.vertex_edges.row(a))
    if (edge_other_end(c, e, a) == b) return e;
  return -1;
}

std::int64_t pick_edge(const PickIndex& index, const PickView& view, std::span<const double> positions,
                       const Complex& c, double mx, double my, double radius_px, bool xray) {
  // Candidates: edges of the indexed points within a generous window (an edge's ends may lie
  // well away from the point of it under the mouse).
  const double window = std::max(8.0 * radius_px, 160.0);
  const std::vector<std::uint32_t> near = index.in_rect(mx - window, my - window, mx + window, my + window, xray);
  auto screen = [&](std::uint32_t v, glm::dvec2& s) {  // false only behind the camera
    const double* p = &positions[3 * std::size_t(v)];
    double depth = std::numeric_limits<double>::quiet_NaN();  // project_point sets it when w > 0
    return project_point(view, glm::dvec3(p[0], p[1], p[2]), s, depth) || !std::isnan(depth);
  };
  std::int64_t best = -1;
  double best_d = radius_px;
  const glm::dvec2 m(mx, my);
  for (const std::uint32_t v : near) {
    for (const std::uint32_t e : c.vertex_edges.row(v)) {
      glm::dvec2 a, b;
      if (!screen(c.edge_verts[2 * std::size_t(e)], a) || !screen(c.edge_verts[2 * std::size_t(e) + 1], b)) continue;
      const glm::dvec2 ab = b - a;
      const double len2 = ab.x * ab.x + ab.y * ab.y;
      const double t = len2 > 0.0 ? std::clamp(((m.x - a.x) * ab.x + (m.y - a.y) * ab.y) / len2, 0.0, 1.0) : 0.0;
      const double d = std::hypot(a.x + t * ab.x - m.x, a.y + t * ab.y - m.y);
      if (d < best_d || (d == best_d && best >= 0 && e < best)) best_d = d, best = e;
    }
  }
  return best;
}

}  // namespace sublift
