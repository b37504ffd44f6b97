#pragma once
// One step of fitting a control net to an input surface both ways (issue 17, docs/fit.md):
// Hoppe et al. 1993's distance energy ("Mesh optimization", E_dist over the input's points) plus
// the surface's own points held at their projections onto the input, with springs that keep the
// net's shape. The surface is the net itself, or its limit surface y = L x (L: the scheme's
// limit stencils), which is what a user sees of an approximating scheme like Loop's. With the
// input's vertices q_i held at their closest points on the surface (face, barycentric weights
// b_i) and the surface's points at their projections c_k, the control points x minimise
//   (n / ni) sum_i |B_i L x - q_i|^2 + alpha sum_k h_k |(L x)_k - c_k|^2
//     + kappa sum_edges |(x_a - x_b) - (x0_a - x0_b)|^2,
// a sparse symmetric positive definite system (n net vertices, ni input vertices, the two sums
// weighted alike per point; h_k how firmly point k is held), solved by conjugate gradients from
// x0. Every input vertex pulls the face it is nearest to, so the surface reaches the parts it
// would otherwise cut across (ear tips, spikes); the springs spread each pull over the
// neighbouring points.
#include <optional>
#include <span>
#include <vector>

#include "core/base/triangle_bvh.h"
#include "core/complex/complex.h"
#include "core/multires/limit.h"

namespace sublift {

struct NetSolveWeights {
  double alpha = 1.0;  // the surface's points on their projections
  double kappa = 1.0;  // the net's edge vectors kept
};

struct NetSolveState {
  std::span<const double> control;  // x0, 3 per net vertex (the springs' shape, the first guess)
  std::span<const double> surface;  // its surface points: x0 itself, or L x0
  std::span<const double> targets;  // the surface points' projections onto the input
  const LimitStencils* limit = nullptr;  // L; null: the surface is the net
  // Per input vertex, the surface face it was nearest in an earlier solve of this net (in and
  // out; UINT32_MAX: none): the closest-point search starts there. Empty: no hints.
  std::span<std::uint32_t> hints = {};
  // The surface's closest-point hierarchy, kept between the solves of one net: built on first
  // use, refitted to `surface` after (the same answers, a fraction of the time). Null: built here.
  std::optional<TriangleBvh>* index = nullptr;
};

/// Returns the solved control points (3 per vertex of polygon net `c`, derived rows built;
/// polygons are fan-triangulated as TriangleBvh does).
/// `input`: the input's vertices (3 each); an input vertex pulls the nearest surface face that
/// faces like its normal (`input_normals`; a zero normal: the nearest face), so a thin part's
/// sides do not pull each other. `hold` scales alpha per net vertex (empty: 1 everywhere).
std::vector<double> solve_net(const Complex& c, const NetSolveState& state, std::span<const double> input,
                              std::span<const double> input_normals, std::span<const double> hold, const NetSolveWeights& w = {});

}  // namespace sublift
