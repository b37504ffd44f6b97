#include "core/fit/sparse_product.h"

#include <algorithm>
#include <cstdint>
#include <vector>

#include "core/base/parallel.h"

namespace sublift::fit_detail {

using Sparse = Eigen::SparseMatrix<double>;

// Columns in chunks on the pool, each summed into a per-thread dense accumulator (`seen` marks
// the rows touched, so a column costs its terms, not the height), then laid end to end.
Eigen::SparseMatrix<double> sparse_product(const Eigen::SparseMatrix<double>& a, const Eigen::SparseMatrix<double>& b) {
  const auto rows = static_cast<std::size_t>(a.rows());
  const auto cols = static_cast<std::uint32_t>(b.cols());
  constexpr std::uint32_t kColumns = 2048;
  const std::uint32_t chunks = (cols + kColumns - 1) / kColumns;
  struct Part {
    std::vector<int> count, inner;
    std::vector<double> value;
  };
  std::vector<Part> parts(chunks);
  parallel_for(chunks, 1, [&](std::uint32_t c0, std::uint32_t c1) {
    thread_local std::vector<double> sum;
    thread_local std::vector<char> seen;  // all clear between columns
    thread_local std::vector<int> at;
    if (sum.size() < rows) sum.resize(rows), seen.resize(rows, 0);
    for (std::uint32_t c = c0; c < c1; ++c) {
      Part& part = parts[c];
      for (std::uint32_t j = c * kColumns; j < std::min(cols, (c + 1) * kColumns); ++j) {
        at.clear();
        for (Sparse::InnerIterator bk(b, j); bk; ++bk) {
          const double y = bk.value();
          for (Sparse::InnerIterator ai(a, bk.index()); ai; ++ai) {
            const auto i = static_cast<std::size_t>(ai.index());
            if (!seen[i]) {
              seen[i] = 1;
              sum[i] = ai.value() * y;
              at.push_back(static_cast<int>(i));
            } else {
              sum[i] += ai.value() * y;
            }
          }
        }
        std::sort(at.begin(), at.end());
        for (const int i : at) part.inner.push_back(i), part.value.push_back(sum[i]), seen[i] = 0;
        part.count.push_back(static_cast<int>(at.size()));
      }
    }
  });
  std::size_t total = 0;
  for (const Part& part : parts) total += part.inner.size();
  Sparse r(a.rows(), b.cols());
  r.resizeNonZeros(static_cast<Eigen::Index>(total));
  int* outer = r.outerIndexPtr();
  std::size_t filled = 0, j = 0;
  outer[0] = 0;
  for (const Part& part : parts) {
    std::copy(part.inner.begin(), part.inner.end(), r.innerIndexPtr() + filled);
    std::copy(part.value.begin(), part.value.end(), r.valuePtr() + filled);
    filled += part.inner.size();
    for (const int k : part.count) outer[j + 1] = outer[j] + k, ++j;
  }
  return r;
}

}  // namespace sublift::fit_detail
