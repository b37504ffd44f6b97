#include "core/analysis/cell_contour.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/base/errors.h"

namespace sublift {
namespace {

struct Node {
  double p[3];
  double f, v;
};

Node mean_of(std::span<const std::uint32_t> verts, std::span<const double> xyz, std::span<const double> field,
             std::span<const double> carried) {
  Node n{{0, 0, 0}, 0, 0};
  for (const std::uint32_t v : verts) {
    for (int k = 0; k < 3; ++k) n.p[k] += xyz[3 * v + k];
    n.f += field[v];
    n.v += carried[v];
  }
  const double s = 1.0 / static_cast<double>(verts.size());
  for (double& x : n.p) x *= s;
  n.f *= s, n.v *= s;
  return n;
}

Node cut(const Node& a, const Node& b, double level) {
  const double t = (level - a.f) / (b.f - a.f);  // a and b lie on opposite sides: b.f != a.f
  Node n;
  for (int k = 0; k < 3; ++k) n.p[k] = a.p[k] + t * (b.p[k] - a.p[k]);
  n.f = level;
  n.v = a.v + t * (b.v - a.v);
  return n;
}

// One triangle; its normal points away from `high` (a tetrahedron corner above the level).
void emit(const Node& a, const Node& b, const Node& c, const Node& high, ContourMesh& out) {
  double u[3], w[3], n[3];
  for (int k = 0; k < 3; ++k) u[k] = b.p[k] - a.p[k], w[k] = c.p[k] - a.p[k];
  n[0] = u[1] * w[2] - u[2] * w[1];
  n[1] = u[2] * w[0] - u[0] * w[2];
  n[2] = u[0] * w[1] - u[1] * w[0];
  const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (!(len > 0.0)) return;  // degenerate piece: nothing to see
  double side = 0.0;
  for (int k = 0; k < 3; ++k) side += n[k] * (high.p[k] - a.p[k]);
  const double s = (side > 0.0 ? -1.0 : 1.0) / len;
  const Node* corner[3] = {&a, &b, &c};
  if (side > 0.0) std::swap(corner[1], corner[2]);  // keep the winding counter-clockwise about n
  for (const Node* q : corner) {
    out.xyz.insert(out.xyz.end(), q->p, q->p + 3);
    for (int k = 0; k < 3; ++k) out.normals.push_back(n[k] * s);
    out.value.push_back(q->v);
  }
}

void march(const std::array<Node, 4>& t, double level, ContourMesh& out) {
  std::array<std::size_t, 4> above{}, below{};
  std::size_t na = 0, nb = 0;
  for (std::size_t i = 0; i < 4; ++i) (t[i].f > level ? above[na++] : below[nb++]) = i;
  if (na == 0 || nb == 0) return;
  if (na == 1 || nb == 1) {
    const bool lone_above = na == 1;
    const std::array<std::size_t, 4>& others = lone_above ? below : above;
    const Node& L = t[lone_above ? above[0] : below[0]];
    const Node a = cut(L, t[others[0]], level);
    const Node b = cut(L, t[others[1]], level);
    const Node c = cut(L, t[others[2]], level);
    emit(a, b, c, lone_above ? L : t[others[0]], out);
    return;
  }
  // Two above (a0, a1), two below (b0, b1): a quad through the four crossing edges in cyclic order.
  const Node& a0 = t[above[0]];
  const Node& a1 = t[above[1]];
  const Node& b0 = t[below[0]];
  const Node& b1 = t[below[1]];
  const Node p = cut(a0, b0, level), q = cut(a0, b1, level), r = cut(a1, b1, level), s = cut(a1, b0, level);
  emit(p, q, r, a0, out);
  emit(p, r, s, a0, out);
}

}  // namespace

void contour_cells(const Complex& c, std::span<const double> xyz, std::span<const double> field, double level,
                   std::span<const double> carried, ContourMesh& out) {
  if (c.dim != 3) throw Error("contour: the complex is not a volume lattice");
  const std::size_t n = c.num_vertices;
  if (xyz.size() != 3 * n || field.size() != n || carried.size() != n) {
    throw Error("contour: " + std::to_string(n) + " vertices, but " + std::to_string(xyz.size()) + " coordinates, " +
                std::to_string(field.size()) + " field and " + std::to_string(carried.size()) + " carried values");
  }
  auto node = [&](std::uint32_t v) {
    return Node{{xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]}, field[v], carried[v]};
  };
  std::vector<std::uint32_t> cell_vertices;
  for (std::size_t cell = 0; cell < c.num_cells(); ++cell) {
    cell_vertices.clear();
    for (const std::uint32_t f : c.cell_faces.row(cell)) {
      const auto corners = c.faces.row(f);
      cell_vertices.insert(cell_vertices.end(), corners.begin(), corners.end());
    }
    std::sort(cell_vertices.begin(), cell_vertices.end());
    cell_vertices.erase(std::unique(cell_vertices.begin(), cell_vertices.end()), cell_vertices.end());
    // Skip cells the level set cannot cross (every value on one side; the centroids are means).
    bool any_above = false, any_below = false;
    for (const std::uint32_t v : cell_vertices) (field[v] > level ? any_above : any_below) = true;
    if (!any_above || !any_below) continue;
    const Node centre = mean_of(cell_vertices, xyz, field, carried);
    for (const std::uint32_t f : c.cell_faces.row(cell)) {
      const auto corners = c.faces.row(f);
      const Node face = mean_of(corners, xyz, field, carried);
      for (std::size_t i = 0; i < corners.size(); ++i) {
        march({centre, face, node(corners[i]), node(corners[(i + 1) % corners.size()])}, level, out);
      }
    }
  }
}

void slice_cells(const Complex& c, std::span<const double> xyz, const double normal[3], double offset,
                 std::span<const double> values, ContourMesh& out) {
  std::vector<double> distance(xyz.size() / 3);
  for (std::size_t v = 0; v < distance.size(); ++v) {
    distance[v] = normal[0] * xyz[3 * v] + normal[1] * xyz[3 * v + 1] + normal[2] * xyz[3 * v + 2] - offset;
  }
  contour_cells(c, xyz, distance, 0.0, values, out);
}

}  // namespace sublift
