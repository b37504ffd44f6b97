#pragma once
// Fitting the levels of a base mesh to any input surface (issue 17, docs/fit.md), coarse to
// fine: subdivide the fitted level, relax its new points (so the parametrisation stays even),
// attract every point to the closest point of the input, analyse the level back into coefficients;
// then analyse the finest fitted level, so the input's detail becomes wavelets.
#include <cstdint>
#include <span>
#include <vector>

#include "core/base/csr.h"
#include "core/fit/base_mesh.h"
#include "core/multires/hierarchy.h"

namespace sublift {

struct FitOptions {
  Scheme scheme = Scheme::Loop;  // the triangle schemes (the base is triangles)
  int levels = 3;
  int relax_rounds = 3;          // per level: relax then attract, this many times
  double relax = 0.5;            // how far a new point moves towards its neighbours' mean
};

struct FitLevelReport {
  int level = 0;
  std::uint32_t vertices = 0;
  double rms = 0, max = 0;       // control net -> input, as fractions of the input's bbox diagonal
  double ms = 0;
};

struct Fitted {
  Hierarchy hierarchy;           // analysed: synthesising its finest level gives the fitted net
  std::vector<double> finest;    // the fitted finest control net (3 per vertex)
  std::vector<FitLevelReport> levels;
};

/// Fits `base` (from decimate_to_base of this input) to the input (`faces`, `positions`).
/// Throws Error for schemes other than the triangle schemes.
Fitted fit_levels(const BaseMesh& base, const Csr& faces, std::span<const double> positions, const FitOptions& options = {});

}  // namespace sublift
