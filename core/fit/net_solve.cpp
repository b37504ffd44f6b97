#include "core/fit/net_solve.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "core/base/parallel.h"
#include "core/base/points.h"
#include "core/base/triangle_bvh.h"
#include "core/fit/net_system.h"

namespace sublift {

namespace {

// Barycentric weights of q (on or near triangle a, b, c) clamped into the triangle.
glm::dvec3 barycentric(const glm::dvec3& q, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  const glm::dvec3 e1 = b - a, e2 = c - a, d = q - a;
  const double d11 = glm::dot(e1, e1), d12 = glm::dot(e1, e2), d22 = glm::dot(e2, e2);
  const double d1 = glm::dot(d, e1), d2 = glm::dot(d, e2);
  const double det = d11 * d22 - d12 * d12;
  if (!(det > 0)) return {1.0, 0.0, 0.0};  // a degenerate face: its first corner
  double v = (d22 * d1 - d12 * d2) / det, w = (d11 * d2 - d12 * d1) / det;
  v = std::clamp(v, 0.0, 1.0);
  w = std::clamp(w, 0.0, 1.0 - v);
  return {1.0 - v - w, v, w};
}

}  // namespace

std::vector<double> solve_net(const Complex& c, const NetSolveState& st, std::span<const double> input,
                              std::span<const double> input_normals, std::span<const double> hold, const NetSolveWeights& wt) {
  const std::uint32_t n = c.num_vertices, ne = c.num_edges();
  const std::uint32_t ni = static_cast<std::uint32_t>(input.size() / 3);
  if (n == 0 || ni == 0) return {st.control.begin(), st.control.end()};
  // Each input vertex's closest point on the surface.
  std::optional<TriangleBvh> own;
  std::optional<TriangleBvh>& slot = st.index ? *st.index : own;
  if (slot) slot->refit(st.surface);
  else slot.emplace(st.surface, c.faces);
  const TriangleBvh& surface = *slot;
  // On a polygon, the foot lies on one triangle of its fan (corners 0, t, t + 1), as the
  // hierarchy of closest points triangulates it.
  struct Foot {
    std::uint32_t face, fan;
    glm::dvec3 b;
  };
  std::vector<Foot> foot(ni);
  parallel_for(ni, 2048, [&](std::uint32_t lo, std::uint32_t hi) {
    for (std::uint32_t i = lo; i < hi; ++i) {
      const glm::dvec3 q = at(input, i), nq = at(input_normals, i);
      const std::uint32_t hint = st.hints.empty() ? UINT32_MAX : st.hints[i];
      TriangleBvh::Closest cl = surface.closest(q, glm::dot(nq, nq) > 0 ? &nq : nullptr, hint);
      if (cl.face == UINT32_MAX) cl = surface.closest(q, nullptr, hint);
      if (!st.hints.empty()) st.hints[i] = cl.face;
      const auto r = c.faces.row(cl.face);
      Foot best{cl.face, 1, {}};
      double best_d = INFINITY;
      for (std::uint32_t t = 1; t + 1 < r.size(); ++t) {
        const glm::dvec3 p0 = at(st.surface, r[0]), p1 = at(st.surface, r[t]), p2 = at(st.surface, r[t + 1]);
        const glm::dvec3 b = barycentric(cl.point, p0, p1, p2);
        const double d = glm::distance(cl.point, b[0] * p0 + b[1] * p1 + b[2] * p2);
        if (d < best_d) best_d = d, best = {cl.face, t, b};
      }
      foot[i] = best;
    }
  });
  // The data terms on the surface points: M = D + s B^T B lives on the net's vertices and edges
  // (B^T B couples the corners of a face only), with right-hand side D c + s B^T q. A polygon's
  // fan diagonals (0, m), m = 2 .. k - 2, are no edges: their couplings go to `fan`.
  const double scale = double(n) / double(ni);
  std::vector<double> diag(n), off(ne, 0.0), rhs(3 * std::size_t(n));
  std::vector<std::uint32_t> fan_at(c.faces.rows() + 1, 0);
  for (std::size_t f = 0; f < c.faces.rows(); ++f) fan_at[f + 1] = fan_at[f] + std::max<std::uint32_t>(c.faces.size(f), 3) - 3;
  std::vector<double> fan(fan_at.back(), 0.0);
  for (std::uint32_t v = 0; v < n; ++v) {
    diag[v] = wt.alpha * (hold.empty() ? 1.0 : hold[v]);
    for (int k = 0; k < 3; ++k) rhs[3 * std::size_t(v) + k] = diag[v] * st.targets[3 * std::size_t(v) + k];
  }
  for (std::uint32_t i = 0; i < ni; ++i) {
    const std::uint32_t f = foot[i].face;
    const auto r = c.faces.row(f);
    const auto es = c.face_edges.row(f);
    const std::uint32_t t = foot[i].fan, k = static_cast<std::uint32_t>(r.size());
    const std::uint32_t corner[3] = {0, t, t + 1};
    for (int j = 0; j < 3; ++j) {
      const double bj = foot[i].b[j];
      const std::uint32_t a = corner[j], b = corner[(j + 1) % 3];
      diag[r[a]] += scale * bj * bj;
      for (int d = 0; d < 3; ++d) rhs[3 * std::size_t(r[a]) + d] += scale * bj * input[3 * std::size_t(i) + d];
      const double w = scale * bj * foot[i].b[(j + 1) % 3];
      // face edge m joins corners m and m + 1 (mod k); otherwise a diagonal (0, a + b)
      if (b == a + 1 || (a == k - 1 && b == 0)) off[es[a]] += w;
      else fan[fan_at[f] + a + b - 2] += w;
    }
  }
  std::vector<fit_detail::Coupling> couplings;
  for (std::size_t f = 0; f < c.faces.rows(); ++f)
    for (std::uint32_t m = fan_at[f]; m < fan_at[f + 1]; ++m)
      if (fan[m] != 0.0) couplings.push_back({c.faces.row(f)[0], c.faces.row(f)[m - fan_at[f] + 2], fan[m]});
  // The springs K: kappa times the graph Laplacian, towards x0's edge vectors (b += K x0).
  // Without L, K goes into M's rows.
  fit_detail::NetSystem a;
  a.net = &c;
  if (st.limit) {
    a.limit = {st.limit->rows.offsets, st.limit->rows.items, st.limit->weights};
    a.limit_t = fit_detail::transposed(a.limit, n);
    a.kappa = wt.kappa;
  } else {
    for (std::uint32_t v = 0; v < n; ++v) diag[v] += wt.kappa * c.vertex_edges.size(v);
    for (double& o : off) o -= wt.kappa;
  }
  a.data = fit_detail::net_rows(c, diag, off, couplings);
  std::vector<double> b(rhs.size());
  if (st.limit) fit_detail::multiply(a.limit_t, rhs, b);
  else b = rhs;
  parallel_for(n, 4096, [&](std::uint32_t lo, std::uint32_t hi) {
    for (std::uint32_t v = lo; v < hi; ++v)
      for (const std::uint32_t e : c.vertex_edges.row(v))
        for (int d = 0; d < 3; ++d) b[3 * std::size_t(v) + d] += wt.kappa * (st.control[3 * std::size_t(v) + d] - st.control[3 * std::size_t(edge_other_end(c, e, v)) + d]);
  });
  std::vector<double> out(st.control.begin(), st.control.end());
  fit_detail::solve_cg3(a, b, out, 1e-10, 500);
  return out;
}

}  // namespace sublift
