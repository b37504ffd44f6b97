#include "core/lifting_sparse.h"

#include <algorithm>
#include <cmath>

#include "core/lifting_detail.h"
#include "core/parallel.h"

namespace sublift {
namespace {

using namespace lifting_detail;

// Rows per chunk when the rows of one sub-step are spread over threads: small changes stay on
// the calling thread.
constexpr std::uint32_t kSparseGrain = 2048;

// Reverse rows of one source group: source (local index) -> targets (local index).
struct Reverse {
  const std::uint32_t* offsets = nullptr;
  const std::uint32_t* items = nullptr;
  std::uint32_t stride = 0;  // fixed-size rows (edge_verts) when offsets == nullptr
};

Reverse reverse_of(const Csr& rows) { return {rows.offsets.data(), rows.items.data(), 0}; }
Reverse reverse_pairs(const std::vector<std::uint32_t>& pairs) { return {nullptr, pairs.data(), 2}; }

// One gather sub-step restricted to the targets that read a changed source: collect them
// through the reverse rows, then evaluate each row as lifting.cpp's gather does.
template <int G>
void sparse_gather(std::uint32_t num_targets, std::uint32_t target_base, const std::uint8_t* target_m,
                   const Group (&groups_in)[G], const Reverse (&rev)[G], const std::uint32_t (&source_count)[G],
                   double sign, SparseDelta& d) {
  if (!num_targets) return;
  Group groups[G];
  for (int g = 0; g < G; ++g) {
    groups[g] = groups_in[g];
    for (double& w : groups[g].weight) w *= sign;
  }
  const std::uint32_t epoch = ++d.epoch;
  d.candidates.clear();
  const std::size_t n_list = d.list.size();
  for (std::size_t k = 0; k < n_list; ++k) {
    const std::uint32_t v = d.list[k];
    for (int g = 0; g < G; ++g) {
      const std::uint32_t b = groups[g].source_base;
      if (v < b || v >= b + source_count[g]) continue;
      const std::uint32_t s = v - b;
      const std::uint32_t* row;
      std::uint32_t len;
      if (rev[g].offsets) {
        row = rev[g].items + rev[g].offsets[s];
        len = rev[g].offsets[s + 1] - rev[g].offsets[s];
      } else {
        row = rev[g].items + std::size_t(s) * rev[g].stride;
        len = rev[g].stride;
      }
      for (std::uint32_t i = 0; i < len; ++i) {
        const std::uint32_t t = row[i];
        std::uint32_t& st = d.stamp[target_base + t];
        if (st != epoch) {
          st = epoch;
          d.candidates.push_back(t);
        }
      }
    }
  }
  // Rows are independent (each writes its own target, reads other classes): evaluate them on
  // all threads, then list the new targets.
  const std::uint32_t nc = static_cast<std::uint32_t>(d.candidates.size());
  parallel_for(nc, kSparseGrain, [&](std::uint32_t begin, std::uint32_t end) {
    for (std::uint32_t k = begin; k < end; ++k) {
      const std::uint32_t i = d.candidates[k];
      const int m = target_m ? target_m[i] : 0;
      double acc[3] = {0, 0, 0}, sum[3];
      accumulate_row<3, G>(groups, i, m, d.x.data(), 3, sum, acc);
      double* dst = d.x.data() + std::size_t(target_base + i) * 3;
      for (int c = 0; c < 3; ++c) dst[c] += acc[c];
    }
  });
  for (const std::uint32_t i : d.candidates) d.at(target_base + i);
}

void wlift_cells(const Complex& p, const Classes& k, double a, double sign, SparseDelta& d) {
  if (!k.nc) return;
  const Group g[3] = {group_of(p.cell_verts, 0), group_of(p.cell_edges, k.E0), group_of(p.cell_faces, k.F0)};
  Group w[3] = {g[0], g[1], g[2]};
  for (int s = 0; s < 3; ++s) set_wlift_weight(w[s], 3, s, a);
  const Reverse r[3] = {reverse_of(p.vertex_cells), reverse_of(p.edge_cells), reverse_of(p.face_cells)};
  const std::uint32_t n[3] = {k.nv, k.ne, k.nf};
  sparse_gather<3>(k.nc, k.C0, nullptr, w, r, n, sign, d);
}

void wlift_faces(const Complex& p, const Classes& k, double a, double sign, SparseDelta& d) {
  if (!k.nf) return;
  Group w[2] = {group_of(p.faces, 0), group_of(p.face_edges, k.E0)};
  for (int s = 0; s < 2; ++s) set_wlift_weight(w[s], 2, s, a);
  const Reverse r[2] = {reverse_of(p.vertex_faces), reverse_of(p.edge_faces)};
  const std::uint32_t n[2] = {k.nv, k.ne};
  sparse_gather<2>(k.nf, k.F0, nullptr, w, r, n, sign, d);
}

void wlift_edges(const Complex& p, const Classes& k, double a, double sign, SparseDelta& d) {
  if (!k.ne) return;
  Group w[1];
  w[0].items = p.edge_verts.data();
  w[0].stride = 2;
  w[0].source_base = 0;
  set_wlift_weight(w[0], 1, 0, a);
  const Reverse r[1] = {reverse_of(p.vertex_edges)};
  const std::uint32_t n[1] = {k.nv};
  sparse_gather<1>(k.ne, k.E0, nullptr, w, r, n, sign, d);
}

// The s-lift rows may be feature-filtered copies; the unfiltered reverse rows reach a superset
// of their targets, and a visited row that reads no changed source adds exactly zero.
void slift_vertices(const Complex& p, const LiftTables& t, const Classes& k, double a, double sign, SparseDelta& d) {
  Group w[3] = {group_of(pick(t.own_v_from_e, t.v_from_e, p.vertex_edges), k.E0),
                group_of(pick(t.own_v_from_f, t.v_from_f, p.vertex_faces), k.F0),
                group_of(pick(t.own_v_from_c, t.v_from_c, p.vertex_cells), k.C0)};
  for (int s = 0; s < 3; ++s) set_slift_weight(w[s], 0, s + 1, a);
  const Reverse r[3] = {reverse_pairs(p.edge_verts), reverse_of(p.faces), reverse_of(p.cell_verts)};
  const std::uint32_t n[3] = {k.ne, k.nf, k.nc};
  sparse_gather<3>(k.nv, 0, p.vertex_dim.data(), w, r, n, sign, d);
}

void slift_edges(const Complex& p, const LiftTables& t, const Classes& k, double a, double sign, SparseDelta& d) {
  if (!k.nf) return;
  Group w[2] = {group_of(pick(t.own_e_from_f, t.e_from_f, p.edge_faces), k.F0),
                group_of(pick(t.own_e_from_c, t.e_from_c, p.edge_cells), k.C0)};
  for (int s = 0; s < 2; ++s) set_slift_weight(w[s], 1, s + 2, a);
  const Reverse r[2] = {reverse_of(p.face_edges), reverse_of(p.cell_edges)};
  const std::uint32_t n[2] = {k.nf, k.nc};
  sparse_gather<2>(k.ne, k.E0, p.edge_dim.data(), w, r, n, sign, d);
}

void slift_faces(const Complex& p, const LiftTables& t, const Classes& k, double a, double sign, SparseDelta& d) {
  if (!k.nc) return;
  Group w[1] = {group_of(pick(t.own_f_from_c, t.f_from_c, p.face_cells), k.C0)};
  set_slift_weight(w[0], 2, 3, a);
  const Reverse r[1] = {reverse_of(p.cell_faces)};
  const std::uint32_t n[1] = {k.nc};
  sparse_gather<1>(k.nf, k.F0, p.face_dim.data(), w, r, n, sign, d);
}

void sscale(const Complex& p, const Classes& k, double a, bool inverse, SparseDelta& d) {
  double factor[3][4];  // [topological dim t][feature dim m]: a^(m-t), as lifting.cpp
  for (int t = 0; t < 3; ++t)
    for (int m = 0; m < 4; ++m) {
      const double f = m >= t ? std::pow(a, m - t) : 1.0;
      factor[t][m] = inverse ? 1.0 / f : f;
    }
  for (const std::uint32_t v : d.list) {
    double f;
    if (v < k.E0) f = factor[0][p.vertex_dim[v]];
    else if (v < k.F0) f = factor[1][p.edge_dim[v - k.E0]];
    else if (v < k.C0) f = factor[2][p.face_dim[v - k.F0]];
    else continue;  // cells: factor 1
    if (f == 1.0) continue;
    double* x = d.x.data() + std::size_t(v) * 3;
    for (int c = 0; c < 3; ++c) x[c] *= f;
  }
}

}  // namespace

void SparseDelta::reset(std::uint32_t n) {
  clear();
  if (x.size() != std::size_t(n) * 3) {
    x.assign(std::size_t(n) * 3, 0.0);
    in_list.assign(n, 0);
    stamp.assign(n, 0);
    epoch = 0;
  }
}

void SparseDelta::clear() {
  for (const std::uint32_t v : list) {
    std::fill_n(x.data() + std::size_t(v) * 3, 3, 0.0);
    in_list[v] = 0;
  }
  list.clear();
}

void lift_synthesize_sparse(const Complex& p, const LiftTables& t, const LiftProgram& program, SparseDelta& d) {
  const Classes k(p);
  for (const LiftStep& s : program) {
    switch (s.op) {
      case LiftOp::WLift:
        wlift_cells(p, k, s.a, 1.0, d);
        wlift_faces(p, k, s.a, 1.0, d);
        wlift_edges(p, k, s.a, 1.0, d);
        break;
      case LiftOp::SLift:
        slift_vertices(p, t, k, s.a, 1.0, d);
        slift_edges(p, t, k, s.a, 1.0, d);
        slift_faces(p, t, k, s.a, 1.0, d);
        break;
      case LiftOp::SScale: sscale(p, k, s.a, false, d); break;
    }
  }
}

void lift_analyze_sparse(const Complex& p, const LiftTables& t, const LiftProgram& program, SparseDelta& d) {
  const Classes k(p);
  for (auto it = program.rbegin(); it != program.rend(); ++it) {
    const LiftStep& s = *it;
    switch (s.op) {
      case LiftOp::WLift:
        wlift_edges(p, k, s.a, -1.0, d);
        wlift_faces(p, k, s.a, -1.0, d);
        wlift_cells(p, k, s.a, -1.0, d);
        break;
      case LiftOp::SLift:
        slift_faces(p, t, k, s.a, -1.0, d);
        slift_edges(p, t, k, s.a, -1.0, d);
        slift_vertices(p, t, k, s.a, -1.0, d);
        break;
      case LiftOp::SScale: sscale(p, k, s.a, true, d); break;
    }
  }
}

}  // namespace sublift
