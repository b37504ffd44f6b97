// The modeler's texture coordinates: the base's UVs kept beside the session, refined for each
// level by the linear rule (core/multires/level_uv.h), saved and exported with the levels.
#include "app/modeler/modeler_state.h"
#include "core/complex/face_varying.h"
#include "core/multires/level_uv.h"

namespace sublift {

void ModelerState::remember_uv(const Complex& base, FaceVaryingUV uv) {
  if (uv.empty() || !uv_problem(base, uv).empty()) return;
  for (auto& [faces, kept] : uv_bases_)
    if (faces.offsets == base.faces.offsets && faces.items == base.faces.items) return void(kept = std::move(uv));
  uv_bases_.emplace_back(base.faces, std::move(uv));
}

FaceVaryingUV ModelerState::base_uv() const {
  const Complex& base = session_->hierarchy().levels.front();
  for (const auto& [faces, uv] : uv_bases_)
    if (faces.offsets == base.faces.offsets && faces.items == base.faces.items) return uv;
  return {};
}

FaceVaryingUV ModelerState::level_uv(int level) const {
  const Hierarchy& h = session_->hierarchy();
  const FaceVaryingUV base = base_uv();
  if (base.empty() || !uv_refinement_problem(h.scheme).empty() || level < 0 || level > h.finest_level()) return {};
  return uv_at_level(h, base, level);
}

UvVertexSplit ModelerState::shown_uv_split() const {
  if (texture_.empty() || anim_) return {};
  const int level = shown_level();
  const Complex& c = session_->hierarchy().levels[std::size_t(level)];
  if (c.dim != 2 || faces_.items != c.faces.items || faces_.offsets != c.faces.offsets) return {};
  const FaceVaryingUV uv = level_uv(level);
  if (uv.empty()) return {};
  return split_at_uv_seams(faces_, uv, c.num_vertices);
}

FaceVaryingUV ModelerState::uv_in_file_order(const FaceVaryingUV& uv, const Complex& level) const {
  Csr faces = input_order_.faces;
  for (std::uint32_t& v : faces.items) v = input_order_.engine_vertex[v];
  return uv_for_faces(level.faces, uv, faces);
}

}  // namespace sublift
