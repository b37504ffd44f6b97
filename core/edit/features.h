#pragma once
// Creases and corners marked in the modeler (issue 19; Blender's Shift+E): a feature is a
// property of the base, so marking one rebuilds the hierarchy on the base with its new feature
// dims, and the finest level as shown (gains applied) is analysed by the new rules: the shape
// stays and the detail is kept, now as the wavelets of the new rules (perfect reconstruction;
// gains become 1). Tags are derive_feature_tags (core/complex/feature_tags.h): what projects
// and OBJ exports carry.
#include <cstdint>
#include <span>
#include <vector>

#include "core/complex/complex_build.h"
#include "core/edit/session.h"

namespace sublift {

/// Base edges joining two of `selection` (ascending).
std::vector<std::uint32_t> edges_within(const Complex& c, std::span<const unsigned> selection);

/// `tags` with the creases on `edges` of `c` set (on) or cleared (off). A boundary edge is a
/// feature already and takes no tag.
FeatureTags with_creases(const Complex& c, FeatureTags tags, std::span<const std::uint32_t> edges, bool on);
/// `tags` with corners at `vertices` set or cleared.
FeatureTags with_corners(FeatureTags tags, std::span<const unsigned> vertices, bool on);

/// The session's hierarchy on its base with `tags` (the same scheme and levels), holding the
/// finest shape the session shows. Throws Error when the base cannot take the tags.
Hierarchy with_base_features(const Session& s, const FeatureTags& tags);

}  // namespace sublift
