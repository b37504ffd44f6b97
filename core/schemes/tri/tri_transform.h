#pragma once
// One transition (level j -> j+1) of the triangle-mesh wavelet transform of Lounsbery, DeRose
// & Warren (paper 004 sec. 6) as explicit sparse lifting sub-steps, in the same form as the
// sqrt(2) transform (core/schemes/sqrt2/sqrt2_transform.h): Weighted steps and, for Loop, a Matrix step
// (core/engine/transition.h), run by the one executor.
//
// Fine layout (core/complex/refine_tri.h): [old vertices | edge midpoints], the wavelet of coarse edge e
// on fine vertex nv + e. With psi_m = phi_m^{j+1} - sum_i alpha_{i,m} phi_i^j
// (core/schemes/tri/tri_wavelets.h) the fine coefficients are c^{j+1} = P (c^j - A d) + [0; d], so
// synthesis runs
//   update   old vertex i += sum_m (-alpha_{i,m}) d_m           (u = c^j - A d)
//   predict  new vertex m += sum_i P(m, i) u_i                   (the edge rule)
//   smooth   old = P_oo u                                       (Loop only: its vertex rule)
// and analysis backwards; Loop's first analysis step solves P_oo u = c_old (Eigen BiCGSTAB,
// sec. 6.3: not local, so slower), the interpolating schemes have P_oo = I and are linear time
// both ways (integer mode exact, as for sqrt2).
#include <cstdint>
#include <vector>

#include "core/complex/complex.h"
#include "core/engine/transition.h"
#include "core/schemes/tri/tri_rules.h"

namespace sublift {

struct TriTransitionResult {
  Transition transition;
  std::vector<double> norm2;  // ||psi||^2 per coarse edge, a level-j face having area 1
  std::uint32_t anchored_edges = 0;  // irregular edges whose wavelet was found through an anchor
  std::vector<std::int32_t> fine_face_types;  // for the next level (TriLevel::coarse_types)
};

/// Builds the sub-steps for the 1-to-4 split of `coarse` (derived rows needed) into `fine` (=
/// refine_tri(coarse); its derived rows are built on a copy if a wavelet has to be solved) with
/// k-disc wavelets. Uses a process-wide cache of face and edge types per (scheme, disc).
/// Update rows that read only regular wavelets share one weight pattern (WeightedStep::weight_at:
/// a third of the memory, no sort of their terms); `shared_rows` false lists every row's own
/// weights in edge order, the reference the shared rows are tested against. Irregular edges
/// near a few far-apart irregular vertices are keyed through those (TriWaveletBuilder's anchor
/// types) where they number at least `edges_per_anchor`: at 32, anchors that serve nothing
/// (crowded and unique, as on a fitted base) cost at most about a seventh of the edges' own
/// keys, and a deep level has hundreds per anchor. 0 keys every edge by its own signature, the
/// reference the anchors are tested against. `coarse_face_types`: the previous level's
/// fine_face_types, when `coarse` is that level's fine mesh (faces whose type it knows are looked
/// up without a signature); may be null.
TriTransitionResult build_tri_transition(const Complex& coarse, const Complex& fine, Scheme s, int disc,
                                         bool shared_rows = true, std::uint32_t edges_per_anchor = 32,
                                         const std::vector<std::int32_t>* coarse_face_types = nullptr);

/// Loop's limit positions (rows over the vertices of `c`, a triangle mesh; derived rows not
/// needed): smooth or dart vertex (1 - n g) v + g sum of neighbours, g = 1 / (3 / (8 beta) + n);
/// on two feature edges (boundary or crease) 2/3 v + 1/6 (x0 + x1); a corner stays. The feature
/// rules are those of core/schemes/tri/tri_rules.h.
void loop_limit_rows(const Complex& c, Csr& rows, std::vector<double>& weights);

}  // namespace sublift
