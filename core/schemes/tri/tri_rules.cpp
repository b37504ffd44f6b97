#include "core/schemes/tri/tri_rules.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>
#include <numeric>
#include <optional>
#include <string>
#include <utility>

#include "core/base/errors.h"
#include "core/base/parallel.h"
#include "core/engine/stencil_rows.h"
#include "core/schemes/registry.h"

namespace sublift {

namespace {

// Preconditions of build_tri_stencils; throws TopologyError naming the element.
void check_surface(const Complex& c) {
  if (c.dim != 2 || c.num_cells() != 0)
    throw TopologyError("triangle subdivision needs a surface (dim 2, no cells), got dim " + std::to_string(c.dim) +
                        " with " + std::to_string(c.num_cells()) + " cells");
  if (c.face_edges.offsets != c.faces.offsets)
    throw TopologyError("triangle subdivision: face_edges are not aligned with faces");
  for (std::uint32_t f = 0; f < c.num_faces(); ++f)
    if (c.faces.size(f) != 3)
      throw TopologyError("triangle subdivision needs triangles: face " + std::to_string(f) + " has " +
                          std::to_string(c.faces.size(f)) + " corners");
  for (std::uint32_t e = 0; e < c.num_edges(); ++e) {
    const std::uint32_t n = c.edge_faces.size(e);
    if (n > 2)
      throw TopologyError("triangle subdivision needs a manifold surface: edge " + std::to_string(e) + " (vertices " +
                          std::to_string(c.edge_verts[2 * e]) + ", " + std::to_string(c.edge_verts[2 * e + 1]) +
                          ") has " + std::to_string(n) + " faces");
    if (n == 0)
      throw TopologyError("triangle subdivision: edge " + std::to_string(e) + " lies on no face");
  }
  if (c.vertex_dim.size() != c.num_vertices || c.edge_dim.size() != c.num_edges())
    throw TopologyError("triangle subdivision: feature dims missing");
}

// Topological queries shared by the schemes over a checked triangle surface.
struct TriTopo {
  const Complex& c;
  std::vector<std::uint8_t> feature_edge;    // boundary or edge_dim 1
  std::vector<std::uint32_t> feature_count;  // feature edges per vertex
  std::vector<std::uint8_t> manifold_;       // per vertex, when every row is made

  // `every_row`: the flags of every vertex are worked out at once (in parallel), else per ask.
  TriTopo(const Complex& cx, bool every_row) : c(cx) {
    const std::uint32_t nv = c.num_vertices, ne = c.num_edges();
    feature_edge.resize(ne);
    feature_count.assign(nv, 0);
    for (std::uint32_t e = 0; e < ne; ++e) {
      feature_edge[e] = c.edge_faces.size(e) != 2 || c.edge_dim[e] == 1;
      if (feature_edge[e]) ++feature_count[c.edge_verts[2 * e]], ++feature_count[c.edge_verts[2 * e + 1]];
    }
    if (!every_row) return;
    manifold_.resize(nv);
    parallel_for(nv, 8192, [&](std::uint32_t v0, std::uint32_t v1) {
      for (std::uint32_t v = v0; v < v1; ++v) manifold_[v] = fans(v) <= 1;
    });
  }

  // Whether the faces around v form at most one fan.
  bool manifold(std::uint32_t v) const { return manifold_.empty() ? fans(v) <= 1 : manifold_[v] != 0; }

  // The corner of triangle f that is not on edge e.
  std::uint32_t opposite(std::uint32_t f, std::uint32_t e) const {
    const std::uint32_t a = c.edge_verts[2 * e], b = c.edge_verts[2 * e + 1];
    for (std::uint32_t v : c.faces.row(f))
      if (v != a && v != b) return v;
    assert(false);
    return a;
  }
  // The face of (at most two-faced) edge e other than f; f itself when e has one face.
  std::uint32_t other_face(std::uint32_t e, std::uint32_t f) const {
    const auto fs = c.edge_faces.row(e);
    return fs[0] == f ? fs.back() : fs[0];
  }
  // The edge of triangle f at corner v other than e.
  std::uint32_t other_edge_at(std::uint32_t f, std::uint32_t v, std::uint32_t e) const {
    const std::uint32_t b = c.faces.offsets[f];
    for (std::uint32_t k = 0; k < 3; ++k)
      if (c.faces.items[b + k] == v) {
        const std::uint32_t e_out = c.face_edges.items[b + k], e_in = c.face_edges.items[b + (k + 2) % 3];
        return e_out == e ? e_in : e_out;
      }
    assert(false);
    return e;
  }
  // The feature edge at v other than e (v has exactly two).
  std::uint32_t other_feature_edge(std::uint32_t v, std::uint32_t e) const {
    for (std::uint32_t g : c.vertex_edges.row(v))
      if (g != e && feature_edge[g]) return g;
    assert(false);
    return e;
  }

