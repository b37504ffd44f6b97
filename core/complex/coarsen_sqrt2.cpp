// Coarsening a closed quad mesh that is one sqrt(2) step (refine_sqrt2.h) of a polygon mesh:
// one quad (a, c_B, b, c_A) per coarse edge a-b, so corners alternate old vertices and face
// points, and the quads around a face point close into a fan whose old corners are the face.
// Meshes with curves (boundaries, creases) refine them only every other step, with triangles
// in between; they are not detected here (docs/rebuild.md).
#include <algorithm>
#include <string>

#include "core/complex/coarsen.h"

namespace sublift::detect {

namespace {

constexpr std::uint8_t kNone = 255;
constexpr std::uint8_t V = Coarsening::Old, F = Coarsening::FacePoint;

}  // namespace

Attempt coarsen_sqrt2(const Mesh& m, const Star& s, int candidate) {
  Attempt at;
  const std::uint32_t n = m.n;
  auto fail = [&](std::uint32_t v, std::string why) {
    at.ok = false;
    at.where = m.input[v];
    at.why = std::move(why);
    return at;
  };
  for (std::uint32_t v = 0; v < n; ++v)
    if (s.boundary[v])
      return fail(v, "vertex " + std::to_string(m.input[v]) +
                         " lies on a boundary; sqrt(2) levels are found in closed meshes only (boundaries refine every other step)");
  std::vector<std::uint8_t> lab(n, kNone);
  std::vector<std::uint32_t> queue;
  queue.reserve(n);
  std::uint32_t clash = UINT32_MAX;
  auto set = [&](std::uint32_t v, std::uint8_t l) {
    if (lab[v] == kNone) {
      lab[v] = l;
      ++at.progress;
      queue.push_back(v);
      return true;
    }
    if (lab[v] != l && clash == UINT32_MAX) clash = v;
    return lab[v] == l;
  };
  const auto q0 = m.faces.row(0);
  set(q0[0], candidate == 0 ? V : F);
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const std::uint32_t w = queue[head];
    const std::uint8_t other = lab[w] == V ? F : V;
    for (std::uint32_t f : s.vertex_faces.row(w)) {
      const auto q = m.faces.row(f);
      const unsigned k = corner_of(q, w);
      if (!set(q[(k + 1) & 3u], other) || !set(q[(k + 2) & 3u], lab[w]) || !set(q[(k + 3) & 3u], other))
        return fail(clash, "the quads around vertex " + std::to_string(m.input[clash]) +
                               " cannot alternate old vertices and face points as a sqrt(2) step makes them");
    }
  }
  for (std::uint32_t v = 0; v < n; ++v)
    if (lab[v] == kNone) return fail(v, "vertex " + std::to_string(m.input[v]) + " is not reached from the rest of its piece");

  Coarsening& c = at.c;
  c.kind = lab;
  c.a.assign(n, 0);
  c.b.assign(n, 0);
  std::vector<std::uint32_t> coarse_id(n);
  std::uint32_t nv = 0, nf = 0;
  for (std::uint32_t v = 0; v < n; ++v) coarse_id[v] = lab[v] == V ? nv++ : nf++;
  if (nv == 0 || nf == 0) return fail(0, "no vertex of a coarser mesh is left");
  // Old vertices: each quad around one is a coarse edge (its diagonal); no edge twice.
  std::vector<std::uint32_t> others;
  for (std::uint32_t v = 0; v < n; ++v) {
    if (lab[v] != V) continue;
    c.a[v] = coarse_id[v];
    if (s.vertex_faces.size(v) != 4) ++at.score;
    others.clear();
    for (std::uint32_t f : s.vertex_faces.row(v)) {
      const auto q = m.faces.row(f);
      others.push_back(q[(corner_of(q, v) + 2) & 3u]);
    }
    if (has_repeat(others))
      return fail(v, "two edges of the coarser mesh would join vertex " + std::to_string(m.input[v]) + " to the same vertex");
  }
  // Face points: a closed fan of n >= 3 quads; the corner after the face point starts each edge.
  c.coarse_faces.offsets.assign(1, 0);
  c.coarse_faces.items.reserve(n);
  for (std::uint32_t v = 0; v < n; ++v) {
    if (lab[v] != F) continue;
    c.a[v] = coarse_id[v];
    const auto fs = s.vertex_faces.row(v);
    if (fs.size() < 3) return fail(v, "face point " + std::to_string(m.input[v]) + " has " + std::to_string(fs.size()) + " quads; a face needs 3 or more");
    // The quads (face point, a, ., b) around it: corner a, one after it, starts edge a-b.
    others.clear();
    if (!fan_corners(m, s, v, 1, others))
      return fail(v, "the quads around face point " + std::to_string(m.input[v]) + " do not close into one fan");
    for (std::uint32_t x : others) c.coarse_faces.items.push_back(coarse_id[x]);
    if (has_repeat(others))
      return fail(v, "the face around face point " + std::to_string(m.input[v]) + " would visit a vertex twice");
    c.coarse_faces.offsets.push_back(static_cast<std::uint32_t>(c.coarse_faces.items.size()));
  }
  name_coarse_vertices(m, lab, coarse_id, nv, c);
  at.ok = true;
  return at;
}

}  // namespace sublift::detect
