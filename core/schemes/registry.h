#pragma once
// The one table of what each scheme is (docs/architecture.md): its name, refinement, the
// complexes it takes, whether it interpolates, integer support, level limit, limit evaluation,
// wavelet norms and the builder that compiles one level transition. Every branch on the scheme
// elsewhere asks this table; adding a scheme means writing its builder and one entry here.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/engine/level_build.h"
#include "core/schemes/scheme.h"

namespace sublift {

enum class Refinement : std::uint8_t {
  Split,  // 1-to-2^dim splits of any polyhedral complex, [v | e | f | c] (refine.h)
  Sqrt2,  // Wang & Ma's sqrt(2) steps of quad-dominant surfaces (refine_sqrt2.h)
  Tri,    // 1-to-4 triangle splits, [v | e] (refine_tri.h)
};

enum class LimitRule : std::uint8_t {
  ControlNet,   // the limit is the control net (linear, interpolating schemes)
  Eigen,        // per-configuration eigen-analysis of the subdivision matrix (cubic)
  LoopMasks,    // Loop's closed-form limit masks
};

using LevelBuilder = LevelBuild (*)(Complex& parent, const LevelContext& ctx);
/// LoopMasks: the limit-position rows over the vertices of a finest level (derived rows not needed).
using LimitRows = void (*)(const Complex& c, Csr& rows, std::vector<double>& weights);

struct SchemeInfo {
  Scheme id;
  const char* name;
  Refinement refinement;
  bool surfaces_only;      // refuses curves and lattices
  bool triangles_only;     // refuses faces with other than three corners
  bool interpolates;       // the limit passes through every control point
  bool integer;            // has an exact integer mode
  int levels_per_split;    // levels that make one 1-to-4 refinement: sqrt2 2, else 1
  LimitRule limit;
  LimitRows limit_rows;    // LoopMasks only, else nullptr
  LevelBuilder build;
  // Peak bytes per finest-level vertex of building a hierarchy and synthesizing its finest level
  // (surfaces and curves, lattices; 0: not refined), measured with sublift-cli subdivide's
  // peak RSS at 10^5..10^6 vertices, rounded up (docs/memory.md). The up-front memory check.
  double peak_bytes[2];
};

/// Largest number of levels a project, command or hierarchy accepts per 1-to-4 split; a scheme
/// takes max_levels(s) = levels_per_split times as many.
inline constexpr int kMaxLevels = 12;

const SchemeInfo& scheme_info(Scheme s);
std::span<const SchemeInfo> all_schemes();

/// "linear" / "cubic" / "sqrt2" / "linear-tri" / "butterfly" / "loop"; parse throws
/// std::invalid_argument on other names.
std::string scheme_name(Scheme s);
Scheme parse_scheme(const std::string& name);
/// "linear, cubic, sqrt2, linear-tri, butterfly or loop", for messages.
std::string scheme_names_list();

inline int max_levels(Scheme s) { return kMaxLevels * scheme_info(s).levels_per_split; }
inline bool scheme_interpolates(Scheme s) { return scheme_info(s).interpolates; }
inline int scheme_levels_per_split(Scheme s) { return scheme_info(s).levels_per_split; }
inline bool scheme_is_tri(Scheme s) { return scheme_info(s).refinement == Refinement::Tri; }

/// The L2 norm of a level-j wavelet by area scaling, for schemes without exact norms: each
/// level multiplies the cell count by 2^dim (sqrt2: by 2), so a basis function's norm is
/// 2^(-j * dim / 2) (sqrt2: 2^(-j / 2)). The one place for this factor.
double wavelet_scale(Scheme s, int dim, int level);

}  // namespace sublift
