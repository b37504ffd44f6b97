#include "core/base/magnitude.h"

#include <cmath>

#include "core/base/errors.h"
#include "core/base/text_lines.h"

namespace sublift {

namespace {
std::string exact(double v) { return format_shortest(v); }
std::string why(double v) { return std::isfinite(v) ? "exceeds the supported magnitude " + max_coordinate_text() : "is not finite"; }
}  // namespace

std::string max_coordinate_text() {
  return "1e" + std::to_string(static_cast<int>(std::lround(std::log10(kMaxCoordinate))));
}

std::optional<std::size_t> first_out_of_range(std::span<const double> values) {
  for (std::size_t i = 0; i < values.size(); ++i)
    if (!in_supported_range(values[i])) return i;
  return std::nullopt;
}

std::string out_of_range_text(double v) { return why(v) + " (" + exact(v) + ")"; }

void check_writable_positions(const std::string& path, std::span<const double> xyz, std::string_view what) {
  const auto i = first_out_of_range(xyz);
  if (!i) return;
  throw InputError(path, 0, std::string(what) + " of vertex " + std::to_string(*i / 3) + " " + why(xyz[*i]) + " (coordinate " +
                                std::to_string(*i % 3) + " is " + exact(xyz[*i]) + "); nothing written");
}

void check_writable_positions(const std::string& path, std::span<const glm::dvec3> xyz, std::string_view what) {
  // glm::dvec3 is three packed doubles.
  static_assert(sizeof(glm::dvec3) == 3 * sizeof(double));
  check_writable_positions(path, std::span<const double>(xyz.empty() ? nullptr : &xyz[0].x, 3 * xyz.size()), what);
}

}  // namespace sublift
