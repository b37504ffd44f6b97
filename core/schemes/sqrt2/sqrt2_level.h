#pragma once
// One level of a sqrt(2) hierarchy (paper 001): refine_sqrt2, the transition and the sites of
// the new points.
#include "core/engine/level_build.h"

namespace sublift {

/// `ctx.level` is the sqrt(2) level index of `parent` (curves are refined after odd levels).
LevelBuild build_sqrt2_level(Complex& parent, const LevelContext& ctx);

}  // namespace sublift
