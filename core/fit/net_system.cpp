#include "core/fit/net_system.h"

#include <algorithm>
#include <array>
#include <limits>

#include "core/base/parallel.h"

namespace sublift::fit_detail {

namespace {

constexpr std::uint32_t kGrain = 4096;

using Sums = std::array<double, 3>;

// N sums of f(v, sums) over [0, n), in blocks of a fixed size added in order, so the bits do not
// depend on the threads. f may also write its own vertex's entries.
template <std::size_t N = 3, class F>
std::array<double, N> block_sums(std::uint32_t n, const F& f) {
  const std::uint32_t blocks = (n + kGrain - 1) / kGrain;
  std::vector<std::array<double, N>> part(blocks, std::array<double, N>{});
  parallel_for(blocks, 1, [&](std::uint32_t b0, std::uint32_t b1) {
    for (std::uint32_t b = b0; b < b1; ++b)
      for (std::uint32_t v = b * kGrain; v < std::min(n, (b + 1) * kGrain); ++v) f(v, part[b]);
  });
  std::array<double, N> total{};
  for (const auto& s : part)
    for (std::size_t k = 0; k < N; ++k) total[k] += s[k];
  return total;
}

}  // namespace

void multiply(RowsView m, std::span<const double> x, std::span<double> y) {
  parallel_for(static_cast<std::uint32_t>(m.rows()), kGrain, [&](std::uint32_t b, std::uint32_t e) {
    for (std::uint32_t r = b; r < e; ++r) {
      double s0 = 0, s1 = 0, s2 = 0;
      for (std::uint32_t k = m.offsets[r]; k < m.offsets[r + 1]; ++k) {
        const double* p = x.data() + 3 * std::size_t(m.cols[k]);
        const double w = m.w[k];
        s0 += w * p[0], s1 += w * p[1], s2 += w * p[2];
      }
      y[3 * std::size_t(r)] = s0, y[3 * std::size_t(r) + 1] = s1, y[3 * std::size_t(r) + 2] = s2;
    }
  });
}

WeightedRows transposed(RowsView m, std::uint32_t cols) {
  WeightedRows t;
  t.offsets.assign(std::size_t(cols) + 1, 0);
  for (const std::uint32_t c : m.cols) ++t.offsets[c + 1];
  for (std::uint32_t c = 0; c < cols; ++c) t.offsets[c + 1] += t.offsets[c];
  t.cols.resize(m.cols.size());
  t.w.resize(m.cols.size());
  std::vector<std::uint32_t> next(t.offsets.begin(), t.offsets.end() - 1);
  for (std::uint32_t r = 0; r < m.rows(); ++r)
    for (std::uint32_t k = m.offsets[r]; k < m.offsets[r + 1]; ++k) {
      const std::uint32_t at = next[m.cols[k]]++;
      t.cols[at] = r, t.w[at] = m.w[k];
    }
  return t;
}

WeightedRows net_rows(const Complex& c, std::span<const double> diagonal, std::span<const double> edge, std::span<const Coupling> couplings) {
  const std::uint32_t n = c.num_vertices;
  std::vector<std::uint32_t> more(std::size_t(n) + 1, 0);  // the couplings' rows, counted then placed
  for (const Coupling& k : couplings) ++more[k.a + 1], ++more[k.b + 1];
  WeightedRows m;
  m.offsets.resize(std::size_t(n) + 1);
  m.offsets[0] = 0;
  for (std::uint32_t v = 0; v < n; ++v) m.offsets[v + 1] = m.offsets[v] + 1 + c.vertex_edges.size(v) + more[v + 1];
  m.cols.resize(m.offsets[n]);
  m.w.resize(m.offsets[n]);
  std::vector<std::uint32_t> next(n);
  for (std::uint32_t v = 0; v < n; ++v) {
    std::uint32_t at = m.offsets[v];
    m.cols[at] = v, m.w[at] = diagonal[v], ++at;
    for (const std::uint32_t e : c.vertex_edges.row(v)) m.cols[at] = edge_other_end(c, e, v), m.w[at] = edge[e], ++at;
    next[v] = at;
  }
  for (const Coupling& k : couplings) {
    m.cols[next[k.a]] = k.b, m.w[next[k.a]++] = k.w;
    m.cols[next[k.b]] = k.a, m.w[next[k.b]++] = k.w;
  }
  return m;
}

void NetSystem::apply(std::span<const double> x, std::span<double> y) const {
  if (limit.rows() == 0) return multiply(data, x, y);
  lx_.resize(x.size()), mlx_.resize(x.size());
  multiply(limit, x, lx_);
  multiply(data, lx_, mlx_);
  multiply(limit_t, mlx_, y);
  // + K x: kappa times each edge's difference.
  const Complex& c = *net;
  parallel_for(c.num_vertices, kGrain, [&](std::uint32_t b, std::uint32_t e) {
    for (std::uint32_t v = b; v < e; ++v) {
      double s0 = 0, s1 = 0, s2 = 0;
      const double* p = x.data() + 3 * std::size_t(v);
      for (const std::uint32_t edge : c.vertex_edges.row(v)) {
        const double* q = x.data() + 3 * std::size_t(edge_other_end(c, edge, v));
        s0 += p[0] - q[0], s1 += p[1] - q[1], s2 += p[2] - q[2];
      }
      double* o = y.data() + 3 * std::size_t(v);
      o[0] += kappa * s0, o[1] += kappa * s1, o[2] += kappa * s2;
    }
  });
}

std::vector<double> NetSystem::diagonal() const {
  const std::uint32_t n = static_cast<std::uint32_t>(data.offsets.size() - 1);
  std::vector<double> d(n);
  if (limit.rows() == 0) {
    for (std::uint32_t v = 0; v < n; ++v) d[v] = data.w[data.offsets[v]];  // net_rows puts it first
    return d;
  }
  // (L^T M L)_jj = sum over i, k in column j of L of L_ij M_ik L_kj.
  parallel_for(n, kGrain, [&](std::uint32_t b, std::uint32_t e) {
    thread_local std::vector<double> column;  // L_kj of column j, zero elsewhere
    if (column.size() < n) column.assign(n, 0.0);
    for (std::uint32_t j = b; j < e; ++j) {
      const std::uint32_t lo = limit_t.offsets[j], hi = limit_t.offsets[j + 1];
      for (std::uint32_t k = lo; k < hi; ++k) column[limit_t.cols[k]] = limit_t.w[k];
      double s = 0;
      for (std::uint32_t k = lo; k < hi; ++k) {
        const std::uint32_t i = limit_t.cols[k];
        double mi = 0;
        for (std::uint32_t m = data.offsets[i]; m < data.offsets[i + 1]; ++m) mi += data.w[m] * column[data.cols[m]];
        s += limit_t.w[k] * mi;
      }
      for (std::uint32_t k = lo; k < hi; ++k) column[limit_t.cols[k]] = 0.0;
      d[j] = s + kappa * net->vertex_edges.size(j);
    }
  });
  return d;
}

int solve_cg3(const NetSystem& a, std::span<const double> b, std::span<double> x, double tol, int max_iterations) {
  const std::uint32_t n = static_cast<std::uint32_t>(b.size() / 3);
  std::vector<double> inv = a.diagonal();
  for (double& d : inv) d = d != 0.0 ? 1.0 / d : 1.0;
  std::vector<double> r(b.size()), p(b.size()), q(b.size());
  a.apply(x, q);
  // r = b - A x, p = z = r / diag; |b|^2, |r|^2 and r . z per coordinate.
  const std::array<double, 9> start = block_sums<9>(n, [&](std::uint32_t v, std::array<double, 9>& s) {
    for (int k = 0; k < 3; ++k) {
      const std::size_t i = 3 * std::size_t(v) + k;
      r[i] = b[i] - q[i];
      p[i] = inv[v] * r[i];
      s[k] += b[i] * b[i], s[3 + k] += r[i] * r[i], s[6 + k] += r[i] * p[i];
    }
  });
  std::array<bool, 3> active{};
  Sums threshold{}, rz{};
  for (int k = 0; k < 3; ++k) {
    threshold[k] = std::max(tol * tol * start[k], std::numeric_limits<double>::min());
    if (start[k] == 0.0)  // Eigen's answer to a zero right-hand side
      for (std::uint32_t v = 0; v < n; ++v) x[3 * std::size_t(v) + k] = 0.0;
    active[k] = start[k] != 0.0 && start[3 + k] >= threshold[k];
    rz[k] = start[6 + k];
  }
  int iterations = 0;
  while (iterations < max_iterations && (active[0] || active[1] || active[2])) {
    a.apply(p, q);
    const Sums pq = block_sums(n, [&](std::uint32_t v, Sums& s) {
      for (int k = 0; k < 3; ++k) s[k] += p[3 * std::size_t(v) + k] * q[3 * std::size_t(v) + k];
    });
    Sums alpha{};
    for (int k = 0; k < 3; ++k) alpha[k] = active[k] ? rz[k] / pq[k] : 0.0;
    // |r|^2 for the test and r . z (z = r / diag) for the next direction, in one pass.
    const std::array<double, 6> sums = block_sums<6>(n, [&](std::uint32_t v, std::array<double, 6>& s) {
      for (int k = 0; k < 3; ++k) {
        if (!active[k]) continue;
        const std::size_t i = 3 * std::size_t(v) + k;
        x[i] += alpha[k] * p[i];
        r[i] -= alpha[k] * q[i];
        s[k] += r[i] * r[i];
        s[3 + k] += r[i] * (inv[v] * r[i]);
      }
    });
    for (int k = 0; k < 3; ++k) active[k] = active[k] && sums[k] >= threshold[k];
    ++iterations;
    Sums beta{};
    for (int k = 0; k < 3; ++k) beta[k] = active[k] ? sums[3 + k] / rz[k] : 0.0, rz[k] = sums[3 + k];
    parallel_for(n, kGrain, [&](std::uint32_t b0, std::uint32_t b1) {
      for (std::uint32_t v = b0; v < b1; ++v)
        for (int k = 0; k < 3; ++k)
          if (active[k]) p[3 * std::size_t(v) + k] = inv[v] * r[3 * std::size_t(v) + k] + beta[k] * p[3 * std::size_t(v) + k];
    });
  }
  return iterations;
}

}  // namespace sublift::fit_detail
