#pragma once
// A hierarchy with real detail for the compression tests (core, modeler, GUI): the finest level
// of a bundled shape refined J times, plus smooth waves of three lengths and a little Gaussian
// noise, analysed.
#include <string>
#include <vector>

#include "core/base/bounds.h"
#include "core/analysis/experiments.h"
#include "core/multires/hierarchy.h"
#include "core/io/lattice/shape_io.h"

namespace sublift::testing {

/// `path` refined `levels` times with `scheme`, plus waves of 2, 5 and 11 lengths per diagonal
/// (amplitudes 2%, 0.8%, 0.3% of the diagonal, times `scale`) and N(0, (noise x diagonal)^2)
/// noise, analysed. (With much more noise than detail, or on cubic lattices and open cubic
/// surfaces, keeping the largest few wavelets can raise the L2 error above keeping none:
/// Bertram's cubic wavelets are far from orthogonal; docs/compression.md.)
inline Hierarchy detailed_hierarchy(const std::string& path, Scheme scheme, int levels, double scale = 1.0,
                                    double noise = 0.0005, std::uint64_t seed = 7) {
  Shape s = read_shape(path);
  Hierarchy h = make_hierarchy(std::move(s.base), levels, scheme, 3);
  set_base(h, s.positions);
  const std::vector<double> fine = synthesize(h, levels);
  std::vector<double> model = gaussian_noise(h.num_vertices(levels), noise * bbox_diagonal(fine), seed);
  const double amplitude[3] = {0.02, 0.008, 0.003}, waves[3] = {2, 5, 11};
  for (int k = 0; k < 3; ++k) {
    const std::vector<double> bent = smooth_perturbation(fine, scale * amplitude[k], waves[k]);
    for (std::size_t i = 0; i < model.size(); ++i) model[i] += bent[i] - fine[i];
  }
  for (std::size_t i = 0; i < model.size(); ++i) model[i] += fine[i];
  analyze(h, model);
  return h;
}

}  // namespace sublift::testing
