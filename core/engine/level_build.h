#pragma once
// What a scheme's builder (core/schemes/) makes of one level: the finer complex and the
// transition to it. The hierarchy calls the builder its scheme's registry entry names.
#include <cstdint>
#include <vector>

#include "core/complex/child_sites.h"
#include "core/complex/complex.h"
#include "core/engine/transition.h"

namespace sublift {

/// What one level's builder returns: the finer complex, the transition to it and, where the
/// scheme knows them, where its new vertices sit and its wavelets' exact L2 norms.
struct LevelBuild {
  Complex fine;
  Transition transition;
  bool has_sites = false;       // ChildSites are implicit for the Split refinement
  ChildSites sites;
  std::vector<double> norms;    // per new vertex; empty: area scaling (wavelet_scale)
  // What the scheme hands to the next level's build (LevelContext::carry), opaque here: the
  // triangle schemes' face types of `fine`, so the next level looks them up without signatures.
  std::vector<std::int32_t> carry;
};

struct LevelContext {
  int level = 0;       // the scheme's level index of `parent`
  int disc = 2;        // the triangle schemes' k-disc wavelets
  bool adjacency = true;  // whether `fine` needs its derived rows
  const std::vector<std::int32_t>* carry = nullptr;  // the build of `parent`'s LevelBuild::carry, if known
};

}  // namespace sublift
