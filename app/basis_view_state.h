#pragma once
// The modeler's basis-function mode (issue 5): one scaling function or wavelet of the edit level,
// computed with core/basis.h on the edit level's complex and positions, and what the viewport
// draws of it — the function on the level j+K shape (limit positions where the scheme has them),
// a colour value per vertex, optionally displaced along the normal as a height field, and the
// support outline on the level-j net. GL-free: ModelerView uploads it.
//
// Colour: values / max|value| onto viridis; symmetric (0 -> 0.5) for wavelets, duals and any
// function with negative values, else 0 -> 0 (dark) and the maximum -> 1.
// Height field: surfaces move along their vertex normal, curves along the in-plane normal
// (tangent x Z, or tangent x Y for curves along Z), by value / max|value| * scale * the model's
// bounding-box diagonal. Lattices are coloured on their boundary surface only (no slices or
// iso-surface in this slice) and never displaced.
// Support outline: the level-j net edges that touch the support — an end vertex, or the edge's
// midpoint child at level j+1 (when K >= 1), carries a non-zero value at level j+K.
#include <cstdint>
#include <string>
#include <vector>

#include "core/basis.h"
#include "core/csr.h"
#include "core/session.h"

namespace sublift {

struct BasisSettings {
  bool on = false;
  BasisKind kind = BasisKind::Scaling;
  std::uint32_t index = 0;    // level-j vertex (scaling) or e/f/c vertex of level j+1 (wavelet)
  bool dual = false;
  int extra_levels = -1;      // K; -1: core's default
  bool height = false;        // displace as a height field (surfaces, curves)
  double height_scale = 0.2;  // times the bounding-box diagonal at max|value|
};

struct BasisDisplay {
  BasisSettings settings;
  int level = 0;                         // j
  BasisFunction function;
  std::vector<double> base_positions;    // level j+K limit positions (3 per vertex)
  std::vector<double> positions, normals;  // as drawn (displaced when settings.height)
  Csr faces;                             // surfaces: finest faces; lattices: boundary; curves: none
  std::vector<std::uint32_t> curve_edges;  // curves: finest edges
  std::vector<float> colour;             // 0..1 per finest vertex
  bool symmetric = false;
  std::vector<std::uint32_t> support_edges;  // level-j net edges (vertex pairs) touching the support
  double model_size = 1.0;               // bounding-box diagonal of base_positions
};

/// Computes the function of `settings` for edit level `level` of `session`. Throws Error (an
/// index out of range, a wavelet index on a v vertex, a level j+K too large).
BasisDisplay compute_basis_display(const Session& session, int level, const BasisSettings& settings);

/// Recomputes positions and normals for settings.height / height_scale (no new function).
void apply_basis_height(BasisDisplay& d);

/// The wavelet "nearest" level-j vertex v: the edge wavelet on the midpoint of v's first edge
/// (index nv_j + e); -1 when v has no edge.
long long edge_wavelet_at(const Complex& level_j, std::uint32_t v);

}  // namespace sublift
