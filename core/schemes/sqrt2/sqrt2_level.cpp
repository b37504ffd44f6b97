#include "core/schemes/sqrt2/sqrt2_level.h"

#include "core/complex/refine_sqrt2.h"
#include "core/schemes/sqrt2/sqrt2_transform.h"

namespace sublift {
namespace {

ChildSites sites_of(const Complex& coarse, const Sqrt2Children& ch) {
  ChildSites s;
  s.edge_child.assign(coarse.num_edges(), UINT32_MAX);
  s.face_child.assign(coarse.num_faces(), UINT32_MAX);
  const std::uint32_t nc = ch.curve_step ? static_cast<std::uint32_t>(ch.curve_edges.size()) : 0;
  s.site.reserve(nc + ch.point_faces.size());
  for (std::uint32_t k = 0; k < nc; ++k) {
    s.site.push_back(ch.curve_edges[k]);
    s.edge_child[ch.curve_edges[k]] = coarse.num_vertices + k;
  }
  for (std::uint32_t k = 0; k < ch.point_faces.size(); ++k) {
    s.site.push_back(coarse.num_edges() + ch.point_faces[k]);
    s.face_child[ch.point_faces[k]] = ch.first_face_point + k;
  }
  return s;
}

}  // namespace

LevelBuild build_sqrt2_level(Complex& parent, const LevelContext& ctx) {
  Sqrt2Step step = refine_sqrt2(parent, ctx.level);  // builds the derived rows anyway
  LevelBuild b;
  b.transition = std::move(build_sqrt2_transition(parent, step.fine, step.children).transition);
  b.has_sites = true;
  b.sites = sites_of(parent, step.children);
  b.fine = std::move(step.fine);
  return b;
}

}  // namespace sublift
