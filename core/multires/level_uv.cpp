#include "core/multires/level_uv.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "core/base/errors.h"
#include "core/complex/face_varying.h"
#include "core/schemes/registry.h"

namespace sublift {

std::string uv_refinement_problem(Scheme scheme) {
  if (scheme_info(scheme).refinement == Refinement::Sqrt2)
    return "sqrt2 cannot carry texture coordinates: its new faces lie across the parent's edges, so a UV seam would run through a face (use linear, cubic or a triangle scheme)";
  return "";
}

FaceVaryingUV uv_at_level(const Hierarchy& h, const FaceVaryingUV& base, int level) {
  if (const std::string why = uv_refinement_problem(h.scheme); !why.empty()) throw InputError("uv", 0, why);
  if (const std::string why = uv_problem(h.levels.front(), base); !why.empty()) throw InputError("uv", 0, why);
  FaceVaryingUV uv = base;
  for (int j = 0; j < level; ++j) {
    const Complex& c = h.levels[static_cast<std::size_t>(j)];
    uv = scheme_is_tri(h.scheme) ? refine_uv_tri(c, uv) : refine_uv_split(c, uv);
  }
  return uv;
}

FaceVaryingUV uv_for_output(const Hierarchy& h, const FaceVaryingUV& base, int level, std::vector<std::string>& notes) {
  if (base.empty()) return {};
  if (const std::string why = uv_refinement_problem(h.scheme); !why.empty()) {
    notes.push_back("texture coordinates not written: " + why);
    return {};
  }
  return uv_at_level(h, base, level);
}

FaceVaryingUV coarsen_file_uv(const Hierarchy& h, const Csr& file_faces, const FaceVaryingUV& file_uv,
                              std::span<const std::uint32_t> engine_vertex, std::string* why) {
  if (file_uv.empty()) return {};
  try {
    if (engine_vertex.empty()) return coarsen_uv(h, file_uv, why);
    Csr faces = file_faces;
    for (std::uint32_t& v : faces.items) v = engine_vertex[v];
    return coarsen_uv(h, uv_for_faces(faces, file_uv, h.levels.back().faces), why);
  } catch (const TopologyError& e) {
    if (why) *why = e.what();
    return {};
  }
}

FaceVaryingUV coarsen_uv(const Hierarchy& h, const FaceVaryingUV& finest, std::string* why) {
  const auto fail = [&](const std::string& w) {
    if (why) *why = w;
    return FaceVaryingUV{};
  };
  if (std::string w = uv_refinement_problem(h.scheme); !w.empty()) return fail(w);
  const Complex& fine = h.levels.back();
  if (std::string w = uv_problem(fine, finest); !w.empty()) return fail(w);
  const bool tri = scheme_is_tri(h.scheme);
  const Complex& base = h.levels.front();
  FaceVaryingUV out;
  std::unordered_map<std::uint32_t, std::uint32_t> point_of;  // finest UV point -> base UV point
  out.corners.resize(base.faces.items.size());
  for (std::uint32_t f = 0; f < base.num_faces(); ++f)
    for (std::uint32_t i = 0; i < base.faces.offsets[f + 1] - base.faces.offsets[f]; ++i) {
      // The descendant at corner i: refine.h numbers a face's corner children by corner slot,
      // refine_tri.h as 4f + k; each keeps the parent corner's vertex as its corner 0.
      std::uint32_t face = tri ? 4 * f + i : base.faces.offsets[f] + i;
      for (int j = 1; j < h.finest_level(); ++j) face = tri ? 4 * face : h.levels[std::size_t(j)].faces.offsets[face];
      const std::uint32_t slot = h.finest_level() == 0 ? base.faces.offsets[f] + i : fine.faces.offsets[face];
      const std::uint32_t p = finest.corners[slot];
      const auto [it, added] = point_of.try_emplace(p, std::uint32_t(out.num_points()));
      if (added) out.points.insert(out.points.end(), {finest.points[2 * p], finest.points[2 * p + 1]});
      out.corners[base.faces.offsets[f] + i] = it->second;
    }
  const FaceVaryingUV again = uv_at_level(h, out, h.finest_level());
  double range = 1.0, worst = 0.0;
  for (double x : finest.points) range = std::max(range, std::abs(x));
  for (std::size_t k = 0; k < finest.corners.size(); ++k)
    for (int c = 0; c < 2; ++c)
      worst = std::max(worst, std::abs(again.points[2 * again.corners[k] + c] - finest.points[2 * finest.corners[k] + c]));
  if (worst > 1e-6 * range)
    return fail("the UVs are not the linear refinement of their base corners' (they differ by up to " + std::to_string(worst) + ")");
  return out;
}

}  // namespace sublift
