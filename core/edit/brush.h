#pragma once
// Sculpt brushes at any level (issue 19): one dab moves the control points of the edit level
// within the brush radius; Session::move_each then resynthesises the finer levels, so their
// detail rides along, and folds the change into the coarser ones. A stroke is a run of dabs in
// one history entry.
//
// The kinds, as Blender's sculpt brushes (w = strength * falloff(d / radius), d the distance of
// a control point from the dab centre; "area" = the points within the radius):
//   Draw     along the area's mean normal by w * radius / 4 (invert: inwards)
//   Inflate  along each point's own normal by w * radius / 4
//   Smooth   towards the mean of its edge neighbours by w (relaxes the level's coefficients)
//   Grab     by w times the mouse motion since the last dab (Blender's snake hook)
//   Flatten  towards the plane through the area's mean point across its mean normal, by w
//   Pinch    towards the centre, in the tangent plane, by w / 2
// Falloff curves of t = d / radius in [0, 1]: smooth 1 - smoothstep(t) (Blender's default),
// linear 1 - t, sharp (1 - t)^2, constant 1. Front faces only leaves out points whose normal
// looks away from the viewer. Normals are the area-weighted normals of the level's faces.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "core/complex/complex.h"

namespace sublift {

enum class BrushKind : std::uint8_t { Draw, Inflate, Smooth, Grab, Flatten, Pinch };
enum class Falloff : std::uint8_t { Smooth, Linear, Sharp, Constant };

const char* brush_name(BrushKind k);
/// "draw", "inflate", "smooth", "grab", "flatten", "pinch"; throws Error naming them otherwise.
BrushKind parse_brush(const std::string& name);
const char* falloff_name(Falloff f);
Falloff parse_falloff(const std::string& name);
double falloff_weight(Falloff f, double t);
/// Whether a kind moves along normals (and so needs a surface).
bool brush_needs_normals(BrushKind k);

struct BrushSettings {
  BrushKind kind = BrushKind::Draw;
  double radius = 0.1;    // world units
  double strength = 0.5;  // 0..1
  Falloff falloff = Falloff::Smooth;
  bool front_faces_only = true;
  bool invert = false;    // Ctrl held: draw/inflate inwards, pinch outwards, flatten away
};

struct Dab {
  glm::dvec3 center{0.0};
  glm::dvec3 view_dir{0.0, 0.0, -1.0};  // from the eye into the scene (front-face test)
  glm::dvec3 motion{0.0};               // Grab: world motion of the brush since the last dab
};

/// The moves of one dab on a level's net: the points it reaches (ascending) and 3 deltas each.
/// `c` needs its upward rows (build_adjacency): vertex_edges for Smooth, and for a surface
/// vertex_faces, from which the normals of the points reached are found (only theirs: a dab
/// costs a scan of the positions plus the area). Throws Error on settings out of range, and for
/// the kinds that move along normals on curves and lattices.
void brush_dab(const BrushSettings& b, const Dab& dab, const Complex& c, std::span<const double> positions,
               std::vector<std::uint32_t>& vertices, std::vector<double>& deltas);

/// Dab spacing along a stroke, as a fraction of the radius (Blender's default spacing is 10 % of
/// the diameter): a fast mouse move leaves dabs this far apart, not one per mouse event.
inline constexpr double kDabSpacing = 0.2;

/// The dab centres a stroke from the last dab at `from` to the brush now at `to` adds: evenly
/// spaced `spacing` apart from `from` (not including it), none while |to - from| < spacing, at
/// most `most` (the last ones dropped when the mouse jumped far).
std::vector<glm::dvec3> dab_centres_along(const glm::dvec3& from, const glm::dvec3& to, double spacing, std::size_t most = 64);

/// The nearest hit of the ray (origin, unit dir) with the polygons `faces` (fans of triangles)
/// of `positions`; false when it misses. Brute force over the faces.
bool ray_hit(std::span<const double> positions, const Csr& faces, const glm::dvec3& origin, const glm::dvec3& dir,
             glm::dvec3& hit);

}  // namespace sublift
