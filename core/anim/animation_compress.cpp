#include "core/anim/animation_compress.h"

#include <algorithm>
#include <cmath>

#include "core/analysis/compress.h"
#include "core/base/parallel.h"

namespace sublift {

std::vector<FrameError> frame_errors(const SpaceTime& st, std::span<const double> a, std::span<const double> b,
                                     double diagonal) {
  const int J = st.levels();
  const std::uint32_t nvs = st.surface_vertices(J);
  const auto& lv = st.layer_vertices[std::size_t(J)];
  std::vector<FrameError> out(std::size_t(st.layers(J)));
  for (std::size_t t = 0; t < out.size(); ++t) {
    double sum = 0, worst = 0;
    for (std::uint32_t p = 0; p < nvs; ++p) {
      const std::size_t v = lv[t * nvs + p];
      const double d = std::hypot(a[3 * v] - b[3 * v], a[3 * v + 1] - b[3 * v + 1], a[3 * v + 2] - b[3 * v + 2]);
      sum += d * d;
      worst = std::max(worst, d);
    }
    out[t] = {worst / diagonal, std::sqrt(sum / nvs) / diagonal};
  }
  return out;
}

PerFrameCompression per_frame_compression(const SpaceTime& st, std::span<const double> finest, std::size_t stored,
                                          double diagonal) {
  const Hierarchy& s = st.surface_levels;
  const int J = st.levels(), n = st.layers(J);
  const std::uint32_t nv0 = s.num_vertices(0), nvs = s.num_vertices(J);
  const std::size_t per = std::size_t(nvs) * 3;
  // Every frame's coefficients, frame after frame, in the surface hierarchy's layout.
  std::vector<double> coeffs(std::size_t(n) * per);
  parallel_for(std::uint32_t(n), 1, [&](std::uint32_t begin, std::uint32_t end) {
    for (std::uint32_t t = begin; t < end; ++t) {
      const std::vector<double> layer = layer_positions(st, finest, J, int(t));
      double* x = &coeffs[t * per];
      std::copy(layer.begin(), layer.end(), x);
      for (int j = J - 1; j >= 0; --j) analyze_transition(s, j, x, 3, false);
    }
  });
  const std::vector<double> norms = wavelet_l2_norms(s);
  struct Ranked {
    double magnitude;
    std::uint32_t frame, vertex;
  };
  std::vector<Ranked> ranked;
  ranked.reserve(std::size_t(n) * (nvs - nv0));
  for (std::uint32_t t = 0; t < std::uint32_t(n); ++t)
    for (std::uint32_t v = nv0; v < nvs; ++v) {
      const double* w = &coeffs[t * per + 3 * std::size_t(v)];
      ranked.push_back({std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]) * norms[v - nv0], t, v});
    }
  PerFrameCompression r;
  r.wavelets = ranked.size();
  const std::size_t base = std::size_t(n) * nv0;
  r.kept = stored > base ? std::min(stored - base, ranked.size()) : 0;
  r.stored = base + r.kept;
  std::nth_element(ranked.begin(), ranked.begin() + std::ptrdiff_t(r.kept), ranked.end(), [](const Ranked& a, const Ranked& b) {
    return a.magnitude != b.magnitude ? a.magnitude > b.magnitude : (a.frame != b.frame ? a.frame < b.frame : a.vertex < b.vertex);
  });
  for (std::size_t i = r.kept; i < ranked.size(); ++i)
    std::fill_n(&coeffs[ranked[i].frame * per + 3 * std::size_t(ranked[i].vertex)], 3, 0.0);
  r.errors.resize(std::size_t(n));
  parallel_for(std::uint32_t(n), 1, [&](std::uint32_t begin, std::uint32_t end) {
    for (std::uint32_t t = begin; t < end; ++t) {
      double* x = &coeffs[t * per];
      for (int j = 0; j < J; ++j) synthesize_transition(s, j, x, 3, false);
      const std::vector<double> layer = layer_positions(st, finest, J, int(t));
      double sum = 0, worst = 0;
      for (std::uint32_t p = 0; p < nvs; ++p) {
        const double d = std::hypot(x[3 * p] - layer[3 * p], x[3 * p + 1] - layer[3 * p + 1], x[3 * p + 2] - layer[3 * p + 2]);
        sum += d * d;
        worst = std::max(worst, d);
      }
      r.errors[t] = {worst / diagonal, std::sqrt(sum / nvs) / diagonal};
    }
  });
  return r;
}

}  // namespace sublift