  // Number of fans of faces around v: faces joined through v's two-faced edges (union-find over
  // the sorted vertex_faces row, so high valences stay n log n).
  std::uint32_t fans(std::uint32_t v) const {
    const auto vf = c.vertex_faces.row(v);
    thread_local std::vector<std::uint32_t> parent;
    parent.resize(vf.size());
    std::iota(parent.begin(), parent.end(), 0u);
    auto find = [&](std::uint32_t i) {
      while (parent[i] != i) i = parent[i] = parent[parent[i]];
      return i;
    };
    auto local = [&](std::uint32_t f) {
      return static_cast<std::uint32_t>(std::lower_bound(vf.begin(), vf.end(), f) - vf.begin());
    };
    std::uint32_t count = static_cast<std::uint32_t>(vf.size());
    for (std::uint32_t e : c.vertex_edges.row(v)) {
      const auto ef = c.edge_faces.row(e);
      if (ef.size() != 2) continue;
      const std::uint32_t x = find(local(ef[0])), y = find(local(ef[1]));
      if (x != y) parent[x] = y, --count;
    }
    return count;
  }
};

// ---- Linear ------------------------------------------------------------------------------

void linear_edge_row(const TriTopo& t, std::uint32_t e, RowBuilder& row) {
  row.add(t.c.edge_verts[2 * e], 0.5);  // 004 sec. 4.1, Fig. 2: midpoints
  row.add(t.c.edge_verts[2 * e + 1], 0.5);
}

// ---- Butterfly ---------------------------------------------------------------------------

// ZSS96's extraordinary-vertex weights s_0..s_{K-1} and the centre weight s_K, computed in the
// same order as OpenMesh's ModifiedButterflyT::init_weights.
std::vector<double> butterfly_weights(std::uint32_t K) {
  std::vector<double> w(K + 1);
  if (K == 3) {
    w = {5.0 / 12, -1.0 / 12, -1.0 / 12, 3.0 / 4};
  } else if (K == 4) {
    w = {3.0 / 8, 0, -1.0 / 8, 0, 3.0 / 4};
  } else {
    const double invK = 1.0 / static_cast<double>(K);
    double sum = 0;
    for (std::uint32_t j = 0; j < K; ++j) {
      w[j] = (0.25 + std::cos(2.0 * std::numbers::pi * static_cast<double>(j) * invK) +
              0.5 * std::cos(4.0 * std::numbers::pi * static_cast<double>(j) * invK)) *
             invK;
      sum += w[j];
    }
    w[K] = 1.0 - sum;
  }
  return w;
}

// What the butterfly's rows read besides the topology.
struct ButterflyTables {
  std::vector<std::vector<double>> weights;  // by valence, for the valences present but 6
  std::vector<std::uint8_t> open_;           // per vertex, when every row is made

  ButterflyTables(const TriTopo& t, bool every_row) {
    const Complex& c = t.c;
    if (every_row) {
      open_.resize(c.num_vertices);
      for (std::uint32_t v = 0; v < c.num_vertices; ++v) open_[v] = find_open(t, v);
    }
    for (std::uint32_t v = 0; v < c.num_vertices; ++v) {
      const std::uint32_t K = c.vertex_edges.size(v);
      if (K == 6 || K < 3) continue;
      if (weights.size() <= K) weights.resize(K + 1);
      if (weights[K].empty()) weights[K] = butterfly_weights(K);
    }
  }

