#pragma once
// Edits of a space-time lattice: move control point `point` of level `level` at finest frame
// `frame` by (dx, dy, dz). The point numbers the surface's level-`level` vertices (the base
// mesh's vertices at level 0, in file order); the frame must be one that level has a layer at
// (a multiple of 2^(J - level), or 0), so a level-0 edit sits on a base time step and spreads
// over the frames of its time support, with the finer motion kept.
//
// File format: one edit per line, `level frame point dx dy dz`; blank lines and `#` comments
// (whole-line or trailing) are allowed. Errors name the file and line.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/anim/spacetime.h"

namespace sublift {

struct AnimationEdit {
  int level = 0;
  int frame = 0;
  std::uint32_t point = 0;
  double delta[3] = {0, 0, 0};
  std::size_t line = 0;  // in the file, for messages
};

/// Parses edits. Throws InputError (file, line) on a wrong field count, a field that is not a
/// number, a negative or fractional level, frame or point, a non-finite delta.
std::vector<AnimationEdit> parse_animation_edits(std::string_view text, const std::string& file);
std::vector<AnimationEdit> read_animation_edits(const std::string& path);

/// The lattice vertex of level `level` at finest frame `frame` over surface point `point`.
/// Throws InputError (file, line of `e`) naming the level's layer frames when the frame is not
/// one of them, or when the level or point is out of range.
std::uint32_t edit_vertex(const SpaceTime& st, const AnimationEdit& e, const std::string& file);

}  // namespace sublift
