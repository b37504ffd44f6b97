#pragma once
// The experiments of Wang & Ma (paper 001 sec. 5, Tables 2-4, 6-7) and Bertram (paper 000
// sec. 5.1, Table 1), for any scheme make_hierarchy accepts (docs/experiments.md).
//
// Conventions shared by all three:
// - levels are the hierarchy's: J is the finest, 0 the base; "level L" of a model is its
//   analysis down to L with every wavelet of levels >= L dropped, synthesised back to J
//   without detail (001 sec. 5: "subdivide the resulting mesh ... again to level 10 without
//   considering wavelet coefficients of finer levels");
// - errors compare finest-level vertices with a reference model's finest vertices: rms is
//   sqrt(mean over vertices of |p - q|^2), max the largest |p - q| (000 Table 1); both are
//   divided by the bounding-box diagonal of the reference (001: "relative errors, i.e. the
//   ratios of absolute errors to the diameters of the respective original models");
// - the functions overwrite h's coefficients; its topology (levels, tables) is what they use,
//   so a new scheme only needs make_hierarchy to build it.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/base/bounds.h"
#include "core/complex/complex.h"
#include "core/multires/hierarchy.h"

namespace sublift {

/// Error of a finest-level model against the reference, relative to the reference's diagonal.
struct ShapeError {
  double rms = 0;
  double max = 0;
};

/// One row of the noise or fit experiment.
struct LevelError {
  int level = 0;
  double rms = 0, max = 0;
  double ratio = 0;      // rms(L) / rms(J); NaN when rms(J) is 0 (noise: 001's R; fit: NaN)
  double max_ratio = 0;  // max(L) / max(J), 000 Table 1's normalisation; NaN likewise
};

struct LevelExperiment {
  double diagonal = 0;                 // bounding-box diagonal of the reference model
  std::uint32_t finest_vertices = 0;
  std::vector<LevelError> levels;      // L = J down to 0
};

/// One row of the compression experiment.
struct KeepError {
  double fraction = 0;       // requested fraction of wavelet coefficients
  std::size_t kept = 0;      // wavelet coefficients kept
  double rms = 0, max = 0;
};

struct CompressExperiment {
  double diagonal = 0;
  std::uint32_t finest_vertices = 0;
  std::size_t wavelets = 0;  // wavelet coefficient vectors in all (vertices of levels 1..J not in level 0)
  std::vector<KeepError> rows;  // in the order of the requested fractions
};

/// How compress ranks wavelet coefficients (rank_wavelets, core/analysis/compress.h): L2-normalised
/// (keep_largest's: |w| ||psi||_2, wavelet_l2_norms) or by the raw Euclidean norm of the
/// coefficient vector.
enum class Ranking : std::uint8_t { L2, Raw };

/// rms and max of |a_i - ref_i| over xyz triples, divided by `diagonal`. Sizes must match.
ShapeError shape_error(std::span<const double> a, std::span<const double> ref, double diagonal);

/// 3 * vertices independent N(0, stddev^2) values: Box-Muller on splitmix64 (the stream
/// x_k = seed + (k+1) * 0x9E3779B97F4A7C15, mixed), draws 4i..4i+3 for vertex i, so the values
/// do not depend on the standard library or the thread count.
std::vector<double> gaussian_noise(std::uint32_t vertices, double stddev, std::uint64_t seed);

/// 001 Table 2 / 000 Table 1: the base subdivided J times (the clean model), N(0, (sigma d)^2)
/// added to every coordinate of every finest vertex (d the clean model's diagonal), then
/// low-passed to each level and compared with the clean model. Level J is the noisy input.
LevelExperiment noise_experiment(Hierarchy& h, std::span<const double> base_xyz, double sigma, std::uint64_t seed);
LevelExperiment noise_experiment(const Complex& base, std::span<const double> base_xyz, Scheme scheme, int levels,
                                 double sigma, std::uint64_t seed);

/// 001 Tables 3-4: each level of the analysed finest model (finest_xyz, num_vertices(J) triples)
/// low-passed and compared with it; level J is the model itself (error 0).
LevelExperiment fit_experiment(Hierarchy& h, std::span<const double> finest_xyz);
LevelExperiment fit_experiment(const Complex& base, Scheme scheme, int levels, std::span<const double> finest_xyz);

/// 001 Tables 6-7: the finest model analysed, the largest `fractions` (each 0..1) of wavelet
/// coefficients kept with the level-0 scaling coefficients, synthesised to J and compared with it.
CompressExperiment compress_experiment(Hierarchy& h, std::span<const double> finest_xyz,
                                       std::span<const double> fractions, Ranking ranking = Ranking::L2);
CompressExperiment compress_experiment(const Complex& base, Scheme scheme, int levels,
                                       std::span<const double> finest_xyz, std::span<const double> fractions,
                                       Ranking ranking = Ranking::L2);

/// A smooth test model for fit and compress: xyz + a d (sin(2 pi k y'/d), sin(2 pi k z'/d),
/// sin(2 pi k x'/d)), with x' = x - min x etc. and d the bounding-box diagonal of xyz.
std::vector<double> smooth_perturbation(std::span<const double> xyz, double amplitude, double waves);

}  // namespace sublift
