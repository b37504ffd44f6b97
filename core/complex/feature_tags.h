#pragma once
// The inverse of assign_feature_dims for writers: the fewest tags (feature faces, crease edges,
// corners) from which the builders of complex_build.h give back a complex's feature dims.
// Automatic features (boundaries, non-manifold edges and faces) need no tag.
#include "core/complex/complex.h"
#include "core/complex/complex_build.h"

namespace sublift {

/// Tags that reproduce `c`'s face, edge and vertex dims on reading (docs/features.md rules).
/// Uses c's derived rows, building them on a copy when absent. Dims that no tag can produce (a feature lowered
/// below what topology gives) are left to the topology.
FeatureTags derive_feature_tags(const Complex& c);

}  // namespace sublift
