#include "core/fit/fit_levels.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/base/errors.h"
#include "core/complex/complex_build.h"
#include "core/base/bounds.h"
#include "core/base/triangle_bvh.h"

namespace sublift {

namespace {

// The coefficients that synthesise `x` (level L's net) at level L, finer wavelets zero.
void set_level(Hierarchy& h, int L, std::vector<double> x) {
  for (int j = L - 1; j >= 0; --j) analyze_transition(h, j, x.data(), h.channels, h.integer);
  std::fill(h.coeffs.begin(), h.coeffs.end(), 0.0);
  std::copy(x.begin(), x.end(), h.coeffs.begin());
}

}  // namespace

Fitted fit_levels(const BaseMesh& base, const Csr& faces, std::span<const double> positions, const FitOptions& o) {
  if (!scheme_is_tri(o.scheme)) throw Error("fitting takes the triangle schemes for now (linear-tri, butterfly, loop)");
  Fitted out;
  const TriangleBvh input(positions, faces);
  const double diag = bbox_diagonal(positions);
  out.hierarchy = make_hierarchy(complex_from_polygons(base.num_vertices, base.faces, base.tags), o.levels, o.scheme, 3);
  Hierarchy& h = out.hierarchy;
  set_base(h, base.positions);
  std::vector<double> x;
  for (int l = 1; l <= o.levels; ++l) {
    const auto t0 = std::chrono::steady_clock::now();
    x = synthesize(h, l);  // the fitted level l-1, subdivided
    Complex c = h.levels[static_cast<std::size_t>(l)];
    if (c.vertex_edges.rows() != c.num_vertices) build_adjacency(c);
    const std::uint32_t first_new = h.num_vertices(l - 1), n = c.num_vertices;
    std::vector<double> mean(3 * std::size_t(n));
    for (int round = 0; round < o.relax_rounds; ++round) {
      // Relax the new points towards their neighbours' mean, then attract them to the input.
      for (std::uint32_t v = first_new; v < n; ++v) {
        double m[3] = {0, 0, 0};
        const auto es = c.vertex_edges.row(v);
        for (std::uint32_t e : es) {
          const std::uint32_t w = c.edge_verts[2 * e] == v ? c.edge_verts[2 * e + 1] : c.edge_verts[2 * e];
          for (int k = 0; k < 3; ++k) m[k] += x[3 * std::size_t(w) + k] / double(es.size());
        }
        for (int k = 0; k < 3; ++k) mean[3 * std::size_t(v) + k] = m[k];
      }
      // Old points moved too where the scheme approximates (Loop): every point is attracted.
      for (std::uint32_t v = 0; v < n; ++v) {
        double p[3];
        const double t = v >= first_new ? o.relax : 0.0;
        for (int k = 0; k < 3; ++k) p[k] = (1 - t) * x[3 * std::size_t(v) + k] + t * mean[3 * std::size_t(v) + k];
        const glm::dvec3 q = input.closest({p[0], p[1], p[2]}).point;
        for (int k = 0; k < 3; ++k) x[3 * std::size_t(v) + k] = q[k];
      }
    }
    FitLevelReport rep;
    rep.level = l;
    rep.vertices = n;
    double sum = 0;
    for (std::uint32_t v = 0; v < n; ++v) {
      const double d = input.closest({x[3 * std::size_t(v)], x[3 * std::size_t(v) + 1], x[3 * std::size_t(v) + 2]}).distance / diag;
      sum += d * d;
      rep.max = std::max(rep.max, d);
    }
    rep.rms = std::sqrt(sum / n);
    if (l < o.levels) set_level(h, l, x);
    rep.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    out.levels.push_back(rep);
  }
  if (o.levels == 0) x = synthesize(h, 0);
  analyze(h, x);
  out.finest = std::move(x);
  return out;
}

}  // namespace sublift
