#pragma once
// One transition (level j -> j+1) of the interpolatory sqrt(2) wavelet transform (paper 001,
// Wang & Ma, eq. 9-14), as explicit sparse lifting sub-steps built once from the refinement
// (core/complex/refine_sqrt2.h). GL-free; Scheme::Sqrt2 hierarchies (core/multires/hierarchy.h) hold one per level.
//
// Layout: the fine level's vertex array [old vertices | curve points | face points], `channels`
// doubles per vertex (x[v * channels + c]). After analysis the old vertices hold the coarse
// scaling coefficients and the new points the wavelet coefficients.
//
// Sub-steps, in synthesis order (each reads only values no row of the same sub-step writes):
//   update   old vertex += sum over wavelets w of (omega or eta) * w    (001 eq. 9 first line, 14)
//   predict  new point  += its subdivision rule on old vertices        (001 eq. 2, 11)
// Analysis runs the sub-steps backwards with the opposite sign (eq. 10). Integer mode rounds
// each row's increment to floor(sum + 1/2) and adds/subtracts it, so the two are exact inverses.
//
// Rules (docs/sqrt2.md, "Transform"). A vertex is *inner* when none of its edges is a curve edge
// (refine_sqrt2.h); an inner corner enters the face rule when its faces also close into one fan
// and its valence is 3..1000.
//   face point of a face with corners c_0..c_{m-1}: (1/l) sum over its l inner corners of the
//     corner estimate alpha_0 c_i + sum_j alpha_{i,j} c_{i,j} (eq. 1 for an inner quad: l = m = 4;
//     001 sec. 4's 4/l rule next to curves; any polygon at level 0); l = 0: the corners' mean.
//   curve point (a, p, q, b): eq. 11 (a); a corner variant (b) when a or b is kNone; the midpoint
//     when both are.
//   lifting: a face point of a quad whose 4 corners and 8 outer neighbours phi_4..11 all exist
//     and are inner lifts phi_0..11 with sqrt2_omega(n0..n3) (eq. 9). Other quads' face points
//     (next to a curve, sec. 4) lift only inner scaling functions: S_k dropped for a corner p_k
//     on a curve, and any missing or curve phi; their omega solve G omega = -H on the actual
//     masks (G = I + P^T P, H = P[f] over the kept vertices; P = the predict step). Face points
//     of level-0 non-quads are not lifted. Curve points lift with eta: case (a) a, p, q, b;
//     case (b) the two points away from the curve end; none for the midpoint rule.
#include <cstdint>
#include <vector>

#include "core/complex/complex.h"
#include "core/base/csr.h"
#include "core/engine/transition.h"
#include "core/complex/refine_sqrt2.h"

namespace sublift {

/// One sqrt(2) transition (steps: update, predict) and how its face points were lifted.
struct Sqrt2Transition {
  Transition transition;
  std::uint32_t lifted_face_points = 0;      // face points lifted with the omega table
  std::uint32_t near_curve_face_points = 0;  // lifted with a local solve (sec. 4)
};

/// Builds the sub-steps of the step coarse -> fine described by `children` (refine_sqrt2's
/// output). `coarse` needs its derived rows (build_adjacency). Throws TopologyError when `fine`
/// does not match `children`.
Sqrt2Transition build_sqrt2_transition(const Complex& coarse, const Complex& fine, const Sqrt2Children& children);

}  // namespace sublift
