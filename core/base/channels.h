#pragma once
// Values are stored vertex-major with `channels` numbers per vertex; the first three are x, y, z.
#include <cstddef>
#include <span>
#include <vector>

namespace sublift {

/// x, y, z of every vertex (the first three channels; missing ones 0).
inline std::vector<double> xyz_of(std::span<const double> values, int channels) {
  const std::size_t n = values.size() / static_cast<std::size_t>(channels);
  std::vector<double> xyz(3 * n, 0.0);
  for (std::size_t v = 0; v < n; ++v)
    for (int k = 0; k < 3 && k < channels; ++k) xyz[3 * v + k] = values[v * channels + k];
  return xyz;
}

}  // namespace sublift
