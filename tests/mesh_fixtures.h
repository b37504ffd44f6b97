#pragma once
// Base meshes and lattices generated in code, shared by the peer tests and the benchmarks:
// a regular quad torus, a cube and an n^3 hexahedral block. Positions are xyz doubles, three
// per vertex, in vertex order.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <numeric>
#include <random>
#include <vector>

#include "core/base/csr.h"

namespace sublift::fixtures {

/// A polygon mesh as the engine's builders take it.
struct Polygons {
  std::uint32_t num_vertices = 0;
  Csr faces;
  std::vector<double> positions;
};

/// A lattice as complex_from_cells takes it: face loops and cells as lists of loops.
struct Cells {
  std::uint32_t num_vertices = 0;
  Csr face_loops, cell_faces;
  std::vector<double> positions;
};

inline void push_row(Csr& csr, std::initializer_list<std::uint32_t> items) {
  csr.items.insert(csr.items.end(), items);
  csr.offsets.push_back(static_cast<std::uint32_t>(csr.items.size()));
}

/// Regular quad torus of nu x nv quads (every vertex valence 4). Vertex (i, j) is j * nu + i;
/// radii R = 2 and r = 0.7, with a small deterministic wobble so no coordinate is special.
inline Polygons torus(std::uint32_t nu, std::uint32_t nv) {
  Polygons m;
  m.num_vertices = nu * nv;
  m.positions.reserve(3 * std::size_t{m.num_vertices});
  for (std::uint32_t j = 0; j < nv; ++j)
    for (std::uint32_t i = 0; i < nu; ++i) {
      const double u = 2 * std::numbers::pi * i / nu, v = 2 * std::numbers::pi * j / nv;
      const double r = 0.7 + 0.05 * std::sin(3 * u + 2 * v);
      m.positions.insert(m.positions.end(),
                         {(2 + r * std::cos(v)) * std::cos(u), (2 + r * std::cos(v)) * std::sin(u), r * std::sin(v)});
    }
  for (std::uint32_t j = 0; j < nv; ++j)
    for (std::uint32_t i = 0; i < nu; ++i) {
      const std::uint32_t i1 = (i + 1) % nu, j1 = (j + 1) % nv;
      push_row(m.faces, {j * nu + i, j * nu + i1, j1 * nu + i1, j1 * nu + i});
    }
  return m;
}

/// A quad, a pentagon and a triangle around one inner vertex (2), the rest boundary: 7
/// vertices, no positions (topology tests).
inline Polygons mixed_patch() {
  Polygons m;
  m.num_vertices = 7;
  push_row(m.faces, {0, 1, 2, 3});
  push_row(m.faces, {1, 4, 5, 6, 2});
  push_row(m.faces, {3, 2, 6});
  return m;
}

/// The octahedron's 8 outward triangles on 6 vertices, no positions.
inline Polygons octahedron() {
  Polygons m;
  m.num_vertices = 6;
  const std::uint32_t t[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (const auto& f : t) push_row(m.faces, {f[0], f[1], f[2]});
  return m;
}

/// `m` as another tool may write it: vertices renumbered by a random permutation (perm[old] =
/// new; positions follow when present), faces reordered and each face's corners rotated.
inline Polygons shuffled(const Polygons& m, unsigned seed, std::vector<std::uint32_t>* perm_out = nullptr) {
  std::mt19937 rng(seed);
  std::vector<std::uint32_t> perm(m.num_vertices);
  std::iota(perm.begin(), perm.end(), 0u);
  std::shuffle(perm.begin(), perm.end(), rng);
  std::vector<std::size_t> order(m.faces.rows());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::shuffle(order.begin(), order.end(), rng);
  Polygons out{m.num_vertices, {}, {}};
  for (std::size_t f : order) {
    const auto row = m.faces.row(f);
    const std::size_t r = rng() % row.size();
    for (std::size_t k = 0; k < row.size(); ++k) out.faces.items.push_back(perm[row[(k + r) % row.size()]]);
    out.faces.offsets.push_back(static_cast<std::uint32_t>(out.faces.items.size()));
  }
  if (!m.positions.empty()) {
    out.positions.resize(m.positions.size());
    for (std::uint32_t v = 0; v < m.num_vertices; ++v)
      for (int k = 0; k < 3; ++k) out.positions[3 * std::size_t(perm[v]) + k] = m.positions[3 * std::size_t(v) + k];
  }
  if (perm_out) *perm_out = std::move(perm);
  return out;
}

/// Unit cube [0,1]^3, outward-oriented quads.
inline Polygons cube() {
  Polygons m;
  m.num_vertices = 8;
  for (std::uint32_t k = 0; k < 8; ++k)
    m.positions.insert(m.positions.end(), {double(k & 1), double((k >> 1) & 1), double((k >> 2) & 1)});
  const std::uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                     {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) push_row(m.faces, {q[0], q[1], q[2], q[3]});
  return m;
}

/// Block of n^3 unit hexahedra: (n+1)^3 vertices, vertex (x, y, z) = (z (n+1) + y) (n+1) + x;
/// every cell lists its own 6 quads (shared faces appear twice and are merged by the builder).
inline Cells hex_block(std::uint32_t n) {
  Cells m;
  const std::uint32_t s = n + 1;
  m.num_vertices = s * s * s;
  for (std::uint32_t z = 0; z < s; ++z)
    for (std::uint32_t y = 0; y < s; ++y)
      for (std::uint32_t x = 0; x < s; ++x) m.positions.insert(m.positions.end(), {double(x), double(y), double(z)});
  auto id = [s](std::uint32_t x, std::uint32_t y, std::uint32_t z) { return (z * s + y) * s + x; };
  for (std::uint32_t z = 0; z < n; ++z)
    for (std::uint32_t y = 0; y < n; ++y)
      for (std::uint32_t x = 0; x < n; ++x) {
        const std::uint32_t c[8] = {id(x, y, z),         id(x + 1, y, z),         id(x, y + 1, z),
                                    id(x + 1, y + 1, z), id(x, y, z + 1),         id(x + 1, y, z + 1),
                                    id(x, y + 1, z + 1), id(x + 1, y + 1, z + 1)};
        const std::uint32_t first = static_cast<std::uint32_t>(m.face_loops.rows());
        push_row(m.face_loops, {c[0], c[2], c[3], c[1]});  // z-
        push_row(m.face_loops, {c[4], c[5], c[7], c[6]});  // z+
        push_row(m.face_loops, {c[0], c[1], c[5], c[4]});  // y-
        push_row(m.face_loops, {c[2], c[6], c[7], c[3]});  // y+
        push_row(m.face_loops, {c[0], c[4], c[6], c[2]});  // x-
        push_row(m.face_loops, {c[1], c[3], c[7], c[5]});  // x+
        push_row(m.cell_faces, {first, first + 1, first + 2, first + 3, first + 4, first + 5});
      }
  return m;
}

// ---- high valence (issue 18: limit stencils whose cost must stay gentle) --------------------

/// A closed wavy prism over an n-gon (caps of n vertices, n side quads), jittered so every
/// rotational frequency is present: after one level each cap's face point has valence n.
inline Polygons ngon_prism(std::uint32_t n, unsigned seed = 1) {
  Polygons m;
  m.num_vertices = 2 * n;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.02, 0.02);
  for (std::uint32_t z = 0; z < 2; ++z)
    for (std::uint32_t i = 0; i < n; ++i) {
      const double a = 2 * std::numbers::pi * i / n;
      const double r = 1.0 + 0.1 * std::cos(5 * a) + jitter(rng);
      m.positions.insert(m.positions.end(), {r * std::cos(a), r * std::sin(a), z + 0.1 * std::sin(3 * a) + jitter(rng)});
    }
  m.faces.offsets = {0};
  for (std::uint32_t i = 0; i < n; ++i) m.faces.items.push_back(n - 1 - i);  // bottom, facing down
  m.faces.offsets.push_back(n);
  for (std::uint32_t i = 0; i < n; ++i) m.faces.items.push_back(n + i);
  m.faces.offsets.push_back(2 * n);
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t j = (i + 1) % n;
    push_row(m.faces, {i, j, n + j, n + i});
  }
  return m;
}

