#include "core/multires/limit.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <unordered_map>

#include "core/base/parallel.h"
#include "core/complex/polygon_normal.h"
#include "core/multires/limit_solve.h"

namespace sublift {
namespace {

constexpr std::uint32_t kGrain = 4096;
constexpr std::int32_t kOther = -1;  // dim of a patch primitive not incident to the centre (irrelevant)
constexpr std::size_t kKeyedRotations = 16;  // fans up to this valence key every rotation (canonical_patch)

// ---------------------------------------------------------------------------------------------
// Local patches: the feature-filtered closed star of a vertex as a small Complex whose vertex 0 is
// the centre. Only the dims of the centre and of primitives incident to it influence the star's
// evolution (the s-lift of a receiver reads only its own incident primitives of dim <= its own),
// so the others get the complex dimension and the key records just the relevant ones.

struct Patch {
  Complex c;
  std::vector<std::uint32_t> global;  // local vertex -> vertex of the source complex
  std::vector<std::int32_t> key;      // determines c completely
};

// First-appearance numbering of source ids (hashed: a patch of a valence-1000 vertex has
// thousands of vertices).
struct LocalIds {
  std::vector<std::uint32_t>& list;
  std::unordered_map<std::uint32_t, std::uint32_t> at{};
  // The local id of g and whether it was new.
  std::pair<std::uint32_t, bool> get(std::uint32_t g) {
    const auto [it, fresh] = at.try_emplace(g, static_cast<std::uint32_t>(list.size()));
    if (fresh) list.push_back(g);
    return {it->second, fresh};
  }
};

// Builds the patch of `v` from its star primitives in the given order (edges, faces, cells).
Patch make_patch(const Complex& C, std::uint32_t v, std::span<const std::uint32_t> E, std::span<const std::uint32_t> F,
                 std::span<const std::uint32_t> K) {
  Patch p;
  std::vector<std::uint32_t> gedges, gfaces;
  LocalIds verts{p.global}, edges{gedges}, faces{gfaces};
  verts.get(v);
  const std::uint8_t D = static_cast<std::uint8_t>(C.dim);
  auto add_edge = [&](std::uint32_t e) {
    const auto [le, fresh] = edges.get(e);
    if (fresh) {
      const std::uint32_t a = C.edge_verts[2 * std::size_t(e)], b = C.edge_verts[2 * std::size_t(e) + 1];
      std::uint32_t la = verts.get(a).first, lb = verts.get(b).first;
      if (la > lb) std::swap(la, lb);
      p.c.edge_verts.insert(p.c.edge_verts.end(), {la, lb});
      p.c.edge_dim.push_back(a == v || b == v ? C.edge_dim[e] : D);
    }
    return le;
  };
  for (std::uint32_t e : E) add_edge(e);
  auto add_face = [&](std::uint32_t f) {
    const auto [lf, fresh] = faces.get(f);
    if (!fresh) return lf;
    const auto vs = C.faces.row(f);
    const auto es = C.face_edges.row(f);
    const std::size_t n = vs.size();
    std::size_t start = n;
    for (std::size_t i = 0; i < n; ++i)
      if (vs[i] == v) start = i;
    const bool at_v = start != n;
    std::vector<std::uint32_t> lv(n), le(n);
    for (std::size_t i = 0; i < n; ++i) lv[i] = verts.get(vs[i]).first;
    if (!at_v) start = std::size_t(std::min_element(lv.begin(), lv.end()) - lv.begin());
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t i = (start + k) % n;
      p.c.faces.items.push_back(lv[i]);
      p.c.face_edges.items.push_back(add_edge(es[i]));
    }
    p.c.faces.offsets.push_back(static_cast<std::uint32_t>(p.c.faces.items.size()));
    p.c.face_edges.offsets.push_back(static_cast<std::uint32_t>(p.c.face_edges.items.size()));
    p.c.face_dim.push_back(at_v ? C.face_dim[f] : D);
    return lf;
  };
  for (std::uint32_t f : F) add_face(f);
  for (std::uint32_t k : K) {
    for (std::uint32_t f : C.cell_faces.row(k)) p.c.cell_faces.items.push_back(add_face(f));
    p.c.cell_faces.offsets.push_back(static_cast<std::uint32_t>(p.c.cell_faces.items.size()));
  }
  p.c.dim = C.dim;
  p.c.num_vertices = static_cast<std::uint32_t>(p.global.size());
  p.c.vertex_dim.assign(p.c.num_vertices, D);
  p.c.vertex_dim[0] = C.vertex_dim[v];
  // Key: everything above, in local numbering.
  auto& key = p.key;
  key = {C.dim, C.vertex_dim[v], std::int32_t(p.c.num_vertices), std::int32_t(p.c.num_edges())};
  for (std::uint32_t e = 0; e < p.c.num_edges(); ++e) {
    const bool at_v = p.c.edge_verts[2 * e] == 0;
    key.insert(key.end(), {std::int32_t(p.c.edge_verts[2 * e]), std::int32_t(p.c.edge_verts[2 * e + 1]),
                           at_v ? std::int32_t(p.c.edge_dim[e]) : kOther});
  }
  key.push_back(std::int32_t(p.c.num_faces()));
  for (std::uint32_t f = 0; f < p.c.num_faces(); ++f) {
    const auto vs = p.c.faces.row(f);
    key.push_back(std::int32_t(vs.size()));
    for (std::uint32_t x : vs) key.push_back(std::int32_t(x));
    for (std::uint32_t x : p.c.face_edges.row(f)) key.push_back(std::int32_t(x));
    key.push_back(vs[0] == 0 ? std::int32_t(p.c.face_dim[f]) : kOther);
  }
  key.push_back(std::int32_t(p.c.num_cells()));
  for (std::uint32_t k = 0; k < p.c.num_cells(); ++k) {
    key.push_back(std::int32_t(p.c.cell_faces.size(k)));
    for (std::uint32_t x : p.c.cell_faces.row(k)) key.push_back(std::int32_t(x));
  }
  return p;
}

// The upward rows the stencil builder reads (the finest level keeps none; only these are built).
struct Adj {
  const Csr& vertex_edges;
  const Csr& vertex_faces;
  const Csr& vertex_cells;
  const Csr& cell_verts;
};

// The feature-filtered star of v: incident primitives of feature dim <= dim(v), in stored order.
struct Star {
  std::vector<std::uint32_t> edges, faces, cells;
};

Star filtered_star(const Complex& C, const Adj& A, std::uint32_t v) {
  Star s;
  const std::uint8_t m = C.vertex_dim[v];
  for (std::uint32_t e : A.vertex_edges.row(v))
    if (C.edge_dim[e] <= m) s.edges.push_back(e);
  for (std::uint32_t f : A.vertex_faces.row(v))
    if (C.face_dim[f] <= m) s.faces.push_back(f);
  if (m == 3 && A.vertex_cells.rows() == C.num_vertices)
    for (std::uint32_t k : A.vertex_cells.row(v)) s.cells.push_back(k);
  return s;
}

// The patch in canonical order where the star is a closed fan of faces (each star edge in exactly
// two star faces, one cycle): the smallest key over all starting faces and both directions, so
// that rotated copies of a configuration share one cache entry. Elsewhere: stored order.
Patch canonical_patch(const Complex& C, std::uint32_t v, const Star& s) {
  const std::size_t n = s.faces.size();
  bool fan = s.cells.empty() && n >= 1 && s.edges.size() == n;
  std::vector<std::array<std::uint32_t, 2>> fe(n);  // the two star edges of each face at v
  for (std::size_t i = 0; fan && i < n; ++i) {
    const auto vs = C.faces.row(s.faces[i]);
    const auto es = C.face_edges.row(s.faces[i]);
    int found = 0;
    for (std::size_t k = 0; k < vs.size(); ++k)
      if (vs[k] == v) {
        ++found;
        fe[i] = {es[(k + vs.size() - 1) % vs.size()], es[k]};
      }
    fan = found == 1;
  }
  std::vector<std::uint32_t> cyc_f, cyc_e;  // face i lies between edges i and i+1
  if (fan) {
    auto in_star = [&](std::uint32_t e) { return std::find(s.edges.begin(), s.edges.end(), e) != s.edges.end(); };
    for (std::size_t i = 0; i < n && fan; ++i) fan = in_star(fe[i][0]) && in_star(fe[i][1]);
    for (std::uint32_t e : s.edges) {
      int uses = 0;
      for (std::size_t i = 0; i < n; ++i) uses += (fe[i][0] == e) + (fe[i][1] == e);
      fan = fan && uses == 2;
    }
    std::size_t cur = 0;
    std::uint32_t enter = fan ? fe[0][0] : 0;
    std::vector<char> seen(n, 0);
    while (fan && !seen[cur]) {
      seen[cur] = 1;
      cyc_f.push_back(s.faces[cur]);
      cyc_e.push_back(enter);
      const std::uint32_t exit = fe[cur][0] == enter ? fe[cur][1] : fe[cur][0];
      std::size_t next = n;
      for (std::size_t i = 0; i < n; ++i)
        if (i != cur && (fe[i][0] == exit || fe[i][1] == exit)) next = i;
      if (next == n) fan = false;
      cur = next;
      enter = exit;
    }
    fan = fan && cyc_f.size() == n && cur == 0;
  }
  if (!fan) return make_patch(C, v, s.edges, s.faces, s.cells);
  // The star edges and faces from cyclic position `start`, forwards (dir 0) or backwards.
  std::vector<std::uint32_t> es(n), fs(n);
  auto order = [&](std::size_t start, int dir) {
    for (std::size_t k = 0; k < n; ++k) {
      if (dir == 0) {
        es[k] = cyc_e[(start + k) % n];
        fs[k] = cyc_f[(start + k) % n];
      } else {
        es[k] = cyc_e[(start + n - k) % n];
        fs[k] = cyc_f[(start + 2 * n - k - 1) % n];
      }
    }
  };
  // Large fans: the key of every start costs O(n^2) in all, so only the starts whose sequence of
  // (face size, face dim, edge dim) is smallest are keyed, one per direction. Any start gives a
  // correct patch; the choice only decides which rotated copies share a cache entry.
  std::vector<std::size_t> starts[2];
  if (n <= kKeyedRotations) {
    for (int dir = 0; dir < 2; ++dir)
      for (std::size_t start = 0; start < n; ++start) starts[dir].push_back(start);
  } else {
    auto sig = [&](std::size_t start, int dir, std::size_t k) {
      const std::uint32_t f = dir == 0 ? cyc_f[(start + k) % n] : cyc_f[(start + 2 * n - k - 1) % n];
      const std::uint32_t e = dir == 0 ? cyc_e[(start + k) % n] : cyc_e[(start + n - k) % n];
      return std::array<std::uint32_t, 3>{C.faces.size(f), C.face_dim[f], C.edge_dim[e]};
    };
    for (int dir = 0; dir < 2; ++dir) {
      std::size_t best = 0;
      for (std::size_t start = 1; start < n; ++start)
        for (std::size_t k = 0; k < n; ++k) {
          const auto a = sig(start, dir, k), b = sig(best, dir, k);
          if (a != b) {
            if (a < b) best = start;
            break;
          }
        }
      starts[dir].push_back(best);
    }
  }
  Patch best;
  for (int dir = 0; dir < 2; ++dir)
    for (const std::size_t start : starts[dir]) {
      order(start, dir);
      Patch p = make_patch(C, v, es, fs, {});
      if (best.key.empty() || p.key < best.key) best = std::move(p);
    }
  return best;
}

// ---------------------------------------------------------------------------------------------
// Fast paths for the regular configurations (exact rational masks).

enum Kind : std::uint8_t { kIdentity, kCurve, kQuad, kHex, kGeneric };

struct Regular {
  Kind kind = kGeneric;
  std::uint32_t n = 0;
  std::array<std::uint32_t, 27> verts{};  // star, centre first
  std::array<double, 27> w{}, du{}, dv{};
};

// Classifies v; fills r for the regular kinds.
void classify(const Complex& C, const Adj& A, std::uint32_t v, Regular& r) {
  const std::uint8_t m = C.vertex_dim[v];
  r.kind = kGeneric;
  if (m == 0) {
    r.kind = kIdentity;
    r.n = 1;
    r.verts[0] = v;
    r.w[0] = 1.0;
    return;
  }
  if (m == 1) {
    std::uint32_t nb[2], cnt = 0;
    for (std::uint32_t e : A.vertex_edges.row(v))
      if (C.edge_dim[e] <= 1) {
        if (cnt == 2) return;
        nb[cnt++] = edge_other_end(C, e, v);
      }
    if (cnt != 2 || nb[0] == nb[1]) return;
    r.kind = kCurve;
    r.n = 3;
    r.verts[0] = v, r.verts[1] = nb[0], r.verts[2] = nb[1];
    r.w[0] = 2.0 / 3.0, r.w[1] = 1.0 / 6.0, r.w[2] = 1.0 / 6.0;
    return;
  }
  if (m == 2) {
    // Four quads of dim 2 at v, four dim-2 edges, one closed fan.
    std::uint32_t fq[4], cnt = 0;
    for (std::uint32_t f : A.vertex_faces.row(v))
      if (C.face_dim[f] <= 2) {
        if (cnt == 4 || C.faces.size(f) != 4) return;
        fq[cnt++] = f;
      }
    if (cnt != 4) return;
    std::uint32_t ecnt = 0;
    for (std::uint32_t e : A.vertex_edges.row(v))
      if (C.edge_dim[e] <= 2) {
        if (C.edge_dim[e] != 2 || ecnt == 4) return;
        ++ecnt;
      }
    if (ecnt != 4) return;
    std::uint32_t nxt[4], prv[4], diag[4];
    for (int i = 0; i < 4; ++i) {
      const auto q = C.faces.row(fq[i]);
      int at = -1;
      for (int k = 0; k < 4; ++k)
        if (q[k] == v) {
          if (at >= 0) return;
          at = k;
        }
      if (at < 0) return;
      nxt[i] = q[(at + 1) & 3], diag[i] = q[(at + 2) & 3], prv[i] = q[(at + 3) & 3];
      const std::uint32_t e_in = C.face_edges.row(fq[i])[(at + 3) & 3], e_out = C.face_edges.row(fq[i])[at];
      if (C.edge_dim[e_in] != 2 || C.edge_dim[e_out] != 2) return;
    }
    // Neighbours: each appears as nxt of one face and prv of another (closed, oriented fan) or
    // twice with flipped orientation; require exactly four distinct, each in exactly two faces.
    std::uint32_t nb[4], nn = 0;
    for (int i = 0; i < 4; ++i)
      for (std::uint32_t x : {nxt[i], prv[i]}) {
        bool have = false;
        for (std::uint32_t k = 0; k < nn; ++k) have |= nb[k] == x;
        if (!have) {
          if (nn == 4) return;
          nb[nn++] = x;
        }
      }
    if (nn != 4) return;
    for (std::uint32_t k = 0; k < 4; ++k) {
      int uses = 0;
      for (int i = 0; i < 4; ++i) uses += (nxt[i] == nb[k]) + (prv[i] == nb[k]);
      if (uses != 2) return;
      for (int i = 0; i < 4; ++i)
        if (diag[i] == nb[k] || diag[i] == v) return;
    }
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
        if (diag[i] == diag[j]) return;
    // Axes: u towards nxt[0], v towards prv[0] (so du x dv follows face 0's orientation).
    const std::uint32_t a = nxt[0], b = prv[0];
    auto shares_face = [&](std::uint32_t x, std::uint32_t y) {
      for (int i = 0; i < 4; ++i)
        if ((nxt[i] == x && prv[i] == y) || (nxt[i] == y && prv[i] == x)) return true;
      return false;
    };
    std::uint32_t a_opp = ~0u, b_opp = ~0u;
    for (std::uint32_t k = 0; k < 4; ++k) {
      if (nb[k] != a && !shares_face(a, nb[k])) a_opp = nb[k];
      if (nb[k] != b && !shares_face(b, nb[k])) b_opp = nb[k];
    }
    for (std::uint32_t k = 0; k < 4; ++k) {  // the link is one 4-cycle, not two 2-cycles
      int adjacent = 0;
      for (std::uint32_t j = 0; j < 4; ++j) adjacent += j != k && shares_face(nb[k], nb[j]);
      if (adjacent != 2) return;
    }
    if (a_opp == ~0u || b_opp == ~0u || a_opp == b || b_opp == a) return;
    r.kind = kQuad;
    r.n = 9;
    r.verts[0] = v;
    r.w[0] = 16.0 / 36.0, r.du[0] = 0, r.dv[0] = 0;
    const std::uint32_t ring[4] = {a, b, a_opp, b_opp};
    const double su[4] = {1, 0, -1, 0}, sv[4] = {0, 1, 0, -1};
    for (int k = 0; k < 4; ++k) {
      r.verts[1 + k] = ring[k];
      r.w[1 + k] = 4.0 / 36.0;
      r.du[1 + k] = su[k] / 3.0;
      r.dv[1 + k] = sv[k] / 3.0;
    }
    for (int i = 0; i < 4; ++i) {
      // Diagonal of face i sits at (+-1, +-1): the signs of the face's two edge neighbours.
      double x = 0, y = 0;
      for (std::uint32_t nbr : {nxt[i], prv[i]}) {
        if (nbr == a) x = 1;
        if (nbr == a_opp) x = -1;
        if (nbr == b) y = 1;
        if (nbr == b_opp) y = -1;
      }
      if (x == 0 || y == 0) return;
      r.verts[5 + i] = diag[i];
      r.w[5 + i] = 1.0 / 36.0;
      r.du[5 + i] = x / 12.0;
      r.dv[5 + i] = y / 12.0;
    }
    return;
  }
  // m == 3: six dim-3 edges, twelve dim-3 quads each on ... four-valent links, eight hexahedra.
  if (A.vertex_cells.rows() != C.num_vertices) return;
  const auto ve = A.vertex_edges.row(v), vf = A.vertex_faces.row(v), vk = A.vertex_cells.row(v);
  if (ve.size() != 6 || vf.size() != 12 || vk.size() != 8) return;
  for (std::uint32_t e : ve)
    if (C.edge_dim[e] != 3) return;
  std::uint32_t n = 0;
  r.verts[n++] = v;
  for (std::uint32_t e : ve) r.verts[n++] = edge_other_end(C, e, v);
  for (std::uint32_t f : vf) {
    if (C.face_dim[f] != 3 || C.faces.size(f) != 4) return;
    const auto q = C.faces.row(f);
    int at = -1;
    for (int k = 0; k < 4; ++k)
      if (q[k] == v) at = k;
    r.verts[n++] = q[(at + 2) & 3];
  }
  // Each edge on four of the faces (the link is an octahedron).
  for (std::uint32_t e : ve) {
    int uses = 0;
    for (std::uint32_t f : vf)
      for (std::uint32_t x : C.face_edges.row(f)) uses += x == e;
    if (uses != 4) return;
  }
  for (std::uint32_t k : vk) {
    if (C.cell_faces.size(k) != 6 || A.cell_verts.size(k) != 8) return;
    // Opposite vertex: on none of the cell's faces through v.
    std::uint32_t opp = ~0u;
    int through = 0;
    for (std::uint32_t f : C.cell_faces.row(k)) {
      const auto q = C.faces.row(f);
      through += std::find(q.begin(), q.end(), v) != q.end();
    }
    if (through != 3) return;
    for (std::uint32_t x : A.cell_verts.row(k)) {
      bool on = false;
      for (std::uint32_t f : C.cell_faces.row(k)) {
        const auto q = C.faces.row(f);
        if (std::find(q.begin(), q.end(), v) != q.end() && std::find(q.begin(), q.end(), x) != q.end()) on = true;
      }
      if (!on) {
        if (opp != ~0u) return;
        opp = x;
      }
    }
    if (opp == ~0u) return;
    r.verts[n++] = opp;
  }
  // All 27 distinct.
  std::array<std::uint32_t, 27> sorted = r.verts;
  std::sort(sorted.begin(), sorted.end());
  if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) return;
  r.kind = kHex;
  r.n = 27;
  r.w[0] = 64.0 / 216.0;
  for (int i = 1; i <= 6; ++i) r.w[i] = 16.0 / 216.0;
  for (int i = 7; i <= 18; ++i) r.w[i] = 4.0 / 216.0;
  for (int i = 19; i <= 26; ++i) r.w[i] = 1.0 / 216.0;
}

