#include "core/complex/shapes.h"

#include <cmath>
#include <numbers>

#include "core/complex/complex_build.h"

namespace sublift {

SurfaceMesh make_quad_torus(int n, int m, double R, double r) {
  SurfaceMesh t;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const double u = 2 * std::numbers::pi * i / n, v = 2 * std::numbers::pi * j / m;
      t.positions.emplace_back((R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v));
    }
  auto id = [&](int i, int j) { return static_cast<std::uint32_t>(((i + n) % n) * m + (j + m) % m); };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const std::uint32_t f[4] = {id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)};
      t.add_face(f);
    }
  return t;
}

Complex make_curve_loop(int n, std::vector<double>& positions) {
  Csr lines;
  positions.clear();
  for (int i = 0; i < n; ++i) {
    const double a = 2 * std::numbers::pi * i / n;
    positions.insert(positions.end(), {std::cos(a), std::sin(a), 0.0});
    lines.items.push_back(static_cast<std::uint32_t>(i));
  }
  lines.items.push_back(0);
  lines.offsets.push_back(static_cast<std::uint32_t>(lines.items.size()));
  return complex_from_polylines(static_cast<std::uint32_t>(n), lines);
}

Complex make_hex_block(int n, std::vector<double>& positions) {
  const int s = n + 1;
  auto id = [&](int i, int j, int k) { return static_cast<std::uint32_t>((k * s + j) * s + i); };
  positions.clear();
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) positions.insert(positions.end(), {double(i), double(j), double(k)});
  Csr loops, cells;
  auto quad = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
    loops.items.insert(loops.items.end(), {a, b, c, d});
    loops.offsets.push_back(static_cast<std::uint32_t>(loops.items.size()));
    cells.items.push_back(static_cast<std::uint32_t>(loops.rows() - 1));
  };
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        quad(id(i, j, k), id(i, j + 1, k), id(i + 1, j + 1, k), id(i + 1, j, k));                  // bottom
        quad(id(i, j, k + 1), id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1));  // top
        quad(id(i, j, k), id(i + 1, j, k), id(i + 1, j, k + 1), id(i, j, k + 1));                  // front
        quad(id(i, j + 1, k), id(i, j + 1, k + 1), id(i + 1, j + 1, k + 1), id(i + 1, j + 1, k));  // back
        quad(id(i, j, k), id(i, j, k + 1), id(i, j + 1, k + 1), id(i, j + 1, k));                  // left
        quad(id(i + 1, j, k), id(i + 1, j + 1, k), id(i + 1, j + 1, k + 1), id(i + 1, j, k + 1));  // right
        cells.offsets.push_back(static_cast<std::uint32_t>(cells.items.size()));
      }
  return complex_from_cells(static_cast<std::uint32_t>(s * s * s), loops, cells);
}

std::vector<double> flatten_positions(const SurfaceMesh& mesh) {
  std::vector<double> x;
  x.reserve(mesh.positions.size() * 3);
  for (const auto& p : mesh.positions) x.insert(x.end(), {p.x, p.y, p.z});
  return x;
}

}  // namespace sublift
