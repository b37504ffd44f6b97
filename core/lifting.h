#pragma once
// Lifting programs and their sub-steps (paper 000 sec. 3-4, DESIGN.md "The math").
//
// A program is a list of steps run on the vertex array of level j+1, laid out by class
// [v | e | f | c] (refine.h), `channels` doubles per vertex. Each step gathers into one class
// at a time from other classes, in an order that reads only values from before the step:
//   w-lift(a): c += 8a^3 v̄ + 12a^2 ē + 6a f̄;  f += 4a^2 v̄ + 4a ē;  e += 2a v̄   (000 eq. 3.16)
//   s-lift(a): v += ... from e, f, c;  e += ... from f, c;  f += 2a c̄        (000 eq. 3.17)
//   s-scale(a): a primitive of topological dim k, feature dim m is multiplied by a^(m-k) (3.18)
// where a receiver of topological dim t and feature dim m takes from neighbours of topological
// dim k (t < k <= m) whose feature dim is <= m, with weight a^(k-t) C(m-t, k-t) 2^(k-t) times
// their centroid. Synthesis runs the sub-steps forwards; analysis runs their inverses (-=, /=)
// backwards. In integer mode each added term is rounded (floor(x + 1/2)) the same way both
// ways and s-scale is skipped (000 sec. 4), so analysis and synthesis are exact inverses.
#include <cstdint>
#include <string>
#include <vector>

#include "core/complex.h"

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

/// The feature-filtered upward rows one transition needs, built once from the level-j complex.
/// Rows that no feature filter changes are not copied (the complex's own rows are used).
struct LiftTables {
  Csr v_from_e, v_from_f, v_from_c, e_from_f, e_from_c, f_from_c;
  bool own_v_from_e = false, own_v_from_f = false, own_v_from_c = false;
  bool own_e_from_f = false, own_e_from_c = false, own_f_from_c = false;
  std::size_t bytes() const;
};

/// Builds the tables of the transition from `parent` (level j) to its refinement.
LiftTables build_lift_tables(const Complex& parent);

/// Runs `program` forwards on `x` (level j+1 values, parent.num_child_vertices() * channels).
void lift_synthesize(const Complex& parent, const LiftTables& t, const LiftProgram& program,
                     double* x, int channels, bool integer);

/// Runs the inverse of `program` (analysis) on `x`, in place.
void lift_analyze(const Complex& parent, const LiftTables& t, const LiftProgram& program,
                  double* x, int channels, bool integer);

/// Threads used by the lifting loops (default: hardware concurrency, at most 8).
void set_lift_threads(int n);

}  // namespace sublift
