#include "core/lifting.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <thread>

#include "core/lifting_detail.h"
#include "core/parallel.h"

namespace sublift {
namespace {

using namespace lifting_detail;

// Targets per chunk handed to a thread: large enough to amortise the hand-out, small enough
// to balance two cores when one is busy with something else.
constexpr std::uint32_t kGrain = 8192;

// x[target] += sign * sum_g weight_g(m) * centroid_g, for targets [0, n) of one class. The
// group count G and channel count C are template parameters so the loops unroll; C == 0 means
// "channels at run time".
template <int C, int G, bool Integer>
void gather(std::uint32_t n, std::uint32_t target_base, const std::uint8_t* target_m, const Group* groups_in,
            double* x, int channels, double sign) {
  const int ch = C > 0 ? C : channels;
  std::array<Group, G> groups;
  for (int g = 0; g < G; ++g) {
    groups[g] = groups_in[g];
    for (double& w : groups[g].weight) w *= sign;
  }
  parallel_for(n, kGrain, [&, groups](std::uint32_t begin, std::uint32_t end) {
    std::vector<double> heap(C > 0 ? 0 : 2 * std::size_t(ch));
    double stack[C > 0 ? 2 * C : 1];
    double* acc = C > 0 ? stack : heap.data();
    double* sum = C > 0 ? stack + C : heap.data() + ch;
    for (std::uint32_t i = begin; i < end; ++i) {
      const int m = target_m ? target_m[i] : 0;
      for (int c = 0; c < ch; ++c) acc[c] = 0.0;
      const bool any = accumulate_row<C, G>(groups.data(), i, m, x, ch, sum, acc);
      if (!any) continue;
      double* dst = x + std::size_t(target_base + i) * ch;
      if constexpr (Integer) {
        for (int c = 0; c < ch; ++c) dst[c] += sign * std::floor(sign * acc[c] + 0.5);
      } else {
        for (int c = 0; c < ch; ++c) dst[c] += acc[c];
      }
    }
  });
}

template <int C, int G>
void gather_mode(std::uint32_t n, std::uint32_t target_base, const std::uint8_t* target_m, const Group* groups,
                 double* x, int channels, double sign, bool integer) {
  if (integer) gather<C, G, true>(n, target_base, target_m, groups, x, channels, sign);
  else gather<C, G, false>(n, target_base, target_m, groups, x, channels, sign);
}

template <int G>
void gather_channels(std::uint32_t n, std::uint32_t target_base, const std::uint8_t* target_m, const Group* groups,
                     double* x, int channels, double sign, bool integer) {
  switch (channels) {
    case 1: return gather_mode<1, G>(n, target_base, target_m, groups, x, channels, sign, integer);
    case 3: return gather_mode<3, G>(n, target_base, target_m, groups, x, channels, sign, integer);
    case 4: return gather_mode<4, G>(n, target_base, target_m, groups, x, channels, sign, integer);
    default: return gather_mode<0, G>(n, target_base, target_m, groups, x, channels, sign, integer);
  }
}

void run_gather(std::uint32_t n, std::uint32_t target_base, const std::uint8_t* target_m, const Group* groups,
                int num_groups, double* x, int channels, double sign, bool integer) {
  switch (num_groups) {
    case 1: return gather_channels<1>(n, target_base, target_m, groups, x, channels, sign, integer);
    case 2: return gather_channels<2>(n, target_base, target_m, groups, x, channels, sign, integer);
    default: return gather_channels<3>(n, target_base, target_m, groups, x, channels, sign, integer);
  }
}

void wlift_cells(const Complex& p, const Classes& k, double a, double* x, int ch, double sign, bool integer) {
  if (!k.nc) return;
  Group g[3] = {group_of(p.cell_verts, 0), group_of(p.cell_edges, k.E0), group_of(p.cell_faces, k.F0)};
  for (int s = 0; s < 3; ++s) set_wlift_weight(g[s], 3, s, a);
  run_gather(k.nc, k.C0, nullptr, g, 3, x, ch, sign, integer);
}

void wlift_faces(const Complex& p, const Classes& k, double a, double* x, int ch, double sign, bool integer) {
  if (!k.nf) return;
  Group g[2] = {group_of(p.faces, 0), group_of(p.face_edges, k.E0)};
  for (int s = 0; s < 2; ++s) set_wlift_weight(g[s], 2, s, a);
  run_gather(k.nf, k.F0, nullptr, g, 2, x, ch, sign, integer);
}

void wlift_edges(const Complex& p, const Classes& k, double a, double* x, int ch, double sign, bool integer) {
  if (!k.ne) return;
  Group g;
  g.items = p.edge_verts.data();
  g.stride = 2;
  g.source_base = 0;
  set_wlift_weight(g, 1, 0, a);
  run_gather(k.ne, k.E0, nullptr, &g, 1, x, ch, sign, integer);
}


void slift_vertices(const Complex& p, const LiftTables& t, const Classes& k, double a, double* x, int ch, double sign,
                    bool integer) {
  Group g[3] = {group_of(pick(t.own_v_from_e, t.v_from_e, p.vertex_edges), k.E0),
                group_of(pick(t.own_v_from_f, t.v_from_f, p.vertex_faces), k.F0),
                group_of(pick(t.own_v_from_c, t.v_from_c, p.vertex_cells), k.C0)};
  for (int s = 0; s < 3; ++s) set_slift_weight(g[s], 0, s + 1, a);
  run_gather(k.nv, 0, p.vertex_dim.data(), g, k.nc ? 3 : (k.nf ? 2 : 1), x, ch, sign, integer);
}

void slift_edges(const Complex& p, const LiftTables& t, const Classes& k, double a, double* x, int ch, double sign,
                 bool integer) {
  if (!k.nf) return;
  Group g[2] = {group_of(pick(t.own_e_from_f, t.e_from_f, p.edge_faces), k.F0),
                group_of(pick(t.own_e_from_c, t.e_from_c, p.edge_cells), k.C0)};
  for (int s = 0; s < 2; ++s) set_slift_weight(g[s], 1, s + 2, a);
  run_gather(k.ne, k.E0, p.edge_dim.data(), g, k.nc ? 2 : 1, x, ch, sign, integer);
}

void slift_faces(const Complex& p, const LiftTables& t, const Classes& k, double a, double* x, int ch, double sign,
                 bool integer) {
  if (!k.nc) return;
  Group g = group_of(pick(t.own_f_from_c, t.f_from_c, p.face_cells), k.C0);
  set_slift_weight(g, 2, 3, a);
  run_gather(k.nf, k.F0, p.face_dim.data(), &g, 1, x, ch, sign, integer);
}

// s-scale: a class-t vertex of feature dim m is multiplied (or divided) by a^(m-t).
void sscale(const Complex& p, const Classes& k, double a, double* x, int ch, bool inverse) {
  auto scale_class = [&](std::uint32_t n, std::uint32_t base, const std::uint8_t* dims, int t) {
    double factor[4];
    for (int m = 0; m < 4; ++m) factor[m] = m >= t ? std::pow(a, m - t) : 1.0;
    if (inverse)
      for (double& f : factor) f = 1.0 / f;
    parallel_for(n, kGrain, [&](std::uint32_t b, std::uint32_t e) {
      for (std::uint32_t i = b; i < e; ++i) {
        const double f = factor[dims[i]];
        if (f == 1.0) continue;
        double* v = x + std::size_t(base + i) * ch;
        for (int c = 0; c < ch; ++c) v[c] *= f;
      }
    });
  };
  scale_class(k.nv, 0, p.vertex_dim.data(), 0);
  scale_class(k.ne, k.E0, p.edge_dim.data(), 1);
  scale_class(k.nf, k.F0, p.face_dim.data(), 2);
  // Cells have feature dim 3 = their topological dim: factor 1.
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

}  // namespace

LiftProgram linear_program() { return {{LiftOp::SLift, -0.25}, {LiftOp::WLift, 0.5}}; }

LiftProgram cubic_program() {
  return {{LiftOp::SLift, -0.375}, {LiftOp::WLift, 0.5}, {LiftOp::SLift, 0.5}, {LiftOp::SScale, 0.5}};
}

void set_lift_threads(int n) { set_parallel_threads(n); }

std::size_t LiftTables::bytes() const {
  return v_from_e.bytes() + v_from_f.bytes() + v_from_c.bytes() + e_from_f.bytes() + e_from_c.bytes() +
         f_from_c.bytes();
}

LiftTables build_lift_tables(const Complex& p) {
  LiftTables t;
  t.own_v_from_e = filter_rows(p.vertex_edges, p.vertex_dim, &p.edge_dim, 0, t.v_from_e);
  t.own_v_from_f = filter_rows(p.vertex_faces, p.vertex_dim, &p.face_dim, 0, t.v_from_f);
  t.own_v_from_c = filter_rows(p.vertex_cells, p.vertex_dim, nullptr, 3, t.v_from_c);
  t.own_e_from_f = filter_rows(p.edge_faces, p.edge_dim, &p.face_dim, 0, t.e_from_f);
  t.own_e_from_c = filter_rows(p.edge_cells, p.edge_dim, nullptr, 3, t.e_from_c);
  t.own_f_from_c = filter_rows(p.face_cells, p.face_dim, nullptr, 3, t.f_from_c);
  return t;
}

void lift_synthesize(const Complex& p, const LiftTables& t, const LiftProgram& program, double* x, int ch,
                     bool integer) {
  const Classes k(p);
  for (const LiftStep& s : program) {
    switch (s.op) {
      case LiftOp::WLift:  // c, then f, then e: each reads only classes not yet updated
        wlift_cells(p, k, s.a, x, ch, 1.0, integer);
        wlift_faces(p, k, s.a, x, ch, 1.0, integer);
        wlift_edges(p, k, s.a, x, ch, 1.0, integer);
        break;
      case LiftOp::SLift:  // v, then e, then f
        slift_vertices(p, t, k, s.a, x, ch, 1.0, integer);
        slift_edges(p, t, k, s.a, x, ch, 1.0, integer);
        slift_faces(p, t, k, s.a, x, ch, 1.0, integer);
        break;
      case LiftOp::SScale:
        if (!integer) sscale(p, k, s.a, x, ch, false);
        break;
    }
  }
}

void lift_analyze(const Complex& p, const LiftTables& t, const LiftProgram& program, double* x, int ch,
                  bool integer) {
  const Classes k(p);
  for (auto it = program.rbegin(); it != program.rend(); ++it) {
    const LiftStep& s = *it;
    switch (s.op) {
      case LiftOp::WLift:
        wlift_edges(p, k, s.a, x, ch, -1.0, integer);
        wlift_faces(p, k, s.a, x, ch, -1.0, integer);
        wlift_cells(p, k, s.a, x, ch, -1.0, integer);
        break;
      case LiftOp::SLift:
        slift_faces(p, t, k, s.a, x, ch, -1.0, integer);
        slift_edges(p, t, k, s.a, x, ch, -1.0, integer);
        slift_vertices(p, t, k, s.a, x, ch, -1.0, integer);
        break;
      case LiftOp::SScale:
        if (!integer) sscale(p, k, s.a, x, ch, true);
        break;
    }
  }
}

}  // namespace sublift
