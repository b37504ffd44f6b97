#include "core/schemes/registry.h"

#include <cmath>
#include <stdexcept>

#include "core/schemes/bertram/bertram_transition.h"
#include "core/schemes/sqrt2/sqrt2_level.h"
#include "core/schemes/tri/tri_level.h"
#include "core/schemes/tri/tri_transform.h"

namespace sublift {
namespace {

LevelBuild linear_level(Complex& parent, const LevelContext& ctx) { return build_bertram_level(parent, linear_program(), ctx); }
LevelBuild cubic_level(Complex& parent, const LevelContext& ctx) { return build_bertram_level(parent, cubic_program(), ctx); }
LevelBuild linear_tri_level(Complex& parent, const LevelContext& ctx) { return build_tri_level(parent, Scheme::LinearTri, ctx); }
LevelBuild butterfly_level(Complex& parent, const LevelContext& ctx) { return build_tri_level(parent, Scheme::Butterfly, ctx); }
LevelBuild loop_level(Complex& parent, const LevelContext& ctx) { return build_tri_level(parent, Scheme::Loop, ctx); }

using R = Refinement;
using L = LimitRule;
// id, name, refinement, surfaces only, triangles only, interpolates, integer, levels per split,
// limit, limit rows, builder, peak bytes
constexpr SchemeInfo kSchemes[] = {
    {Scheme::Linear, "linear", R::Split, false, false, false, true, 1, L::ControlNet, nullptr, linear_level, {400, 900}},
    {Scheme::Cubic, "cubic", R::Split, false, false, false, true, 1, L::Eigen, nullptr, cubic_level, {400, 900}},
    {Scheme::Sqrt2, "sqrt2", R::Sqrt2, true, false, true, true, 2, L::ControlNet, nullptr, build_sqrt2_level, {900, 0}},
    {Scheme::LinearTri, "linear-tri", R::Tri, true, true, true, true, 1, L::ControlNet, nullptr, linear_tri_level, {1250, 0}},
    {Scheme::Butterfly, "butterfly", R::Tri, true, true, true, true, 1, L::ControlNet, nullptr, butterfly_level, {1600, 0}},
    {Scheme::Loop, "loop", R::Tri, true, true, false, false, 1, L::LoopMasks, loop_limit_rows, loop_level, {1500, 0}},
};

}  // namespace

std::span<const SchemeInfo> all_schemes() { return kSchemes; }

const SchemeInfo& scheme_info(Scheme s) {
  for (const SchemeInfo& i : kSchemes)
    if (i.id == s) return i;
  throw std::logic_error("scheme without a registry entry");
}

std::string scheme_name(Scheme s) { return scheme_info(s).name; }

std::string scheme_names_list() {
  std::string out;
  const std::size_t n = std::size(kSchemes);
  for (std::size_t i = 0; i < n; ++i) out += std::string(i == 0 ? "" : i + 1 == n ? " or " : ", ") + kSchemes[i].name;
  return out;
}

Scheme parse_scheme(const std::string& name) {
  for (const SchemeInfo& i : kSchemes)
    if (name == i.name) return i.id;
  throw std::invalid_argument("unknown scheme '" + name + "' (expected " + scheme_names_list() + ")");
}

double wavelet_scale(Scheme s, int dim, int level) {
  const double per_level = scheme_info(s).refinement == Refinement::Sqrt2 ? 1.0 : double(dim);
  return std::pow(2.0, -0.5 * level * per_level);
}

}  // namespace sublift
