#include "core/analysis/wavelet_colour.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/base/errors.h"

namespace sublift {

std::vector<float> wavelet_magnitude_field(const Hierarchy& h, std::span<const double> gains, int l) {
  if (l < 0 || l >= h.finest_level())
    throw Error("colour level " + std::to_string(l) + " is outside 0.." + std::to_string(h.finest_level() - 1));
  if (h.channels < 3) throw Error("colouring by |w| needs positions (3 channels)");
  const std::size_t ch = static_cast<std::size_t>(h.channels);
  const double gain = static_cast<std::size_t>(l) < gains.size() ? gains[static_cast<std::size_t>(l)] : 1.0;
  const std::uint32_t lo = h.num_vertices(l), hi = h.num_vertices(l + 1);
  std::vector<float> out(h.num_vertices(h.finest_level()), 0.0f);
  float largest = 0.0f;
  for (std::uint32_t v = lo; v < hi; ++v) {
    const double* w = &h.coeffs[std::size_t(v) * ch];
    const auto m = static_cast<float>(std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]) * std::abs(gain));
    out[v] = m;
    largest = std::max(largest, m);
  }
  // Carry the values to the finest level by linear refinement (children numbered [v|e|f|c]).
  for (int k = l + 1; k < h.finest_level(); ++k) {
    const Complex& c = h.levels[static_cast<std::size_t>(k)];
    const std::uint32_t nv = c.num_vertices, ne = c.num_edges(), nf = c.num_faces();
    for (std::uint32_t e = 0; e < ne; ++e) out[nv + e] = 0.5f * (out[c.edge_verts[2 * e]] + out[c.edge_verts[2 * e + 1]]);
    for (std::uint32_t f = 0; f < nf; ++f) {
      float sum = 0.0f;
      for (const std::uint32_t v : c.faces.row(f)) sum += out[v];
      out[nv + ne + f] = c.faces.size(f) > 0 ? sum / static_cast<float>(c.faces.size(f)) : 0.0f;
    }
    if (c.cell_verts.rows() == c.num_cells()) {
      for (std::uint32_t cell = 0; cell < c.num_cells(); ++cell) {
        float sum = 0.0f;
        for (const std::uint32_t v : c.cell_verts.row(cell)) sum += out[v];
        const auto count = c.cell_verts.size(cell);
        out[nv + ne + nf + cell] = count > 0 ? sum / static_cast<float>(count) : 0.0f;
      }
    }
  }
  if (largest > 0.0f)
    for (float& v : out) v /= largest;
  return out;
}

}  // namespace sublift
