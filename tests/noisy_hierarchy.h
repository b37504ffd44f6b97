#pragma once
// A hierarchy with detail at every level, the input of the CLI's project tests.
#include <cstdint>
#include <vector>

#include "core/complex/complex_build.h"
#include "core/complex/shapes.h"
#include "core/multires/hierarchy.h"
#include "tests/test_shapes.h"

namespace sublift::testing {

/// make_quad_torus(n, m) as `levels` levels of `scheme` whose wavelets are not zero: the
/// subdivision of the base plus uniform noise in [-amplitude, amplitude] (random_values with
/// `seed`) at the finest level, analysed.
inline Hierarchy noisy_torus(int n, int m, int levels, Scheme scheme, std::uint64_t seed, double amplitude) {
  const SurfaceMesh mesh = make_quad_torus(n, m);
  Hierarchy h = make_hierarchy(complex_from_surface_mesh(mesh), levels, scheme, 3);
  set_base(h, flatten_positions(mesh));
  std::vector<double> fine = synthesize(h, levels);
  const std::vector<double> r = random_values(fine.size(), seed, -amplitude, amplitude);
  for (std::size_t i = 0; i < fine.size(); ++i) fine[i] += r[i];
  analyze(h, fine);
  return h;
}

}  // namespace sublift::testing
