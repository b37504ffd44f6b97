#pragma once
// Time-varying surfaces as swept lattices (paper 000 sec. 1 and 7; docs/animation.md).
//
// An animation of one mesh with fixed connectivity becomes a volume lattice: the base mesh swept
// through time into one cell layer per base time step (a prism over every triangle, a hexahedron
// over every quad, an n-gon prism over every n-gon). The lattice refines like any other
// (Catmull-Clark style, refine.h), and because the sweep is a product of the surface and a time
// interval, so is every level: level j is the surface refined j times, repeated on
// layers(j) = K 2^j + 1 layers (K 2^j when cyclic). Each layer is the surface at one time.
//
// Time. The first and last layers are boundary faces of the lattice (the time axis ends in a
// cusp: the first and last frames are feature surfaces, refined by the surface rule alone), or,
// for a cyclic animation, the last cell layer joins the last layer to the first (a periodic time
// axis, K >= 3 so that no two time edges join the same pair of vertices). Time carries no
// feature tags.
//
// Fitting. Layer t of level J is frame t of the sampled animation, refined in space the way the
// lattice refines a frame that does not move (fill_layers); the whole finest level is then
// analysed, and perfect reconstruction makes it interpolate those layers to rounding.
//
// Vertex map. layer_vertices[j][t * nv_s(j) + p] is the lattice vertex of level j at layer t and
// surface vertex p of the surface's level j, found by following refine.h's child numbering: a
// vertex of layer t gives its v-child on layer 2t; an edge in a layer its e-child on layer 2t; a
// time edge over surface vertex p, between layers t and t+1, the v-child p on layer 2t+1; a side
// face over surface edge e the e-child; a cell over surface face f the f-child.
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "core/complex/complex.h"
#include "core/multires/hierarchy.h"

namespace sublift {

/// The base lattice: `surface` (dim 2) swept over `base_steps` cell layers (open: base_steps + 1
/// layers of vertices; cyclic: base_steps, the last cell layer closing onto layer 0). Vertex
/// t * nv + p sits on layer t over surface vertex p. Throws Error for a surface that is not dim 2,
/// base_steps < 1 (cyclic: < 3).
Complex sweep_lattice(const Complex& surface, int base_steps, bool cyclic);

struct SpaceTime {
  Complex surface;  // the base mesh, level 0 of every layer
  int base_steps = 0;
  bool cyclic = false;
  Hierarchy lattice;  // the swept lattice's levels 0..J and coefficients (3 channels)
  Hierarchy surface_levels;  // the surface's levels 0..J with the same scheme (coefficients unused)
  std::vector<std::vector<std::uint32_t>> layer_vertices;  // per level, layers(j) * nv_s(j)

  int levels() const { return lattice.finest_level(); }
  /// Layers of level j: base_steps 2^j (+ 1 when open).
  int layers(int level) const;
  std::uint32_t surface_vertices(int level) const { return surface_levels.num_vertices(level); }
};

/// Finest layer count for base_steps and levels (K 2^J + 1, or K 2^J cyclic).
int space_time_frames(int base_steps, int levels, bool cyclic);
/// The base_steps whose finest level has exactly `frames` layers, if any.
std::optional<int> space_time_base_steps(int frames, int levels, bool cyclic);

/// Sweeps `surface` and builds `levels` levels of `scheme` (linear or cubic: the schemes that
/// refine lattices) with zero coefficients, plus the surface levels and vertex maps. Throws
/// Error for another scheme and as sweep_lattice and make_hierarchy do.
SpaceTime make_space_time(const Complex& surface, int base_steps, bool cyclic, int levels, Scheme scheme);

/// The level-`level` control points of frame values `base_values` (3 per surface vertex): the
/// surface's own subdivision with zero wavelets, in the surface level's vertex order.
std::vector<double> subdivide_frame(const SpaceTime& st, std::span<const double> base_values, int level);

/// The finest level that represents `frames` (layers(J) frames of 3 * nv_s(0) values, frame-major):
/// layer t is layer t of the synthesis of the *static* lattice whose every base layer is frame t.
/// So a static animation fills the lattice with its own subdivision and analyses to zero
/// wavelets, and each layer is the frame's shape as the lattice refines it. (The volume rule is
/// a product of the surface and time rules only on quads at regular vertices; elsewhere a layer
/// differs slightly from the frame's own surface subdivision: FitReport::max_surface_gap.)
/// Throws Error when the frame count or sizes do not match.
std::vector<double> fill_layers(const SpaceTime& st, std::span<const double> frames);

struct FitReport {
  double max_error = 0;        // largest |synthesis - fill_layers| after analysis, any value
  double max_surface_gap = 0;  // largest distance of a finest layer's point from subdivide_frame's
};

/// Fills the finest level from the frames (fill_layers) and analyses: st.lattice.coeffs then
/// holds level 0 and every wavelet.
FitReport fit_frames(SpaceTime& st, std::span<const double> frames);

/// The positions of layer `layer` of a level's values (3 per lattice vertex of that level),
/// in the surface level's vertex order.
std::vector<double> layer_positions(const SpaceTime& st, std::span<const double> level_values, int level, int layer);

/// The surface at finest frame `frame` (fractional: between two layers, the linear blend of both;
/// cyclic: taken modulo the frame count, the last layer blending into the first), from the
/// finest level's values (3 per lattice vertex), in the surface's finest vertex order.
std::vector<double> frame_positions(const SpaceTime& st, std::span<const double> finest_values, double frame);

/// The layer of level `level` nearest to finest frame `frame` (cyclic: modulo its layers).
int nearest_layer(const SpaceTime& st, int level, double frame);

/// Whether the wavelet on lattice vertex v of level j+1 (v >= nv_j) lies on an odd layer of level
/// j+1: a time wavelet (new in time); the rest are space wavelets on the layers of level j.
/// One flag per wavelet, index v - nv_0, as rank_wavelets' candidates take them.
std::vector<std::uint8_t> time_wavelet_flags(const SpaceTime& st);

}  // namespace sublift
