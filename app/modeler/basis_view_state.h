#pragma once
// The modeler's basis-function mode (issue 5): one scaling function or wavelet of the edit level,
// computed with core/multires/basis.h on the edit level's complex and positions, and what the viewport
// draws of it — the function on the level j+K shape (limit positions where the scheme has them),
// a colour value per vertex, optionally displaced along the normal as a height field, and the
// support outline on the level-j net. GL-free: ModelerView uploads it.
//
// Colour: values / max|value| onto viridis; symmetric (0 -> 0.5) for wavelets, duals and any
// function with negative values, else 0 -> 0 (dark) and the maximum -> 1.
// Height field: surfaces move along their vertex normal, curves along the in-plane normal
// (tangent x Z, or tangent x Y for curves along Z), by value / max|value| * scale * the model's
// bounding-box diagonal. Lattices are never displaced: they show the function as colour on
// their boundary surface, or, when a slice plane or an iso-surface is asked for, on a plane
// normal to x, y or z through the volume (at a fraction of the function's bounds) and on the
// surfaces where the function equals +-iso_level * max|value| (core/analysis/cell_contour.h; the negative
// one only for functions with negative values), coloured by the same map.
// Curves also give a plot: the values along the curve component holding the largest |value|,
// in parameter order, over the support and a margin of a tenth of its length on either side.
// Level: a function of any level 0..J can be shown while another level is edited; its support
// outline is drawn on the level-j net (net_positions).
// Support outline: the level-j net edges that touch the support — an end vertex, or the edge's
// midpoint child at level j+1 (when K >= 1), carries a non-zero value at level j+K.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/multires/basis.h"
#include "core/base/csr.h"
#include "core/edit/session.h"
#include "ui/basis_settings.h"

namespace sublift {

/// Finest vertices the modeler's default K may reach (core's own default allows 4e6).
inline constexpr double kModelerBasisVertices = 1.0e6;

/// The same function (request's kind, index, dual, K, level); the view settings may differ.
bool same_function(const BasisSettings& a, const BasisSettings& b);

struct BasisDisplay {
  BasisSettings settings;
  int level = 0;                         // j
  BasisFunction function;
  std::vector<double> base_positions;    // level j+K limit positions (3 per vertex)
  std::vector<double> positions, normals;  // as drawn (displaced when settings.height)
  Csr faces;                             // as drawn: surfaces: finest faces; lattices: boundary
                                         // or slice/iso triangles; curves: none
  Csr boundary;                          // lattices: the finest boundary faces
  std::vector<std::uint32_t> curve_edges;  // curves: finest edges
  std::vector<float> vertex_colour;      // 0..1 per finest vertex
  std::vector<float> colour;             // 0..1 per drawn vertex
  std::vector<float> plot;               // curves: values along the curve (see above)
  bool symmetric = false;
  std::vector<std::uint32_t> support_edges;  // level-j net edges (vertex pairs) touching the support
  std::vector<double> net_positions;     // level-j control points (for the outline)
  double model_size = 1.0;               // bounding-box diagonal of base_positions
};

/// Computes the function of `settings` for edit level `level` of `session`. Throws Error (an
/// index out of range, a wavelet index on a v vertex, a level j+K too large).
BasisDisplay compute_basis_display(const Session& session, int level, const BasisSettings& settings);

/// Recomputes what is drawn for the view settings (height field, slice, iso-surfaces) without
/// computing a new function.
void apply_basis_view(BasisDisplay& d);

/// The colour map's value (0..1) of function value `v` in display `d`.
float basis_colour(const BasisDisplay& d, double v);

/// What a click on control point `vertex` of edit level `edit_level` picks: a scaling function
/// of that level at it; a wavelet: the wavelet of level edit_level - 1 on it when it is an
/// e/f/c vertex of that level (the level j+1 net), else the edge wavelet at it
/// (edge_wavelet_at) on the edit level. Empty when there is none (an isolated vertex).
struct BasisTarget {
  int level = 0;
  std::uint32_t index = 0;
};
std::optional<BasisTarget> basis_target_at(const Hierarchy& h, int edit_level, BasisKind kind, std::uint32_t vertex);

/// The wavelet "nearest" level-j vertex v: the edge wavelet on the midpoint of v's first edge
/// (index nv_j + e); -1 when v has no edge.
long long edge_wavelet_at(const Complex& level_j, std::uint32_t v);

}  // namespace sublift
