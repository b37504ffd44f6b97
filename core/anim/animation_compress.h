#pragma once
// Errors per frame of a space-time lattice, and the baseline it is measured against: every
// frame compressed on its own with the surface wavelets (docs/animation.md).
//
// Sizes count stored coefficient vectors (3 doubles each): the space-time lattice stores its
// level-0 control points (base layers x base vertices) and the wavelets it keeps; per-frame
// compression stores every frame's base control points (frames x base vertices) and the
// wavelets it keeps. Both rank wavelets by |w| ||psi|| (compress.h's one ranking), the
// per-frame one over the wavelets of all frames together, so at the same stored count the two
// are compared at their best.
#include <cstddef>
#include <span>
#include <vector>

#include "core/anim/spacetime.h"

namespace sublift {

struct FrameError {
  double max = 0, rms = 0;  // over the layer's points, / the animation's bounding-box diagonal
};

/// Per finest layer: the distance between two finest levels of the lattice (3 per vertex).
std::vector<FrameError> frame_errors(const SpaceTime& st, std::span<const double> a, std::span<const double> b,
                                     double diagonal);

struct PerFrameCompression {
  std::size_t stored = 0;     // coefficient vectors stored: frames x base vertices + kept wavelets
  std::size_t kept = 0;       // wavelets kept over all frames
  std::size_t wavelets = 0;   // wavelets of all frames
  std::vector<FrameError> errors;
};

/// Each finest layer of `finest` (the lattice's finest level, 3 per vertex) analysed on its own
/// on the surface's levels, then the largest `stored - frames x base vertices` wavelets of all
/// frames kept (none when `stored` is smaller: the frames' base control points alone are more).
PerFrameCompression per_frame_compression(const SpaceTime& st, std::span<const double> finest, std::size_t stored,
                                          double diagonal);

}  // namespace sublift
