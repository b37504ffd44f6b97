#include "core/fit/base_quads.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <tuple>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "core/base/edge_key.h"

namespace sublift {

namespace {

struct Candidate {
  double deviation;  // the quad's worst corner, degrees from 90
  std::uint32_t f, g;
  std::uint32_t quad[4];
};

}  // namespace

std::size_t pair_into_quads(BaseMesh& base, double max_corner_deviation_deg) {
  const Csr& faces = base.faces;
  const auto at = [&](std::uint32_t v) {
    return glm::dvec3(base.positions[3 * std::size_t(v)], base.positions[3 * std::size_t(v) + 1], base.positions[3 * std::size_t(v) + 2]);
  };
  // Half-edges of the triangles, sorted by their undirected edge: an inner edge is two of them.
  struct Half {
    std::uint64_t edge;
    std::uint32_t face, corner;  // the half-edge runs from corner to corner + 1
  };
  std::vector<Half> halves;
  for (std::uint32_t f = 0; f < faces.rows(); ++f) {
    const auto r = faces.row(f);
    if (r.size() != 3) continue;
    for (std::uint32_t k = 0; k < 3; ++k) halves.push_back({edge_key(r[k], r[(k + 1) % 3]), f, k});
  }
  std::sort(halves.begin(), halves.end(), [](const Half& a, const Half& b) { return std::tie(a.edge, a.face) < std::tie(b.edge, b.face); });
  std::vector<std::uint64_t> creases;
  for (const auto& [a, b] : base.tags.crease_edges) creases.push_back(edge_key(a, b));
  std::sort(creases.begin(), creases.end());

  std::vector<Candidate> candidates;
  for (std::size_t i = 0; i + 1 < halves.size(); ++i) {
    const Half &h = halves[i], &o = halves[i + 1];
    if (h.edge != o.edge || (i + 2 < halves.size() && halves[i + 2].edge == h.edge)) continue;
    if (std::binary_search(creases.begin(), creases.end(), h.edge)) continue;
    const auto rf = faces.row(h.face), rg = faces.row(o.face);
    const std::uint32_t a = rf[h.corner], b = rf[(h.corner + 1) % 3], c = rf[(h.corner + 2) % 3];
    const std::uint32_t d = rg[(o.corner + 2) % 3];
    if (rg[o.corner] != b || rg[(o.corner + 1) % 3] != a || d == c) continue;  // not opposite, or a doubled pair
    // f = (a, b, c) and g = (b, a, d) share a-b; without it the cycle is a -> d -> b -> c.
    const std::uint32_t q[4] = {a, d, b, c};
    glm::dvec3 p[4];
    for (int k = 0; k < 4; ++k) p[k] = at(q[k]);
    // Convex both ways: each diagonal splits the quad into two triangles facing alike.
    const glm::dvec3 n1 = glm::cross(p[1] - p[0], p[2] - p[0]), n2 = glm::cross(p[2] - p[0], p[3] - p[0]);
    const glm::dvec3 n3 = glm::cross(p[2] - p[1], p[3] - p[1]), n4 = glm::cross(p[3] - p[1], p[0] - p[1]);
    if (glm::dot(n1, n2) <= 0 || glm::dot(n3, n4) <= 0 || glm::dot(n1 + n2, n3 + n4) <= 0) continue;
    double worst = 0;
    for (int k = 0; k < 4; ++k) {
      const glm::dvec3 u = p[(k + 1) % 4] - p[k], w = p[(k + 3) % 4] - p[k];
      const double lu = glm::length(u), lw = glm::length(w);
      if (lu == 0 || lw == 0) {
        worst = 180;
        break;
      }
      const double angle = std::acos(std::clamp(glm::dot(u, w) / (lu * lw), -1.0, 1.0)) * 180.0 / std::numbers::pi;
      worst = std::max(worst, std::abs(angle - 90.0));
    }
    if (worst <= max_corner_deviation_deg) candidates.push_back({worst, h.face, o.face, {q[0], q[1], q[2], q[3]}});
  }
  std::stable_sort(candidates.begin(), candidates.end(), [](const Candidate& x, const Candidate& y) { return x.deviation < y.deviation; });

  // Greedy: the best quads first, each triangle in one quad at most. Then augmenting paths: an
  // unmatched triangle takes a partner's place, whose old partner moves on along the path to an
  // unmatched triangle, so two more triangles become a quad (the dual of a closed triangle mesh
  // is cubic and bridgeless, so it has a perfect matching: Petersen's theorem, Blossom-Quad).
  // Paths are searched depth-first to a bounded length (a heuristic: a general graph's odd
  // cycles can hide a path); each quad still passes the shape test.
  const std::size_t nf = faces.rows();
  std::vector<std::int64_t> merged(nf, -1);  // face -> candidate it joins
  std::vector<std::vector<std::uint32_t>> options(nf);  // face -> candidates it is in, best first
  for (std::uint32_t k = 0; k < candidates.size(); ++k) options[candidates[k].f].push_back(k), options[candidates[k].g].push_back(k);
  std::size_t quads = 0;
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    const Candidate& c = candidates[k];
    if (merged[c.f] >= 0 || merged[c.g] >= 0) continue;
    merged[c.f] = merged[c.g] = static_cast<std::int64_t>(k);
    ++quads;
  }
  const auto other = [&](std::uint32_t k, std::uint32_t f) { return candidates[k].f == f ? candidates[k].g : candidates[k].f; };
  std::vector<std::uint32_t> seen(nf, 0), path;
  std::uint32_t stamp = 0;
  constexpr int kMaxPath = 15;  // candidates on a path (odd: one more unmatched than matched)
  // Depth-first from unmatched face f: pairs f with a neighbour g; g's old partner h must pair on.
  const auto augment = [&](auto&& self, std::uint32_t f, int depth) -> bool {
    seen[f] = stamp;
    for (std::uint32_t k : options[f]) {
      const std::uint32_t g = other(k, f);
      if (seen[g] == stamp) continue;
      if (merged[g] < 0) {
        path.push_back(k);
        return true;
      }
      if (depth + 2 > kMaxPath) continue;
      const std::uint32_t h = other(static_cast<std::uint32_t>(merged[g]), g);
      if (seen[h] == stamp) continue;
      seen[g] = stamp;
      path.push_back(k);
      if (self(self, h, depth + 2)) return true;
      path.pop_back();
    }
    return false;
  };
  for (std::uint32_t f = 0; f < nf; ++f) {
    if (merged[f] >= 0 || options[f].empty()) continue;
    ++stamp;
    path.clear();
    if (!augment(augment, f, 1)) continue;
    for (std::uint32_t k : path) merged[candidates[k].f] = merged[candidates[k].g] = k;
    ++quads;
  }
  Csr out;
  for (std::uint32_t f = 0; f < faces.rows(); ++f) {
    if (merged[f] < 0) {
      const auto r = faces.row(f);
      out.items.insert(out.items.end(), r.begin(), r.end());
    } else {
      const Candidate& c = candidates[static_cast<std::size_t>(merged[f])];
      if (f != std::min(c.f, c.g)) continue;
      out.items.insert(out.items.end(), c.quad, c.quad + 4);
    }
    out.offsets.push_back(static_cast<std::uint32_t>(out.items.size()));
  }
  base.faces = std::move(out);
  return quads;
}

}  // namespace sublift
