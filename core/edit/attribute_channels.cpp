#include "core/edit/attribute_channels.h"

#include "core/base/errors.h"
#include "core/edit/level_ops.h"

namespace sublift {

Hierarchy channel_range(const Hierarchy& h, int first, int count) {
  if (first < 0 || count < 1 || first + count > h.channels)
    throw Error("channels " + std::to_string(first) + ".." + std::to_string(first + count - 1) + " of a hierarchy of " +
                std::to_string(h.channels));
  Hierarchy out = h;  // the levels and tables as they are; the coefficients of those channels
  out.channels = count;
  const std::size_t n = h.coeffs.size() / std::size_t(h.channels);
  out.coeffs.assign(n * std::size_t(count), 0.0);
  for (std::size_t v = 0; v < n; ++v)
    for (int k = 0; k < count; ++k) out.coeffs[v * std::size_t(count) + std::size_t(k)] = h.coeffs[v * std::size_t(h.channels) + std::size_t(first + k)];
  return out;
}

Hierarchy merge_channels(const Hierarchy& a, const Hierarchy& b) {
  if (a.levels.size() != b.levels.size() || a.coeffs.size() / std::size_t(a.channels) != b.coeffs.size() / std::size_t(b.channels))
    throw Error("merging channels of hierarchies with different levels");
  Hierarchy out = a;
  const std::size_t n = a.coeffs.size() / std::size_t(a.channels), ca = std::size_t(a.channels), cb = std::size_t(b.channels);
  out.channels = a.channels + b.channels;
  out.coeffs.resize(n * (ca + cb));
  for (std::size_t v = n; v-- > 0;) {  // back to front: the first channels move right in place
    for (std::size_t k = cb; k-- > 0;) out.coeffs[v * (ca + cb) + ca + k] = b.coeffs[v * cb + k];
    for (std::size_t k = ca; k-- > 0;) out.coeffs[v * (ca + cb) + k] = a.coeffs[v * ca + k];
  }
  return out;
}

std::optional<Hierarchy> attributes_for(const Hierarchy& attributes, const Hierarchy& target, std::string* why) {
  const auto fail = [&](const std::string& w) -> std::optional<Hierarchy> {
    if (why) *why = w;
    return std::nullopt;
  };
  const Complex &a0 = attributes.levels.front(), &t0 = target.levels.front();
  if (a0.num_vertices != t0.num_vertices || a0.faces.offsets != t0.faces.offsets || a0.faces.items != t0.faces.items)
    return fail("the base changed");
  // Levels first (zero detail added, or cut), as the session's Subdivide and Delete Higher did;
  // then the finest values kept and analysed again on the target's base (its features) and
  // scheme, as a scheme switch or a crease change does for the positions.
  Hierarchy h = attributes;
  if (scheme_info(h.scheme).refinement != scheme_info(target.scheme).refinement)
    return fail(scheme_name(target.scheme) + " refines differently from " + scheme_name(h.scheme));
  while (h.finest_level() < target.finest_level()) {
    append_level(h, false);
    h.coeffs.resize(std::size_t(h.levels.back().num_vertices) * std::size_t(h.channels), 0.0);
  }
  if (h.finest_level() > target.finest_level()) h = delete_higher(h, target.finest_level());
  const bool features = a0.edge_dim != t0.edge_dim || a0.vertex_dim != t0.vertex_dim || a0.edge_sharpness != t0.edge_sharpness ||
                        a0.vertex_sharpness != t0.vertex_sharpness;
  if (h.scheme != target.scheme || features || h.disc != target.disc) {
    const std::vector<double> fine = synthesize(h, h.finest_level());
    Hierarchy again = make_hierarchy(t0, h.finest_level(), target.scheme, h.channels, false, target.first_level, target.disc);
    analyze(again, fine);
    h = std::move(again);
  }
  return h;
}

}  // namespace sublift
