#pragma once
// Wavelet compression and level of detail for every scheme (paper 004 sec. 7.2;
// docs/compression.md).
//
// Rationale. A hierarchy's finest shape is its level-0 scaling coefficients plus every wavelet.
// Dropping the wavelets that contribute least gives an approximation of the same finest level
// (a level of detail) that holds fewer non-zero numbers (compression). The wavelet of fine vertex
// v contributes about |w_v| ||psi_v||_2 to the L2 error when it is dropped, so a Compressor ranks
// the wavelets once by that normalised magnitude — |w_v| the Euclidean norm of the coefficient
// vector times its level's gain, ||psi_v||_2 from wavelet_l2_norms() — and any count can then be
// applied with one synthesis. Keeping the first k of the ranking is progressive: keeping more
// always keeps a superset.
//
// Layout and invariants.
// - Candidates are the wavelets that may be removed: all of them, or those whose vertex lies in
//   a Region (its position on the fully synthesised level where it lives: level j+1 for a
//   level-j wavelet). Every other wavelet and every scaling coefficient is always kept, bit for
//   bit.
// - order() lists the candidates' fine-vertex indices v (nv_0 <= v < nv_J), largest magnitude
//   first, ties to the lower index: rank_wavelets(), the one ranking of every compress path
//   (keep_largest's, the experiments'), so with no region `keep F` keeps exactly the wavelets
//   keep_largest(h, F) keeps (llround(F x candidates) of them, keep_ranked's rounding).
// - Shapes are synthesised with per-level gains (the session's detail gains; default 1). Errors
//   compare the finest control points' x, y, z (the first three channels, missing ones 0) with
//   the uncompressed finest shape and are divided by its bounding-box diagonal.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/base/surface_mesh.h"
#include "core/multires/hierarchy.h"

namespace sublift {

/// A group of channels compressed together (positions x, y, z; a colour's r, g, b, a; one
/// scalar): channels [first, first + count). count 0: every channel, ranked together, with errors
/// on x, y, z (the default, what a 3-channel hierarchy means).
struct ChannelRange {
  int first = 0, count = 0;
};

/// A named channel group of a hierarchy with attribute channels: "position" (x, y, z), "colour"
/// (red, green, blue, alpha together), every other attribute on its own (its name).
struct ChannelGroup {
  std::string name;
  std::vector<std::string> channels;
  ChannelRange range;
};

/// The groups of a hierarchy of `channels` channels whose channels 3.. are `attributes` (none for
/// x, y, z alone or when the names do not match the channels). `first_attribute` is the channel
/// number of attributes[0]: 3 in a project, 0 in a hierarchy of attribute channels alone (then
/// no position group is listed).
std::vector<ChannelGroup> channel_groups(int channels, std::span<const VertexAttribute> attributes, int first_attribute = 3);

/// L2 norm of each wavelet, index v - nv_0 for the wavelet on fine vertex v: h.wavelet_norms when
/// the scheme knows them exactly, else the area scaling 2^(-j dim / 2) of a level-j wavelet
/// (sqrt2: 2^(-j / 2), each level halves the area). The one source of the norms the rankings
/// use (rank_wavelets). Throws Error when h.wavelet_norms is non-empty but does not hold one
/// value per wavelet.
std::vector<double> wavelet_l2_norms(const Hierarchy& h);

/// One place of a wavelet ranking: the wavelet on fine vertex `index` and its magnitude.
struct RankedWavelet {
  double magnitude = 0.0;
  std::uint32_t index = 0;
};

/// The wavelet ranking, the one every compress path uses (Compressor, keep_largest, the
/// experiments' l2 and raw rankings): each wavelet v of level j with magnitude
/// |w_v| x |gains[j]| x norms[v - nv_0] — |w_v| the Euclidean norm of its coefficient vector in
/// h.coeffs, gains per level 0..J-1 (empty: 1), norms one per wavelet (wavelet_l2_norms(h) for
/// the normalised ranking; empty: the raw magnitude, no norm factor) — sorted largest first,
/// ties to the lower index. `candidates`, when not empty, holds one flag per wavelet (index
/// v - nv_0): only the flagged ones are ranked. `channels`: |w_v| over that group only. Throws
/// Error on sizes, gains or a range outside the channels.
std::vector<RankedWavelet> rank_wavelets(const Hierarchy& h, std::span<const double> norms,
                                         std::span<const double> gains = {},
                                         std::span<const std::uint8_t> candidates = {}, ChannelRange channels = {});

/// Keeps the first llround(fraction x ranking.size()) wavelets of `ranking` and zeroes the rest
/// in h.coeffs (every channel); returns how many were kept. keep_largest(h, F) is
/// keep_ranked(h, rank_wavelets(h, wavelet_l2_norms(h)), F). Throws Error outside [0, 1].
std::size_t keep_ranked(Hierarchy& h, std::span<const RankedWavelet> ranking, double fraction);
/// Zeroes all but the largest `fraction` (0..1) of the wavelet coefficients by the one ranking
/// (|w| x ||psi||, exact norms or wavelet_scale). Returns how many were kept.
std::size_t keep_largest(Hierarchy& h, double fraction);

/// The control net of `level` synthesised from `coeffs` (h's layout and size) with the wavelets
/// of each level l multiplied by gains[l] (empty: all 1), on h's topology; what synthesize(h,
/// level) gives when coeffs = h.coeffs and the gains are 1, bit for bit. Throws Error on sizes.
std::vector<double> synthesize_coefficients(const Hierarchy& h, std::span<const double> coeffs,
                                            std::span<const double> gains, int level);

/// A region of space restricting which wavelets may be removed.
struct Region {
  enum class Kind : std::uint8_t { Box, Sphere };
  Kind kind = Kind::Box;
  std::array<double, 3> lo{}, hi{};  // Box: corners, lo <= hi on every axis
  std::array<double, 3> centre{};    // Sphere
  double radius = 0.0;
  /// Whether point p (x, y, z) lies inside or on the boundary.
  bool contains(const double* p) const;
};

/// Parses `box:x0,y0,z0,x1,y1,z1` (two opposite corners, any order) or `sphere:cx,cy,cz,r`
/// (r >= 0). Throws Error naming what is wrong.
Region parse_region(std::string_view spec);

/// How the number of kept candidates is chosen.
enum class CompressMode : std::uint8_t {
  Keep,       // a fraction F in [0, 1] of the candidates, largest first
  Threshold,  // candidates with normalised magnitude >= T x diagonal
  Linf,       // as few as found with the maximum finest-vertex error <= E x diagonal
};
/// "keep" / "threshold" / "linf".
std::string compress_mode_name(CompressMode m);

struct CompressOptions {
  bool normalise = true;          // false: rank by the raw magnitude (x gain), for experiments
  std::optional<Region> region;   // only wavelets inside are candidates for removal
  std::vector<double> gains;      // per level 0..J-1, as the session applies them (empty: all 1)
  // A channel group (count > 0): ranked by its own magnitude, only its channels zeroed, its
  // errors over its channels relative to the diagonal of their bounding box (for a colour, of
  // the colours' range). Groups are disjoint, so compressing each on its own and merging the
  // channels is the same as compressing them one after the other.
  ChannelRange channels;
};

/// One compressed shape.
struct Compression {
  std::size_t keep = 0;        // candidates kept: the first `keep` of the ranking
  std::size_t kept = 0;        // wavelets kept, the ones that are not candidates included
  std::size_t total = 0;       // wavelets
  double l2_error = 0.0;       // RMS over finest vertices of |p - p_full|, / diagonal (p: x, y, z or the group)
  double linf_error = 0.0;     // max over finest vertices of |p - p_full|, / diagonal
  std::vector<double> coeffs;  // h.coeffs with the removed wavelets zero (stored values, no gains)
  std::vector<double> finest;  // its finest control net (channels per vertex, gains applied)
};

/// Ranks the wavelets of a hierarchy once and applies any count, threshold or tolerance.
class Compressor {
 public:
  /// Ranks h's wavelets (one synthesis, one sort). h's topology must outlive the Compressor;
  /// its coefficients are copied. Throws Error on bad gains or wavelet norms, or when the finest
  /// shape has no extent.
  explicit Compressor(const Hierarchy& h, CompressOptions options = {});

