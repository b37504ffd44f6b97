#include "core/multires/limit_solve.h"

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <numbers>
#include <numeric>
#include <span>
#include <unordered_map>

#include "core/engine/executor.h"
#include "core/multires/hierarchy.h"

namespace sublift {
namespace {

using SparseRows = Eigen::SparseMatrix<double, Eigen::RowMajor>;
using Cx = std::complex<double>;

// The star's local operators: S maps the level-1 star to the level-2 star, P the patch to the
// level-1 star. Star order: [centre | star edges | star faces | star cells], each in the order of
// the centre's upward rows (for a canonical fan that is the cyclic order, limit.cpp).
struct Operators {
  bool ok = false;
  std::uint8_t m = 0;                      // feature dim of the centre
  std::uint32_t edges = 0, faces = 0, cells = 0;
  SparseRows S, P;
};

// Synthesis columns of transition t for the parent vertices 0..columns-1, on the child vertices
// with row[x] >= 0: three impulses per sparse run, one per channel. Columns with col[j] < 0 must
// not reach those rows; their total |value| there is returned instead of stored.
double impulse_columns(const Transition& t, const Complex& parent, std::uint32_t children, std::uint32_t columns,
                       const std::vector<std::int32_t>& row, const std::vector<std::int32_t>& col,
                       std::vector<Eigen::Triplet<double>>& out) {
  const SparseIndex index = build_sparse_index(t);
  SparseDelta d;
  d.reset(children);
  double outside = 0;
  for (std::uint32_t j0 = 0; j0 < columns; j0 += 3) {
    const std::uint32_t j1 = std::min(columns, j0 + 3);
    for (std::uint32_t j = j0; j < j1; ++j) d.at(j)[j - j0] = 1.0;
    run_synthesis_sparse(t, parent, index, d);
    for (const std::uint32_t x : d.list) {
      if (row[x] < 0) continue;
      const double* v = d.x.data() + 3 * std::size_t(x);
      for (std::uint32_t j = j0; j < j1; ++j) {
        const double w = v[j - j0];
        if (w == 0.0) continue;
        if (col[j] >= 0)
          out.emplace_back(row[x], col[j], w);
        else
          outside += std::abs(w);
      }
    }
    d.clear();
  }
  return outside;
}

// For each star primitive p of level 0, the level-1 primitive at the centre (one of `upward`)
// whose corners hold p's child vertex first + p; appends id_base + its index to `out`. One pass
// over the centre's rows (a valence-1000 star has 1000 of each). `unique`: exactly one must.
template <class Corners>
bool append_children(std::span<const std::uint32_t> upward, const Corners& corners, std::uint32_t first,
                     const std::vector<std::uint32_t>& parents, std::uint32_t id_base, bool unique,
                     std::vector<std::uint32_t>& out) {
  std::unordered_map<std::uint32_t, std::pair<std::uint32_t, std::uint32_t>> holder;  // vertex -> (primitive, count)
  for (const std::uint32_t u : upward)
    for (const std::uint32_t x : corners(u)) {
      auto& h = holder[x];
      h.first = u;
      ++h.second;
    }
  for (const std::uint32_t p : parents) {
    const auto it = holder.find(first + p);
    if (it == holder.end() || (unique && it->second.second != 1)) return false;
    out.push_back(id_base + it->second.first);
  }
  return true;
}

Operators local_operators(const Complex& patch) {
  Operators o;
  const std::uint32_t np = patch.num_vertices;
  const Hierarchy h = make_hierarchy(patch, 2, Scheme::Cubic, 3);
  const Complex& P0 = h.levels[0];
  const Complex& P1 = h.levels[1];
  const std::uint8_t m = o.m = P0.vertex_dim[0];
  // Star of the centre at level 0 (feature-filtered) and the level-1 vertices it maps to.
  std::vector<std::uint32_t> se, sf, sc;
  for (std::uint32_t e : P0.vertex_edges.row(0))
    if (P0.edge_dim[e] <= m) se.push_back(e);
  for (std::uint32_t f : P0.vertex_faces.row(0))
    if (P0.face_dim[f] <= m) sf.push_back(f);
  if (m == 3)
    for (std::uint32_t k : P0.vertex_cells.row(0)) sc.push_back(k);
  o.edges = static_cast<std::uint32_t>(se.size());
  o.faces = static_cast<std::uint32_t>(sf.size());
  o.cells = static_cast<std::uint32_t>(sc.size());
  const std::uint32_t E0 = P0.num_vertices, F0 = E0 + P0.num_edges(), K0 = F0 + P0.num_faces();
  std::vector<std::uint32_t> I1{0};
  for (std::uint32_t e : se) I1.push_back(E0 + e);
  for (std::uint32_t f : sf) I1.push_back(F0 + f);
  for (std::uint32_t k : sc) I1.push_back(K0 + k);
  // The level-1 primitives at the centre that are children of those, and their level-2 children.
  const std::uint32_t nv1 = P1.num_vertices, ne1 = P1.num_edges(), nf1 = P1.num_faces();
  std::vector<std::uint32_t> I2{0};
  const auto edge_ends = [&](std::uint32_t e1) {
    return std::array<std::uint32_t, 2>{P1.edge_verts[2 * e1], P1.edge_verts[2 * e1 + 1]};
  };
  const auto face_corners = [&](std::uint32_t f1) { return P1.faces.row(f1); };
  const auto cell_corners = [&](std::uint32_t k1) { return P1.cell_verts.row(k1); };
  if (!append_children(P1.vertex_edges.row(0), edge_ends, E0, se, nv1, false, I2) ||
      !append_children(P1.vertex_faces.row(0), face_corners, F0, sf, nv1 + ne1, true, I2) ||
      (!sc.empty() && !append_children(P1.vertex_cells.row(0), cell_corners, K0, sc, nv1 + ne1 + nf1, true, I2)))
    return o;
  const auto k = static_cast<std::int32_t>(I1.size());
  std::vector<std::int32_t> row1(nv1, -1), row2(h.num_vertices(2), -1), col_p(np), col_s(nv1, -1);
  for (std::int32_t i = 0; i < k; ++i) row1[I1[std::size_t(i)]] = row2[I2[std::size_t(i)]] = col_s[I1[std::size_t(i)]] = i;
  std::iota(col_p.begin(), col_p.end(), 0);
  std::vector<Eigen::Triplet<double>> t;
  impulse_columns(h.transitions[0], P0, nv1, np, row1, col_p, t);
  o.P.resize(k, np);
  o.P.setFromTriplets(t.begin(), t.end());
  t.clear();
  // Every level-1 vertex is probed: those outside the star must not reach the level-2 star.
  if (impulse_columns(h.transitions[1], P1, h.num_vertices(2), nv1, row2, col_s, t) > 1e-12) return o;
  o.S.resize(k, k);
  o.S.setFromTriplets(t.begin(), t.end());
  o.ok = true;
  return o;
}

std::vector<double> to_vector(const Eigen::VectorXd& v) { return {v.data(), v.data() + v.size()}; }

// Dense: Eigen's eigen-analysis of S (any configuration; cubic in the star size).
PatchSolution solve_dense(const Operators& o) {
  PatchSolution out;
  const Eigen::MatrixXd S(o.S);
  const Eigen::Index k = S.rows();
  // Spectrum, descending by modulus.
  Eigen::EigenSolver<Eigen::MatrixXd> es(S, /*computeEigenvectors=*/false);
  std::vector<Cx> ev(es.eigenvalues().data(), es.eigenvalues().data() + k);
  std::sort(ev.begin(), ev.end(), [](Cx a, Cx b) { return std::abs(a) > std::abs(b); });
  for (Cx z : ev) out.spectrum.push_back(std::abs(z));
  if (std::abs(ev[0] - 1.0) > 1e-9 || (k > 1 && std::abs(ev[1]) > 1.0 - 1e-9)) return out;
  // Left eigenvector for 1: (S^T - I) l = 0 with sum(l) = 1; the rows of S^T - I sum to zero
  // (S reproduces constants), so one of them can be replaced by the normalisation.
  Eigen::MatrixXd A = S.transpose() - Eigen::MatrixXd::Identity(k, k);
  A.row(0).setOnes();
  Eigen::VectorXd b = Eigen::VectorXd::Zero(k);
  b(0) = 1.0;
  const Eigen::VectorXd l = A.fullPivLu().solve(b);
  out.weights = to_vector(o.P.transpose() * l);
  out.ok = true;
  // Tangents of a surface point: a real double subdominant eigenvalue with a gap below it.
  if (o.m == 2 && k >= 4) {
    const Cx l2 = ev[1], l3 = ev[2];
    const double gap = std::abs(l3) - std::abs(ev[3]);
    if (std::abs(l2.imag()) < 1e-9 && std::abs(l3.imag()) < 1e-9 && std::abs(l2 - l3) < 1e-9 && gap > 1e-6 &&
        std::abs(l2) > 1e-6) {
      const Eigen::MatrixXd B = S.transpose() - l2.real() * Eigen::MatrixXd::Identity(k, k);
      Eigen::JacobiSVD<Eigen::MatrixXd> svd(B, Eigen::ComputeFullV);
      const auto& sv = svd.singularValues();
      if (sv(k - 2) < 1e-8 * std::max(1.0, sv(0))) {
        out.du = to_vector(o.P.transpose() * Eigen::VectorXd(svd.matrixV().col(k - 1)));
        out.dv = to_vector(o.P.transpose() * Eigen::VectorXd(svd.matrixV().col(k - 2)));
      }
    }
  }
  return out;
}

// The limit position's left eigenvector by power iteration, l <- S^T l from the centre's impulse:
// it converges as |lambda_2|^i (about 0.65^i for quads at any valence), so ~100 sparse products.
bool power_iteration(const SparseRows& S, Eigen::VectorXd& l) {
  const SparseRows St = S.transpose();
  l = Eigen::VectorXd::Zero(S.rows());
  l(0) = 1.0;
  int settled = -1;  // iterations since the change fell below 1e-15: a few more take it to round-off
  for (int it = 0; it < 5000; ++it) {
    Eigen::VectorXd next = St * l;
    const double change = (next - l).lpNorm<Eigen::Infinity>();
    l.swap(next);
    if (settled < 0 && change <= 1e-15) settled = 0;
    if (settled >= 0 && ++settled == 40) return true;
  }
  return false;
}

// A uniform fan's S is block-circulant in the star order [c | e_0..e_{n-1} | f_0..f_{n-1}]:
// S[a_i][b_j] = G_ab[(j - i) mod n] for the classes a, b in {e, f}, and the centre's row and
// column are constant on each class. Then every frequency w of the rotation is an invariant
// subspace: B_w = sum_d G_d zeta^(w d) with zeta = exp(2 pi i / n) (2 x 2; at w = 0 the centre
// joins, 3 x 3), and a left eigenvector w of B_1 gives S's left eigenvectors l_{a_j} = w_a zeta^-j.
struct Circulant {
  std::uint32_t n = 0;
  double cc = 0, c_to[2] = {0, 0}, to_c[2] = {0, 0};        // S[c][c], S[c][a_j], S[a_i][c]
  std::vector<std::pair<std::uint32_t, double>> G[2][2];  // non-zeros (d, value) of G_ab
};

bool circulant(const Operators& o, Circulant& z) {
  const std::uint32_t n = o.edges;
  if (o.m != 2 || o.cells != 0 || o.faces != n || n < 3) return false;
  z.n = n;
  constexpr double kTol = 1e-13, kZero = 1e-14;
  auto cls = [n](Eigen::Index r, std::uint32_t& i) {  // -1 centre, 0 edge, 1 face
    if (r == 0) return -1;
    i = static_cast<std::uint32_t>(r - 1) % n;
    return r <= Eigen::Index(n) ? 0 : 1;
  };
  std::vector<double> gen[2][2];
  for (auto& a : gen)
    for (auto& g : a) g.assign(n, 0.0);
  bool seen_c_to[2] = {false, false};
  // Generators from the centre's row and from rows e_0 and f_0.
  for (const Eigen::Index r : {Eigen::Index(0), Eigen::Index(1), Eigen::Index(n) + 1})
    for (SparseRows::InnerIterator it(o.S, r); it; ++it) {
      std::uint32_t i = 0, j = 0;
      const int a = cls(r, i), b = cls(it.col(), j);
      if (a < 0 && b < 0) z.cc = it.value();
      else if (a < 0) {
        if (seen_c_to[b] && std::abs(z.c_to[b] - it.value()) > kTol) return false;
        z.c_to[b] = it.value(), seen_c_to[b] = true;
      } else if (b < 0) z.to_c[a] = it.value();
      else gen[a][b][j] = it.value();
    }
  std::size_t nnz[2][2] = {{0, 0}, {0, 0}};
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b)
      for (std::uint32_t d = 0; d < n; ++d)
        if (std::abs(gen[a][b][d]) > kZero) z.G[a][b].emplace_back(d, gen[a][b][d]), ++nnz[a][b];
  // Every row matches its class's generator shifted by its index, with as many non-zeros.
  std::size_t centre_row[2] = {0, 0};
  for (Eigen::Index r = 0; r < o.S.rows(); ++r) {
    std::uint32_t i = 0, j = 0;
    const int a = cls(r, i);
    std::size_t count[2] = {0, 0};
    for (SparseRows::InnerIterator it(o.S, r); it; ++it) {
      const int b = cls(it.col(), j);
      double expect;
      if (a < 0) expect = b < 0 ? z.cc : z.c_to[b];
      else expect = b < 0 ? z.to_c[a] : gen[a][b][(j + n - i) % n];
      if (std::abs(it.value() - expect) > kTol) return false;
      if (b >= 0 && std::abs(it.value()) > kZero) ++(a < 0 ? centre_row[b] : count[b]);
    }
    if (a >= 0 && (count[0] != nnz[a][0] || count[1] != nnz[a][1])) return false;
  }
  for (int b = 0; b < 2; ++b)
    if (centre_row[b] != 0 && centre_row[b] != n) return false;
  // The centre column is constant on each class: every row e_i / f_i was compared with to_c, but
  // a row without a centre entry must have a zero generator there.
  for (int a = 0; a < 2; ++a)
    if (std::abs(z.to_c[a]) > kZero) {
      std::size_t with = 0;
      for (Eigen::Index r = 1; r < o.S.rows(); ++r) {
        std::uint32_t i = 0;
        if (cls(r, i) == a && o.S.coeff(r, 0) != 0.0) ++with;
      }
      if (with != n) return false;
    }
  return true;
}

Eigen::Matrix2cd frequency_block(const Circulant& z, std::uint32_t w) {
  Eigen::Matrix2cd B = Eigen::Matrix2cd::Zero();
  const double step = 2 * std::numbers::pi * double(w) / double(z.n);
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b)
      for (const auto& [d, g] : z.G[a][b]) B(a, b) += g * std::polar(1.0, step * double(d));
  return B;
}

