// Coarsening a mesh that is one sqrt(2) step (refine_sqrt2.h) of a polygon mesh. Each coarse
// edge a-b inside makes a quad (a, c_B, b, c_A), so quad corners alternate old vertices and new
// points; around a new point its faces close into a fan whose old corners, in order, are its
// coarse face. Boundaries (curves) refine every other step:
//   keep step (coarse level even): a boundary edge x-y is kept and gets the triangle (x, y, c_X);
//     its apex is a face point, its ends old vertices;
//   curve step (coarse level odd): a boundary edge p-q of a triangle (q, p, k) gets a curve point
//     b, which lies on the fine boundary with the open fan (p, ., k, b), (q, b, k, .): the coarse
//     triangle is (p, k, q).
// A fine mesh with triangles is a keep step's child; one with boundary points and no triangles a
// curve step's. Creases (curves between two faces) are not detected (docs/rebuild.md).
#include <algorithm>
#include <string>

#include "core/complex/coarsen.h"

namespace sublift::detect {

namespace {

constexpr std::uint8_t N = Coarsening::FacePoint;  // a sqrt(2) step's new point

// The corner after and before v in face row q.
std::uint32_t after(std::span<const std::uint32_t> q, std::uint32_t v) { return q[(corner_of(q, v) + 1) % q.size()]; }
std::uint32_t before(std::span<const std::uint32_t> q, std::uint32_t v) { return q[(corner_of(q, v) + q.size() - 1) % q.size()]; }

// Whether edge x-y has only one face (a boundary edge): the faces around x holding y.
bool boundary_edge(const Mesh& m, const Star& s, std::uint32_t x, std::uint32_t y) {
  int n = 0;
  for (std::uint32_t f : s.vertex_faces.row(x)) {
    const auto q = m.faces.row(f);
    n += std::find(q.begin(), q.end(), y) != q.end();
  }
  return n == 1;
}

}  // namespace

Attempt coarsen_sqrt2(const Mesh& m, const Star& s, int candidate) {
  Attempt at;
  const std::uint32_t n = m.n;
  auto fail = [&](std::uint32_t v, std::string why) { return failed(at, m.input[v], std::move(why)); };
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
  auto conflict = [&](std::uint32_t v) {
    return fail(v, "the faces around vertex " + std::to_string(m.input[v]) + " cannot alternate old vertices and new points as a sqrt(2) step makes them");
  };
  // Triangles fix their labels: the boundary edge's ends are old, the apex a face point.
  bool triangles = false;
  for (std::size_t f = 0; f < m.faces.rows(); ++f) {
    const auto q = m.faces.row(f);
    if (q.size() != 3) continue;
    triangles = true;
    int k = -1;
    for (int i = 0; i < 3; ++i)
      if (boundary_edge(m, s, q[std::size_t(i)], q[std::size_t(i + 1) % 3])) k = k < 0 ? i : 3;
    if (k < 0)
      return fail(q[0], "the triangle at vertex " + std::to_string(m.input[q[0]]) +
                            " lies inside: a sqrt(2) step makes only quads there (triangles hang on boundary edges; creases are not detected)");
    if (k == 3)
      return fail(q[0], "the triangle at vertex " + std::to_string(m.input[q[0]]) + " has two boundary edges; a sqrt(2) step's triangles have one");
    if (!set(q[std::size_t(k)], V) || !set(q[std::size_t(k + 1) % 3], V) || !set(q[std::size_t(k + 2) % 3], N)) return conflict(clash);
  }
  if (triangles && candidate != 0) return at;  // the triangles decided: one labelling only
  if (!triangles) set(m.faces.row(0)[0], candidate == 0 ? V : N);
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const std::uint32_t w = queue[head];
    const std::uint8_t other = lab[w] == V ? N : V;
    for (std::uint32_t f : s.vertex_faces.row(w)) {
      const auto q = m.faces.row(f);
      if (q.size() != 4) continue;
      const unsigned k = corner_of(q, w);
      if (!set(q[(k + 1) & 3u], other) || !set(q[(k + 2) & 3u], lab[w]) || !set(q[(k + 3) & 3u], other)) return conflict(clash);
    }
  }
  for (std::uint32_t v = 0; v < n; ++v)
    if (lab[v] == kNone) return fail(v, "vertex " + std::to_string(m.input[v]) + " is not reached from the rest of its piece");

