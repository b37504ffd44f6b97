#include "core/schemes/tri/tri_level.h"

#include <algorithm>
#include <cmath>

#include "core/complex/refine_tri.h"
#include "core/schemes/tri/tri_transform.h"

namespace sublift {

LevelBuild build_tri_level(Complex& parent, Scheme scheme, const LevelContext& ctx) {
  LevelBuild b;
  // The child's derived rows only when the next level wants them (a wavelet that has to be solved
  // builds its own copy of them).
  b.fine = refine_tri(parent, ctx.adjacency);
  TriTransitionResult r = build_tri_transition(parent, b.fine, scheme, ctx.disc, true, 32, ctx.carry);
  b.carry = std::move(r.fine_face_types);
  const std::uint32_t nv = parent.num_vertices, ne = parent.num_edges();
  b.has_sites = true;
  b.sites.site.resize(ne);
  b.sites.edge_child.resize(ne);
  b.sites.face_child.assign(parent.num_faces(), UINT32_MAX);
  for (std::uint32_t e = 0; e < ne; ++e) {
    b.sites.site[e] = e;
    b.sites.edge_child[e] = nv + e;
  }
  const double area = std::pow(0.25, ctx.level);
  b.norms.reserve(r.norm2.size());
  for (double n2 : r.norm2) b.norms.push_back(std::sqrt(std::max(0.0, n2 * area)));
  b.transition = std::move(r.transition);
  return b;
}

}  // namespace sublift
