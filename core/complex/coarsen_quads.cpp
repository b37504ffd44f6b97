// Coarsening a quad mesh that is one 1-to-4 split (refine.h) of a polygon mesh: every quad is
// (old vertex, edge point, face point, edge point) of its parent face's corner. Labels spread
// from a seed quad through old vertices and face points: around either, each quad's other
// corners are fixed (edge point, the opposite kind, edge point).
#include <algorithm>
#include <string>

#include "core/complex/coarsen.h"

namespace sublift::detect {

namespace {

const char* kind_word(std::uint8_t l) { return l == V ? "a vertex" : l == E ? "an edge point" : "a face point"; }

}  // namespace

Attempt coarsen_quads(const Mesh& m, const Star& s, int candidate) {
  Attempt at;
  const std::uint32_t n = m.n;
  std::vector<std::uint8_t> lab(n, kNone);
  std::vector<std::uint32_t> queue;
  queue.reserve(n / 2 + 1);
  auto fail = [&](std::uint32_t v, std::string why) { return failed(at, m.input[v], std::move(why)); };
  std::uint32_t clash = UINT32_MAX;
  std::uint8_t clash_want = 0;
  auto set = [&](std::uint32_t v, std::uint8_t l) {
    if (lab[v] == kNone) {
      lab[v] = l;
      ++at.progress;
      if (l != E) queue.push_back(v);
      return true;
    }
    if (lab[v] != l && clash == UINT32_MAX) clash = v, clash_want = l;
    return lab[v] == l;
  };

  static constexpr std::uint8_t kPattern[4] = {V, E, F, E};
  const auto q0 = m.faces.row(0);
  for (unsigned k = 0; k < 4; ++k) set(q0[k], kPattern[(k + static_cast<unsigned>(candidate)) & 3u]);
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const std::uint32_t w = queue[head];
    const std::uint8_t opposite = lab[w] == V ? F : V;
    for (std::uint32_t f : s.vertex_faces.row(w)) {
      const auto q = m.faces.row(f);
      const unsigned k = corner_of(q, w);
      if (!set(q[(k + 1) & 3u], E) || !set(q[(k + 2) & 3u], opposite) || !set(q[(k + 3) & 3u], E))
        return fail(clash, "the quads around vertex " + std::to_string(m.input[clash]) + " do not follow a quad split: it would be both " +
                               kind_word(lab[clash]) + " and " + kind_word(clash_want) + " of the coarser mesh");
    }
  }
  for (std::uint32_t v = 0; v < n; ++v)
    if (lab[v] == kNone) return fail(v, "vertex " + std::to_string(m.input[v]) + " is not reached from the rest of its piece by quads of a split");

  // Edge points: 4 quads (2 on a boundary) between two old vertices and 2 (1) face points.
  Coarsening& c = at.c;
  c.kind = lab;
  c.a.assign(n, 0);
  c.b.assign(n, 0);
  std::vector<std::uint32_t> coarse_id(n, UINT32_MAX);
  std::uint32_t nv = 0, nf = 0;
  for (std::uint32_t v = 0; v < n; ++v) coarse_id[v] = lab[v] == V ? nv++ : lab[v] == F ? nf++ : UINT32_MAX;
  if (nv == 0 || nf == 0) return fail(0, "no vertex of a coarser mesh is left");
  for (std::uint32_t v = 0; v < n; ++v) {
    if (lab[v] != E) continue;
    const auto fs = s.vertex_faces.row(v);
    const std::size_t want = s.boundary[v] ? 2 : 4;
    if (fs.size() != want)
      return fail(v, "vertex " + std::to_string(m.input[v]) + " has " + std::to_string(fs.size()) + " quads around it where an edge point needs " +
                         std::to_string(want) + (s.boundary[v] ? " (on a boundary)" : ""));
    std::uint32_t ends[2] = {UINT32_MAX, UINT32_MAX}, faces_seen[2] = {UINT32_MAX, UINT32_MAX};
    unsigned ne = 0, nfs = 0;
    for (std::uint32_t f : fs) {
      const auto q = m.faces.row(f);
      const unsigned k = corner_of(q, v);
      for (std::uint32_t x : {q[(k + 1) & 3u], q[(k + 3) & 3u]}) {
        std::uint32_t* list = lab[x] == V ? ends : faces_seen;
        unsigned& count = lab[x] == V ? ne : nfs;
        if (std::find(list, list + count, x) != list + count) continue;
        if (count == 2) return fail(v, "edge point " + std::to_string(m.input[v]) + " touches more than two vertices or faces of the coarser mesh");
        list[count++] = x;
      }
    }
    if (ne != 2 || nfs != want / 2)
      return fail(v, "edge point " + std::to_string(m.input[v]) + " does not sit between two vertices of the coarser mesh");
    c.a[v] = coarse_id[ends[0]];
    c.b[v] = coarse_id[ends[1]];
  }
  // An old vertex's edge points lead to distinct vertices (no doubled coarse edge).
  if (!check_old_vertices(m, s, lab, coarse_id, 4, 2, [&](std::span<const std::uint32_t> q, unsigned k) {
    const std::uint32_t e = q[(k + 1) & 3u];
    return c.a[e] == coarse_id[q[k]] ? c.b[e] : c.a[e];
  }, at))
    return at;
  std::vector<std::uint32_t> others;
  // Face points: inside, with a closed fan of n >= 3 quads whose old corners make the face.
  c.coarse_faces.items.reserve(n);
  for (std::uint32_t v = 0; v < n; ++v) {
    if (lab[v] != F) continue;
    c.a[v] = coarse_id[v];
    const auto fs = s.vertex_faces.row(v);
    if (s.boundary[v]) return fail(v, "vertex " + std::to_string(m.input[v]) + " would be a face point but lies on the boundary");
    if (fs.size() < 3) return fail(v, "face point " + std::to_string(m.input[v]) + " has " + std::to_string(fs.size()) + " quads; a face needs 3 or more");
    // The quads (face point, e, old, e') around it: their old corners, two after it.
    others.clear();
    if (!fan_corners(m, s, v, 2, others))
      return fail(v, "the quads around face point " + std::to_string(m.input[v]) + " do not close into one fan");
    for (std::uint32_t x : others) c.coarse_faces.items.push_back(coarse_id[x]);
    c.coarse_faces.offsets.push_back(static_cast<std::uint32_t>(c.coarse_faces.items.size()));
  }
  name_coarse_vertices(m.input, lab, coarse_id, nv, c);
  at.ok = true;
  return at;
}

}  // namespace sublift::detect
