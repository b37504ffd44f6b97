#pragma once
// Basis functions of the wavelet hierarchy (issue 5): one coefficient set to one, all others
// zero, synthesised from level j to level j+K (primal functions), or the row of the analysis
// operator from level j+K down to that coefficient (dual functions).
//
// Conventions.
//   - The request names a coefficient of level j of a complex that is itself the base refined
//     `level` times (the complex passed in, with its feature dims). A scaling coefficient is
//     vertex i < nv_j; a wavelet coefficient of level j lives on an e/f/c vertex i of level j+1
//     (nv_j <= i < nv_{j+1}); indices are the engine's order (refine.h, [v | e | f | c]).
//   - Values live on the vertices of level j+K in the engine's order, one scalar each.
//     Primal: `control` are the synthesised control values; `values` are their limit values (the
//     finest level's limit stencils, core/multires/limit.h, applied to the scalar), `limit` = true.
//     Dual: `control` = `values` = the weights w of the analysis row (coefficient = sum_k w_k x_k
//     for level j+K values x), `limit` = false.
//   - Primal integral: sum_k values_k * mu_k, where mu_k is the dual cell measure of finest vertex
//     k: every finest cell (edge of a curve, face of a surface, cell of a lattice) has parametric
//     measure 2^(-(level+K)*dim) and gives it in equal parts to its corners. A base quad, hex or
//     curve edge thus has measure 1 (a base n-gon n/4; a base hexahedron 1). sqrt2 (whose
//     levels halve the area): a quad of level L has 2^-L, a triangle on a kept curve half that. First moments:
//     sum_k values_k * mu_k * p_k with p_k the finest limit positions of the geometry passed in.
//   - Dual "integral" and "moments": the functional applied to the constant 1 and to the x, y, z
//     coordinate functions of the finest control positions, i.e. sum_k w_k and sum_k w_k p_k
//     (1 and the coefficient's position for a dual scaling function, 0 for a dual wavelet when
//     the scheme reproduces constants and linear functions).
//   - Support: per level l in j..j+K, the number of non-zero level-l control values (exact zeros;
//     for a wavelet, level j has none). `support` lists the finest vertices where the control or
//     the limit value is non-zero. For duals the per-level counts are those of the adjoint
//     program's intermediate vectors.
#include <cstdint>
#include <span>
#include <vector>

#include "core/complex/complex.h"
#include "core/multires/hierarchy.h"

namespace sublift {

enum class BasisKind : std::uint8_t { Scaling, Wavelet };

struct BasisRequest {
  int level = 0;                  // j: how many times the complex passed in refines the base (measures)
  BasisKind kind = BasisKind::Scaling;
  std::uint32_t index = 0;        // vertex of level j (scaling) or e/f/c vertex of level j+1 (wavelet)
  bool dual = false;              // the analysis row instead of the synthesised function
  int extra_levels = -1;          // K; -1 = default_extra_levels
  double max_vertices = 4.0e6;    // level j+K may have at most this many vertices
};

struct BasisFunction {
  int level = 0;                   // j (as requested)
  int extra_levels = 0;            // K actually used
  Complex finest;                  // level j+K (without adjacency)
  std::vector<double> control;     // per finest vertex: control values (dual: weights)
  std::vector<double> values;      // per finest vertex: limit values (dual: weights)
  bool limit = false;              // `values` are limit values
  std::vector<std::uint32_t> support_per_level;  // levels j..j+K
  std::vector<std::uint32_t> support;            // finest vertices with a non-zero value
  double integral = 0, min = 0, max = 0;
  double moment[3] = {0, 0, 0};
};

/// K for a complex of this dimension: 6 for curves, 4 for surfaces, 3 for volumes (sqrt2: twice
/// as many, its levels being half steps), lowered until level K of `c` has at most
/// `max_vertices` vertices (at least 0). `level`: which sqrt(2) level `c` is.
int default_extra_levels(const Complex& c, double max_vertices = 4.0e6, Scheme scheme = Scheme::Cubic, int level = 0);

/// The basis function of request `r` on `level_j` (a complex of level r.level with its feature
/// dims; adjacency is built on a copy if missing) under `scheme`. `level_j_positions` (3 per
/// vertex) are synthesised along for the moments; `finest_positions`, when given, receives the
/// finest limit positions (3 per vertex). Throws Error for an index outside its range, a
/// wavelet index on a v vertex, K < 0 or a finest level above r.max_vertices.
BasisFunction basis_function(const Complex& level_j, Scheme scheme, const BasisRequest& r,
                             std::span<const double> level_j_positions,
                             std::vector<double>* finest_positions = nullptr);

}  // namespace sublift
