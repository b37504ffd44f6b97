#pragma once
// Rebuilding the levels of a dense mesh that another tool subdivided (docs/rebuild.md):
// detect_levels finds the base and the labels, the hierarchy is built on that base, and the
// user's positions are analysed, so every level is an exact coarse approximation and the
// detail is wavelets. The input's vertex order is kept beside the hierarchy.
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "core/base/csr.h"
#include "core/base/surface_mesh.h"
#include "core/complex/complex_build.h"
#include "core/complex/detect_levels.h"
#include "core/multires/hierarchy.h"

namespace sublift {

/// What `auto` picks for a mesh: Loop for all-triangle meshes, else cubic (the quad split).
Scheme rebuild_auto_scheme(const Csr& faces);

/// The split a scheme's refinement makes on surfaces; throws Error for schemes whose
/// refinement is not detected (sqrt(2)).
SplitKind rebuild_split(Scheme s);

/// Fine tags carried down the levels of `d` to its base: a crease on both halves of a coarse
/// edge creases that edge, a corner on an old vertex stays. What cannot be carried (a crease
/// inside a coarse face, half a coarse edge, a corner on an edge or face point) is dropped and
/// said in `dropped`, naming input vertices.
struct CarriedFeatures {
  FeatureTags base;
  std::size_t creases = 0, corners = 0;  // fine tags given
  std::vector<std::string> dropped;
};
CarriedFeatures carry_features_down(const DetectedLevels& d, const FeatureTags& fine);

struct Rebuilt {
  Hierarchy hierarchy;
  DetectedLevels detected;
  std::vector<std::uint32_t> engine_vertex;  // input vertex i -> vertex of the finest level
  double detect_ms = 0, build_ms = 0, analysis_ms = 0;  // wall time of the three stages
  CarriedFeatures features;
};

/// Detects up to `levels` levels (-1: as many as the mesh holds, up to max_levels(scheme)),
/// builds the hierarchy on the base found and analyses `positions` (3 per input vertex). With
/// `levels` >= 0 and a mesh that holds fewer, throws Error naming where it stops.
/// Told the stage and the fraction of all the work done (0..1); answering false cancels.
using RebuildProgress = std::function<bool(const char* stage, double fraction)>;

/// `fine_tags`: the input's creases and corners (input vertex numbers), carried to the base.
/// `progress` (may be empty) is called between stages and levels; when it answers false the
/// rebuild throws Cancelled.
/// `attributes` (one value per input vertex each: colours, scalars) are analysed as channels 3..
/// beside x, y, z.
Rebuilt rebuild_hierarchy(std::uint32_t num_vertices, const Csr& faces, std::span<const double> positions, Scheme scheme,
                          int levels, bool integer = false, int disc = 2, const FeatureTags& fine_tags = {},
                          const RebuildProgress& progress = {}, std::span<const VertexAttribute> attributes = {});

/// The same for a volume lattice (`fine` with adjacency; linear or cubic scheme): the 1-to-8
/// split of simple cells (detect_volume_levels). Feature tags of lattices are not carried.
Rebuilt rebuild_volume_hierarchy(const Complex& fine, std::span<const double> positions, Scheme scheme, int levels,
                                 bool integer = false, const RebuildProgress& progress = {});

}  // namespace sublift