  std::size_t total() const { return total_; }
  std::size_t candidates() const { return order_.size(); }
  /// Candidate fine-vertex indices, largest normalised magnitude first (ties: lower index).
  std::span<const std::uint32_t> order() const { return order_; }
  /// Their normalised magnitudes, in the same order (non-increasing).
  std::span<const double> magnitudes() const { return magnitude_; }
  /// Bounding-box diagonal of the uncompressed finest shape (the unit of errors and thresholds;
  /// of the group's channels when options.channels names one).
  double diagonal() const { return diagonal_; }
  /// The uncompressed finest control net (channels per vertex, gains applied).
  std::span<const double> reference() const { return reference_; }
  const CompressOptions& options() const { return options_; }

  /// Candidates kept for a fraction in [0, 1]: llround(fraction x candidates()), the rounding
  /// of keep_ranked, keep_largest and `synthesize --keep`. Throws Error outside [0, 1].
  std::size_t count_for_fraction(double fraction) const;
  /// Candidates whose magnitude is >= threshold x diagonal(). Throws Error unless threshold >= 0.
  std::size_t count_for_threshold(double threshold) const;
  /// The fewest candidates found that keep the maximum finest-vertex error <= tolerance x
  /// diagonal(): bisection over the ranking with one synthesis per probe. The answer k keeps the
  /// bound and k - 1 breaks it (or k is 0): the largest prefix removal found, not a global
  /// optimum (the error is not monotone in k in general). Throws Error unless tolerance >= 0.
  std::size_t count_for_linf(double tolerance) const;
  /// Dispatches to the three above.
  std::size_t count(CompressMode mode, double value) const;

  /// Stored coefficients with every candidate after the first `keep` zeroed.
  std::vector<double> coefficients(std::size_t keep) const;
  /// The compressed shape keeping the first `keep` candidates (clamped to candidates()).
  Compression evaluate(std::size_t keep) const;
  Compression run(CompressMode mode, double value) const { return evaluate(count(mode, value)); }

 private:
  double linf_of(std::size_t keep) const;

  const Hierarchy* h_;
  CompressOptions options_;
  std::vector<double> coeffs_;
  std::vector<std::uint32_t> order_;
  std::vector<double> magnitude_;
  std::vector<double> reference_, reference_xyz_;
  std::size_t total_ = 0;
  double diagonal_ = 0.0;
};

}  // namespace sublift