inline void cross(const double* a, const double* b, double* c) {
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

// The limit position of v from its stencil row.
inline void limit_row(const LimitStencils& s, std::uint32_t v, const double* control, double* out) {
  double acc[3] = {0, 0, 0};
  for (std::uint32_t k = s.rows.offsets[v]; k < s.rows.offsets[v + 1]; ++k) {
    const double* p = control + 3 * std::size_t(s.rows.items[k]);
    const double w = s.weights[k];
    acc[0] += w * p[0], acc[1] += w * p[1], acc[2] += w * p[2];
  }
  out[0] = acc[0], out[1] = acc[1], out[2] = acc[2];
}

// tu x tv of v's exact tangents; false when v has none or they are degenerate.
inline bool tangent_cross(const LimitStencils& s, std::uint32_t v, const double* control, double* t) {
  const std::uint32_t b = s.tangent_rows.offsets[v], e = s.tangent_rows.offsets[v + 1];
  if (b == e) return false;
  double tu[3] = {0, 0, 0}, tv[3] = {0, 0, 0};
  for (std::uint32_t k = b; k < e; ++k) {
    const double* p = control + 3 * std::size_t(s.tangent_rows.items[k]);
    for (int c = 0; c < 3; ++c) tu[c] += s.du[k] * p[c], tv[c] += s.dv[k] * p[c];
  }
  cross(tu, tv, t);
  const double tl = std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
  const double lu = std::sqrt(tu[0] * tu[0] + tu[1] * tu[1] + tu[2] * tu[2]);
  const double lv = std::sqrt(tv[0] * tv[0] + tv[1] * tv[1] + tv[2] * tv[2]);
  return tl > 1e-12 * lu * lv && tl > 0;
}

// Final normal of v from its face-normal sum `fn` and the tangent stencils.
inline void finish_normal(const LimitStencils& s, std::uint32_t v, const double* control, const double* fn, double* out) {
  double n[3] = {fn[0], fn[1], fn[2]}, t[3];
  if (tangent_cross(s, v, control, t)) {
    const double d = t[0] * fn[0] + t[1] * fn[1] + t[2] * fn[2];
    const double sign = d < 0 ? -1.0 : 1.0;
    for (int c = 0; c < 3; ++c) n[c] = sign * t[c];
  }
  const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  for (int c = 0; c < 3; ++c) out[c] = len > 0 ? n[c] / len : 0.0;
}

}  // namespace

