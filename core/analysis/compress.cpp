#include "core/analysis/compress.h"

#include <algorithm>
#include <cmath>

#include "core/base/bounds.h"
#include "core/base/channels.h"
#include "core/base/errors.h"
#include "core/analysis/experiments.h"
#include "core/base/text_lines.h"

namespace sublift {

std::vector<ChannelGroup> channel_groups(int channels, std::span<const VertexAttribute> attributes, int first_attribute) {
  if (channels <= first_attribute || attributes.size() != std::size_t(channels - first_attribute)) return {};
  std::vector<ChannelGroup> out;
  if (first_attribute == 3) out.push_back({"position", {"x", "y", "z"}, {0, 3}});
  const auto colour = [](const std::string& n) { return n == "red" || n == "green" || n == "blue" || n == "alpha"; };
  for (std::size_t k = 0; k < attributes.size();) {
    std::size_t end = k + 1;
    if (colour(attributes[k].name))
      while (end < attributes.size() && colour(attributes[end].name)) ++end;
    ChannelGroup g{end > k + 1 ? "colour" : attributes[k].name, {}, {int(std::size_t(first_attribute) + k), int(end - k)}};
    for (std::size_t i = k; i < end; ++i) g.channels.push_back(attributes[i].name);
    out.push_back(std::move(g));
    k = end;
  }
  return out;
}
namespace {

void check_gains(const Hierarchy& h, std::span<const double> gains) {
  if (!gains.empty() && gains.size() != static_cast<std::size_t>(h.finest_level()))
    throw Error("compress: one gain per level 0.." + std::to_string(h.finest_level() - 1) + " is needed, got " +
                std::to_string(gains.size()));
  for (const double g : gains)
    if (!std::isfinite(g)) throw Error("compress: a detail gain is not finite");
}

// Level j's wavelets [nv_j, nv_{j+1}) of x times its gain, then transition j -> j+1 in place.
void synthesize_step(const Hierarchy& h, std::span<const double> gains, int j, std::vector<double>& x) {
  const auto b = x.begin() + std::ptrdiff_t(std::size_t(h.num_vertices(j)) * h.channels);
  const auto e = x.begin() + std::ptrdiff_t(std::size_t(h.num_vertices(j + 1)) * h.channels);
  if (!gains.empty()) {
    const double g = gains[static_cast<std::size_t>(j)];
    for (auto it = b; it != e; ++it) *it *= g;
  }
  const bool zero = std::all_of(b, e, [](double v) { return v == 0.0; });
  synthesize_transition(h, j, x.data(), h.channels, h.integer, zero);
}

// The channels [first, first + count) a range names (count 0: all of them).
std::pair<int, int> checked_range(const Hierarchy& h, ChannelRange r) {
  if (r.count == 0) return {0, h.channels};
  if (r.first < 0 || r.count < 0 || r.first + r.count > h.channels)
    throw Error("compress: channels " + std::to_string(r.first) + ".." + std::to_string(r.first + r.count - 1) + " of a hierarchy of " +
                std::to_string(h.channels));
  return {r.first, r.count};
}

// The values whose error is measured: x, y, z (no group) or the group's channels.
std::vector<double> measured_of(std::span<const double> x, int channels, ChannelRange r) {
  if (r.count == 0) return xyz_of(x, channels);
  const std::size_t n = x.size() / std::size_t(channels);
  std::vector<double> out(n * std::size_t(r.count));
  for (std::size_t v = 0; v < n; ++v)
    std::copy_n(&x[v * std::size_t(channels) + std::size_t(r.first)], r.count, &out[v * std::size_t(r.count)]);
  return out;
}

// RMS and max of |a_v - b_v| over vertices (width values each), / unit.
ShapeError group_error(std::span<const double> a, std::span<const double> b, int width, double unit) {
  if (width == 3) return shape_error(a, b, unit);
  ShapeError e;
  const std::size_t n = a.size() / std::size_t(width);
  double sum = 0;
  for (std::size_t v = 0; v < n; ++v) {
    double d = 0;
    for (int k = 0; k < width; ++k) d += (a[v * width + k] - b[v * width + k]) * (a[v * width + k] - b[v * width + k]);
    sum += d;
    e.max = std::max(e.max, std::sqrt(d) / unit);
  }
  e.rms = n ? std::sqrt(sum / double(n)) / unit : 0.0;
  return e;
}

// The diagonal of the bounding box of n points of `width` values.
double box_diagonal(std::span<const double> x, int width) {
  if (width == 3) return bbox_diagonal(x);
  double d = 0;
  for (int k = 0; k < width; ++k) {
    double lo = INFINITY, hi = -INFINITY;
    for (std::size_t i = std::size_t(k); i < x.size(); i += std::size_t(width)) lo = std::min(lo, x[i]), hi = std::max(hi, x[i]);
    if (hi >= lo) d += (hi - lo) * (hi - lo);
  }
  return std::sqrt(d);
}

// llround(fraction x n), at most n: the one rounding of a kept fraction.
std::size_t count_of_fraction(std::size_t n, double fraction) {
  if (!(fraction >= 0.0 && fraction <= 1.0)) throw Error("keep fraction must be in [0, 1], got " + std::to_string(fraction));
  return std::min(n, static_cast<std::size_t>(std::llround(fraction * double(n))));
}

std::vector<double> numbers_of(std::string_view text, std::string_view spec) {
  std::vector<double> out;
  std::size_t at = 0;
  while (at <= text.size()) {
    const std::size_t comma = std::min(text.find(',', at), text.size());
    const std::string_view token = text.substr(at, comma - at);
    const auto v = parse_double(token);
    if (!v) throw Error("region '" + std::string(spec) + "': '" + std::string(token) + "' is not a finite number");
    out.push_back(*v);
    at = comma + 1;
  }
  return out;
}

}  // namespace

std::vector<double> wavelet_l2_norms(const Hierarchy& h) {
  const std::size_t count = h.coeffs.size() / static_cast<std::size_t>(h.channels) - h.num_vertices(0);
  if (!h.wavelet_norms.empty()) {
    if (h.wavelet_norms.size() != count)
      throw Error("the hierarchy holds " + std::to_string(h.wavelet_norms.size()) + " wavelet norms for " +
                  std::to_string(count) + " wavelets");
    return h.wavelet_norms;
  }
  std::vector<double> out;
  out.reserve(count);
  const int dim = h.levels.front().dim;
  for (int j = 0; j < h.finest_level(); ++j) {
    const double scale = wavelet_scale(h.scheme, dim, j);
    out.insert(out.end(), h.num_vertices(j + 1) - h.num_vertices(j), scale);
  }
  return out;
}

std::vector<RankedWavelet> rank_wavelets(const Hierarchy& h, std::span<const double> norms,
                                         std::span<const double> gains, std::span<const std::uint8_t> candidates,
                                         ChannelRange channels) {
  check_gains(h, gains);
  const int J = h.finest_level(), ch = h.channels;
  const auto [first, count] = checked_range(h, channels);
  const std::uint32_t nv0 = h.num_vertices(0);
  const std::size_t total = h.num_vertices(J) - nv0;
  if (!norms.empty() && norms.size() != total)
    throw Error("ranking: " + std::to_string(norms.size()) + " wavelet norms for " + std::to_string(total) + " wavelets");
  if (!candidates.empty() && candidates.size() != total)
    throw Error("ranking: " + std::to_string(candidates.size()) + " candidate flags for " + std::to_string(total) +
                " wavelets");
  std::vector<RankedWavelet> all;
  all.reserve(total);
  for (int j = 0; j < J; ++j) {
    const double g = gains.empty() ? 1.0 : gains[static_cast<std::size_t>(j)];
    for (std::uint32_t v = h.num_vertices(j); v < h.num_vertices(j + 1); ++v) {
      if (!candidates.empty() && !candidates[v - nv0]) continue;
      const double m = channel_norm(&h.coeffs[std::size_t(v) * ch + std::size_t(first)], count) * std::abs(g);
      all.push_back({norms.empty() ? m : m * norms[v - nv0], v});
    }
  }
  std::sort(all.begin(), all.end(), [](const RankedWavelet& a, const RankedWavelet& b) {
    return a.magnitude != b.magnitude ? a.magnitude > b.magnitude : a.index < b.index;
  });
  return all;
}

std::size_t keep_ranked(Hierarchy& h, std::span<const RankedWavelet> ranking, double fraction) {
  const std::size_t keep = count_of_fraction(ranking.size(), fraction);
  for (std::size_t k = keep; k < ranking.size(); ++k)
    std::fill_n(h.coeffs.begin() + std::ptrdiff_t(std::size_t(ranking[k].index) * h.channels), h.channels, 0.0);
  return keep;
}

std::vector<double> synthesize_coefficients(const Hierarchy& h, std::span<const double> coeffs,
                                            std::span<const double> gains, int level) {
  if (level < 0 || level > h.finest_level())
    throw Error("level " + std::to_string(level) + " is outside 0.." + std::to_string(h.finest_level()));
  if (coeffs.size() != h.coeffs.size())
    throw Error("synthesis needs " + std::to_string(h.coeffs.size()) + " coefficients, got " +
                std::to_string(coeffs.size()));
  check_gains(h, gains);
  std::vector<double> x(coeffs.begin(), coeffs.begin() + std::ptrdiff_t(std::size_t(h.num_vertices(level)) * h.channels));
  for (int j = 0; j < level; ++j) synthesize_step(h, gains, j, x);
  return x;
}

bool Region::contains(const double* p) const {
  if (kind == Kind::Sphere) {
    const double dx = p[0] - centre[0], dy = p[1] - centre[1], dz = p[2] - centre[2];
    return dx * dx + dy * dy + dz * dz <= radius * radius;
  }
  for (int a = 0; a < 3; ++a)
    if (p[a] < lo[static_cast<std::size_t>(a)] || p[a] > hi[static_cast<std::size_t>(a)]) return false;
  return true;
}

Region parse_region(std::string_view spec) {
  const std::size_t colon = spec.find(':');
  const std::string_view kind = spec.substr(0, colon);
  if (colon == std::string_view::npos || (kind != "box" && kind != "sphere"))
    throw Error("region '" + std::string(spec) + "' must be box:x0,y0,z0,x1,y1,z1 or sphere:cx,cy,cz,r");
  const std::vector<double> v = numbers_of(spec.substr(colon + 1), spec);
  Region r;
  if (kind == "box") {
    if (v.size() != 6) throw Error("region '" + std::string(spec) + "': a box needs 6 numbers, got " + std::to_string(v.size()));
    r.kind = Region::Kind::Box;
    for (std::size_t a = 0; a < 3; ++a) {
      r.lo[a] = std::min(v[a], v[a + 3]);
      r.hi[a] = std::max(v[a], v[a + 3]);
    }
    return r;
  }
  if (v.size() != 4) throw Error("region '" + std::string(spec) + "': a sphere needs 4 numbers, got " + std::to_string(v.size()));
  if (v[3] < 0) throw Error("region '" + std::string(spec) + "': the radius must not be negative");
  r.kind = Region::Kind::Sphere;
  r.centre = {v[0], v[1], v[2]};
  r.radius = v[3];
  return r;
}

std::string compress_mode_name(CompressMode m) {
  switch (m) {
    case CompressMode::Keep: return "keep";
    case CompressMode::Threshold: return "threshold";
    case CompressMode::Linf: return "linf";
  }
  return "keep";
}

Compressor::Compressor(const Hierarchy& h, CompressOptions options)
    : h_(&h), options_(std::move(options)), coeffs_(h.coeffs) {
  check_gains(h, options_.gains);
  const int J = h.finest_level();
  const std::uint32_t nv0 = h.num_vertices(0), nvJ = h.num_vertices(J);
  total_ = nvJ - nv0;
  const std::vector<double> norms = wavelet_l2_norms(h);
  const int ch = h.channels;

  // One synthesis: the reference shape, and where each wavelet lives (level j+1 for level j).
  std::vector<std::uint8_t> inside;
  std::vector<double> x(coeffs_.begin(), coeffs_.begin() + std::ptrdiff_t(std::size_t(nv0) * ch));
  if (options_.region) inside.assign(total_, 0);
  for (int j = 0; j < J; ++j) {
    x.resize(std::size_t(h.num_vertices(j + 1)) * ch);
    std::copy(coeffs_.begin() + std::ptrdiff_t(std::size_t(h.num_vertices(j)) * ch),
              coeffs_.begin() + std::ptrdiff_t(std::size_t(h.num_vertices(j + 1)) * ch),
              x.begin() + std::ptrdiff_t(std::size_t(h.num_vertices(j)) * ch));
    synthesize_step(h, options_.gains, j, x);
    if (!options_.region) continue;
    for (std::uint32_t v = h.num_vertices(j); v < h.num_vertices(j + 1); ++v) {
      double p[3] = {0, 0, 0};
      for (int c = 0; c < 3 && c < ch; ++c) p[c] = x[std::size_t(v) * ch + c];
      inside[v - nv0] = options_.region->contains(p) ? 1 : 0;
    }
  }
  reference_ = std::move(x);
  checked_range(h, options_.channels);
  const int width = options_.channels.count == 0 ? 3 : options_.channels.count;
  reference_xyz_ = measured_of(reference_, ch, options_.channels);
  diagonal_ = box_diagonal(reference_xyz_, width);
  if (!(diagonal_ > 0) || !std::isfinite(diagonal_))
    throw Error(options_.channels.count == 0
                    ? "compress: the finest shape has no extent (bounding-box diagonal 0), so errors cannot be relative to it"
                    : "compress: channels " + std::to_string(options_.channels.first) + ".." +
                          std::to_string(options_.channels.first + options_.channels.count - 1) +
                          " are constant on the finest level (no range), so errors cannot be relative to it");

  // The ranking, on the stored coefficients (coeffs_ is h.coeffs).
  const std::vector<RankedWavelet> all =
      rank_wavelets(h, options_.normalise ? std::span<const double>(norms) : std::span<const double>(), options_.gains,
                    inside, options_.channels);
  order_.reserve(all.size());
  magnitude_.reserve(all.size());
  for (const RankedWavelet& e : all) {
    order_.push_back(e.index);
    magnitude_.push_back(e.magnitude);
  }
}

std::size_t Compressor::count_for_fraction(double fraction) const { return count_of_fraction(order_.size(), fraction); }

std::size_t Compressor::count_for_threshold(double threshold) const {
  if (!(threshold >= 0.0) || !std::isfinite(threshold))
    throw Error("threshold must be a finite number >= 0, got " + std::to_string(threshold));
  const double t = threshold * diagonal_;
  return static_cast<std::size_t>(
      std::partition_point(magnitude_.begin(), magnitude_.end(), [t](double m) { return m >= t; }) - magnitude_.begin());
}

double Compressor::linf_of(std::size_t keep) const {
  const std::vector<double> x = synthesize_coefficients(*h_, coefficients(keep), options_.gains, h_->finest_level());
  const int width = options_.channels.count == 0 ? 3 : options_.channels.count;
  return group_error(measured_of(x, h_->channels, options_.channels), reference_xyz_, width, diagonal_).max;
}

std::size_t Compressor::count_for_linf(double tolerance) const {
  if (!(tolerance >= 0.0) || !std::isfinite(tolerance))
    throw Error("L-infinity tolerance must be a finite number >= 0, got " + std::to_string(tolerance));
  // Keeping every candidate reproduces the reference exactly (error 0), so hi is good from the
  // start; lo is always a count found to break the bound.
  std::size_t hi = order_.size();
  if (hi == 0 || linf_of(0) <= tolerance) return 0;
  std::size_t lo = 0;
  while (hi - lo > 1) {
    const std::size_t mid = lo + (hi - lo) / 2;
    if (linf_of(mid) <= tolerance) {
      hi = mid;
    } else {
      lo = mid;
    }
  }
  return hi;
}

std::size_t Compressor::count(CompressMode mode, double value) const {
  switch (mode) {
    case CompressMode::Keep: return count_for_fraction(value);
    case CompressMode::Threshold: return count_for_threshold(value);
    case CompressMode::Linf: return count_for_linf(value);
  }
  return order_.size();
}

std::vector<double> Compressor::coefficients(std::size_t keep) const {
  std::vector<double> c = coeffs_;
  const int ch = h_->channels;
  const auto [first, count] = checked_range(*h_, options_.channels);  // a group zeroes its own channels
  for (std::size_t k = std::min(keep, order_.size()); k < order_.size(); ++k)
    std::fill_n(c.begin() + std::ptrdiff_t(std::size_t(order_[k]) * ch + std::size_t(first)), count, 0.0);
  return c;
}

Compression Compressor::evaluate(std::size_t keep) const {
  Compression out;
  out.keep = std::min(keep, order_.size());
  out.total = total_;
  out.kept = total_ - order_.size() + out.keep;
  out.coeffs = coefficients(out.keep);
  out.finest = synthesize_coefficients(*h_, out.coeffs, options_.gains, h_->finest_level());
  const int width = options_.channels.count == 0 ? 3 : options_.channels.count;
  const ShapeError e = group_error(measured_of(out.finest, h_->channels, options_.channels), reference_xyz_, width, diagonal_);
  out.l2_error = e.rms;
  out.linf_error = e.max;
  return out;
}

std::size_t keep_largest(Hierarchy& h, double fraction) {
  if (!(fraction >= 0.0 && fraction <= 1.0)) throw Error("keep fraction must be in [0, 1]");
  return keep_ranked(h, rank_wavelets(h, wavelet_l2_norms(h)), fraction);
}

}  // namespace sublift