  // OpenMesh's is_boundary(vertex), on the mesh cut along creases; plus the vertices OpenMesh
  // cannot hold (valence < 3 inside, non-manifold), which get no K-point stencil either.
  static bool find_open(const TriTopo& t, std::uint32_t v) {
    return t.feature_count[v] > 0 || t.c.vertex_edges.size(v) < 3 || !t.manifold(v);
  }
  bool open(const TriTopo& t, std::uint32_t v) const { return open_.empty() ? find_open(t, v) : open_[v] != 0; }
};

void butterfly_edge_row(const TriTopo& t, const ButterflyTables& tables, std::uint32_t e, RowBuilder& row) {
  const Complex& c = t.c;
  const auto open = [&](std::uint32_t v) { return tables.open(t, v); };

  // The curve neighbour across end a of feature edge e, or the reflection 2a - b.
  auto curve_neighbour = [&](RowBuilder& row, std::uint32_t e, std::uint32_t a, std::uint32_t b, double w) {
    if (t.feature_count[a] == 2 && c.vertex_dim[a] != 0) {
      row.add(edge_other_end(c, t.other_feature_edge(a, e), a), w);
    } else {
      row.add(a, 2 * w);
      row.add(b, -w);
    }
  };
  // K-point stencil of interior vertex a (valence K) for edge e, scaled by `scale`. Ring walk
  // through the faces: r_0 is the other end of e (ZSS96; weights symmetric in j <-> K - j).
  auto k_point = [&](RowBuilder& row, std::uint32_t e, std::uint32_t a, double scale) {
    const std::uint32_t K = c.vertex_edges.size(a);
    const std::vector<double>& w = tables.weights[K];
    std::uint32_t edge = e, face = c.edge_faces.row(e)[0];
    for (std::uint32_t j = 0; j < K; ++j) {
      row.add(edge_other_end(c, edge, a), scale * w[j]);
      edge = t.other_edge_at(face, a, edge);
      face = t.other_face(edge, face);
    }
    assert(edge == e);
    row.add(a, scale * w[K]);
  };

  const std::uint32_t a0 = c.edge_verts[2 * e], a1 = c.edge_verts[2 * e + 1];
  if (t.feature_edge[e]) {
    // 4-point rule along the boundary / crease curve (OpenMesh: boundary edges).
    row.add(a0, 9.0 / 16), row.add(a1, 9.0 / 16);
    curve_neighbour(row, e, a0, a1, -1.0 / 16);
    curve_neighbour(row, e, a1, a0, -1.0 / 16);
  } else {
    const std::uint32_t K0 = c.vertex_edges.size(a0), K1 = c.vertex_edges.size(a1);
    const bool o0 = open(a0), o1 = open(a1);
    if ((K0 == 6 && K1 == 6) || (o0 && K1 == 6) || (o1 && K0 == 6) || (o0 && o1)) {
      // 8-point rule (ZSS96 regular butterfly): 1/2, 1/8, -1/16.
      row.add(a0, 0.5), row.add(a1, 0.5);
      for (std::uint32_t f : c.edge_faces.row(e)) {
        const std::uint32_t b = t.opposite(f, e);
        row.add(b, 1.0 / 8);
        for (std::uint32_t a : {a0, a1}) {
          const std::uint32_t wing = t.other_edge_at(f, a, e);
          if (t.feature_edge[wing]) {  // the missing vertex made by symmetry: a + b - a'
            row.add(a, -1.0 / 16), row.add(b, -1.0 / 16), row.add(a == a0 ? a1 : a0, 1.0 / 16);
          } else {
            row.add(t.opposite(t.other_face(wing, f), wing), -1.0 / 16);
          }
        }
      }
    } else {
      // K-point rule at the extraordinary interior end(s), averaged when both are.
      const bool k0 = K0 != 6 && !o0, k1 = K1 != 6 && !o1;
      const double scale = k0 && k1 ? 0.5 : 1.0;
      if (k0) k_point(row, e, a0, scale);
      if (k1) k_point(row, e, a1, scale);
    }
  }
}

// ---- Loop --------------------------------------------------------------------------------

void loop_edge_row(const TriTopo& t, std::uint32_t e, RowBuilder& row) {
  const Complex& c = t.c;
  const std::uint32_t a0 = c.edge_verts[2 * e], a1 = c.edge_verts[2 * e + 1];
  if (t.feature_edge[e]) {
    row.add(a0, 0.5), row.add(a1, 0.5);  // Sdc Loop crease edge mask
  } else {
    row.add(a0, 3.0 / 8), row.add(a1, 3.0 / 8);  // Loop 1987 edge mask: 3/8, 3/8, 1/8, 1/8
    for (std::uint32_t f : c.edge_faces.row(e)) row.add(t.opposite(f, e), 1.0 / 8);
  }
}

void loop_vertex_row(const TriTopo& t, std::uint32_t v, RowBuilder& row) {
  const Complex& c = t.c;
  const auto edges = c.vertex_edges.row(v);
  const std::uint32_t s = t.feature_count[v];
  if (c.vertex_dim[v] == 0 || s > 2 || edges.empty() || !t.manifold(v)) {
    row.add(v, 1.0);  // corner: fixed
  } else if (s == 2) {
    row.add(v, 0.75);  // crease vertex: 1/8, 3/4, 1/8 along the crease
    for (std::uint32_t e : edges)
      if (t.feature_edge[e]) row.add(edge_other_end(c, e, v), 0.125);
  } else {
    // Smooth or dart: Loop's original beta, computed as Sdc::Scheme<SCHEME_LOOP> does.
    const std::uint32_t n = static_cast<std::uint32_t>(edges.size());
    double e_weight = 0.0625, v_weight = 0.625;
    if (n != 6) {
      const double dn = static_cast<double>(n), inv = 1.0 / dn;
      const double cos_theta = std::cos(std::numbers::pi * 2.0 * inv);
      const double beta = 0.25 * cos_theta + 0.375;
      e_weight = (0.625 - beta * beta) * inv;
      v_weight = 1.0 - e_weight * dn;
    }
    row.add(v, v_weight);
    for (std::uint32_t e : edges) row.add(edge_other_end(c, e, v), e_weight);
  }
}

}  // namespace

struct TriRowRules::Impl {
  Scheme scheme;
  TriTopo topo;
  std::optional<ButterflyTables> butterfly;