ProbedStencil probe_limit_stencil(const Complex& c, std::uint32_t v, LimitSolver solver) {
  const Adj A{c.vertex_edges, c.vertex_faces, c.vertex_cells, c.cell_verts};
  const Patch p = canonical_patch(c, v, filtered_star(c, A, v));
  ProbedStencil out;
  static_cast<PatchSolution&>(out) = solve_limit_patch(p.c, solver);
  out.vertices = p.global;
  return out;
}

LimitStencils build_limit_stencils(const Hierarchy& h) {
  LimitStencils s;
  const Complex& fin = h.levels.back();
  const std::uint32_t nv = fin.num_vertices;
  if (scheme_info(h.scheme).limit == LimitRule::ControlNet) {  // the limit is the control net
    s.rows.offsets.resize(std::size_t(nv) + 1);
    std::iota(s.rows.offsets.begin(), s.rows.offsets.end(), 0u);
    s.rows.items.resize(nv);
    std::iota(s.rows.items.begin(), s.rows.items.end(), 0u);
    s.weights.assign(nv, 1.0);
    s.tangent_rows.offsets.assign(std::size_t(nv) + 1, 0);
    s.users = s.rows;
    return s;
  }
  if (scheme_info(h.scheme).limit == LimitRule::LoopMasks) {  // Loop's limit masks; normals from the faces (no tangent rows)
    scheme_info(h.scheme).limit_rows(fin, s.rows, s.weights);
    s.tangent_rows.offsets.assign(std::size_t(nv) + 1, 0);
    s.users = transpose(s.rows, nv);
    return s;
  }
  Complex copy;
  Csr vertex_edges, vertex_faces;
  const bool has_adj = fin.vertex_edges.rows() == nv && (fin.num_cells() == 0 || fin.vertex_cells.rows() == nv);
  if (!has_adj && fin.num_cells()) {  // lattices: everything (cells' vertices included)
    copy.dim = fin.dim;
    copy.num_vertices = nv;
    copy.edge_verts = fin.edge_verts;
    copy.faces = fin.faces;
    copy.face_edges = fin.face_edges;
    copy.cell_faces = fin.cell_faces;
    copy.vertex_dim = fin.vertex_dim;
    copy.edge_dim = fin.edge_dim;
    copy.face_dim = fin.face_dim;
    build_adjacency(copy);
  } else if (!has_adj) {  // curves and surfaces: just the two upward rows read below
    vertex_edges = transpose_pairs(fin.edge_verts, nv);
    vertex_faces = transpose(fin.faces, nv);
  }
  const bool use_copy = !has_adj && fin.num_cells();
  const Complex& C = use_copy ? copy : fin;
  const Adj A = has_adj || use_copy ? Adj{C.vertex_edges, C.vertex_faces, C.vertex_cells, C.cell_verts}
                                    : Adj{vertex_edges, vertex_faces, fin.vertex_cells, fin.cell_verts};

  // Pass 1: row lengths of the regular kinds; the rest are solved below.
  std::vector<std::uint8_t> kind(nv);
  s.rows.offsets.assign(std::size_t(nv) + 1, 0);
  s.tangent_rows.offsets.assign(std::size_t(nv) + 1, 0);
  parallel_for(nv, kGrain, [&](std::uint32_t b, std::uint32_t e) {
    Regular r;
    for (std::uint32_t v = b; v < e; ++v) {
      classify(C, A, v, r);
      kind[v] = r.kind;
      s.rows.offsets[v + 1] = r.kind == kGeneric ? 0 : r.n;
      s.tangent_rows.offsets[v + 1] = r.kind == kQuad ? r.n - 1 : 0;
    }
  });
  // Generic vertices: canonical patch, cached solve.
  std::map<std::vector<std::int32_t>, PatchSolution> cache;
  struct GenericRow {
    std::uint32_t v;
    std::vector<std::uint32_t> verts;
    const PatchSolution* solved;
  };
  std::vector<GenericRow> generic;
  for (std::uint32_t v = 0; v < nv; ++v) {
    if (kind[v] != kGeneric) continue;
    Patch p = canonical_patch(C, v, filtered_star(C, A, v));
    auto it = cache.find(p.key);
    if (it == cache.end()) it = cache.emplace(p.key, solve_limit_patch(p.c, LimitSolver::Auto)).first;
    const PatchSolution& sol = it->second;
    if (sol.ok) {
      ++s.extraordinary;
      s.rows.offsets[v + 1] = static_cast<std::uint32_t>(p.global.size());
      s.tangent_rows.offsets[v + 1] = sol.du.empty() ? 0 : static_cast<std::uint32_t>(p.global.size());
      generic.push_back({v, std::move(p.global), &sol});
    } else {
      ++s.unsolved;
      kind[v] = kIdentity;
      s.rows.offsets[v + 1] = 1;
    }
  }
  s.configurations = cache.size();
  for (std::size_t v = 0; v < nv; ++v) {
    s.rows.offsets[v + 1] += s.rows.offsets[v];
    s.tangent_rows.offsets[v + 1] += s.tangent_rows.offsets[v];
  }
  s.rows.items.resize(s.rows.offsets.back());
  s.weights.resize(s.rows.offsets.back());
  s.tangent_rows.items.resize(s.tangent_rows.offsets.back());
  s.du.resize(s.tangent_rows.offsets.back());
  s.dv.resize(s.tangent_rows.offsets.back());
  // Pass 2: fill.
  parallel_for(nv, kGrain, [&](std::uint32_t b, std::uint32_t e) {
    Regular r;
    for (std::uint32_t v = b; v < e; ++v) {
      if (kind[v] == kGeneric) continue;
      const std::uint32_t o = s.rows.offsets[v];
      if (kind[v] == kIdentity) {
        s.rows.items[o] = v;
        s.weights[o] = 1.0;
        continue;
      }
      classify(C, A, v, r);
      for (std::uint32_t k = 0; k < r.n; ++k) {
        s.rows.items[o + k] = r.verts[k];
        s.weights[o + k] = r.w[k];
      }
      if (r.kind == kQuad) {
        const std::uint32_t t = s.tangent_rows.offsets[v] - 1;  // slot 0 (the centre) has zero weights
        for (std::uint32_t k = 1; k < r.n; ++k) {
          s.tangent_rows.items[t + k] = r.verts[k];
          s.du[t + k] = r.du[k];
          s.dv[t + k] = r.dv[k];
        }
      }
    }
  });
  for (const GenericRow& g : generic) {
    const std::uint32_t o = s.rows.offsets[g.v];
    for (std::size_t k = 0; k < g.verts.size(); ++k) {
      s.rows.items[o + k] = g.verts[k];
      s.weights[o + k] = g.solved->weights[k];
    }
    if (!g.solved->du.empty()) {
      const std::uint32_t t = s.tangent_rows.offsets[g.v];
      for (std::size_t k = 0; k < g.verts.size(); ++k) {
        s.tangent_rows.items[t + k] = g.verts[k];
        s.du[t + k] = g.solved->du[k];
        s.dv[t + k] = g.solved->dv[k];
      }
    }
  }
  // Tangent rows always read a subset of the position row's vertices, so users = transpose(rows).
  s.users = transpose(s.rows, nv);
  return s;
}

