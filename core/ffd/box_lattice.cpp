#include "core/ffd/box_lattice.h"

#include <cmath>
#include <cstdint>
#include <string>

#include "core/complex/complex_build.h"
#include "core/base/errors.h"

namespace sublift {

Shape make_box_lattice(const std::array<double, 3>& lo_in, const std::array<double, 3>& hi_in, int nx, int ny,
                       int nz, double margin) {
  for (int a = 0; a < 3; ++a) {
    if (!std::isfinite(lo_in[a]) || !std::isfinite(hi_in[a])) throw Error("box lattice: bounds are not finite");
    if (lo_in[a] > hi_in[a]) throw Error("box lattice: lower bound above upper bound on axis " + std::to_string(a));
  }
  if (!std::isfinite(margin) || margin < 0) throw Error("box lattice: margin must be finite and >= 0");
  if (nx < 1 || ny < 1 || nz < 1) throw Error("box lattice: cell counts must be >= 1");
  const double cells = double(nx) * double(ny) * double(nz);
  if (cells >= 1e6)
    throw Error("box lattice: " + std::to_string(static_cast<long long>(cells)) + " cells (limit 999999)");

  std::array<double, 3> lo = lo_in, hi = hi_in;
  double diag2 = 0;
  for (int a = 0; a < 3; ++a) diag2 += (hi[a] - lo[a]) * (hi[a] - lo[a]);
  double diag = std::sqrt(diag2);
  if (!std::isfinite(diag)) throw Error("box lattice: box too large");
  // Zero extents would make flat cells that no point can be located in.
  const double pad = diag > 0 ? 0.1 * diag : 1.0;
  for (int a = 0; a < 3; ++a)
    if (hi[a] - lo[a] <= 1e-12 * diag) {
      const double c = 0.5 * (lo[a] + hi[a]);
      lo[a] = c - 0.5 * pad;
      hi[a] = c + 0.5 * pad;
    }
  diag2 = 0;
  for (int a = 0; a < 3; ++a) diag2 += (hi[a] - lo[a]) * (hi[a] - lo[a]);
  diag = std::sqrt(diag2);
  for (int a = 0; a < 3; ++a) lo[a] -= margin * diag, hi[a] += margin * diag;

  const std::uint32_t sx = std::uint32_t(nx) + 1, sy = std::uint32_t(ny) + 1, sz = std::uint32_t(nz) + 1;
  auto id = [&](std::uint32_t i, std::uint32_t j, std::uint32_t k) { return (k * sy + j) * sx + i; };
  const int n[3] = {nx, ny, nz};
  Shape s;
  s.positions.reserve(std::size_t(sx) * sy * sz * 3);
  for (std::uint32_t k = 0; k < sz; ++k)
    for (std::uint32_t j = 0; j < sy; ++j)
      for (std::uint32_t i = 0; i < sx; ++i) {
        const std::uint32_t ijk[3] = {i, j, k};
        for (int a = 0; a < 3; ++a) {
          // The last layer is exactly hi, not lo + n * step.
          const double t = double(ijk[a]) / double(n[a]);
          s.positions.push_back(ijk[a] == std::uint32_t(n[a]) ? hi[a] : lo[a] + t * (hi[a] - lo[a]));
        }
      }
  Csr loops, cell_faces;
  loops.items.reserve(std::size_t(cells) * 24);
  auto quad = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
    loops.items.insert(loops.items.end(), {a, b, c, d});
    loops.offsets.push_back(static_cast<std::uint32_t>(loops.items.size()));
    cell_faces.items.push_back(static_cast<std::uint32_t>(loops.rows() - 1));
  };
  // Outward loops for a positively oriented cell (x right, y back, z up).
  for (std::uint32_t k = 0; k + 1 < sz; ++k)
    for (std::uint32_t j = 0; j + 1 < sy; ++j)
      for (std::uint32_t i = 0; i + 1 < sx; ++i) {
        quad(id(i, j, k), id(i, j + 1, k), id(i + 1, j + 1, k), id(i + 1, j, k));
        quad(id(i, j, k + 1), id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1));
        quad(id(i, j, k), id(i + 1, j, k), id(i + 1, j, k + 1), id(i, j, k + 1));
        quad(id(i, j + 1, k), id(i, j + 1, k + 1), id(i + 1, j + 1, k + 1), id(i + 1, j + 1, k));
        quad(id(i, j, k), id(i, j, k + 1), id(i, j + 1, k + 1), id(i, j + 1, k));
        quad(id(i + 1, j, k), id(i + 1, j + 1, k), id(i + 1, j + 1, k + 1), id(i + 1, j, k + 1));
        cell_faces.offsets.push_back(static_cast<std::uint32_t>(cell_faces.items.size()));
      }
  s.base = complex_from_cells(sx * sy * sz, loops, cell_faces);
  return s;
}

}  // namespace sublift
