#include "core/hierarchy.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/errors.h"
#include "core/refine.h"

namespace sublift {

std::string scheme_name(Scheme s) { return s == Scheme::Linear ? "linear" : "cubic"; }

Scheme parse_scheme(const std::string& name) {
  if (name == "linear") return Scheme::Linear;
  if (name == "cubic") return Scheme::Cubic;
  throw std::invalid_argument("unknown scheme '" + name + "' (expected linear or cubic)");
}

LiftProgram scheme_program(Scheme s) { return s == Scheme::Linear ? linear_program() : cubic_program(); }

std::size_t Hierarchy::bytes() const {
  std::size_t b = coeffs.capacity() * sizeof(double);
  for (const Complex& c : levels) b += c.bytes();
  for (const LiftTables& t : tables) b += t.bytes();
  return b;
}

Hierarchy make_hierarchy(Complex base, int levels, Scheme scheme, int channels, bool integer) {
  if (levels < 0 || levels > 16) throw Error("number of levels must be in 0..16, got " + std::to_string(levels));
  if (channels < 1) throw Error("at least one channel is needed");
  Hierarchy h;
  h.scheme = scheme;
  h.integer = integer;
  h.channels = channels;
  if (base.vertex_edges.rows() != base.num_vertices) build_adjacency(base);
  h.levels.reserve(static_cast<std::size_t>(levels) + 1);
  h.levels.push_back(std::move(base));
  for (int j = 0; j < levels; ++j) {
    const Complex& parent = h.levels.back();
    const double next = double(parent.num_child_vertices());
    if (next > 4.0e9) throw Error("level " + std::to_string(j + 1) + " would have more than 2^32 vertices");
    h.tables.push_back(build_lift_tables(parent));
    Complex child = refine(parent, /*adjacency=*/j + 1 < levels);
    h.levels.push_back(std::move(child));
  }
  h.coeffs.assign(std::size_t(h.levels.back().num_vertices) * std::size_t(channels), 0.0);
  return h;
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
  const LiftProgram program = scheme_program(h.scheme);
  for (int j = h.finest_level() - 1; j >= 0; --j)
    lift_analyze(h.levels[j], h.tables[j], program, h.coeffs.data(), h.channels, h.integer);
}

std::vector<double> synthesize(const Hierarchy& h, int level) {
  if (level < 0 || level > h.finest_level())
    throw Error("level " + std::to_string(level) + " is outside 0.." + std::to_string(h.finest_level()));
  std::vector<double> x(h.coeffs.begin(), h.coeffs.begin() + std::size_t(h.num_vertices(level)) * h.channels);
  const LiftProgram program = scheme_program(h.scheme);
  // A leading s-lift only reads wavelet coefficients (e/f/c classes): when a level has none, it
  // adds exactly zero and is skipped (000 sec. 4: "the first lifting operation does not have an
  // impact"). Pure subdivision then costs what the subdivision rules cost.
  LiftProgram without_first(program.begin() + (program.empty() || program.front().op != LiftOp::SLift ? 0 : 1),
                            program.end());
  for (int j = 0; j < level; ++j) {
    const auto b = x.begin() + std::size_t(h.num_vertices(j)) * h.channels;
    const auto e = x.begin() + std::size_t(h.num_vertices(j + 1)) * h.channels;
    const bool zero = std::all_of(b, e, [](double v) { return v == 0.0; });
    lift_synthesize(h.levels[j], h.tables[j], zero ? without_first : program, x.data(), h.channels, h.integer);
  }
  return x;
}

static double norm(const double* v, int ch) {
  double s = 0;
  for (int c = 0; c < ch; ++c) s += v[c] * v[c];
  return std::sqrt(s);
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
      const double n = norm(&h.coeffs[std::size_t(i) * h.channels], h.channels);
      s.wavelet_max = std::max(s.wavelet_max, n);
      sum2 += n * n;
    }
    s.wavelet_rms = s.wavelets ? std::sqrt(sum2 / s.wavelets) : 0.0;
    out.push_back(s);
  }
  return out;
}

std::size_t keep_largest(Hierarchy& h, double fraction) {
  if (!(fraction >= 0.0 && fraction <= 1.0)) throw Error("keep fraction must be in [0, 1]");
  struct Entry {
    double magnitude;
    std::uint32_t index;
  };
  std::vector<Entry> all;
  const int dim = h.levels.front().dim;
  for (int j = 0; j < h.finest_level(); ++j) {
    const double scale = std::pow(2.0, -0.5 * j * dim);  // L2 norm of a level-j basis function
    for (std::uint32_t i = h.num_vertices(j); i < h.num_vertices(j + 1); ++i)
      all.push_back({norm(&h.coeffs[std::size_t(i) * h.channels], h.channels) * scale, i});
  }
  const auto keep = static_cast<std::size_t>(std::llround(fraction * double(all.size())));
  if (keep < all.size()) {
    std::nth_element(all.begin(), all.begin() + keep, all.end(), [](const Entry& a, const Entry& b) {
      return a.magnitude != b.magnitude ? a.magnitude > b.magnitude : a.index < b.index;
    });
    for (std::size_t k = keep; k < all.size(); ++k)
      std::fill_n(h.coeffs.begin() + std::size_t(all[k].index) * h.channels, h.channels, 0.0);
  }
  return std::min(keep, all.size());
}

}  // namespace sublift
