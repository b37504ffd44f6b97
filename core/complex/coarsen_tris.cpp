// Coarsening a triangle mesh that is one 1-to-4 split (refine_tri.h): each parent triangle
// (A, B, C) left three corner triangles (A, eAB, eCA), ... and a middle one (eAB, eBC, eCA).
// From an old vertex A, its corner triangle (A, x, y) leads across x-y to the middle triangle
// (x, y, z), and across x-z and y-z to the corner triangles of the two other old vertices.
#include <algorithm>
#include <string>

#include "core/complex/coarsen.h"

namespace sublift::detect {

namespace {

constexpr std::uint8_t kCorner = 1, kMiddle = 2;

// The face other than f that holds both x and y; UINT32_MAX on a boundary edge, and
// UINT32_MAX - 1 where more than two faces share the edge.
std::uint32_t across(const Mesh& m, const Star& s, std::uint32_t f, std::uint32_t x, std::uint32_t y) {
  std::uint32_t found = UINT32_MAX;
  for (std::uint32_t g : s.vertex_faces.row(x)) {
    if (g == f) continue;
    const auto q = m.faces.row(g);
    if (q[0] == y || q[1] == y || q[2] == y) {
      if (found != UINT32_MAX) return UINT32_MAX - 1;
      found = g;
    }
  }
  return found;
}

std::uint32_t third(std::span<const std::uint32_t> q, std::uint32_t x, std::uint32_t y) {
  for (std::uint32_t v : q)
    if (v != x && v != y) return v;
  return UINT32_MAX;
}

}  // namespace

Attempt coarsen_tris(const Mesh& m, const Star& s, int candidate) {
  Attempt at;
  const std::uint32_t n = m.n, nt = static_cast<std::uint32_t>(m.faces.rows());
  std::vector<std::uint8_t> lab(n, kNone), role(nt, 0);
  std::vector<std::uint32_t> queue;
  queue.reserve(n / 4 + 1);
  auto fail = [&](std::uint32_t v, std::string why) { return failed(at, m.input[v], std::move(why)); };
  auto set = [&](std::uint32_t v, std::uint8_t l) {
    if (lab[v] == kNone) {
      lab[v] = l;
      ++at.progress;
      if (l == V) queue.push_back(v);
      return true;
    }
    return lab[v] == l;
  };
  auto conflict = [&](std::uint32_t v) {
    return fail(v, "the triangles around vertex " + std::to_string(m.input[v]) +
                       " do not follow a 1-to-4 triangle split (a flipped edge or a vertex of the wrong valence nearby)");
  };

  const auto q0 = m.faces.row(0);
  if (candidate < 3) {
    set(q0[static_cast<unsigned>(candidate)], V);
  } else {  // face 0 is a middle triangle: across its edge q0[0]-q0[1] lies a corner triangle
    const std::uint32_t g = across(m, s, 0, q0[0], q0[1]);
    if (g >= UINT32_MAX - 1) return conflict(q0[0]);
    set(third(m.faces.row(g), q0[0], q0[1]), V);
  }
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const std::uint32_t v = queue[head];
    for (std::uint32_t f : s.vertex_faces.row(v)) {
      const auto q = m.faces.row(f);
      const unsigned k = corner_of(q, v);
      const std::uint32_t x = q[(k + 1) % 3], y = q[(k + 2) % 3];
      if (!set(x, E) || !set(y, E) || role[f] == kMiddle) return conflict(v);
      role[f] = kCorner;
      const std::uint32_t mid = across(m, s, f, x, y);
      if (mid >= UINT32_MAX - 1 || role[mid] == kCorner) return conflict(x);
      role[mid] = kMiddle;
      const std::uint32_t z = third(m.faces.row(mid), x, y);
      if (!set(z, E)) return conflict(z);
      for (std::uint32_t e : {x, y}) {
        const std::uint32_t g = across(m, s, mid, e, z);
        if (g >= UINT32_MAX - 1 || role[g] == kMiddle) return conflict(e);
        role[g] = kCorner;
        if (!set(third(m.faces.row(g), e, z), V)) return conflict(e);
      }
    }
  }
  for (std::uint32_t v = 0; v < n; ++v)
    if (lab[v] == kNone) return fail(v, "vertex " + std::to_string(m.input[v]) + " is not reached from the rest of its piece by triangles of a split");
  std::uint32_t corners = 0, middles = 0;
  for (std::uint32_t f = 0; f < nt; ++f) {
    if (role[f] == 0) return fail(m.faces.row(f)[0], "a triangle at vertex " + std::to_string(m.input[m.faces.row(f)[0]]) + " is not reached by the split");
    (role[f] == kCorner ? corners : middles)++;
  }
  if (corners != 3 * middles) return fail(q0[0], "corner and middle triangles are not 3 to 1 as a split makes them");

