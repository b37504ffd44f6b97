#pragma once
// Csr: compressed rows of 32-bit indices, the one adjacency container of the hierarchy.
// Row r holds items[offsets[r] .. offsets[r+1]); offsets.size() == rows + 1.
#include <cstdint>
#include <span>
#include <vector>

namespace sublift {

struct Csr {
  std::vector<std::uint32_t> offsets{0};
  std::vector<std::uint32_t> items;

  std::size_t rows() const { return offsets.size() - 1; }
  std::uint32_t size(std::size_t r) const { return offsets[r + 1] - offsets[r]; }
  std::span<const std::uint32_t> row(std::size_t r) const {
    return {items.data() + offsets[r], offsets[r + 1] - offsets[r]};
  }
  void clear() {
    offsets.assign(1, 0);
    items.clear();
  }
  std::size_t bytes() const { return (offsets.capacity() + items.capacity()) * sizeof(std::uint32_t); }
};

/// Transposes `down` (rows = higher primitives, items = lower ones, all < num_lower) into
/// upward rows (lower -> higher), each row listing the higher primitives in increasing order.
Csr transpose(const Csr& down, std::size_t num_lower);

/// The same for rows of exactly two items stored flat (edges' end vertices), without building
/// a Csr for them first.
Csr transpose_pairs(const std::vector<std::uint32_t>& pairs, std::size_t num_lower);

}  // namespace sublift
