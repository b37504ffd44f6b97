#include "core/multires/hierarchy.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "core/base/channels.h"
#include "core/base/errors.h"
#include "core/base/magnitude.h"
#include "core/base/memory_budget.h"
#include "core/complex/level_counts.h"
#include "core/complex/refine_sqrt2.h"
#include "core/engine/executor.h"

namespace sublift {

std::size_t Hierarchy::bytes() const {
  std::size_t b = coeffs.capacity() * sizeof(double) + wavelet_norms.capacity() * sizeof(double) +
                  carry.capacity() * sizeof(std::int32_t);
  for (const Complex& c : levels) b += c.bytes();
  for (const Transition& t : transitions) b += t.bytes();
  for (const ChildSites& s : sites) b += (s.site.capacity() + s.edge_child.capacity() + s.face_child.capacity()) * 4;
  return b;
}

namespace {

// Refuses, before anything is built, levels 0..levels of base that would pass the budget.
void check_levels_memory(const Complex& base, int levels, Scheme scheme, int first_level) {
  const double need = predicted_hierarchy_bytes(base, levels, scheme, first_level);
  if (need <= kUncheckedBytes) return;  // not even the level counts' text
  const double top = predicted_level_counts(base, levels, scheme, first_level).back();
  check_memory(need, "subdividing to level " + std::to_string(levels) + " (" + std::to_string(std::llround(top)) + " vertices)");
}

}  // namespace

double predicted_hierarchy_bytes(const Complex& c, int levels, Scheme scheme, int first_level) {
  const SchemeInfo& info = scheme_info(scheme);
  const double per = info.peak_bytes[c.dim == 3 && info.peak_bytes[1] > 0 ? 1 : 0];
  return predicted_level_counts(c, levels, scheme, first_level).back() * per;
}

void append_level(Hierarchy& h, bool adjacency) {
  Complex& parent = h.levels.back();
  if (parent.vertex_edges.rows() != parent.num_vertices) build_adjacency(parent);
  const int j = h.finest_level();
  if (predicted_level_counts(parent, 1, h.scheme, h.first_level + j).back() > 4.0e9)
    throw Error("level " + std::to_string(j + 1) + " would have more than 2^32 vertices");
  check_levels_memory(h.levels.front(), j + 1, h.scheme, h.first_level);
  LevelBuild b = scheme_info(h.scheme).build(parent, {h.first_level + j, h.disc, adjacency, h.carry.empty() ? nullptr : &h.carry});
  if (!b.norms.empty()) {
    h.wavelet_norms.resize(std::size_t(parent.num_vertices) - h.levels.front().num_vertices);
    h.wavelet_norms.insert(h.wavelet_norms.end(), b.norms.begin(), b.norms.end());
  }
  h.transitions.push_back(std::move(b.transition));
  if (b.has_sites) h.sites.push_back(std::move(b.sites));
  h.levels.push_back(std::move(b.fine));
  h.carry = std::move(b.carry);
}

void pop_level(Hierarchy& h) {
  if (h.levels.size() < 2) throw Error("the hierarchy has no level to remove");
  h.levels.pop_back();
  h.transitions.pop_back();
  h.carry.clear();  // it was the popped level's
  if (!h.sites.empty()) h.sites.pop_back();
  if (!h.wavelet_norms.empty())
    h.wavelet_norms.resize(std::size_t(h.levels.back().num_vertices) - h.levels.front().num_vertices);
}

Hierarchy make_hierarchy(Complex base, int levels, Scheme scheme, int channels, bool integer, int first_level, int disc,
                         const LevelProgress& progress) {
  const SchemeInfo& info = scheme_info(scheme);
  const int most = max_levels(scheme);
  if (levels < 0 || levels > most)
    throw Error("number of levels must be in 0.." + std::to_string(most) + ", got " + std::to_string(levels));
  if (channels < 1) throw Error("at least one channel is needed");
  if (info.surfaces_only && (base.dim != 2 || base.num_cells() != 0))
    throw Error("the " + scheme_name(scheme) + " scheme refines " +
                std::string(info.triangles_only ? "triangle meshes" : "surfaces") + " only; this is a " +
                std::string(base.dim == 1 ? "curve" : base.dim == 3 ? "volume lattice" : "complex") +
                " (use linear or cubic)");
  if (integer && !info.integer)
    throw Error("integer mode needs an interpolating scheme; " + scheme_name(scheme) +
                "'s analysis solves a linear system (use butterfly or linear-tri)");
  if (first_level < 0) throw Error("the first sqrt(2) level must not be negative");
  Hierarchy h;
  h.scheme = scheme;
  h.integer = integer;
  h.channels = channels;
  h.first_level = info.refinement == Refinement::Sqrt2 ? first_level : 0;
  if (disc < 1 || disc > 3) throw Error("the wavelet disc must have 1, 2 or 3 rings, got " + std::to_string(disc));
  h.disc = disc;
  if (base.vertex_edges.rows() != base.num_vertices) build_adjacency(base);
  check_levels_memory(base, levels, scheme, h.first_level);
  std::vector<double> counts;  // the work of level j: about its vertex count
  double total = 0, done = 0;
  if (progress) {
    counts = predicted_level_counts(base, levels, scheme, h.first_level);
    for (int j = 1; j <= levels; ++j) total += counts[static_cast<std::size_t>(j)];
  }
  h.levels.reserve(static_cast<std::size_t>(levels) + 1);
  h.levels.push_back(std::move(base));
  for (int j = 0; j < levels; ++j) {
    if (progress && !progress(total > 0 ? done / total : 0.0)) throw Cancelled("building the levels was cancelled");
    append_level(h, /*adjacency=*/j + 1 < levels);
    if (progress) done += counts[static_cast<std::size_t>(j) + 1];
  }
  h.coeffs.assign(std::size_t(h.levels.back().num_vertices) * std::size_t(channels), 0.0);
  return h;
}

void synthesize_transition(const Hierarchy& h, int j, double* x, int channels, bool integer, bool wavelets_zero) {
  const auto J = static_cast<std::size_t>(j);
  run_synthesis(h.transitions[J], h.levels[J], x, channels, integer, wavelets_zero);
}

void analyze_transition(const Hierarchy& h, int j, double* x, int channels, bool integer) {
  const auto J = static_cast<std::size_t>(j);
  run_analysis(h.transitions[J], h.levels[J], x, channels, integer);
}

std::vector<double> predicted_level_counts(const Complex& c, int levels, Scheme scheme, int first_level) {
  const Refinement refinement = scheme_info(scheme).refinement;
  if (refinement == Refinement::Tri) {
    // V' = V + E, E' = 2E + 3F, F' = 4F.
    double v = c.num_vertices, e = c.num_edges(), f = c.num_faces();
    std::vector<double> out{v};
    for (int l = 1; l <= levels; ++l) {
      v += e;
      e = 2 * e + 3 * f;
      f *= 4;
      out.push_back(v);
    }
    return out;
  }
  if (refinement == Refinement::Split) return predicted_vertex_counts(c, levels);
  std::vector<double> out{double(c.num_vertices)};
  if (first_level % 2 == 0) {
    // Two sqrt(2) steps are one 1-to-4 step; the odd level between adds one point per face.
    const int splits = (levels + 1) / 2;
    const std::vector<double> v = predicted_vertex_counts(c, splits);
    const std::vector<double> f = predicted_face_counts(c, splits);
    for (int l = 1; l <= levels; ++l) out.push_back(l % 2 == 0 ? v[std::size_t(l / 2)] : v[std::size_t(l / 2)] + f[std::size_t(l / 2)]);
    return out;
  }
  // From an odd level: one point per curve edge and quad (exact when c has its derived rows;
  // else at most one per edge and face), then an estimate of twice as many per level.
  double n = double(c.num_vertices);
  if (c.edge_faces.rows() == c.num_edges()) {
    for (std::uint32_t e = 0; e < c.num_edges(); ++e) n += sqrt2_is_curve_edge(c, e) ? 1 : 0;
    for (std::uint32_t f = 0; f < c.num_faces(); ++f) n += c.faces.size(f) == 4 ? 1 : 0;
  } else {
    n += double(c.num_edges()) + double(c.num_faces());
  }
  for (int l = 1; l <= levels; ++l, n *= 2) out.push_back(n);
  return out;
}

void set_base(Hierarchy& h, std::span<const double> base_values) {
  const std::size_t n = std::size_t(h.num_vertices(0)) * h.channels;
  if (base_values.size() != n)
    throw Error("base needs " + std::to_string(n) + " values, got " + std::to_string(base_values.size()));
  std::fill(h.coeffs.begin(), h.coeffs.end(), 0.0);
  std::copy(base_values.begin(), base_values.end(), h.coeffs.begin());
}

void analyze(Hierarchy& h, std::span<const double> finest_values) {
  if (finest_values.size() != h.coeffs.size())
    throw Error("finest level needs " + std::to_string(h.coeffs.size()) + " values, got " +
                std::to_string(finest_values.size()));
  std::copy(finest_values.begin(), finest_values.end(), h.coeffs.begin());
  for (int j = h.finest_level() - 1; j >= 0; --j) analyze_transition(h, j, h.coeffs.data(), h.channels, h.integer);
}

namespace {

// Synthesis to `level`; with `checked`, each level's values are checked as soon as they exist.
std::vector<double> run_synthesis(const Hierarchy& h, int level, bool checked) {
  if (level < 0 || level > h.finest_level())
    throw Error("level " + std::to_string(level) + " is outside 0.." + std::to_string(h.finest_level()));
  const auto ch = static_cast<std::size_t>(h.channels);
  std::vector<double> x(h.coeffs.begin(), h.coeffs.begin() + std::size_t(h.num_vertices(level)) * ch);
  auto check = [&](int j) {
    if (!checked) return;
    const auto i = first_out_of_range(std::span<const double>(x.data(), std::size_t(h.num_vertices(j)) * ch));
    if (i)
      throw Error("synthesis overflows at level " + std::to_string(j) + ": vertex " + std::to_string(*i / ch) + ", channel " +
                  std::to_string(*i % ch) + " " + out_of_range_text(x[*i]));
  };
  check(0);
  for (int j = 0; j < level; ++j) {
    const auto b = x.begin() + std::size_t(h.num_vertices(j)) * ch;
    const auto e = x.begin() + std::size_t(h.num_vertices(j + 1)) * ch;
    const bool zero = std::all_of(b, e, [](double v) { return v == 0.0; });
    synthesize_transition(h, j, x.data(), h.channels, h.integer, zero);
    check(j + 1);
  }
  return x;
}

}  // namespace

std::vector<double> synthesize(const Hierarchy& h, int level) { return run_synthesis(h, level, false); }

std::vector<double> synthesize_in_range(const Hierarchy& h, int level) { return run_synthesis(h, level, true); }

void apply_gains(Hierarchy& h, std::span<const double> gains) {
  if (gains.empty()) return;
  const int J = h.finest_level();
  if (gains.size() != static_cast<std::size_t>(J))
    throw Error("there are " + std::to_string(gains.size()) + " gains for " + std::to_string(J) + " wavelet levels");
  const auto ch = static_cast<std::size_t>(h.channels);
  for (int l = 0; l < J; ++l) {
    const double g = gains[static_cast<std::size_t>(l)];
    if (!std::isfinite(g)) throw Error("the gain of level " + std::to_string(l) + " is not finite");
    if (g == 1.0) continue;
    if (h.integer) {
      char text[32];
      std::snprintf(text, sizeof text, "%.17g", g);
      throw Error("an integer hierarchy takes no gains (level " + std::to_string(l) + " has gain " + text + ")");
    }
    for (std::size_t i = ch * h.num_vertices(l); i < ch * h.num_vertices(l + 1); ++i) h.coeffs[i] *= g;
  }
}

std::vector<LevelStats> level_stats(const Hierarchy& h) {
  std::vector<LevelStats> out;
  for (int j = 0; j < h.finest_level(); ++j) {
    LevelStats s;
    s.level = j;
    s.vertices = h.num_vertices(j);
    const std::uint32_t b = h.num_vertices(j), e = h.num_vertices(j + 1);
    s.wavelets = e - b;
    double sum2 = 0;
    for (std::uint32_t i = b; i < e; ++i) {
      const double n = channel_norm(&h.coeffs[std::size_t(i) * h.channels], h.channels);
      s.wavelet_max = std::max(s.wavelet_max, n);
      sum2 += n * n;
    }
    s.wavelet_rms = s.wavelets ? std::sqrt(sum2 / s.wavelets) : 0.0;
    out.push_back(s);
  }
  return out;
}

}  // namespace sublift
