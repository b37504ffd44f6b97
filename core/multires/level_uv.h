#pragma once
// A surface's face-varying UVs at every level of its hierarchy (face_varying.h's linear rule,
// applied once per level by the scheme's refinement).
#include <span>
#include <string>
#include <vector>

#include "core/base/surface_mesh.h"
#include "core/multires/hierarchy.h"

namespace sublift {

/// "" when the hierarchy's scheme can carry UVs to its levels; else why not (sqrt(2) makes its
/// new faces across the parent's edges, so a seam would run through a face).
std::string uv_refinement_problem(Scheme scheme);

/// `base` (the UVs of h.levels[0]) refined to level `level`. Throws InputError (file "uv") when
/// the scheme cannot carry UVs or base does not fit h.levels[0].
FaceVaryingUV uv_at_level(const Hierarchy& h, const FaceVaryingUV& base, int level);

/// What a writer of level `level` takes: uv_at_level, or empty (nothing said for an empty `base`;
/// "texture coordinates not written: <why>" added to `notes` when the scheme cannot carry them).
FaceVaryingUV uv_for_output(const Hierarchy& h, const FaceVaryingUV& base, int level, std::vector<std::string>& notes);

/// The base UVs whose refinement is `finest` (UVs per corner of h's finest level): each base
/// corner takes the UV of the finest corner at the same vertex in its corner's descendants, then
/// the refinement of those is compared with `finest`. `*why` (if given) says what failed: the
/// scheme, the fit, or the largest difference (beyond 1e-6 of the UVs' range: float32 files
/// round). Returns an empty set on failure.
FaceVaryingUV coarsen_uv(const Hierarchy& h, const FaceVaryingUV& finest, std::string* why = nullptr);

/// coarsen_uv of a file's UVs: `file_uv` per corner of `file_faces` (the file's faces over its
/// own vertices), carried to the finest level's faces through `engine_vertex` (file vertex ->
/// engine vertex; empty: the file is in the engine's order already). Empty on failure, `*why`
/// saying what failed (a face that is not the finest level's, or coarsen_uv's reason).
FaceVaryingUV coarsen_file_uv(const Hierarchy& h, const Csr& file_faces, const FaceVaryingUV& file_uv,
                              std::span<const std::uint32_t> engine_vertex, std::string* why = nullptr);

}  // namespace sublift
