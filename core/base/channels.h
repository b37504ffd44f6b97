#pragma once
// Values are stored vertex-major with `channels` numbers per vertex; the first three are x, y, z.
#include <cmath>
#include <cstddef>
#include <span>
#include <vector>

#include "core/base/surface_mesh.h"

namespace sublift {

/// The Euclidean length of one vertex's `channels` values (a wavelet's size in the rankings and
/// level statistics).
inline double channel_norm(const double* v, int channels) {
  double s = 0;
  for (int c = 0; c < channels; ++c) s += v[c] * v[c];
  return std::sqrt(s);
}

/// x, y, z of every vertex (the first three channels; missing ones 0).
inline std::vector<double> xyz_of(std::span<const double> values, int channels) {
  const std::size_t n = values.size() / static_cast<std::size_t>(channels);
  std::vector<double> xyz(3 * n, 0.0);
  for (std::size_t v = 0; v < n; ++v)
    for (int k = 0; k < 3 && k < channels; ++k) xyz[3 * v + k] = values[v * channels + k];
  return xyz;
}

/// x, y, z (3 per vertex; empty: none) and the attributes' values interleaved: 3 +
/// attributes.size() values per vertex, or attributes.size() without x, y, z.
std::vector<double> with_attributes(std::span<const double> xyz, std::span<const VertexAttribute> attributes);

/// Channels first.. of `x` (`channels` per vertex) as attributes with the names and types of
/// `names` (one per channel from `first` on).
std::vector<VertexAttribute> attributes_of(std::span<const double> x, int channels, std::span<const VertexAttribute> names,
                                           int first = 3);

/// The attributes' names and types, without their values (what a project's header keeps).
std::vector<VertexAttribute> attribute_names(std::span<const VertexAttribute> attributes);

}  // namespace sublift