// Eigenvalues of a 2 x 2 complex matrix.
std::array<Cx, 2> eigenvalues(const Eigen::Matrix2cd& B) {
  const Cx tr = B.trace(), det = B.determinant();
  const Cx root = std::sqrt(tr * tr - 4.0 * det);
  return {(tr + root) / 2.0, (tr - root) / 2.0};
}

// Structured: no dense matrix of the star's size anywhere.
PatchSolution solve_structured(const Operators& o) {
  PatchSolution out;
  Eigen::VectorXd l;
  if (!power_iteration(o.S, l)) return out;
  Circulant z;
  const bool sym = circulant(o, z);
  if (sym) {
    // The spectrum: frequency 0 (with the centre) and the 2 x 2 blocks of the others.
    Eigen::MatrixXd B0(3, 3);  // dynamic: one EigenSolver instantiation for the file (a fixed 3 x 3 one doubled its build time)
    const double n = z.n;
    double sum[2][2] = {{0, 0}, {0, 0}};
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b)
        for (const auto& [d, g] : z.G[a][b]) sum[a][b] += g;
    B0 << z.cc, n * z.c_to[0], n * z.c_to[1], z.to_c[0], sum[0][0], sum[0][1], z.to_c[1], sum[1][0], sum[1][1];
    std::vector<Cx> ev;
    const Eigen::EigenSolver<Eigen::MatrixXd> e0(B0, false);
    for (int i = 0; i < 3; ++i) ev.push_back(e0.eigenvalues()(i));
    Cx tangent{0, 0};  // the dominant eigenvalue of frequency 1
    double others = 0;  // the largest |eigenvalue| away from frequencies 1 and n - 1, and 1 itself
    for (std::uint32_t w = 1; w < z.n; ++w) {
      const auto pair = eigenvalues(frequency_block(z, w));
      for (const Cx x : pair) ev.push_back(x);
      const Cx top = std::abs(pair[0]) >= std::abs(pair[1]) ? pair[0] : pair[1];
      const Cx low = std::abs(pair[0]) >= std::abs(pair[1]) ? pair[1] : pair[0];
      if (w == 1) tangent = top;
      others = std::max(others, std::abs(low));
      if (w != 1 && w != z.n - 1) others = std::max(others, std::abs(top));
    }
    std::sort(ev.begin(), ev.end(), [](Cx a, Cx b) { return std::abs(a) > std::abs(b); });
    for (const Cx x : ev) out.spectrum.push_back(std::abs(x));
    if (std::abs(ev[0] - 1.0) > 1e-9 || std::abs(ev[1]) > 1.0 - 1e-9) return out;
    // The frequency-0 eigenvalues other than 1 count as "others" as well.
    for (int i = 0; i < 3; ++i)
      if (std::abs(e0.eigenvalues()(i) - 1.0) > 1e-9) others = std::max(others, std::abs(e0.eigenvalues()(i)));
    out.weights = to_vector(o.P.transpose() * l);
    out.ok = true;
    if (std::abs(tangent.imag()) < 1e-9 && std::abs(tangent) > others + 1e-12 && std::abs(tangent) > 1e-6) {
      // Left eigenvector of B_1: B_1^T w = lambda w.
      const Eigen::Matrix2cd M = frequency_block(z, 1).transpose();
      Eigen::Vector2cd w(M(0, 1), tangent - M(0, 0));
      const Eigen::Vector2cd alt(tangent - M(1, 1), M(1, 0));
      if (alt.norm() > w.norm()) w = alt;
      Eigen::VectorXd t1 = Eigen::VectorXd::Zero(o.S.rows()), t2 = t1;
      for (std::uint32_t j = 0; j < z.n; ++j) {
        const Cx turn = std::polar(1.0, -2 * std::numbers::pi * double(j) / n);
        for (int a = 0; a < 2; ++a) {
          const Cx x = w(a) * turn;
          t1(1 + a * z.n + j) = x.real();
          t2(1 + a * z.n + j) = x.imag();
        }
      }
      out.du = to_vector(o.P.transpose() * t1);
      out.dv = to_vector(o.P.transpose() * t2);
    }
    return out;
  }
  // Not a uniform fan: the position only (power iteration converged, so eigenvalue 1 dominates).
  out.weights = to_vector(o.P.transpose() * l);
  out.ok = true;
  return out;
}

}  // namespace

PatchSolution solve_limit_patch(const Complex& patch, LimitSolver solver) {
  const Operators o = local_operators(patch);
  if (!o.ok) return {};
  const bool dense =
      solver == LimitSolver::Dense || (solver == LimitSolver::Auto && std::size_t(o.S.rows()) <= kLimitDenseStar);
  return dense ? solve_dense(o) : solve_structured(o);
}

}  // namespace sublift
