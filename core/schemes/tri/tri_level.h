#pragma once
// One level of a triangle-scheme hierarchy (paper 004): the 1-to-4 split, the k-disc wavelet
// transition, the sites of the edge midpoints and the wavelets' exact norms.
#include "core/engine/level_build.h"
#include "core/schemes/tri/tri_rules.h"

namespace sublift {

/// `ctx.level` j scales the norms: a level-j face has 4^-j of a base face's area.
LevelBuild build_tri_level(Complex& parent, Scheme s, const LevelContext& ctx);

}  // namespace sublift
