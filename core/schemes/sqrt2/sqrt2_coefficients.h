#pragma once
// Coefficient tables of the interpolatory sqrt(2) wavelets (paper 001, Wang & Ma): the face-point
// rule (eq. 1), the boundary 4-point rules (eq. 11), the lifting coefficients omega of the local
// orthogonalisation (eq. 4-10, Table 1) and the boundary/crease coefficients eta (eq. 12-14).
// GL-free and independent of the refinement engine: the masks behind omega are built on a small
// explicit mesh here (docs/sqrt2.md, "sqrt(2) coefficients").
//
// Face-point stencil (eq. 1). A quad p0 p1 p2 p3 (counterclockwise) gets the face point
//   f = 1/4 sum_i ( alpha_0 p_i + sum_{j=0}^{n_i-1} alpha_{i,j} p_{i,j} ),
// where p_{i,0..n_i-1} are the edge neighbours of p_i counterclockwise, starting with
// p_{i,0} = p_{(i+1)%4} and p_{i,1} = p_{(i+3)%4} (the face lies between these two), then the
// outer neighbours p_{i,2}, ..., p_{i,n_i-1} in turn. alpha_0 = 1/2 and
//   alpha_{i,j} = (1 + cos t_j + sin t_j + cos t_{j-1} - sin t_{j-1}) / (2 n_i), t_j = 2 pi j / n_i.
// alpha is symmetric under j <-> 1 - j (mod n_i), so walking the ring clockwise gives the same
// weights; each corner's weights sum to 1 (alpha_0 + sum_j alpha_{i,j} = 1).
//
// Layout of phi_0..phi_11 (Figure 3, reconstructed from Table 1's symmetries, the index sets
// S_k of sec. 4 and the regular G of eq. 7; see docs/sqrt2.md for the sketch):
//   phi_i, i = 0..3: the face corners p_i;
//   phi_{4+2i}: the outer neighbour of p_i on the far side of edge p_i p_{i+1} (the edge-adjacent
//               face across that edge is p_{i+1} p_i phi_{4+2i} phi_{5+2i});
//   phi_{5+2i}: the outer neighbour of p_{i+1} on the same side.
// So phi_4..phi_11 run counterclockwise around the face starting next to p0 below edge p0 p1,
// and p_k's outer neighbours are phi_{4+2k} and phi_{4+(2k+7)%8} (S_0 = {0, 11, 4}, ...).
// For a valence-3 corner p_k these two coincide; the slot 4 + (2k+7)%8 is dropped (omega there is
// an exact 0) and phi_{4+2k} carries the merged function (the paper's case n0 = 3 drops phi_11).
//
// How omega is computed (sec. 3, the paper's DisBas[13] algorithm). A local quad mesh is built:
// the face, a strip one face wide outwards from each edge, and n_k - 3 quadrant grids between
// consecutive edge paths leaving each corner p_k, so p_k has valence n_k and every other vertex 4
// (the paper's simplification for Table 1). One primitive synthesis step (eq. 2) on unit
// coefficients gives the masks: phi_k is 1 at its vertex and, at each face point, 1/4 of its
// eq.-1 weights in the rules of the face's corners; psi is 1 at the centre face point. The inner
// product is the plain sum over all vertex and face points of the products of the masks (this
// reproduces the paper's regular G: a = 179/128, b = 81/512, ...). G omega = -H (eq. 7) is solved
// with the dropped slots' rows/columns zeroed and their diagonal set to 1.
// eta uses the 1-D masks of the curve rules (Figure 5) with the same inner product.
#include <array>

namespace sublift {

/// alpha_0 of eq. 1 (weight of a face corner on its own, before the 1/4).
inline constexpr double kSqrt2Alpha0 = 0.5;

/// alpha_{i,j} of eq. 1 for a corner of valence n >= 3, j in 0..n-1 (indexing above).
double sqrt2_face_alpha(int n, int j);

/// The 4-point curve rule of eq. 11 (a): f = sum_k w[k] p_k, f between p1 and p2:
/// (-1/16, 9/16, 9/16, -1/16).
std::array<double, 4> sqrt2_four_point_weights();

/// The corner variant of eq. 11 (b): f between p1 and the curve end p2, f = sum_k w[k] p_k:
/// (-1/8, 6/8, 3/8) for (p0, p1, p2).
std::array<double, 3> sqrt2_four_point_corner_weights();

/// omega_0..omega_11 of eq. 6-7 for a face whose corners p0..p3 (counterclockwise) have valences
/// n0..n3 (each 3..1000; all other vertices are taken as regular, as the paper does for Table 1).
/// Dropped slots (valence-3 corners) are exactly 0. Cached for valences 3..12 (thread-safe),
/// solved on the fly beyond. Throws TopologyError for a valence outside 3..1000.
std::array<double, 12> sqrt2_omega(int n0, int n1, int n2, int n3);

/// The same without the cache (what the cache stores).
std::array<double, 12> sqrt2_omega_solve(const std::array<int, 4>& valences);

/// eta_0..eta_3 of eq. 12-13, case (a): an inner curve wavelet lifted on p0..p3.
std::array<double, 4> sqrt2_eta_inner();

/// eta_0, eta_1 of eq. 12-13, case (b): the wavelet next to the curve end p2, lifted on p0, p1.
std::array<double, 2> sqrt2_eta_corner();

}  // namespace sublift
