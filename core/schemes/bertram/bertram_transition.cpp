#include "core/schemes/bertram/bertram_transition.h"

#include <cmath>

#include "core/complex/refine.h"

namespace sublift {
namespace {

// Regular-grid neighbour count: a t-dim primitive inside an m-dim regular grid touches
// C(m-t, k-t) 2^(k-t) primitives of dim k (000 eq. 3.16-3.17: 6/12/8, 4/4, 2).
double grid_count(int m, int t, int k) {
  if (k > m || t > m) return 0.0;
  const int n = m - t, r = k - t;
  double binom = 1;
  for (int i = 0; i < r; ++i) binom = binom * (n - i) / (i + 1);
  return binom * std::ldexp(1.0, r);
}

// w-lift ignores features (topological counts of the target primitive, 000 eq. 3.16): the
// number of k-faces of a regular t-cube, C(t, k) 2^(t-k), times a^(t-k).
void set_wlift_weight(CentroidGroup& g, int t, int k, double a) {
  double binom = 1;
  for (int i = 0; i < t - k; ++i) binom = binom * (t - i) / (i + 1);
  const double v = binom * std::ldexp(1.0, t - k) * std::pow(a, t - k);
  for (double& x : g.weight) x = v;
}

// s-lift uses the target's feature dim m.
void set_slift_weight(CentroidGroup& g, int t, int k, double a) {
  for (int m = 0; m < 4; ++m) g.weight[m] = grid_count(m, t, k) * std::pow(a, k - t);
}

struct Classes {
  std::uint32_t nv, ne, nf, nc, E0, F0, C0;
  explicit Classes(const Complex& p)
      : nv(p.num_vertices), ne(p.num_edges()), nf(p.num_faces()), nc(p.num_cells()),
        E0(nv), F0(nv + ne), C0(nv + ne + nf) {}
};

CentroidGroup group(Incidence rows, Incidence reverse, std::uint32_t base, std::uint32_t count, int owned = -1) {
  CentroidGroup g;
  g.rows = rows;
  g.reverse = reverse;
  g.source_base = base;
  g.source_count = count;
  g.owned = static_cast<std::int16_t>(owned);
  return g;
}

CentroidStep step(std::uint32_t base, std::uint32_t count, FeatureDims dims, std::initializer_list<CentroidGroup> gs) {
  CentroidStep s;
  s.target_base = base;
  s.count = count;
  s.target_dims = dims;
  for (const CentroidGroup& g : gs) s.groups[s.num_groups++] = g;
  return s;
}

// Keeps the sources whose feature dim is <= the target's (DESIGN: s-lift stays inside a
// feature); returns whether anything was dropped.
bool filter_rows(const Csr& rows, const std::vector<std::uint8_t>& target_dim,
                 const std::vector<std::uint8_t>* source_dim, std::uint8_t fixed_source_dim, Csr& out) {
  out.clear();
  auto dim_of = [&](std::uint32_t s) { return source_dim ? (*source_dim)[s] : fixed_source_dim; };
  bool dropped = false;
  for (std::size_t r = 0; r < rows.rows() && !dropped; ++r)
    for (std::uint32_t s : rows.row(r)) dropped |= dim_of(s) > target_dim[r];
  if (!dropped) return false;
  out.items.reserve(rows.items.size());
  out.offsets.reserve(rows.offsets.size());
  for (std::size_t r = 0; r < rows.rows(); ++r) {
    for (std::uint32_t s : rows.row(r))
      if (dim_of(s) <= target_dim[r]) out.items.push_back(s);
    out.offsets.push_back(static_cast<std::uint32_t>(out.items.size()));
  }
  out.items.shrink_to_fit();
  return true;
}

// The upward rows an s-lift reads, feature-filtered once per transition.
struct SliftRows {
  int v_from_e = -1, v_from_f = -1, v_from_c = -1, e_from_f = -1, e_from_c = -1, f_from_c = -1;
};

SliftRows filter_slift_rows(const Complex& p, Transition& t) {
  SliftRows r;
  auto own = [&](const Csr& rows, const std::vector<std::uint8_t>& target, const std::vector<std::uint8_t>* source,
                 std::uint8_t fixed) {
    Csr out;
    if (!filter_rows(rows, target, source, fixed, out)) return -1;
    t.owned.push_back(std::move(out));
    return static_cast<int>(t.owned.size()) - 1;
  };
  r.v_from_e = own(p.vertex_edges, p.vertex_dim, &p.edge_dim, 0);
  r.v_from_f = own(p.vertex_faces, p.vertex_dim, &p.face_dim, 0);
  r.v_from_c = own(p.vertex_cells, p.vertex_dim, nullptr, 3);
  r.e_from_f = own(p.edge_faces, p.edge_dim, &p.face_dim, 0);
  r.e_from_c = own(p.edge_cells, p.edge_dim, nullptr, 3);
  r.f_from_c = own(p.face_cells, p.face_dim, nullptr, 3);
  return r;
}

// c, then f, then e: each reads only classes not yet updated.
void add_wlift(Transition& t, const Classes& k, double a) {
  using I = Incidence;
  if (k.nc) {
    CentroidStep s = step(k.C0, k.nc, FeatureDims::None,
                          {group(I::CellVerts, I::VertexCells, 0, k.nv), group(I::CellEdges, I::EdgeCells, k.E0, k.ne),
                           group(I::CellFaces, I::FaceCells, k.F0, k.nf)});
    for (int g = 0; g < 3; ++g) set_wlift_weight(s.groups[g], 3, g, a);
    t.add(s);
  }
  if (k.nf) {
    CentroidStep s = step(k.F0, k.nf, FeatureDims::None,
                          {group(I::Faces, I::VertexFaces, 0, k.nv), group(I::FaceEdges, I::EdgeFaces, k.E0, k.ne)});
    for (int g = 0; g < 2; ++g) set_wlift_weight(s.groups[g], 2, g, a);
    t.add(s);
  }
  if (k.ne) {
    CentroidStep s = step(k.E0, k.ne, FeatureDims::None, {group(I::EdgeVerts, I::VertexEdges, 0, k.nv)});
    set_wlift_weight(s.groups[0], 1, 0, a);
    t.add(s);
  }
}

// v, then e, then f. The reverse rows are unfiltered: they reach a superset of the targets,
// and a visited row that reads no changed source adds exactly zero.
void add_slift(Transition& t, const Classes& k, const SliftRows& r, double a) {
  using I = Incidence;
  {
    CentroidStep s = step(0, k.nv, FeatureDims::Vertex,
                          {group(I::VertexEdges, I::EdgeVerts, k.E0, k.ne, r.v_from_e),
                           group(I::VertexFaces, I::Faces, k.F0, k.nf, r.v_from_f),
                           group(I::VertexCells, I::CellVerts, k.C0, k.nc, r.v_from_c)});
    s.num_groups = k.nc ? 3 : (k.nf ? 2 : 1);
    for (int g = 0; g < 3; ++g) set_slift_weight(s.groups[g], 0, g + 1, a);
    t.add(s);
  }
  if (k.nf) {
    CentroidStep s = step(k.E0, k.ne, FeatureDims::Edge,
                          {group(I::EdgeFaces, I::FaceEdges, k.F0, k.nf, r.e_from_f),
                           group(I::EdgeCells, I::CellEdges, k.C0, k.nc, r.e_from_c)});
    s.num_groups = k.nc ? 2 : 1;
    for (int g = 0; g < 2; ++g) set_slift_weight(s.groups[g], 1, g + 2, a);
    t.add(s);
  }
  if (k.nc) {
    CentroidStep s = step(k.F0, k.nf, FeatureDims::Face, {group(I::FaceCells, I::CellFaces, k.C0, k.nc, r.f_from_c)});
    set_slift_weight(s.groups[0], 2, 3, a);
    t.add(s);
  }
}

// A class-t vertex of feature dim m is multiplied by a^(m-t); cells (m = t = 3) stay.
void add_sscale(Transition& t, const Classes& k, double a) {
  ScaleStep s;
  const std::uint32_t base[3] = {0, k.E0, k.F0}, count[3] = {k.nv, k.ne, k.nf};
  for (int c = 0; c < 3; ++c) {
    s.base[c] = base[c];
    s.count[c] = count[c];
    for (int m = 0; m < 4; ++m) s.factor[c][m] = m >= c ? std::pow(a, m - c) : 1.0;
  }
  t.add(s);
}

}  // namespace

LiftProgram linear_program() { return {{LiftOp::SLift, -0.25}, {LiftOp::WLift, 0.5}}; }

LiftProgram cubic_program() {
  return {{LiftOp::SLift, -0.375}, {LiftOp::WLift, 0.5}, {LiftOp::SLift, 0.5}, {LiftOp::SScale, 0.5}};
}

Transition build_bertram_transition(const Complex& p, const LiftProgram& program) {
  Transition t;
  const Classes k(p);
  t.num_coarse = k.nv;
  t.num_fine = p.num_child_vertices();
  const SliftRows rows = filter_slift_rows(p, t);
  for (const LiftStep& s : program) {
    switch (s.op) {
      case LiftOp::WLift: add_wlift(t, k, s.a); break;
      case LiftOp::SLift: add_slift(t, k, rows, s.a); break;
      case LiftOp::SScale: add_sscale(t, k, s.a); break;
    }
  }
  return t;
}

LevelBuild build_bertram_level(Complex& parent, const LiftProgram& program, const LevelContext& ctx) {
  LevelBuild b;
  b.transition = build_bertram_transition(parent, program);
  b.fine = refine(parent, ctx.adjacency);
  return b;
}

}  // namespace sublift
