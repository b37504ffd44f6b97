#include "core/complex/cell_shapes.h"

#include <algorithm>
#include <map>
#include <set>

#include "core/complex/face_loop.h"

namespace sublift {
namespace {

// One row per CellShape, in its order: name, vertex count and VTK's face table (vtkTetra,
// vtkHexahedron, vtkWedge, vtkPyramid; outward loops).
struct ShapeFacts {
  const char* name;
  int vertices;
  std::vector<std::vector<int>> faces;
};
const ShapeFacts kShapes[] = {
    {"tetrahedron", 4, {{0, 1, 3}, {1, 2, 3}, {2, 0, 3}, {0, 2, 1}}},
    {"hexahedron", 8, {{0, 4, 7, 3}, {1, 2, 6, 5}, {0, 1, 5, 4}, {3, 7, 6, 2}, {0, 3, 2, 1}, {4, 5, 6, 7}}},
    {"wedge", 6, {{0, 1, 2}, {3, 5, 4}, {0, 3, 4, 1}, {1, 4, 5, 2}, {2, 5, 3, 0}}},
    {"pyramid", 5, {{0, 3, 2, 1}, {0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}}},
};
const ShapeFacts& facts(CellShape s) { return kShapes[static_cast<std::size_t>(s)]; }

}  // namespace

int cell_shape_vertex_count(CellShape s) { return facts(s).vertices; }

std::string cell_shape_name(CellShape s) { return facts(s).name; }

const std::vector<std::vector<int>>& cell_shape_faces(CellShape s) { return facts(s).faces; }

namespace {

// Cell k's loops oriented consistently across its edges, the first face's orientation kept.
std::vector<std::vector<std::uint32_t>> consistent_cell_loops(const Complex& c, std::uint32_t k) {
  std::vector<std::vector<std::uint32_t>> loops;
  for (std::uint32_t f : c.cell_faces.row(k)) {
    auto r = c.faces.row(f);
    loops.emplace_back(r.begin(), r.end());
  }
  // Directed edge (a, b) -> faces of this cell that traverse it so; a face and its neighbour
  // agree when they traverse their shared edge in opposite directions.
  auto edges_of = [](const std::vector<std::uint32_t>& l) {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> e;
    for (std::size_t i = 0; i < l.size(); ++i) e.emplace_back(l[i], l[(i + 1) % l.size()]);
    return e;
  };
  const std::size_t n = loops.size();
  std::vector<int> state(n, 0);  // 0 unvisited, 1 oriented
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::size_t>> by_edge;
  for (std::size_t i = 0; i < n; ++i)
    for (auto [a, b] : edges_of(loops[i])) by_edge[{std::min(a, b), std::max(a, b)}].push_back(i);
  for (std::size_t seed = 0; seed < n; ++seed) {
    if (state[seed]) continue;
    state[seed] = 1;
    std::vector<std::size_t> stack{seed};
    while (!stack.empty()) {
      const std::size_t i = stack.back();
      stack.pop_back();
      for (auto [a, b] : edges_of(loops[i])) {
        for (std::size_t j : by_edge[{std::min(a, b), std::max(a, b)}]) {
          if (state[j]) continue;
          // j must traverse b -> a; if it runs a -> b, reverse it.
          const auto ej = edges_of(loops[j]);
          if (std::find(ej.begin(), ej.end(), std::make_pair(a, b)) != ej.end())
            std::reverse(loops[j].begin(), loops[j].end());
          state[j] = 1;
          stack.push_back(j);
        }
      }
    }
  }
  return loops;
}

// Signed volume of closed loops by the divergence theorem (fan triangles about the first vertex).
double signed_volume(const std::vector<std::vector<std::uint32_t>>& loops, std::span<const double> xyz) {
  if (loops.empty()) return 0;
  auto p = [&](std::uint32_t v) { return std::array<double, 3>{xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]}; };
  const auto o = p(loops[0][0]);
  double vol = 0;
  for (const auto& l : loops)
    for (std::size_t i = 1; i + 1 < l.size(); ++i) {
      auto a = p(l[0]), b = p(l[i]), d = p(l[i + 1]);
      for (int t = 0; t < 3; ++t) a[t] -= o[t], b[t] -= o[t], d[t] -= o[t];
      vol += a[0] * (b[1] * d[2] - b[2] * d[1]) - a[1] * (b[0] * d[2] - b[2] * d[0]) +
             a[2] * (b[0] * d[1] - b[1] * d[0]);
    }
  return vol;
}

bool has_positions(const Complex& c, std::span<const double> xyz) {
  return xyz.size() >= 3 * static_cast<std::size_t>(c.num_vertices);
}

// Whether cell k's loop for face f runs as c.faces.row(f) does.
bool runs_forward(const Complex& c, const std::vector<std::vector<std::uint32_t>>& loops, std::uint32_t k,
                  std::uint32_t f) {
  const auto row = c.cell_faces.row(k);
  const auto i = static_cast<std::size_t>(std::find(row.begin(), row.end(), f) - row.begin());
  const auto r = c.faces.row(f);
  return loops[i].size() > 1 && loops[i][0] == r[0] && loops[i][1] == r[1];
}

void reverse_all(std::vector<std::vector<std::uint32_t>>& loops) {
  for (auto& l : loops) std::reverse(l.begin(), l.end());
}

}  // namespace

