#include "core/edit/level_ops.h"

#include <algorithm>
#include <string>

#include "core/base/errors.h"

namespace sublift {
namespace {

void check_level(const Hierarchy& h, int level) {
  if (level < 0 || level > h.finest_level())
    throw Error("level " + std::to_string(level) + " is outside 0.." + std::to_string(h.finest_level()));
}

}  // namespace

Hierarchy delete_higher(const Hierarchy& h, int level) {
  check_level(h, level);
  Hierarchy out = h;
  while (out.finest_level() > level) pop_level(out);
  out.coeffs.resize(std::size_t(out.num_vertices(level)) * static_cast<std::size_t>(h.channels));
  // Norms are per wavelet (index v - nv_0), in vertex order: the kept levels' come first.
  if (!out.wavelet_norms.empty()) out.wavelet_norms.resize(out.num_vertices(level) - out.num_vertices(0));
  return out;
}

Hierarchy delete_lower(const Hierarchy& h, int level, std::span<const double> level_positions) {
  check_level(h, level);
  const std::size_t ch = static_cast<std::size_t>(h.channels);
  const std::uint32_t nl = h.num_vertices(level);
  if (level_positions.size() != std::size_t(nl) * ch)
    throw Error("level " + std::to_string(level) + " has " + std::to_string(nl) + " vertices, got " +
                std::to_string(level_positions.size() / ch) + " positions");
  if (level == 0) return h;
  // The old level L's complex refines into the old levels L+1..J (the same builder, the same
  // numbering); sqrt2 counts its levels from first_level, so curves stay on the odd levels.
  Hierarchy out = make_hierarchy(h.levels[static_cast<std::size_t>(level)], h.finest_level() - level, h.scheme, h.channels,
                                 h.integer, h.first_level + level, h.disc);
  for (int k = 0; k <= out.finest_level(); ++k)
    if (out.num_vertices(k) != h.num_vertices(level + k))
      throw Error("internal: level " + std::to_string(level + k) + " refines differently from level " + std::to_string(level));
  std::copy(level_positions.begin(), level_positions.end(), out.coeffs.begin());
  std::copy(h.coeffs.begin() + static_cast<std::ptrdiff_t>(std::size_t(nl) * ch), h.coeffs.end(),
            out.coeffs.begin() + static_cast<std::ptrdiff_t>(std::size_t(nl) * ch));
  return out;
}

}  // namespace sublift
