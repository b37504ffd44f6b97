#include "core/fit/net_solve.h"

#include <algorithm>
#include <cmath>

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "core/base/parallel.h"
#include "core/base/points.h"
#include "core/base/triangle_bvh.h"
#include "core/fit/sparse_product.h"

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

using Sparse = Eigen::SparseMatrix<double>;

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
  // fan diagonals are no edges: their couplings go to `diagonals`.
  const double scale = double(n) / double(ni);
  std::vector<double> diag(n), off(ne, 0.0);
  std::vector<Eigen::Triplet<double>> diagonals;
  Eigen::MatrixX3d rhs(n, 3);
  for (std::uint32_t v = 0; v < n; ++v) {
    diag[v] = wt.alpha * (hold.empty() ? 1.0 : hold[v]);
    rhs.row(v) = diag[v] * Eigen::RowVector3d(st.targets[3 * v], st.targets[3 * v + 1], st.targets[3 * v + 2]);
  }
  for (std::uint32_t i = 0; i < ni; ++i) {
    const auto r = c.faces.row(foot[i].face);
    const auto es = c.face_edges.row(foot[i].face);
    const std::uint32_t t = foot[i].fan, k = static_cast<std::uint32_t>(r.size());
    const std::uint32_t corner[3] = {0, t, t + 1};
    const glm::dvec3 q = at(input, i);
    for (int j = 0; j < 3; ++j) {
      const double bj = foot[i].b[j];
      const std::uint32_t a = corner[j], b = corner[(j + 1) % 3];
      diag[r[a]] += scale * bj * bj;
      rhs.row(r[a]) += scale * bj * Eigen::RowVector3d(q.x, q.y, q.z);
      const double w = scale * bj * foot[i].b[(j + 1) % 3];
      // face edge m joins corners m and m + 1 (mod k)
      if (b == a + 1) off[es[a]] += w;
      else if (a == k - 1 && b == 0) off[es[a]] += w;
      else diagonals.emplace_back(r[a], r[b], w), diagonals.emplace_back(r[b], r[a], w);
    }
  }
  // The springs: kappa times the graph Laplacian (degree on the diagonal, -kappa per edge),
  // towards x0's edge vectors.
  std::vector<double> degree(n, 0.0);
  for (std::uint32_t e = 0; e < ne; ++e) degree[c.edge_verts[2 * e]] += wt.kappa, degree[c.edge_verts[2 * e + 1]] += wt.kappa;
  // `d` on the diagonal, `o` on the edges, `more` (fan diagonals) first, duplicates summed.
  const auto on_edges = [&](const auto& d, const auto& o, std::span<const Eigen::Triplet<double>> more) {
    std::vector<Eigen::Triplet<double>> t;
    t.reserve(n + 2 * std::size_t(ne) + more.size());
    t.insert(t.end(), more.begin(), more.end());
    for (std::uint32_t v = 0; v < n; ++v) t.emplace_back(v, v, d(v));
    for (std::uint32_t e = 0; e < ne; ++e) {
      t.emplace_back(c.edge_verts[2 * e], c.edge_verts[2 * e + 1], o(e));
      t.emplace_back(c.edge_verts[2 * e + 1], c.edge_verts[2 * e], o(e));
    }
    Sparse m(n, n);
    m.setFromTriplets(t.begin(), t.end());
    return m;
  };
  const auto spring_diagonal = [&](std::uint32_t v) { return degree[v]; };
  const auto spring_edge = [&](std::uint32_t) { return -wt.kappa; };
  Eigen::MatrixX3d x0(n, 3);
  for (std::uint32_t v = 0; v < n; ++v) x0.row(v) = Eigen::RowVector3d(st.control[3 * v], st.control[3 * v + 1], st.control[3 * v + 2]);
  // b += springs * x0, added in the order Eigen's `b = y + springs * x0` adds it (into y,
  // column by column of the springs), so bit for bit, without building the matrix.
  const auto add_pull = [&](Eigen::MatrixX3d& b) {
    for (std::uint32_t v = 0; v < n; ++v) {
      b.row(v) += spring_diagonal(v) * x0.row(v);
      for (std::uint32_t e : c.vertex_edges.row(v)) b.row(edge_other_end(c, e, v)) += spring_edge(e) * x0.row(v);
    }
  };
  Sparse A;
  Eigen::MatrixX3d b;
  if (st.limit) {
    std::vector<Eigen::Triplet<double>> t;
    t.reserve(st.limit->weights.size());
    for (std::uint32_t v = 0; v < n; ++v) {
      const std::uint32_t o = st.limit->rows.offsets[v];
      for (std::uint32_t k = o; k < st.limit->rows.offsets[v + 1]; ++k) t.emplace_back(v, st.limit->rows.items[k], st.limit->weights[k]);
    }
    Sparse L(n, n);
    L.setFromTriplets(t.begin(), t.end());
    const Sparse Lt = L.transpose();
    const Sparse M = on_edges([&](std::uint32_t v) { return diag[v]; }, [&](std::uint32_t e) { return off[e]; }, diagonals);
    A = fit_detail::sparse_product(fit_detail::sparse_product(Lt, M), L) + on_edges(spring_diagonal, spring_edge, {});
    b = Lt * rhs;
    add_pull(b);
  } else {
    // M + springs in one matrix: their diagonal and edge entries are one term each, so the sums
    // are M + springs' bit for bit (rounded otherwise only where a face's diagonal is also an edge).
    A = on_edges([&](std::uint32_t v) { return diag[v] + spring_diagonal(v); }, [&](std::uint32_t e) { return off[e] + spring_edge(e); },
                 diagonals);
    b = rhs;
    add_pull(b);
  }
  // x, y and z are three independent solves: side by side, a solver each (Eigen's keeps its
  // iteration count in itself). Each column's arithmetic is the same as one after another.
  std::vector<double> out(3 * std::size_t(n));
  parallel_for(3, 1, [&](std::uint32_t begin, std::uint32_t end) {
    for (std::uint32_t k = begin; k < end; ++k) {
      Eigen::ConjugateGradient<Sparse, Eigen::Lower | Eigen::Upper> cg;
      cg.setTolerance(1e-10);
      cg.setMaxIterations(500);
      cg.compute(A);
      const Eigen::VectorXd col = cg.solveWithGuess(b.col(k), x0.col(k));
      for (std::uint32_t v = 0; v < n; ++v) out[3 * std::size_t(v) + k] = col[v];
    }
  });
  return out;
}

}  // namespace sublift
