#include "core/base/channels.h"

#include <algorithm>

namespace sublift {

std::vector<double> with_attributes(std::span<const double> xyz, std::span<const VertexAttribute> attributes) {
  const std::size_t p = xyz.empty() ? 0 : 3;
  const std::size_t n = p ? xyz.size() / 3 : attributes.empty() ? 0 : attributes.front().values.size();
  const std::size_t ch = p + attributes.size();
  std::vector<double> x(n * ch);
  for (std::size_t v = 0; v < n; ++v) {
    if (p) std::copy_n(&xyz[3 * v], 3, &x[v * ch]);
    for (std::size_t k = 0; k < attributes.size(); ++k) x[v * ch + p + k] = attributes[k].values[v];
  }
  return x;
}

std::vector<VertexAttribute> attributes_of(std::span<const double> x, int channels, std::span<const VertexAttribute> names, int first) {
  const auto ch = static_cast<std::size_t>(channels), at = static_cast<std::size_t>(first);
  std::vector<VertexAttribute> out = attribute_names(names);
  for (std::size_t k = 0; k < out.size(); ++k) {
    out[k].values.resize(x.size() / ch);
    for (std::size_t v = 0; v < out[k].values.size(); ++v) out[k].values[v] = x[v * ch + at + k];
  }
  return out;
}

std::vector<VertexAttribute> attribute_names(std::span<const VertexAttribute> attributes) {
  std::vector<VertexAttribute> out;
  for (const VertexAttribute& a : attributes) out.push_back({a.name, a.type, {}});
  return out;
}

}  // namespace sublift
