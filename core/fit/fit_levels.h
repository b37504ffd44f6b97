#pragma once
// Fitting the levels of a base mesh to any input surface (issue 17, docs/fit.md), coarse to
// fine: subdivide the fitted level, relax its new points tangentially (so the parametrisation
// stays even), project every point onto the input along its normal (crease and boundary points
// onto the input's feature lines), solve for the net that lies on the input and covers all of it
// (core/fit/net_solve.h), never folding a face; analyse the level back into coefficients; then
// analyse the finest fitted level, so the input's detail becomes wavelets. Reported per level:
// distances both ways, folded faces, time; for the finest level's limit surface, distances both
// ways.
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "core/base/csr.h"
#include "core/base/triangle_bvh.h"
#include "core/fit/base_mesh.h"
#include "core/fit/net_solve.h"
#include "core/multires/hierarchy.h"

namespace sublift {

/// Called between stages and levels; answering false cancels the fit (it throws Cancelled).
using FitProgress = std::function<bool(const char* stage, double fraction)>;

/// The scheme a fit takes when none is named (the CLI, the modeler, scripts): sqrt(2), the one
/// that meets the distance and fold goals on the shared scans (docs/fit.md).
inline constexpr Scheme kDefaultFitScheme = Scheme::Sqrt2;

struct FitOptions {
  Scheme scheme = kDefaultFitScheme;  // any surface scheme (a triangle scheme needs a triangle base)
  int levels = 3;                // with a tolerance: the most levels
  double tolerance = 0;          // > 0: stop at the first level whose fitted surface (Loop: its
                                 // limit surface; else the net) lies within this fraction of the
                                 // diagonal both ways
  int relax_rounds = 3;          // per level: relax and project, then solve, this many times
  double relax = 0.5;            // how far a new point moves towards its neighbours' mean
  bool two_way = true;           // the solve that pulls the net over all of the input
  int limit_rounds = 2;          // approximating schemes: rounds fitting the finest limit surface
  NetSolveWeights weights;
  FitProgress progress;
};

// Distances are fractions of the input's bounding-box diagonal.
struct FitLevelReport {
  int level = 0;
  std::uint32_t vertices = 0;
  double rms = 0, max = 0;            // control net -> input
  double back_rms = 0, back_max = 0;  // input's vertices -> control net
  std::uint32_t folded = 0;           // faces turned over against the subdivided level above
  double ms = 0;
};

struct Fitted {
  Hierarchy hierarchy;           // analysed: synthesising its finest level gives the fitted net
  std::vector<double> finest;    // the fitted finest control net (3 per vertex)
  std::vector<FitLevelReport> levels;
  // The limit surface of the finest level (its limit points as a mesh) -> input, and back.
  double limit_rms = 0, limit_max = 0, limit_back_rms = 0, limit_back_max = 0;
  std::uint32_t limit_folded = 0;
  // The input's feature lines (BaseMesh::input_lines) and the largest distance from their
  // vertices to the fitted creases' and boundaries' limit curves (infinite when the fit has none).
  std::size_t feature_lines = 0;
  double feature_max = 0;
  bool reached_tolerance = false;
  std::vector<std::pair<std::string, double>> stage_ms;  // indexing, hierarchy (level setup), levels, analysis, report
};

/// The levels that bring a base of `base_vertices` to about `input_vertices` (a 1-to-4 split has
/// about four times the vertices of the level above, a sqrt(2) step twice): 1 to 6 splits;
/// 3 (sqrt(2): 6) for the default base (1/64).
int default_fit_levels(std::uint32_t input_vertices, std::uint32_t base_vertices, Scheme scheme);

/// Whether `scheme` gets a quad-dominant base (BaseMeshOptions::quads): the schemes that refine
/// any polygon do; the triangle schemes take triangles.
bool fit_base_quads(Scheme scheme);

/// What fitting asks of the input apart from its base: the closest-point index of its surface,
/// its area-weighted vertex normals (3 per vertex) and its bounding-box diagonal. Independent of
/// the base, so fit_mesh builds it while the base is decimated.
struct FitInputIndex {
  TriangleBvh surface;
  std::vector<double> normals;
  double diagonal = 0;
};
FitInputIndex index_fit_input(const Csr& faces, std::span<const double> positions);

/// Fits `base` (from decimate_to_base of this input) to the input (`faces`, `positions`),
/// indexing the input first (the "indexing" stage). A triangle scheme needs a triangle base
/// (Error otherwise).
Fitted fit_levels(const BaseMesh& base, const Csr& faces, std::span<const double> positions, const FitOptions& options = {});
/// The same with the input's index made already (index_fit_input of this input).
Fitted fit_levels(const BaseMesh& base, const Csr& faces, std::span<const double> positions, const FitOptions& options,
                  const FitInputIndex& index);

struct MeshFit {
  BaseMesh base;
  Fitted fitted;
  double base_ms = 0;  // the decimation (Fitted::stage_ms has the rest; its "indexing" is what
                       // the input's index took beyond the decimation, and the feature lines)
};
/// decimate_to_base, then fit_levels, the input indexed on another thread while the base is
/// decimated (the decimation is serial). `fit.levels` < 0: default_fit_levels for the base made.
MeshFit fit_mesh(std::uint32_t num_vertices, const Csr& faces, std::span<const double> positions, const BaseMeshOptions& base,
                 FitOptions fit);

}  // namespace sublift