void eval_limit(const LimitStencils& s, const double* control, double* limit) {
  const std::uint32_t nv = static_cast<std::uint32_t>(s.rows.rows());
  parallel_for(nv, kGrain, [&](std::uint32_t b, std::uint32_t e) {
    for (std::uint32_t v = b; v < e; ++v) limit_row(s, v, control, limit + 3 * std::size_t(v));
  });
}

// Vertices per chunk of the subset updates (a drag changes ~10^4).
constexpr std::uint32_t kSubsetGrain = 2048;

// The limit vertices reading a changed control vertex (`fresh`), those not yet in changed_limit
// appended to it.
static void find_subset(const LimitStencils& s, std::span<const std::uint32_t> changed_control,
                        std::vector<std::uint32_t>& changed_limit, std::vector<std::uint32_t>& fresh) {
  // Stamps instead of sorting: a drag calls this every frame with ~10^5 user entries.
  thread_local std::vector<std::uint32_t> stamp;
  thread_local std::uint32_t epoch = 0;
  const std::size_t nv = s.rows.rows();
  if (stamp.size() < nv) stamp.assign(nv, 0), epoch = 0;
  if (epoch >= 0xfffffff0u) std::fill(stamp.begin(), stamp.end(), 0u), epoch = 0;
  ++epoch;
  for (std::uint32_t v : changed_limit)
    if (v < nv) stamp[v] = epoch;  // already listed: recomputed below if needed, not appended again
  fresh.clear();
  for (std::uint32_t u : changed_control)
    for (std::uint32_t v : s.users.row(u)) {
      if (stamp[v] == epoch + 1) continue;
      if (stamp[v] != epoch) changed_limit.push_back(v);
      stamp[v] = epoch + 1;
      fresh.push_back(v);
    }
  ++epoch;  // epoch + 1 marked "recomputed"
}

