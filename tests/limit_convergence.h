#pragma once
// The limit-stencil check shared by the limit tests: a finest-level control point approaches the
// limit its stencil predicts under further zero-detail subdivision (the engine's own refinement,
// not the stencil code, gives the sequence).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/complex/complex_build.h"
#include "core/multires/hierarchy.h"
#include "core/multires/limit.h"
#include "tests/mesh_fixtures.h"

namespace sublift::testing {

/// What the error sequence must do: start above `min_first`, fall by at least `rate` a level,
/// and end below `final_tol` and below `last_ratio` times the first error.
struct Convergence {
  double min_first = 1e-4;
  double rate = 0.8;
  double final_tol = HUGE_VAL;
  double last_ratio = 1e-2;
};

inline Hierarchy cubic_surface(const fixtures::Polygons& m, int levels) {
  Hierarchy h = make_hierarchy(complex_from_polygons(m.num_vertices, m.faces), levels, Scheme::Cubic, 3);
  set_base(h, m.positions);
  return h;
}

/// Control point of `vertex` at levels base_levels .. base_levels + more against its limit.
inline void expect_converges(const fixtures::Polygons& m, int base_levels, std::uint32_t vertex, int more, const Convergence& c) {
  const Hierarchy h = cubic_surface(m, base_levels);
  const LimitStencils s = build_limit_stencils(h);
  EXPECT_EQ(s.unsolved, 0u);
  const std::vector<double> x = synthesize(h, base_levels);
  std::vector<double> lim(x.size());
  eval_limit(s, x.data(), lim.data());
  const Hierarchy deep = cubic_surface(m, base_levels + more);
  std::vector<double> errors;
  for (int j = base_levels; j <= base_levels + more; ++j) {
    const std::vector<double> xj = synthesize(deep, j);
    errors.push_back(std::hypot(xj[3 * vertex] - lim[3 * vertex], xj[3 * vertex + 1] - lim[3 * vertex + 1],
                                xj[3 * vertex + 2] - lim[3 * vertex + 2]));
  }
  EXPECT_GT(errors.front(), c.min_first) << "the control point should not already be its limit";
  for (std::size_t k = 1; k < errors.size(); ++k) EXPECT_LT(errors[k], c.rate * errors[k - 1]) << "level " << k;
  EXPECT_LT(errors.back(), c.final_tol);
  EXPECT_LT(errors.back(), errors.front() * c.last_ratio);
}

}  // namespace sublift::testing
