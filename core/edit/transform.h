#pragma once
// Rotate and scale of a (soft) selection, as per-vertex moves for Session::move_each: pure math
// shared by the modeler (R, S), `sublift --script` and `sublift-cli edit`.
//
// Soft selection. A vertex of weight w (soft_selection) is rotated by w * angle and scaled by
// 1 + w * (s - 1), as Blender's proportional editing does: a partial rotation keeps lengths,
// where blending the displacement would shrink the falloff region towards the pivot.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace sublift {

enum class TransformMode : std::uint8_t { Grab, Rotate, Scale };
/// The point rotate and scale turn about: the selection's mean (Blender's "median point"), the
/// active (last clicked) control point, the 3-D cursor, or the world origin.
enum class Pivot : std::uint8_t { Median, Active, Cursor, Origin };

const char* pivot_name(Pivot p);
/// "median", "active", "cursor", "origin"; throws Error naming the choices otherwise.
Pivot parse_pivot(const std::string& name);

/// The pivot point. `positions` holds 3 values per vertex; `active` < 0 (or out of range) falls
/// back to the median; an empty selection's median is the origin.
glm::dvec3 pivot_point(Pivot p, std::span<const double> positions, std::span<const unsigned> selection, long long active,
                       const glm::dvec3& cursor);

/// Per-axis scale factors: uniform `s` (axis < 0), `s` along `axis` only, or with `exclude`
/// (Shift+axis) `s` on the two other axes.
glm::dvec3 scale_factors(double s, int axis, bool exclude);

/// The deltas (3 per vertex, written to `out`) that move vertex vertices[k] from its place in
/// `current` (3 values per vertex of the level) to the image of start[3k..3k+2] under a rotation by weights[k] * angle
/// (radians, right-handed about the unit `axis` through `pivot`) followed by a per-axis scale
/// 1 + weights[k] * (factors - 1) about `pivot`; `weights` empty means 1.
void transform_deltas(std::span<const double> start, std::span<const double> current,
                      std::span<const std::uint32_t> vertices, std::span<const double> weights, const glm::dvec3& pivot,
                      const glm::dvec3& axis, double angle, const glm::dvec3& factors, std::vector<double>& out);

}  // namespace sublift
