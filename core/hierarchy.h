#pragma once
// Hierarchy: levels 0..J of a complex and its wavelet coefficients (DESIGN.md).
//
// Coefficients live in one array in place-lifted layout, `channels` doubles per vertex:
// [ scaling coefficients of level 0 (nv_0) | wavelets of level 0 (nv_1 - nv_0) | wavelets of
// level 1 (nv_2 - nv_1) | ... ], because level j+1 numbers its vertices [v | e | f | c] with the
// v-class equal to level j's vertices. Wavelet coefficients of level j sit on the e/f/c vertices
// of level j+1. Synthesis to level L runs the program on the prefix of nv_L vertices.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/complex.h"
#include "core/lifting.h"

namespace sublift {

enum class Scheme : std::uint8_t { Linear, Cubic };

/// "linear" / "cubic"; parse throws InputError-free std::invalid_argument on other names.
std::string scheme_name(Scheme s);
Scheme parse_scheme(const std::string& name);
LiftProgram scheme_program(Scheme s);

struct Hierarchy {
  Scheme scheme = Scheme::Cubic;
  bool integer = false;
  int channels = 3;
  std::vector<Complex> levels;      // 0..J; the last one without adjacency
  std::vector<LiftTables> tables;   // tables[j]: transition j -> j+1
  std::vector<double> coeffs;       // num_vertices(J) * channels, layout above

  int finest_level() const { return static_cast<int>(levels.size()) - 1; }
  std::uint32_t num_vertices(int level) const { return levels[static_cast<std::size_t>(level)].num_vertices; }
  std::size_t bytes() const;
};

/// Builds levels 0..J of `base` (topology and lifting tables) with all coefficients zero.
Hierarchy make_hierarchy(Complex base, int levels, Scheme scheme, int channels, bool integer = false);

/// Sets the level-0 scaling coefficients (num_vertices(0) * channels values) and zeroes all
/// wavelets: the hierarchy then describes the pure subdivision of the base.
void set_base(Hierarchy& h, std::span<const double> base_values);

/// Analyses a finest-level shape (num_vertices(J) * channels values, in refine.h's order)
/// into the coefficients.
void analyze(Hierarchy& h, std::span<const double> finest_values);

/// The control net of level L (num_vertices(L) * channels values): synthesis from the
/// coefficients of levels < L.
std::vector<double> synthesize(const Hierarchy& h, int level);

/// Per-level wavelet statistics; magnitudes are Euclidean norms of the coefficient vectors.
struct LevelStats {
  int level = 0;               // wavelets of this level live on level+1's e/f/c vertices
  std::uint32_t vertices = 0;  // vertices of level `level`
  std::uint32_t wavelets = 0;
  double wavelet_max = 0, wavelet_rms = 0;
};
std::vector<LevelStats> level_stats(const Hierarchy& h);

/// Zeroes all but the largest `fraction` (0..1) of wavelet coefficients, ranked by
/// L2-normalised magnitude |w| * 2^(-j * dim / 2) for level j. Returns how many were kept.
std::size_t keep_largest(Hierarchy& h, double fraction);

}  // namespace sublift
