#pragma once
// The eigen solve behind an extraordinary limit stencil (limit.cpp, docs/limit_stencils.md): a
// patch (the feature-filtered closed star of a vertex, vertex 0 its centre) is refined twice by
// the cubic scheme; its local subdivision matrices are read off the executor's sparse synthesis
// of unit impulses, and the stencils are left eigenvectors of the star's matrix.
#include <vector>

#include "core/complex/complex.h"
#include "core/multires/limit.h"

namespace sublift {

/// Solves the patch (no adjacency needed) with the given method (LimitSolver in limit.h); the
/// weights are over the patch's local vertices.
PatchSolution solve_limit_patch(const Complex& patch, LimitSolver solver);

}  // namespace sublift