/// A cone of n triangles around apex 0 (ring 1..n, open at the rim): a valence-n vertex.
inline Polygons triangle_cone(std::uint32_t n) {
  Polygons m;
  m.num_vertices = n + 1;
  m.positions = {0.1, -0.05, 0.8};
  m.faces.offsets = {0};
  for (std::uint32_t i = 0; i < n; ++i) {
    const double a = 2 * std::numbers::pi * i / n;
    const double r = 1.0 + 0.15 * std::sin(4 * a);
    m.positions.insert(m.positions.end(), {r * std::cos(a), r * std::sin(a), 0.2 * std::cos(7 * a)});
    push_row(m.faces, {0u, 1 + i, 1 + (i + 1) % n});
  }
  return m;
}

/// n quads around vertex 0 (edge vertices 1..n, corners n+1..2n), or, with `mixed`, every
/// third face a triangle instead (a fan without rotational symmetry).
inline Polygons quad_fan(std::uint32_t n, bool mixed = false) {
  Polygons m;
  m.num_vertices = 2 * n + 1;
  m.positions = {0.0, 0.0, 0.4};
  for (std::uint32_t i = 0; i < n; ++i) {
    const double a = 2 * std::numbers::pi * i / n;
    m.positions.insert(m.positions.end(), {std::cos(a), std::sin(a), 0.1 * std::sin(2 * a)});
  }
  for (std::uint32_t i = 0; i < n; ++i) {
    const double b = 2 * std::numbers::pi * (i + 0.5) / n;
    m.positions.insert(m.positions.end(), {1.4 * std::cos(b), 1.4 * std::sin(b), -0.1 * std::cos(3 * b)});
  }
  m.faces.offsets = {0};
  for (std::uint32_t i = 0; i < n; ++i) {
    if (mixed && i % 3 == 2)
      push_row(m.faces, {0u, 1 + i, 1 + (i + 1) % n});
    else
      push_row(m.faces, {0u, 1 + i, n + 1 + i, 1 + (i + 1) % n});
  }
  return m;
}

}  // namespace sublift::fixtures
