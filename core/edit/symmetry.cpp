#include "core/edit/symmetry.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "core/base/bounds.h"
#include "core/base/errors.h"

namespace sublift {
namespace {

struct Grid {
  double cell;
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells;
  static std::uint64_t key(std::int64_t x, std::int64_t y, std::int64_t z) {
    return (static_cast<std::uint64_t>(x & 0x1fffff) << 42) | (static_cast<std::uint64_t>(y & 0x1fffff) << 21) |
           static_cast<std::uint64_t>(z & 0x1fffff);
  }
  std::int64_t at(double v) const { return static_cast<std::int64_t>(std::floor(v / cell)); }
};

}  // namespace

std::string MirrorMap::problem() const {
  if (unmatched == 0) return {};
  std::string s = std::string(1, "XYZ"[axis]) + " mirror: " + std::to_string(unmatched) + " of " +
                  std::to_string(mirror.size()) + " control points have no mirror image (first:";
  for (std::size_t i = 0; i < first_unmatched.size(); ++i) s += (i ? ", " : " ") + std::to_string(first_unmatched[i]);
  return s + ")";
}

MirrorMap find_mirror(const Complex& c, std::span<const double> positions, int axis, double tolerance) {
  if (axis < 0 || axis > 2) throw Error("the mirror axis must be 0, 1 or 2 (x, y or z)");
  const std::uint32_t n = c.num_vertices;
  if (positions.size() != 3 * std::size_t(n)) throw Error("one position per vertex is needed");
  MirrorMap m;
  m.axis = axis;
  m.mirror.assign(n, -1);
  if (n == 0) return m;
  if (!(tolerance > 0.0)) tolerance = 1e-4 * std::max(bbox_diagonal(positions), 1e-300);
  // By position: nearest reflected point within the tolerance, closest pairs first.
  Grid g{tolerance, {}};
  for (std::uint32_t v = 0; v < n; ++v)
    g.cells[Grid::key(g.at(positions[3 * v]), g.at(positions[3 * v + 1]), g.at(positions[3 * v + 2]))].push_back(v);
  struct Pair {
    double d;
    std::uint32_t a, b;
  };
  std::vector<Pair> pairs;
  for (std::uint32_t v = 0; v < n; ++v) {
    double r[3] = {positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]};
    r[axis] = -r[axis];
    const std::int64_t cx = g.at(r[0]), cy = g.at(r[1]), cz = g.at(r[2]);
    for (std::int64_t dx = -1; dx <= 1; ++dx)
      for (std::int64_t dy = -1; dy <= 1; ++dy)
        for (std::int64_t dz = -1; dz <= 1; ++dz) {
          const auto it = g.cells.find(Grid::key(cx + dx, cy + dy, cz + dz));
          if (it == g.cells.end()) continue;
          for (const std::uint32_t u : it->second) {
            if (u < v) continue;  // each unordered pair once (u == v: on the plane)
            const double d = std::hypot(positions[3 * u] - r[0], positions[3 * u + 1] - r[1], positions[3 * u + 2] - r[2]);
            if (d <= tolerance) pairs.push_back({d, v, u});
          }
        }
  }
  std::sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) { return a.d < b.d || (a.d == b.d && a.a < b.a); });
  for (const Pair& p : pairs) {
    if (m.mirror[p.a] >= 0 || m.mirror[p.b] >= 0) continue;
    m.mirror[p.a] = p.b;
    m.mirror[p.b] = p.a;
    m.by_position += p.a == p.b ? 1 : 2;
  }
  // By topology: an unmatched vertex whose matched neighbours' images share exactly one
  // unmatched neighbour takes it (nearest to its reflection when the rule is met both ways).
  for (bool progress = true; progress;) {
    progress = false;
    for (std::uint32_t v = 0; v < n; ++v) {
      if (m.mirror[v] >= 0) continue;
      std::vector<std::uint32_t> candidates;
      bool first = true, any = false;
      for (const std::uint32_t e : c.vertex_edges.row(v)) {
        const std::int64_t img = m.mirror[edge_other_end(c, e, v)];
        if (img < 0) continue;
        any = true;
        std::vector<std::uint32_t> near;
        for (const std::uint32_t f : c.vertex_edges.row(static_cast<std::uint32_t>(img))) {
          const std::uint32_t w = edge_other_end(c, f, static_cast<std::uint32_t>(img));
          if (m.mirror[w] < 0) near.push_back(w);
        }
        std::sort(near.begin(), near.end());
        if (first) {
          candidates = std::move(near);
          first = false;
        } else {
          std::vector<std::uint32_t> both;
          std::set_intersection(candidates.begin(), candidates.end(), near.begin(), near.end(), std::back_inserter(both));
          candidates = std::move(both);
        }
      }
      if (!any || candidates.size() != 1) continue;
      const std::uint32_t w = candidates.front();
      m.mirror[v] = w;
      m.mirror[w] = v;
      m.by_topology += v == w ? 1 : 2;
      progress = true;
    }
  }
  for (std::uint32_t v = 0; v < n; ++v)
    if (m.mirror[v] < 0) {
      ++m.unmatched;
      if (m.first_unmatched.size() < 8) m.first_unmatched.push_back(v);
    }
  return m;
}

void mirror_deltas(std::span<const MirrorMap* const> maps, std::vector<std::uint32_t>& vertices, std::vector<double>& deltas) {
  std::unordered_map<std::uint32_t, std::size_t> moved;  // vertex -> its entry
  for (std::size_t k = 0; k < vertices.size(); ++k) moved.emplace(vertices[k], k);
  // A vertex on a plane keeps its coordinate across it.
  for (const MirrorMap* m : maps)
    for (std::size_t k = 0; k < vertices.size(); ++k)
      if (vertices[k] < m->mirror.size() && m->mirror[vertices[k]] == vertices[k]) deltas[3 * k + m->axis] = 0.0;
  const std::size_t original = vertices.size();
  // Every non-empty combination of the axes: x, y, xy, z, xz, yz, xyz.
  for (unsigned mask = 1; mask < (1u << maps.size()); ++mask) {
    for (std::size_t k = 0; k < original; ++k) {
      std::int64_t img = vertices[k];
      double d[3] = {deltas[3 * k], deltas[3 * k + 1], deltas[3 * k + 2]};
      for (std::size_t a = 0; a < maps.size() && img >= 0; ++a)
        if (mask & (1u << a)) {
          img = static_cast<std::size_t>(img) < maps[a]->mirror.size() ? maps[a]->mirror[static_cast<std::size_t>(img)] : -1;
          d[maps[a]->axis] = -d[maps[a]->axis];
        }
      if (img < 0 || !moved.emplace(static_cast<std::uint32_t>(img), vertices.size()).second) continue;
      vertices.push_back(static_cast<std::uint32_t>(img));
      deltas.insert(deltas.end(), d, d + 3);
    }
  }
}

}  // namespace sublift
