#include "core/base/csr.h"

namespace sublift {

Csr transpose(const Csr& down, std::size_t num_lower) {
  Csr up;
  up.offsets.assign(num_lower + 1, 0);
  for (std::uint32_t x : down.items) ++up.offsets[x + 1];
  for (std::size_t i = 0; i < num_lower; ++i) up.offsets[i + 1] += up.offsets[i];
  up.items.resize(down.items.size());
  std::vector<std::uint32_t> fill(up.offsets.begin(), up.offsets.end() - 1);
  const std::size_t rows = down.rows();
  for (std::size_t r = 0; r < rows; ++r)
    for (std::uint32_t x : down.row(r)) up.items[fill[x]++] = static_cast<std::uint32_t>(r);
  return up;
}

Csr transpose_pairs(const std::vector<std::uint32_t>& pairs, std::size_t num_lower) {
  Csr up;
  up.offsets.assign(num_lower + 1, 0);
  for (std::uint32_t x : pairs) ++up.offsets[x + 1];
  for (std::size_t i = 0; i < num_lower; ++i) up.offsets[i + 1] += up.offsets[i];
  up.items.resize(pairs.size());
  std::vector<std::uint32_t> fill(up.offsets.begin(), up.offsets.end() - 1);
  for (std::size_t k = 0; k < pairs.size(); ++k) up.items[fill[pairs[k]]++] = static_cast<std::uint32_t>(k / 2);
  return up;
}

}  // namespace sublift