  Coarsening& c = at.c;
  c.kind.assign(n, V);
  c.a.assign(n, 0);
  c.b.assign(n, 0);
  std::vector<std::uint32_t> coarse_id(n, UINT32_MAX);
  std::uint32_t nv = 0;
  for (std::uint32_t v = 0; v < n; ++v)
    if (lab[v] == V) coarse_id[v] = nv++;
  if (nv == 0 || nv == n) return fail(0, "no vertex of a coarser mesh is left");
  // Old vertices: each quad's diagonal and each triangle's boundary edge is a coarse edge, once.
  if (!check_old_vertices(m, s, lab, coarse_id, 4, 2, [&](std::span<const std::uint32_t> q, unsigned k) {
    if (q.size() == 4) return q[(k + 2) & 3u];
    const std::uint32_t next = q[(k + 1) % 3];  // a triangle's boundary edge, from its first end
    return lab[next] == V ? next : UINT32_MAX;
  }, at))
    return at;
  std::vector<std::uint32_t> others;
  // New points: inside, a closed fan gives a coarse face; on the boundary (curve steps only) an
  // open fan of two quads gives a coarse triangle and the point is its boundary edge's curve point.
  c.coarse_faces.items.reserve(n);
  std::uint32_t nf = 0;
  for (std::uint32_t v = 0; v < n; ++v) {
    if (lab[v] != N) continue;
    const auto fs = s.vertex_faces.row(v);
    if (fs.size() < 2 || (!s.boundary[v] && fs.size() < 3))
      return fail(v, "new point " + std::to_string(m.input[v]) + " has " + std::to_string(fs.size()) + " faces; a face needs 3 or more corners");
    if (s.boundary[v] && (triangles || fs.size() != 2))
      return fail(v, "vertex " + std::to_string(m.input[v]) + " would be a new point on the boundary, which a sqrt(2) step makes only as the curve point of an edge (two quads)");
    // Start where the fan starts: any face when closed, the face no other continues when open.
    std::uint32_t first = fs[0];
    if (s.boundary[v])
      for (std::uint32_t f : fs) {
        const std::uint32_t a = after(m.faces.row(f), v);
        bool continued = false;
        for (std::uint32_t g : fs) continued = continued || (g != f && before(m.faces.row(g), v) == a);
        if (!continued) first = f;
      }
    others.clear();
    if (s.boundary[v]) others.push_back(after(m.faces.row(first), v));
    std::uint32_t f = first;
    for (std::size_t step = 0; step < fs.size(); ++step) {
      const auto q = m.faces.row(f);
      others.push_back(s.boundary[v] ? before(q, v) : after(q, v));
      std::uint32_t next = UINT32_MAX;
      for (std::uint32_t g : fs)
        if (g != f && after(m.faces.row(g), v) == before(q, v)) next = g;
      if (step + 1 == fs.size()) {
        if (s.boundary[v] ? next != UINT32_MAX : next != first)
          return fail(v, "the faces around new point " + std::to_string(m.input[v]) + " do not make one fan");
        break;
      }
      if (next == UINT32_MAX || next == first) return fail(v, "the faces around new point " + std::to_string(m.input[v]) + " do not make one fan");
      f = next;
    }
    for (std::uint32_t x : others)
      if (lab[x] != V) return fail(v, "the faces around new point " + std::to_string(m.input[v]) + " do not alternate");
    for (std::uint32_t x : others) c.coarse_faces.items.push_back(coarse_id[x]);
    c.coarse_faces.offsets.push_back(static_cast<std::uint32_t>(c.coarse_faces.items.size()));
    if (s.boundary[v]) {  // the curve point of the coarse boundary edge: its two boundary neighbours
      c.kind[v] = Coarsening::EdgePoint;
      c.a[v] = coarse_id[others.front()];
      c.b[v] = coarse_id[others.back()];
      at.curve_step = true;
    } else {
      c.kind[v] = Coarsening::FacePoint;
      c.a[v] = nf;
    }
    ++nf;
    if (has_repeat(others))
      return fail(v, "the face around new point " + std::to_string(m.input[v]) + " would visit a vertex twice");
  }
  at.keep_step = triangles;
  name_coarse_vertices(m.input, lab, coarse_id, nv, c);
  at.ok = true;
  return at;
}

}  // namespace sublift::detect
