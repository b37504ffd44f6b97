#pragma once
// Switching an editing session to another scheme (the modeler's Scheme menu, `scheme S` in
// scripts, `sublift-cli set --scheme S`): one rule for all three.
//
// The finest resolution stays (two sqrt(2) levels make one 1-to-4 split, so the level count
// scales by levels_per_split). Schemes with the same refinement (linear and cubic; linear-tri,
// butterfly and loop) have the same complex at every level, so the finest net the session shows
// (its gains applied) is analysed by the new scheme: the shape is kept exactly, to rounding, and
// the gains become 1 (they are in the new wavelets). Between refinements (to or from sqrt2) the
// levels are different meshes: the new hierarchy starts from the base's positions with zero
// detail, and `kept_detail` is false so the caller can say so.
#include <functional>
#include <span>
#include <vector>

#include "core/edit/session.h"
#include "core/schemes/registry.h"

namespace sublift {

/// Throws Error when `scheme` cannot refine `base` (a surface scheme on a curve or lattice, a
/// triangle scheme on other polygons), naming the first offending face.
void check_scheme_takes(Scheme scheme, const Complex& base);

/// `level` of a hierarchy of `from` as the level of the same resolution under `to`, capped at
/// `to`'s level limit.
int level_under_scheme(int level, Scheme from, Scheme to);

struct SchemeSwitch {
  Hierarchy hierarchy;      // 3 channels, the new scheme, level_under_scheme(J) levels
  bool kept_detail = false; // the finest shape is the session's (same refinement)
};

/// What a switch reads of the session, copied, so the costly part can run on another thread
/// while the session stays in use: the base, the old scheme and finest level, and the net the
/// new hierarchy starts from (the finest shown net with the same refinement, else level 0's).
struct SchemeSwitchInput {
  Complex base;
  Scheme from = Scheme::Cubic, to = Scheme::Cubic;
  int finest = 0;
  std::vector<double> positions;
};
/// Throws Error as check_scheme_takes does.
SchemeSwitchInput scheme_switch_input(const Session& session, Scheme to);

/// Told the stage and the fraction done; answering false stops the switch with Cancelled.
using SwitchProgress = std::function<bool(const char* stage, double fraction)>;
SchemeSwitch switch_scheme(const SchemeSwitchInput& in, const SwitchProgress& progress = {});

/// The session's shape under `to` (see above), in one call.
SchemeSwitch switch_scheme(const Session& session, Scheme to);

}  // namespace sublift
