#pragma once
// Bertram's lifted linear and cubic B-spline wavelets (paper 000 sec. 3-4, 003) compiled into a
// level transition (core/engine/transition.h). A program is a list of lifting operations:
//   w-lift(a): c += 8a^3 v̄ + 12a^2 ē + 6a f̄;  f += 4a^2 v̄ + 4a ē;  e += 2a v̄   (000 eq. 3.16)
//   s-lift(a): v += ... from e, f, c;  e += ... from f, c;  f += 2a c̄        (000 eq. 3.17)
//   s-scale(a): a primitive of topological dim k, feature dim m is multiplied by a^(m-k) (3.18)
// where a receiver of topological dim t and feature dim m takes from neighbours of topological
// dim k (t < k <= m) whose feature dim is <= m, with weight a^(k-t) C(m-t, k-t) 2^(k-t) times
// their centroid. Each w-lift and s-lift becomes three Centroid steps (one per target class, in
// an order that reads only values from before the operation), each s-scale one Scale step.
#include <cstdint>
#include <vector>

#include "core/complex/complex.h"
#include "core/engine/level_build.h"
#include "core/engine/transition.h"

namespace sublift {

enum class LiftOp : std::uint8_t { WLift, SLift, SScale };

struct LiftStep {
  LiftOp op;
  double a;
};

using LiftProgram = std::vector<LiftStep>;

/// s-lift(-1/4); w-lift(1/2)  (000 eq. 4.1, 003 eq. 1.4)
LiftProgram linear_program();
/// s-lift(-3/8); w-lift(1/2); s-lift(1/2); s-scale(1/2)  (000 eq. 4.2, 003 eq. 1.5)
LiftProgram cubic_program();

/// The transition from `parent` (level j, with its derived rows) to its refinement (refine.h's
/// [v | e | f | c] layout). Rows that a feature filter changes (s-lift stays inside a feature)
/// are copied into the transition; the others are read from the parent.
Transition build_bertram_transition(const Complex& parent, const LiftProgram& program);

/// One level of a Bertram hierarchy: refine(parent) and the transition to it.
LevelBuild build_bertram_level(Complex& parent, const LiftProgram& program, const LevelContext& ctx);

}  // namespace sublift