void eval_limit_subset(const LimitStencils& s, const double* control, std::span<const std::uint32_t> changed_control,
                       double* limit, std::vector<std::uint32_t>& changed_limit) {
  LimitStencils::SubsetPlan& plan = s.subset_plan;
  const bool replay = !plan.fresh.empty() && std::equal(changed_control.begin(), changed_control.end(), plan.control.begin(),
                                                        plan.control.end()) && changed_limit == plan.limit_in;
  if (replay) {
    ++plan.replays;
    changed_limit.insert(changed_limit.end(), plan.appended.begin(), plan.appended.end());
  } else {
    plan.control.assign(changed_control.begin(), changed_control.end());
    plan.limit_in = changed_limit;
    find_subset(s, changed_control, changed_limit, plan.fresh);
    // In vertex order: the stencils are then read in a few forward sweeps instead of at random
    // (the rows are independent, so the values are the same), here and in the caller's normals.
    std::sort(plan.fresh.begin(), plan.fresh.end());
    std::sort(changed_limit.begin() + std::ptrdiff_t(plan.limit_in.size()), changed_limit.end());
    plan.appended.assign(changed_limit.begin() + std::ptrdiff_t(plan.limit_in.size()), changed_limit.end());
  }
  const std::vector<std::uint32_t>& fresh = plan.fresh;
  parallel_for(static_cast<std::uint32_t>(fresh.size()), kSubsetGrain, [&](std::uint32_t b, std::uint32_t e) {
    for (std::uint32_t i = b; i < e; ++i) limit_row(s, fresh[i], control, limit + 3 * std::size_t(fresh[i]));
  });
}

