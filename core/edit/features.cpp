#include "core/edit/features.h"

#include <algorithm>
#include <cmath>

#include "core/base/errors.h"
#include "core/edit/selection.h"

namespace sublift {

std::vector<std::uint32_t> edges_within(const Complex& c, std::span<const unsigned> selection) {
  std::vector<std::uint8_t> in(c.num_vertices, 0);
  for (const unsigned v : selection)
    if (v < c.num_vertices) in[v] = 1;
  std::vector<std::uint32_t> out;
  for (std::uint32_t e = 0; e < c.num_edges(); ++e)
    if (in[c.edge_verts[2 * std::size_t(e)]] && in[c.edge_verts[2 * std::size_t(e) + 1]]) out.push_back(e);
  return out;
}

FeatureTags with_creases(const Complex& c, FeatureTags tags, std::span<const std::uint32_t> edges, bool on) {
  auto key = [](std::uint32_t a, std::uint32_t b) { return a < b ? std::pair(a, b) : std::pair(b, a); };
  std::vector<std::pair<std::uint32_t, std::uint32_t>> keep;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> chosen;
  for (const std::uint32_t e : edges) chosen.push_back(key(c.edge_verts[2 * std::size_t(e)], c.edge_verts[2 * std::size_t(e) + 1]));
  std::sort(chosen.begin(), chosen.end());
  std::vector<float> sharpness;  // kept aligned with the edges; a crease marked here is infinitely sharp
  for (std::size_t k = 0; k < tags.crease_edges.size(); ++k) {
    const auto [a, b] = tags.crease_edges[k];
    if (std::binary_search(chosen.begin(), chosen.end(), key(a, b))) continue;
    keep.push_back(key(a, b));
    sharpness.push_back(k < tags.crease_sharpness.size() ? tags.crease_sharpness[k] : INFINITY);
  }
  if (on) keep.insert(keep.end(), chosen.begin(), chosen.end());
  if (on) sharpness.insert(sharpness.end(), chosen.size(), INFINITY);
  tags.crease_edges = std::move(keep);
  tags.crease_sharpness = std::move(sharpness);
  return tags;
}

FeatureTags with_corners(FeatureTags tags, std::span<const unsigned> vertices, bool on) {
  std::vector<std::uint32_t> chosen(vertices.begin(), vertices.end());
  std::sort(chosen.begin(), chosen.end());
  std::vector<std::uint32_t> keep;
  std::vector<float> sharpness;
  for (std::size_t k = 0; k < tags.corner_vertices.size(); ++k) {
    const std::uint32_t v = tags.corner_vertices[k];
    if (std::binary_search(chosen.begin(), chosen.end(), v)) continue;
    keep.push_back(v);
    sharpness.push_back(k < tags.corner_sharpness.size() ? tags.corner_sharpness[k] : INFINITY);
  }
  if (on) keep.insert(keep.end(), chosen.begin(), chosen.end());
  if (on) sharpness.insert(sharpness.end(), chosen.size(), INFINITY);
  tags.corner_vertices = std::move(keep);
  tags.corner_sharpness = std::move(sharpness);
  return tags;
}

Hierarchy with_base_features(const Session& s, const FeatureTags& tags) {
  const Hierarchy& h = s.hierarchy();
  Complex base = h.levels.front();
  assign_feature_dims(base, tags);
  Hierarchy out = make_hierarchy(std::move(base), h.finest_level(), h.scheme, h.channels, false, h.first_level, h.disc);
  const int J = h.finest_level();
  analyze(out, s.positions(J));  // the finest level as shown: the shape stays, the detail is re-expressed
  return out;
}

}  // namespace sublift
