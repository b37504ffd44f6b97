#pragma once
// Level management of the modeler and `sublift-cli set` (issue 19), as Blender's Multires
// offers it: delete higher, delete lower, apply base.
//
// delete_higher keeps levels 0..L: their coefficients (the base and the wavelets of levels
// below L) are unchanged, so level L's net stays exactly what it was.
// delete_lower makes level L the base: level L's net (synthesised with the gains below L)
// becomes the scaling coefficients of the new level 0 and the wavelets of levels L..J-1 are
// kept as they are; the new level k is the old level L + k, built by refining the old level L's
// complex as before, so the shape at every remaining level is unchanged.
// Apply base (Blender: moves the base mesh towards the subdivided shape) has nothing to do in
// Sublift: level 0 is by construction the coarse shape whose synthesis with the stored detail
// gives every finer level (kApplyBaseNote says so to the user).
#include <span>

#include "core/multires/hierarchy.h"

namespace sublift {

inline constexpr const char* kApplyBaseNote =
    "level 0 already is the coarse shape consistent with the detail: every finer level is its synthesis "
    "with the stored wavelets, so there is nothing to apply (Blender's Apply Base moves the base towards "
    "the subdivided shape because its detail is stored as displacements of the finest level)";

/// Levels 0..level of `h` (throws Error outside 0..J).
Hierarchy delete_higher(const Hierarchy& h, int level);
/// Level `level` as the new level 0, with `level_positions` (its net, channels per vertex) as the
/// base and the wavelets of levels `level`..J-1 kept (throws Error outside 0..J or on a size
/// mismatch).
Hierarchy delete_lower(const Hierarchy& h, int level, std::span<const double> level_positions);

}  // namespace sublift
