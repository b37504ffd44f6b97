#pragma once
// Hierarchy: levels 0..J of a complex and its wavelet coefficients (DESIGN.md).
//
// Coefficients live in one array in place-lifted layout, `channels` doubles per vertex:
// [ scaling coefficients of level 0 (nv_0) | wavelets of level 0 (nv_1 - nv_0) | wavelets of
// level 1 (nv_2 - nv_1) | ... ], because level j+1 numbers its vertices [v | e | f | c] with the
// v-class equal to level j's vertices. Wavelet coefficients of level j sit on the e/f/c vertices
// of level j+1. Synthesis to level L runs the program on the prefix of nv_L vertices.
// The sqrt(2) scheme (paper 001) keeps this layout: level j+1 numbers its vertices [v | curve
// points | face points] (refine_sqrt2.h), so its wavelets too sit on the new vertices.
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "core/complex/child_sites.h"
#include "core/complex/complex.h"
#include "core/engine/transition.h"
#include "core/schemes/registry.h"

namespace sublift {

struct Hierarchy {
  Scheme scheme = Scheme::Cubic;
  bool integer = false;
  int channels = 3;
  std::vector<Complex> levels;      // 0..J; the last one without adjacency
  std::vector<Transition> transitions;  // transitions[j]: j -> j+1, run by core/engine/executor.h
  std::vector<ChildSites> sites;  // sites[j]: new vertices of level j+1; empty where the
                                  // refinement implies them ([v | e | f | c])
  int disc = 2;  // triangle schemes: the rings k of the k-disc wavelets (004 sec. 6.3)
  int first_level = 0;  // the sqrt(2) level index of levels[0] (odd levels keep their curves)
  std::vector<double> coeffs;       // num_vertices(J) * channels, layout above
  // L2 norm of each wavelet (index v - nv_0 for the wavelet on fine vertex v), where the scheme
  // knows it exactly (SchemeInfo::exact_norms); empty otherwise, and then the area scaling
  // wavelet_scale stands in.
  std::vector<double> wavelet_norms;
  // The finest level's LevelBuild::carry, handed to append_level's next build (empty: none).
  std::vector<std::int32_t> carry;

  int finest_level() const { return static_cast<int>(levels.size()) - 1; }
  std::uint32_t num_vertices(int level) const { return levels[static_cast<std::size_t>(level)].num_vertices; }
  std::size_t bytes() const;
};

/// Builds levels 0..J of `base` (topology and lifting tables) with all coefficients zero.
/// Sqrt2 needs a surface; `first_level` says which sqrt(2) level `base` is (a level-j complex
/// taken out of a hierarchy refines as level j does: curves are refined after odd levels).
/// `disc`: the k of the triangle schemes' k-disc wavelets (1, 2 or 3).
/// `progress` (may be empty) is told the fraction of the work done (by the levels' vertex
/// counts) before each level; when it answers false, make_hierarchy throws Cancelled.
using LevelProgress = std::function<bool(double fraction)>;
Hierarchy make_hierarchy(Complex base, int levels, Scheme scheme, int channels, bool integer = false,
                         int first_level = 0, int disc = 2, const LevelProgress& progress = {});

/// Appends level J+1 and transition J -> J+1 (the new level with its derived rows when
/// `adjacency`; the old finest level gets them if it lacks them). Coefficients are not touched.
void append_level(Hierarchy& h, bool adjacency = true);
/// Drops the finest level and its transition (coefficients not touched).
void pop_level(Hierarchy& h);

/// Synthesis of transition j -> j+1 in place on x (level j+1 layout, `channels` per vertex).
/// `wavelets_zero`: the caller knows the level's wavelets are zero, so steps that only read
/// them are skipped (they would add exact zeros; executor.h).
void synthesize_transition(const Hierarchy& h, int j, double* x, int channels, bool integer, bool wavelets_zero = false);
/// Analysis of transition j -> j+1 in place: the exact inverse of synthesize_transition.
void analyze_transition(const Hierarchy& h, int j, double* x, int channels, bool integer);

/// Vertex counts of levels 0..levels that make_hierarchy(c, levels, scheme, ..., first_level)
/// builds (doubles: large requests do not wrap); exact from an even sqrt(2) level, an upper
/// estimate from an odd one.
std::vector<double> predicted_level_counts(const Complex& c, int levels, Scheme scheme, int first_level = 0);

/// Peak bytes of make_hierarchy(c, levels, scheme, ..., first_level) plus one synthesis of its
/// finest level: the predicted finest vertex count times the scheme's measured cost per vertex
/// (SchemeInfo::peak_bytes). make_hierarchy and append_level refuse up front, with this number,
/// what would pass memory_budget() (core/base/memory_budget.h).
double predicted_hierarchy_bytes(const Complex& c, int levels, Scheme scheme, int first_level = 0);

/// Sets the level-0 scaling coefficients (num_vertices(0) * channels values) and zeroes all
/// wavelets: the hierarchy then describes the pure subdivision of the base.
void set_base(Hierarchy& h, std::span<const double> base_values);

/// Analyses a finest-level shape (num_vertices(J) * channels values, in refine.h's order)
/// into the coefficients.
void analyze(Hierarchy& h, std::span<const double> finest_values);

/// The control net of level L (num_vertices(L) * channels values): synthesis from the
/// coefficients of levels < L.
std::vector<double> synthesize(const Hierarchy& h, int level);

/// synthesize(h, level), refusing (Error naming the level, vertex and channel) as soon as a
/// level's values are not finite or exceed kMaxCoordinate (core/base/magnitude.h): results no
/// reader would read back.
std::vector<double> synthesize_in_range(const Hierarchy& h, int level);

/// Multiplies the wavelets of each level l < J by gains[l] (a session's detail gains, as a
/// project saves them; empty: nothing to do), so that synthesize(h, L) is the shape the modeler
/// shows. Throws Error when there are not J gains, a gain is not finite, or h is in integer mode
/// and a gain is not 1.
void apply_gains(Hierarchy& h, std::span<const double> gains);

/// Per-level wavelet statistics; magnitudes are Euclidean norms of the coefficient vectors.
struct LevelStats {
  int level = 0;               // wavelets of this level live on level+1's e/f/c vertices
  std::uint32_t vertices = 0;  // vertices of level `level`
  std::uint32_t wavelets = 0;
  double wavelet_max = 0, wavelet_rms = 0;
};
std::vector<LevelStats> level_stats(const Hierarchy& h);

}  // namespace sublift