std::vector<std::vector<std::uint32_t>> oriented_cell_loops(const Complex& c, std::span<const double> xyz,
                                                            std::uint32_t k) {
  auto loops = consistent_cell_loops(c, k);
  if (has_positions(c, xyz) && signed_volume(loops, xyz) < 0) reverse_all(loops);
  return loops;
}

std::vector<std::vector<std::vector<std::uint32_t>>> oriented_lattice_loops(const Complex& c,
                                                                            std::span<const double> xyz) {
  const std::uint32_t n = c.num_cells();
  std::vector<std::vector<std::vector<std::uint32_t>>> loops(n);
  for (std::uint32_t k = 0; k < n; ++k) loops[k] = consistent_cell_loops(c, k);
  const bool geometry = has_positions(c, xyz);
  const bool upward = c.face_cells.rows() == c.num_faces();  // absent on a bare downward complex
  std::vector<char> seen(n, 0);
  for (std::uint32_t seed = 0; seed < n; ++seed) {
    if (seen[seed]) continue;
    // One connected component through shared faces: each neighbour is flipped so that the
    // shared face runs against this cell's (the first visit decides on a non-orientable lattice).
    std::vector<std::uint32_t> component{seed}, stack{seed};
    seen[seed] = 1;
    while (!stack.empty()) {
      const std::uint32_t k = stack.back();
      stack.pop_back();
      if (!upward) break;
      for (std::uint32_t f : c.cell_faces.row(k))
        for (std::uint32_t m : c.face_cells.row(f)) {
          if (m == k || seen[m]) continue;
          if (runs_forward(c, loops[k], k, f) == runs_forward(c, loops[m], m, f)) reverse_all(loops[m]);
          seen[m] = 1;
          component.push_back(m);
          stack.push_back(m);
        }
    }
    // Outward where the geometry says so for most of the volume.
    if (geometry) {
      double vol = 0;
      for (std::uint32_t k : component) vol += signed_volume(loops[k], xyz);
      if (vol < 0)
        for (std::uint32_t k : component) reverse_all(loops[k]);
    }
  }
  return loops;
}

std::optional<std::array<std::uint32_t, 8>> hexahedron_vertices(const std::vector<std::vector<std::uint32_t>>& loops) {
  if (loops.size() != 6) return std::nullopt;
  for (const auto& l : loops)
    if (l.size() != 4) return std::nullopt;
  std::map<std::uint32_t, std::set<std::uint32_t>> nbr;
  for (const auto& l : loops)
    for (std::size_t i = 0; i < 4; ++i) {
      nbr[l[i]].insert(l[(i + 1) % 4]);
      nbr[l[(i + 1) % 4]].insert(l[i]);
    }
  if (nbr.size() != 8) return std::nullopt;
  // VTK's outward bottom face is 0-3-2-1: the outward loop a b c d gives 0 = a, 1 = d, 2 = c, 3 = b.
  const auto& b = loops[0];
  std::array<std::uint32_t, 8> h{b[0], b[3], b[2], b[1], 0, 0, 0, 0};
  for (int i = 0; i < 4; ++i) {
    std::vector<std::uint32_t> up;
    for (std::uint32_t w : nbr[h[i]])
      if (std::find(b.begin(), b.end(), w) == b.end()) up.push_back(w);
    if (up.size() != 1) return std::nullopt;
    h[4 + i] = up[0];
  }
  std::set<std::vector<std::uint32_t>> have;
  for (const auto& l : loops) have.insert(canonical_loop(l));
  for (const auto& f : cell_shape_faces(CellShape::Hexahedron)) {
    std::vector<std::uint32_t> l;
    for (int i : f) l.push_back(h[static_cast<std::size_t>(i)]);
    if (!have.count(canonical_loop(l))) return std::nullopt;
  }
  return h;
}

}  // namespace sublift
