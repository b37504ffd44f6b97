#pragma once
// Local frames of wavelet coefficients (issue 4): the wavelet on the e- or f-vertex of level j+1
// can be kept as components in an orthonormal frame of the level-j surface, so that when a
// coarse edit turns the surface the detail turns with it.
//
//   edge (a, b):  t = (p_b - p_a) / |.|, n = sum of the unit (Newell) normals of the faces at the
//                 edge made orthogonal to t, b = n x t
//   face:         n = its unit Newell normal, t = first edge (corner 0 to 1) made orthogonal to n,
//                 b = n x t
// Both are equivariant under rotations of the level-j positions, so a rotated coarse shape
// rotates its detail exactly. Degenerate elements (zero-length edge, zero-area faces) use the
// world axes. Surfaces only (dim 2): a lattice or curve keeps world coordinates.
#include <cstdint>
#include <span>
#include <vector>

#include "core/complex/child_sites.h"
#include "core/complex/complex.h"

namespace sublift {

/// Frame columns t, b, n (9 doubles, column-major) of the wavelet on `child` (a vertex of the
/// refined level in [nv, nv + ne + nf)) from `parent` positions (3 per vertex). `sites`: where
/// the children sit when the refinement is not 1-to-4 (sqrt2); nullptr for refine.h's layout.
void wavelet_frame(const Complex& parent, const double* pos, std::uint32_t child, double frame[9],
                   const ChildSites* sites = nullptr);

/// world = F * local and local = F^T * world.
inline void frame_to_world(const double f[9], const double l[3], double w[3]) {
  for (int r = 0; r < 3; ++r) w[r] = f[r] * l[0] + f[3 + r] * l[1] + f[6 + r] * l[2];
}
inline void frame_to_local(const double f[9], const double w[3], double l[3]) {
  for (int c = 0; c < 3; ++c) l[c] = f[3 * c] * w[0] + f[3 * c + 1] * w[1] + f[3 * c + 2] * w[2];
}

/// Children (e- and f-vertices of the refined level) whose frames read any of the `changed`
/// parent vertices; appended to `out` without repeats (stamp: scratch, one entry per child
/// vertex, compared against `epoch`).
void frames_reading(const Complex& parent, std::span<const std::uint32_t> changed, std::vector<std::uint32_t>& out,
                    std::vector<std::uint32_t>& stamp, std::uint32_t epoch, const ChildSites* sites = nullptr);

}  // namespace sublift
