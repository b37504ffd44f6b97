#pragma once
// Internal to core/fit: the sparse product of the fitting solve under a limit surface
// (net_solve.cpp: L^T M L, its largest serial part).
#include <Eigen/SparseCore>

namespace sublift::fit_detail {

/// a * b (column-major, compressed) as Eigen's conservative sparse product computes it: each
/// entry of column j summed over b's column j in stored order, the first term assigned rather
/// than added to zero, nothing pruned, rows sorted. So bit for bit, with the columns made on the
/// pool (tests/fit/net_solve_test.cpp compares the two).
Eigen::SparseMatrix<double> sparse_product(const Eigen::SparseMatrix<double>& a, const Eigen::SparseMatrix<double>& b);

}  // namespace sublift::fit_detail