  Impl(const Complex& c, Scheme s, bool every_row) : scheme(s), topo(c, every_row) {
    if (s == Scheme::Butterfly) butterfly.emplace(topo, every_row);
  }
};

TriRowRules::TriRowRules(const Complex& coarse, Scheme s, bool every_row) {
  check_surface(coarse);
  if (!scheme_is_tri(s)) throw Error(scheme_name(s) + " is not a triangle scheme");
  impl_ = std::make_unique<const Impl>(coarse, s, every_row);
}

TriRowRules::~TriRowRules() = default;

void TriRowRules::add_terms(std::uint32_t v, RowBuilder& row) const {
  const Impl& r = *impl_;
  const std::uint32_t nv = r.topo.c.num_vertices;
  if (v < nv) {
    if (r.scheme == Scheme::Loop) {
      loop_vertex_row(r.topo, v, row);
    } else {
      row.add(v, 1.0);  // interpolating: old vertices are kept
    }
    return;
  }
  const std::uint32_t e = v - nv;
  switch (r.scheme) {
    case Scheme::LinearTri: linear_edge_row(r.topo, e, row); break;
    case Scheme::Butterfly: butterfly_edge_row(r.topo, *r.butterfly, e, row); break;
    default: loop_edge_row(r.topo, e, row); break;
  }
}

void TriRowRules::append_row(std::uint32_t v, Csr& rows, std::vector<double>& weights) const {
  thread_local RowBuilder b;
  add_terms(v, b);
  b.flush(rows, weights);
}

TriStencils build_tri_stencils(const Complex& coarse, Scheme s) {
  const bool derived = coarse.vertex_edges.rows() == coarse.num_vertices &&
                       coarse.vertex_faces.rows() == coarse.num_vertices &&
                       coarse.edge_faces.rows() == coarse.num_edges();
  Complex copy;
  if (!derived) {
    copy = coarse;
    build_adjacency(copy);
  }
  const Complex& c = derived ? coarse : copy;
  const TriRowRules rules(c, s, true);
  const TriRowRules::Impl& r = *rules.impl_;
  TriStencils st;
  // The rule called straight, not through add_terms: a million rows of the same scheme.
  const std::uint32_t ne = c.num_edges();
  switch (s) {
    case Scheme::LinearTri:
      build_rows(ne, st.new_rows, st.new_weights, [&](std::uint32_t e, RowBuilder& row) { linear_edge_row(r.topo, e, row); });
      break;
    case Scheme::Butterfly:
      build_rows(ne, st.new_rows, st.new_weights,
                 [&](std::uint32_t e, RowBuilder& row) { butterfly_edge_row(r.topo, *r.butterfly, e, row); });
      break;
    default:
      build_rows(ne, st.new_rows, st.new_weights, [&](std::uint32_t e, RowBuilder& row) { loop_edge_row(r.topo, e, row); });
      // The interpolating schemes keep their old vertices: no rows.
      build_rows(c.num_vertices, st.old_rows, st.old_weights,
                 [&](std::uint32_t v, RowBuilder& row) { loop_vertex_row(r.topo, v, row); });
      break;
  }
  return st;
}

std::vector<double> subdivide_tri(const TriStencils& st, const double* coarse, std::uint32_t nv, int channels) {
  const std::size_t ne = st.new_rows.rows(), ch = static_cast<std::size_t>(channels);
  if (st.old_rows.rows() != 0 && st.old_rows.rows() != nv)
    throw TopologyError("subdivide_tri: " + std::to_string(st.old_rows.rows()) + " old-vertex rows for " +
                        std::to_string(nv) + " vertices");
  std::vector<double> fine((nv + ne) * ch, 0.0);
  auto apply = [&](const Csr& rows, const std::vector<double>& weights, std::size_t r, double* out) {
    for (std::uint32_t i = rows.offsets[r]; i < rows.offsets[r + 1]; ++i) {
      const double w = weights[i];
      const double* x = coarse + std::size_t(rows.items[i]) * ch;
      for (std::size_t k = 0; k < ch; ++k) out[k] += w * x[k];
    }
  };
  if (st.old_rows.rows() == 0) {
    std::copy(coarse, coarse + std::size_t(nv) * ch, fine.begin());
  } else {
    for (std::uint32_t v = 0; v < nv; ++v) apply(st.old_rows, st.old_weights, v, &fine[v * ch]);
  }
  for (std::size_t e = 0; e < ne; ++e) apply(st.new_rows, st.new_weights, e, &fine[(nv + e) * ch]);
  return fine;
}

}  // namespace sublift