void limit_normals(const LimitStencils& s, const Csr& faces, const double* control, const double* limit,
                   double* normals) {
  const std::uint32_t nv = static_cast<std::uint32_t>(s.rows.rows());
  const std::uint32_t nf = static_cast<std::uint32_t>(faces.rows());
  std::vector<double> fn(3 * std::size_t(nf));
  parallel_for(nf, kGrain, [&](std::uint32_t b, std::uint32_t e) {
    for (std::uint32_t f = b; f < e; ++f) polygon_area_vector(faces.row(f), limit, &fn[3 * std::size_t(f)]);
  });
  std::vector<double> acc(3 * std::size_t(nv), 0.0);
  for (std::uint32_t f = 0; f < nf; ++f)
    for (std::uint32_t v : faces.row(f))
      for (int c = 0; c < 3; ++c) acc[3 * std::size_t(v) + c] += fn[3 * std::size_t(f) + c];
  parallel_for(nv, kGrain, [&](std::uint32_t b, std::uint32_t e) {
    for (std::uint32_t v = b; v < e; ++v)
      finish_normal(s, v, control, &acc[3 * std::size_t(v)], normals + 3 * std::size_t(v));
  });
}

void orient_tangents(LimitStencils& s, const Csr& faces, const double* control, const double* limit) {
  const std::uint32_t nv = static_cast<std::uint32_t>(s.rows.rows());
  std::vector<double> acc(3 * std::size_t(nv), 0.0);
  accumulate_face_normals(faces, limit, acc.data());
  s.tangent_sign.assign(nv, 0);
  parallel_for(nv, kGrain, [&](std::uint32_t b, std::uint32_t e) {
    for (std::uint32_t v = b; v < e; ++v) {
      double t[3];
      if (!tangent_cross(s, v, control, t)) continue;
      const double* fn = &acc[3 * std::size_t(v)];
      const double d = t[0] * fn[0] + t[1] * fn[1] + t[2] * fn[2];
      if (d != 0.0) s.tangent_sign[v] = d < 0 ? -1 : 1;
    }
  });
}

void limit_normals_subset(const LimitStencils& s, const Csr& faces, const Csr& vertex_faces, const double* control,
                          const double* limit, std::span<const std::uint32_t> vertices, double* normals) {
  const bool signs = s.tangent_sign.size() == s.rows.rows();
  parallel_for(static_cast<std::uint32_t>(vertices.size()), kSubsetGrain, [&](std::uint32_t b, std::uint32_t e) {
    for (std::uint32_t i = b; i < e; ++i) {
      const std::uint32_t v = vertices[i];
      double t[3];
      if (signs && s.tangent_sign[v] != 0 && tangent_cross(s, v, control, t)) {
        const double len = std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
        const double k = s.tangent_sign[v] / len;
        for (int c = 0; c < 3; ++c) normals[3 * std::size_t(v) + c] = k * t[c];
        continue;
      }
      double acc[3] = {0, 0, 0}, n[3];
      if (v < vertex_faces.rows())
        for (std::uint32_t f : vertex_faces.row(v)) {
          polygon_area_vector(faces.row(f), limit, n);
          for (int c = 0; c < 3; ++c) acc[c] += n[c];
        }
      finish_normal(s, v, control, acc, normals + 3 * std::size_t(v));
    }
  });
}

}  // namespace sublift
