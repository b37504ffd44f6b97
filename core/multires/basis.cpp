#include "core/multires/basis.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/base/errors.h"
#include "core/engine/executor.h"
#include "core/multires/limit.h"

namespace sublift {
namespace {

std::uint32_t count_nonzero(const double* x, std::uint32_t n) {
  return static_cast<std::uint32_t>(std::count_if(x, x + n, [](double v) { return v != 0.0; }));
}

// Dual cell measure per finest vertex (basis.h): each cell's 2^(-L*dim) split equally over its
// corners. sqrt2 levels halve the area: a quad of level L has 2^-L, a triangle on a kept curve
// (odd L) half of that.
std::vector<double> vertex_measures(const Complex& c, int L, Scheme scheme) {
  std::vector<double> mu(c.num_vertices, 0.0);
  const bool sqrt2 = scheme_info(scheme).refinement == Refinement::Sqrt2;
  const double cell = std::ldexp(1.0, sqrt2 ? -L : -L * c.dim);
  if (c.dim == 1) {
    for (std::uint32_t v : c.edge_verts) mu[v] += 0.5 * cell;
  } else if (c.dim == 2) {
    for (std::size_t f = 0; f < c.faces.rows(); ++f) {
      const auto row = c.faces.row(f);
      const double area = sqrt2 && row.size() == 3 && L % 2 == 1 ? 0.5 * cell : cell;
      for (std::uint32_t v : row) mu[v] += area / double(row.size());
    }
  } else {
    std::vector<std::uint32_t> stamp(c.num_vertices, ~0u), corners;
    for (std::uint32_t k = 0; k < c.num_cells(); ++k) {
      corners.clear();
      for (std::uint32_t f : c.cell_faces.row(k))
        for (std::uint32_t v : c.faces.row(f))
          if (stamp[v] != k) {
            stamp[v] = k;
            corners.push_back(v);
          }
      for (std::uint32_t v : corners) mu[v] += cell / double(corners.size());
    }
  }
  return mu;
}

}  // namespace

int default_extra_levels(const Complex& c, double max_vertices, Scheme scheme, int level) {
  int K = (c.dim == 1 ? 6 : (c.dim == 2 ? 4 : 3)) * scheme_levels_per_split(scheme);
  const std::vector<double> counts = predicted_level_counts(c, K, scheme, level);
  while (K > 0 && counts[static_cast<std::size_t>(K)] > max_vertices) --K;
  return K;
}

BasisFunction basis_function(const Complex& level_j, Scheme scheme, const BasisRequest& r,
                             std::span<const double> level_j_positions, std::vector<double>* finest_positions) {
  const std::uint32_t nv = level_j.num_vertices;
  if (level_j_positions.size() != std::size_t(nv) * 3)
    throw Error("basis function: level " + std::to_string(r.level) + " needs " + std::to_string(3 * std::size_t(nv)) +
                " position values, got " + std::to_string(level_j_positions.size()));
  if (r.level < 0) throw Error("basis function: level must be non-negative");
  const int K = r.extra_levels < 0 ? default_extra_levels(level_j, r.max_vertices, scheme, r.level) : r.extra_levels;
  const int most = max_levels(scheme);
  if (K > most) throw Error("basis function: at most " + std::to_string(most) + " extra levels, got " + std::to_string(K));
  if (r.kind == BasisKind::Wavelet && K < 1) throw Error("basis function: a wavelet needs at least one extra level");
  const double predicted = predicted_level_counts(level_j, K, scheme, r.level).back();
  if (predicted > r.max_vertices)
    throw Error("basis function: " + std::to_string(K) + " extra levels make " + std::to_string(std::llround(predicted)) +
                " vertices, more than the limit of " + std::to_string(std::llround(r.max_vertices)));

  Hierarchy h = make_hierarchy(level_j, K, scheme, 1, false, r.level);
  const std::uint32_t lo = r.kind == BasisKind::Scaling ? 0 : nv;
  const std::uint32_t hi = r.kind == BasisKind::Scaling ? nv : h.num_vertices(1);
  if (r.index < lo || r.index >= hi) {
    if (r.kind == BasisKind::Wavelet && r.index < nv)
      throw Error("basis function: vertex " + std::to_string(r.index) + " of level " + std::to_string(r.level + 1) +
                  " is a v vertex (indices below " + std::to_string(nv) +
                  " are the old vertices); wavelets live on e/f/c vertices " + std::to_string(nv) + ".." +
                  std::to_string(hi - 1));
    throw Error("basis function: " + std::string(r.kind == BasisKind::Scaling ? "scaling" : "wavelet") + " index " +
                std::to_string(r.index) + " is outside " + std::to_string(lo) + ".." + std::to_string(hi - 1));
  }

  BasisFunction out;
  out.level = r.level;
  out.extra_levels = K;
  const std::uint32_t nL = h.num_vertices(K);
  std::vector<double> x(nL, 0.0);
  x[r.index] = 1.0;
  out.support_per_level.push_back(count_nonzero(x.data(), nv));
  for (int l = 0; l < K; ++l) {
    const auto L = static_cast<std::size_t>(l);
    if (r.dual) run_analysis_adjoint(h.transitions[L], h.levels[L], x.data());
    else synthesize_transition(h, l, x.data(), 1, false);
    out.support_per_level.push_back(count_nonzero(x.data(), h.num_vertices(l + 1)));
  }

  // Geometry: the level-j positions synthesised (zero details) to j+K, then their limit.
  std::vector<double> p(std::size_t(nL) * 3, 0.0);
  std::copy(level_j_positions.begin(), level_j_positions.end(), p.begin());
  for (int l = 0; l < K; ++l) synthesize_transition(h, l, p.data(), 3, false);
  const LimitStencils stencils = build_limit_stencils(h);
  std::vector<double> p_limit(p.size());
  eval_limit(stencils, p.data(), p_limit.data());

  out.control = std::move(x);
  if (r.dual) {
    out.values = out.control;
  } else {
    out.limit = true;
    out.values.assign(nL, 0.0);
    for (std::uint32_t v = 0; v < nL; ++v) {
      double s = 0.0;
      for (std::uint32_t k = stencils.rows.offsets[v]; k < stencils.rows.offsets[v + 1]; ++k)
        s += stencils.weights[k] * out.control[stencils.rows.items[k]];
      out.values[v] = s;
    }
  }

  const std::vector<double> mu = vertex_measures(h.levels.back(), r.level + K, scheme);
  const std::vector<double>& moment_positions = r.dual ? p : p_limit;
  out.min = out.values.empty() ? 0.0 : out.values[0];
  out.max = out.min;
  for (std::uint32_t v = 0; v < nL; ++v) {
    const double f = out.values[v];
    out.min = std::min(out.min, f);
    out.max = std::max(out.max, f);
    if (f != 0.0 || out.control[v] != 0.0) out.support.push_back(v);
    const double w = r.dual ? f : f * mu[v];
    out.integral += w;
    for (int c = 0; c < 3; ++c) out.moment[c] += w * moment_positions[std::size_t(v) * 3 + c];
  }
  if (finest_positions) *finest_positions = std::move(p_limit);
  out.finest = std::move(h.levels.back());
  return out;
}

}  // namespace sublift
