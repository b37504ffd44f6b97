#pragma once
// The one bound on the size of the numbers Sublift reads and writes (coordinates, coefficients):
// beyond it, products in normals, areas and inner products overflow or lose all precision. Every
// reader refuses a larger value, so every writer refuses to write one: what Sublift writes it
// can read back.
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include <glm/vec3.hpp>

namespace sublift {

/// Largest magnitude accepted for a coordinate or coefficient (a power of ten).
inline constexpr double kMaxCoordinate = 1e30;

/// kMaxCoordinate as messages print it: "1e30".
std::string max_coordinate_text();

/// True when v is finite and |v| <= kMaxCoordinate.
inline bool in_supported_range(double v) { return v >= -kMaxCoordinate && v <= kMaxCoordinate; }

/// Index of the first value that is not finite or exceeds kMaxCoordinate; nullopt if none.
std::optional<std::size_t> first_out_of_range(std::span<const double> values);

/// Why v is out of range, for messages: "is not finite (nan)" or "exceeds the supported
/// magnitude 1e30 (1.7e+308)". Precondition: !in_supported_range(v).
std::string out_of_range_text(double v);

/// Throws InputError on `path` ("position of vertex 3 exceeds the supported magnitude 1e30
/// (coordinate 1 is 1.7e+308); nothing written") when a value of `xyz` (3 per vertex) is out of
/// range. Writers call it before touching the file.
void check_writable_positions(const std::string& path, std::span<const double> xyz, std::string_view what = "position");
void check_writable_positions(const std::string& path, std::span<const glm::dvec3> xyz, std::string_view what = "position");

}  // namespace sublift