  Coarsening& c = at.c;
  c.kind = lab;
  c.a.assign(n, 0);
  c.b.assign(n, 0);
  std::vector<std::uint32_t> coarse_id(n, UINT32_MAX);
  std::uint32_t nv = 0;
  for (std::uint32_t v = 0; v < n; ++v)
    if (lab[v] == V) coarse_id[v] = nv++;
  // Edge points: 6 triangles (3 on a boundary) and exactly two old vertices around.
  for (std::uint32_t v = 0; v < n; ++v) {
    if (lab[v] != E) continue;
    const auto fs = s.vertex_faces.row(v);
    const std::size_t want = s.boundary[v] ? 3 : 6;
    if (fs.size() != want)
      return fail(v, "vertex " + std::to_string(m.input[v]) + " has " + std::to_string(fs.size()) + " triangles around it where an edge point needs " +
                         std::to_string(want) + (s.boundary[v] ? " (on a boundary)" : ""));
    std::uint32_t ends[2] = {UINT32_MAX, UINT32_MAX};
    unsigned ne = 0;
    for (std::uint32_t f : fs)
      for (std::uint32_t x : m.faces.row(f)) {
        if (lab[x] != V || std::find(ends, ends + ne, x) != ends + ne) continue;
        if (ne == 2) return fail(v, "edge point " + std::to_string(m.input[v]) + " touches more than two vertices of the coarser mesh");
        ends[ne++] = x;
      }
    if (ne != 2) return fail(v, "edge point " + std::to_string(m.input[v]) + " does not sit between two vertices of the coarser mesh");
    c.a[v] = coarse_id[ends[0]];
    c.b[v] = coarse_id[ends[1]];
  }
  if (!check_old_vertices(m, s, lab, coarse_id, 6, 3, [&](std::span<const std::uint32_t> q, unsigned k) {
    const std::uint32_t e = q[(k + 1) % 3];
    return c.a[e] == coarse_id[q[k]] ? c.b[e] : c.a[e];
  }, at))
    return at;
  // One coarse triangle per middle triangle (e1, e2, e3): corners e3^e1, e1^e2, e2^e3, where
  // e^e' is the old vertex the two edges share; a middle triangle keeps its parent's orientation.
  auto shared = [&](std::uint32_t e, std::uint32_t g) {
    if (c.a[e] == c.a[g] || c.a[e] == c.b[g]) return c.a[e];
    if (c.b[e] == c.a[g] || c.b[e] == c.b[g]) return c.b[e];
    return UINT32_MAX;
  };
  c.coarse_faces.items.reserve(3 * static_cast<std::size_t>(middles));
  for (std::uint32_t f = 0; f < nt; ++f) {
    if (role[f] != kMiddle) continue;
    const auto q = m.faces.row(f);
    const std::uint32_t A = shared(q[2], q[0]), B = shared(q[0], q[1]), C = shared(q[1], q[2]);
    if (A == UINT32_MAX || B == UINT32_MAX || C == UINT32_MAX || A == B || B == C || A == C)
      return fail(q[0], "the middle triangle at vertex " + std::to_string(m.input[q[0]]) + " does not span one triangle of the coarser mesh");
    for (std::uint32_t x : {A, B, C}) c.coarse_faces.items.push_back(x);
    c.coarse_faces.offsets.push_back(static_cast<std::uint32_t>(c.coarse_faces.items.size()));
  }
  name_coarse_vertices(m.input, lab, coarse_id, nv, c);
  at.ok = true;
  return at;
}

}  // namespace sublift::detect
