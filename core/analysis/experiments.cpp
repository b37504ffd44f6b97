#include "core/analysis/experiments.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "core/analysis/compress.h"
#include "core/base/bounds.h"
#include "core/base/errors.h"
#include "core/base/parallel.h"

namespace sublift {

namespace {

constexpr std::uint64_t kGamma = 0x9E3779B97F4A7C15ull;  // splitmix64's increment
constexpr std::uint32_t kBlock = 4096;                    // vertices per partial sum

// splitmix64's output function (Steele, Lea, Flood 2014), applied to the k-th state.
std::uint64_t splitmix64(std::uint64_t seed, std::uint64_t k) {
  std::uint64_t z = seed + (k + 1) * kGamma;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

// Two standard normals from two 64-bit draws (Box-Muller); u1 in (0, 1] keeps the log finite.
void box_muller(std::uint64_t a, std::uint64_t b, double& z0, double& z1) {
  const double u1 = double((a >> 11) + 1) * 0x1.0p-53;
  const double u2 = double(b >> 11) * 0x1.0p-53;
  const double r = std::sqrt(-2.0 * std::log(u1));
  z0 = r * std::cos(2.0 * std::numbers::pi * u2);
  z1 = r * std::sin(2.0 * std::numbers::pi * u2);
}

void check_xyz(const Hierarchy& h, std::span<const double> xyz, const char* what) {
  if (h.channels != 3) throw Error("experiments need 3 channels (x, y, z), got " + std::to_string(h.channels));
  const std::size_t want = std::size_t(h.num_vertices(h.finest_level())) * 3;
  if (xyz.size() != want)
    throw Error(std::string(what) + " has " + std::to_string(xyz.size() / 3) + " vertices, the level-" +
                std::to_string(h.finest_level()) + " complex " + std::to_string(want / 3));
}

double ratio(double a, double b) { return b > 0 ? a / b : std::numeric_limits<double>::quiet_NaN(); }

// Finest-level model of `level`: the coefficients of the levels below it synthesised to J with
// every finer wavelet zero (restored afterwards, so h is as it was).
std::vector<double> low_pass_in_place(Hierarchy& h, int level) {
  if (level < 0 || level > h.finest_level()) throw Error("low_pass: level " + std::to_string(level) + " out of range");
  const auto first = std::ptrdiff_t(std::size_t(h.num_vertices(level)) * h.channels);
  const std::vector<double> finer(h.coeffs.begin() + first, h.coeffs.end());
  std::fill(h.coeffs.begin() + first, h.coeffs.end(), 0.0);
  std::vector<double> out = synthesize(h, h.finest_level());
  std::copy(finer.begin(), finer.end(), h.coeffs.begin() + first);
  return out;
}

// Rows L = J..0 of `model` (the input at level J, its low-passed levels below) against `ref`.
LevelExperiment level_errors(Hierarchy& h, std::span<const double> model, std::span<const double> ref) {
  LevelExperiment out;
  out.diagonal = bbox_diagonal(ref);
  out.finest_vertices = h.num_vertices(h.finest_level());
  const int J = h.finest_level();
  for (int L = J; L >= 0; --L) {
    const ShapeError e = L == J ? shape_error(model, ref, out.diagonal) : shape_error(low_pass_in_place(h, L), ref, out.diagonal);
    out.levels.push_back({L, e.rms, e.max, 0, 0});
  }
  for (LevelError& r : out.levels) {
    r.ratio = ratio(r.rms, out.levels.front().rms);
    r.max_ratio = ratio(r.max, out.levels.front().max);
  }
  return out;
}

}  // namespace

ShapeError shape_error(std::span<const double> a, std::span<const double> ref, double diagonal) {
  if (a.size() != ref.size() || a.size() % 3 != 0) throw Error("shape_error: position arrays differ in size");
  if (!(diagonal > 0)) throw Error("shape_error: the reference model has no extent (diagonal 0)");
  const auto n = static_cast<std::uint32_t>(a.size() / 3);
  // Fixed blocks, summed in order afterwards: the result does not depend on the thread count.
  const std::uint32_t blocks = (n + kBlock - 1) / kBlock;
  std::vector<double> sum(blocks), mx(blocks);
  parallel_for(blocks, 1, [&](std::uint32_t b0, std::uint32_t b1) {
    for (std::uint32_t b = b0; b < b1; ++b) {
      double s = 0, m = 0;
      for (std::uint32_t i = b * kBlock; i < std::min(n, (b + 1) * kBlock); ++i) {
        const double dx = a[3 * std::size_t(i)] - ref[3 * std::size_t(i)];
        const double dy = a[3 * std::size_t(i) + 1] - ref[3 * std::size_t(i) + 1];
        const double dz = a[3 * std::size_t(i) + 2] - ref[3 * std::size_t(i) + 2];
        const double d2 = dx * dx + dy * dy + dz * dz;
        s += d2;
        m = std::max(m, d2);
      }
      sum[b] = s;
      mx[b] = m;
    }
  });
  double s = 0, m = 0;
  for (std::uint32_t b = 0; b < blocks; ++b) {
    s += sum[b];
    m = std::max(m, mx[b]);
  }
  if (n == 0) return {};
  return {std::sqrt(s / n) / diagonal, std::sqrt(m) / diagonal};
}

std::vector<double> gaussian_noise(std::uint32_t vertices, double stddev, std::uint64_t seed) {
  std::vector<double> out(std::size_t(vertices) * 3);
  parallel_for(vertices, 4096, [&](std::uint32_t i0, std::uint32_t i1) {
    for (std::uint32_t i = i0; i < i1; ++i) {
      const std::uint64_t k = 4 * std::uint64_t(i);
      double z[4];
      box_muller(splitmix64(seed, k), splitmix64(seed, k + 1), z[0], z[1]);
      box_muller(splitmix64(seed, k + 2), splitmix64(seed, k + 3), z[2], z[3]);
      for (int c = 0; c < 3; ++c) out[3 * std::size_t(i) + c] = stddev * z[c];
    }
  });
  return out;
}

LevelExperiment noise_experiment(Hierarchy& h, std::span<const double> base_xyz, double sigma, std::uint64_t seed) {
  if (!(sigma >= 0) || !std::isfinite(sigma)) throw Error("noise sigma must be a finite number >= 0");
  if (h.channels != 3) throw Error("experiments need 3 channels (x, y, z), got " + std::to_string(h.channels));
  set_base(h, base_xyz);
  const std::vector<double> clean = synthesize(h, h.finest_level());
  const double d = bbox_diagonal(clean);
  std::vector<double> noisy = gaussian_noise(h.num_vertices(h.finest_level()), sigma * d, seed);
  for (std::size_t i = 0; i < noisy.size(); ++i) noisy[i] += clean[i];
  analyze(h, noisy);
  return level_errors(h, noisy, clean);
}

LevelExperiment noise_experiment(const Complex& base, std::span<const double> base_xyz, Scheme scheme, int levels,
                                 double sigma, std::uint64_t seed) {
  Hierarchy h = make_hierarchy(base, levels, scheme, 3);
  return noise_experiment(h, base_xyz, sigma, seed);
}

LevelExperiment fit_experiment(Hierarchy& h, std::span<const double> finest_xyz) {
  check_xyz(h, finest_xyz, "the finest model");
  analyze(h, finest_xyz);
  return level_errors(h, finest_xyz, finest_xyz);
}

LevelExperiment fit_experiment(const Complex& base, Scheme scheme, int levels, std::span<const double> finest_xyz) {
  Hierarchy h = make_hierarchy(base, levels, scheme, 3);
  return fit_experiment(h, finest_xyz);
}

CompressExperiment compress_experiment(Hierarchy& h, std::span<const double> finest_xyz,
                                       std::span<const double> fractions, Ranking ranking) {
  check_xyz(h, finest_xyz, "the finest model");
  for (const double f : fractions)
    if (!(f >= 0.0 && f <= 1.0)) throw Error("keep fractions must be in [0, 1], got " + std::to_string(f));
  analyze(h, finest_xyz);
  const std::vector<double> analysed = h.coeffs;
  CompressExperiment out;
  out.diagonal = bbox_diagonal(finest_xyz);
  out.finest_vertices = h.num_vertices(h.finest_level());
  out.wavelets = out.finest_vertices - h.num_vertices(0);
  // Ranked once (core/analysis/compress.h): the kept wavelets are keep_largest's (l2) or the largest raw
  // magnitudes (raw) for every fraction.
  const std::vector<RankedWavelet> order = rank_wavelets(h, ranking == Ranking::L2 ? wavelet_l2_norms(h) : std::vector<double>{});
  for (const double f : fractions) {
    h.coeffs = analysed;
    const std::size_t kept = keep_ranked(h, order, f);
    const ShapeError e = shape_error(synthesize(h, h.finest_level()), finest_xyz, out.diagonal);
    out.rows.push_back({f, kept, e.rms, e.max});
  }
  h.coeffs = analysed;
  return out;
}

CompressExperiment compress_experiment(const Complex& base, Scheme scheme, int levels,
                                       std::span<const double> finest_xyz, std::span<const double> fractions,
                                       Ranking ranking) {
  Hierarchy h = make_hierarchy(base, levels, scheme, 3);
  return compress_experiment(h, finest_xyz, fractions, ranking);
}

std::vector<double> smooth_perturbation(std::span<const double> xyz, double amplitude, double waves) {
  std::vector<double> out(xyz.begin(), xyz.end());
  const double d = bbox_diagonal(xyz);
  if (!(d > 0)) return out;
  const std::array<double, 3> lo = bounding_box(xyz.data(), xyz.size() / 3)[0];
  const double k = 2.0 * std::numbers::pi * waves / d;
  for (std::size_t i = 0; i + 2 < xyz.size(); i += 3)
    for (int c = 0; c < 3; ++c) out[i + c] += amplitude * d * std::sin(k * (xyz[i + (c + 1) % 3] - lo[(c + 1) % 3]));
  return out;
}

}  // namespace sublift
