#pragma once
// The fitting solve's linear system (core/fit/net_solve.h), applied without forming it:
//   A = L^T M L + K,
// L the limit stencils (or none: the surface is the net), M the data terms on the net's vertices,
// edges and fan diagonals, K the springs (kappa times the graph Laplacian). Formed, L^T M L has
// about 50 entries a row where L has 9 (the cubic scheme; Loop's 7), and building it cost four
// times the solve and gigabytes of fresh memory at a million vertices (docs/fit.md); applied, it
// is three gathers per iteration. Solved by conjugate gradients with Jacobi preconditioning, as
// Eigen's ConjugateGradient does, the three coordinates side by side. Every sum is taken in an
// order fixed by the data, so results do not depend on the number of threads.
#include <cstdint>
#include <span>
#include <vector>

#include "core/complex/complex.h"

namespace sublift::fit_detail {

/// Rows of a sparse matrix over the net's vertices: row r's columns cols[offsets[r]..offsets[r+1])
/// with weights w alongside.
struct WeightedRows {
  std::vector<std::uint32_t> offsets{0}, cols;
  std::vector<double> w;
};

/// Read-only view of such rows (the limit stencils are kept as a Csr and weights).
struct RowsView {
  std::span<const std::uint32_t> offsets, cols;
  std::span<const double> w;
  RowsView() = default;
  RowsView(std::span<const std::uint32_t> o, std::span<const std::uint32_t> c, std::span<const double> ws) : offsets(o), cols(c), w(ws) {}
  RowsView(const WeightedRows& r) : offsets(r.offsets), cols(r.cols), w(r.w) {}  // NOLINT: a view of it
  std::size_t rows() const { return offsets.empty() ? 0 : offsets.size() - 1; }
};

/// The transpose of `m`, whose columns are < `cols` (a counting sort; each row in column order).
WeightedRows transposed(RowsView m, std::uint32_t cols);

/// y = m x, three coordinates per row interleaved (on the pool).
void multiply(RowsView m, std::span<const double> x, std::span<double> y);

/// A coupling of net vertices a and b that is no edge of the net (a polygon's fan diagonal).
struct Coupling {
  std::uint32_t a, b;
  double w;
};

/// Rows over `c`'s vertices: `diagonal[v]` first, then `edge[e]` for each edge of v in
/// vertex_edges order, then the couplings of v (both ways, in list order; repeats kept apart).
WeightedRows net_rows(const Complex& c, std::span<const double> diagonal, std::span<const double> edge, std::span<const Coupling> couplings);

struct NetSystem {
  const Complex* net = nullptr;
  RowsView limit;            // L; empty: the surface is the net (A = M + K)
  WeightedRows limit_t;      // L^T (with `limit`)
  WeightedRows data;         // M, or M + K without a limit
  double kappa = 0;          // K, applied through the net's edges (with `limit`)

  /// y = A x; x and y hold three coordinates per vertex, interleaved. One caller at a time.
  void apply(std::span<const double> x, std::span<double> y) const;
  /// A's diagonal.
  std::vector<double> diagonal() const;

 private:
  mutable std::vector<double> lx_, mlx_;  // apply's L x and M L x
};

/// x (in: the first guess) solves A x = b per coordinate to |r| <= tol |b| or `max_iterations`
/// (Eigen's ConjugateGradient's test, with its DiagonalPreconditioner). Returns the largest
/// iteration count of the three.
int solve_cg3(const NetSystem& a, std::span<const double> b, std::span<double> x, double tol, int max_iterations);

}  // namespace sublift::fit_detail
