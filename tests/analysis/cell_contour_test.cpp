// Slices and iso-surfaces of volume lattices (core/analysis/cell_contour.h): the pieces reproduce affine
// fields exactly, their areas are the cross-sections of known solids, their normals point to
// the low side, and an iso-surface inside a lattice is closed and consistently oriented.
#include <cmath>
#include <map>
#include <string>
#include <tuple>

#include <gtest/gtest.h>

#include "core/analysis/cell_contour.h"
#include "core/base/errors.h"
#include "core/multires/hierarchy.h"
#include "core/io/lattice/shape_io.h"

namespace sublift {
namespace {

Shape load(const std::string& name) { return read_shape(std::string(SUBLIFT_ASSETS_DIR) + "/" + name); }

double area(const ContourMesh& m) {
  double a = 0.0;
  for (std::size_t t = 0; t < m.triangles(); ++t) {
    const double* p = &m.xyz[9 * t];
    const double u[3] = {p[3] - p[0], p[4] - p[1], p[5] - p[2]}, w[3] = {p[6] - p[0], p[7] - p[1], p[8] - p[2]};
    const double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    a += 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  }
  return a;
}

std::vector<double> affine(const Shape& s, double a, double b, double c, double d) {
  std::vector<double> f(s.positions.size() / 3);
  for (std::size_t v = 0; v < f.size(); ++v) {
    f[v] = a * s.positions[3 * v] + b * s.positions[3 * v + 1] + c * s.positions[3 * v + 2] + d;
  }
  return f;
}

// The pyramid (base [-1,1]^2 at z = 0, apex at z = 1.4) cut at z = 0.7: a unit square.
TEST(CellContourTest, PyramidSliceIsTheScaledBaseAndCarriesAffineValuesExactly) {
  const Shape s = load("pyramid_cell.lattice");
  const std::vector<double> g = affine(s, 1.0, 2.0, 3.0, 1.0);
  const double up[3] = {0, 0, 1};
  ContourMesh m;
  slice_cells(s.base, s.positions, up, 0.7, g, m);
  ASSERT_GT(m.triangles(), 0u);
  EXPECT_NEAR(area(m), 1.0, 1e-12);
  for (std::size_t v = 0; v < m.value.size(); ++v) {
    const double* p = &m.xyz[3 * v];
    EXPECT_NEAR(p[2], 0.7, 1e-14);
    EXPECT_NEAR(m.value[v], p[0] + 2 * p[1] + 3 * p[2] + 1.0, 1e-12);
    EXPECT_NEAR(m.normals[3 * v + 2], -1.0, 1e-12);  // towards the side below the plane
  }
}

// The 4x4x4 block [-1,1]^3 cut by the plane x + y = 0: a 2*sqrt(2) by 2 rectangle.
TEST(CellContourTest, ObliqueSliceOfABlockHasTheCrossSectionArea) {
  const Shape s = load("hex_block_4.lattice");
  const double r = 1.0 / std::sqrt(2.0);
  const double n[3] = {r, r, 0};
  ContourMesh m;
  slice_cells(s.base, s.positions, n, 0.0, affine(s, 0, 0, 0, 1), m);
  EXPECT_NEAR(area(m), 4.0 * std::sqrt(2.0), 1e-12);
  // The plane x + y + z = d cuts [-1,1]^3 in a hexagon; in the unit cube's coordinates
  // (u = (x + 1) / 2) it is u1 + u2 + u3 = s = (d + 3) / 2, of area sqrt(3)/2 (s^2 - 3 (s - 1)^2)
  // for 1 <= s <= 2, times 4 back in [-1,1]^3. With d = 0.3 the plane meets no lattice vertex,
  // face or cell centre, and no cell edge is parallel to it: tetrahedra cut two and two give
  // true quads.
  const double t = 1.0 / std::sqrt(3.0), d = 0.3, u = (d + 3.0) / 2.0;
  const double diagonal[3] = {t, t, t};
  ContourMesh hexagon;
  slice_cells(s.base, s.positions, diagonal, d * t, affine(s, 0, 0, 0, 1), hexagon);
  EXPECT_NEAR(area(hexagon), 4.0 * std::sqrt(3.0) / 2.0 * (u * u - 3.0 * (u - 1.0) * (u - 1.0)), 1e-12);
}

TEST(CellContourTest, IsoSurfaceOfAnAffineFieldIsItsPlaneWithNormalsTowardsLowValues) {
  const Shape s = load("hex_block_4.lattice");
  const std::vector<double> x = affine(s, 1, 0, 0, 0);
  ContourMesh m;
  contour_cells(s.base, s.positions, x, 0.25, x, m);
  EXPECT_NEAR(area(m), 4.0, 1e-12);
  for (std::size_t v = 0; v < m.value.size(); ++v) {
    EXPECT_NEAR(m.value[v], 0.25, 1e-14);
    EXPECT_NEAR(m.xyz[3 * v], 0.25, 1e-14);
    EXPECT_NEAR(m.normals[3 * v], -1.0, 1e-12);
  }
}

// A sphere-like iso-surface strictly inside the block: every edge of the triangle soup is used
// by exactly two triangles, in opposite directions (closed and consistently oriented, across
// the tetrahedra of one cell and across cells).
TEST(CellContourTest, IsoSurfaceInsideALatticeIsClosedAndConsistentlyOriented) {
  // Each lattice refined once (linear scheme): the cell-centre children are interior vertices,
  // among cells of every kind (hexahedra, prisms, pyramids, tetrahedra).
  for (const char* name : {"hex_block_4.lattice", "prism_ring.lattice", "pyramid_cell.lattice"}) {
    SCOPED_TRACE(name);
    const Shape base = load(name);
    Hierarchy h = make_hierarchy(base.base, 1, Scheme::Linear, 3);
    set_base(h, base.positions);
    Shape s;
    s.base = h.levels[1];
    s.positions = synthesize(h, 1);
    const Complex& c0 = h.levels[0];
    std::vector<double> f(s.positions.size() / 3);
    // A blob around one interior vertex (distance squared to it), level below its neighbours'.
    const std::size_t centre = c0.num_vertices + c0.num_edges() + c0.num_faces();  // first cell child
    double nearest = 1e300;
    for (std::size_t v = 0; v < f.size(); ++v) {
      double d = 0;
      for (int k = 0; k < 3; ++k) d += std::pow(s.positions[3 * v + k] - s.positions[3 * centre + k], 2);
      f[v] = d;
      if (v != centre) nearest = std::min(nearest, d);
    }
    ContourMesh m;
    contour_cells(s.base, s.positions, f, 0.5 * nearest, f, m);
    ASSERT_GT(m.triangles(), 0u);
    // Key points by their rounded coordinates (the same cut point is computed from the same
    // two nodes in neighbouring tetrahedra, but maybe in the other order).
    using Key = std::tuple<long long, long long, long long>;
    auto key = [&](std::size_t v) {
      return Key{std::llround(m.xyz[3 * v] * 1e9), std::llround(m.xyz[3 * v + 1] * 1e9), std::llround(m.xyz[3 * v + 2] * 1e9)};
    };
    std::map<std::pair<Key, Key>, int> directed;
    for (std::size_t t = 0; t < m.triangles(); ++t) {
      for (int i = 0; i < 3; ++i) ++directed[{key(3 * t + i), key(3 * t + (i + 1) % 3)}];
    }
    for (const auto& [edge, count] : directed) {
      EXPECT_EQ(count, 1);
      const auto back = directed.find({edge.second, edge.first});
      ASSERT_NE(back, directed.end()) << "open edge";
      EXPECT_EQ(back->second, 1);
    }
  }
}

TEST(CellContourTest, RefusesSurfacesAndMismatchedSizes) {
  const Shape s = load("hex_block_4.lattice");
  const std::vector<double> x = affine(s, 1, 0, 0, 0);
  ContourMesh m;
  EXPECT_THROW(contour_cells(s.base, s.positions, std::span(x).first(3), 0.0, x, m), Error);
  Complex surface = s.base;
  surface.dim = 2;
  EXPECT_THROW(contour_cells(surface, s.positions, x, 0.0, x, m), Error);
}

}  // namespace
}  // namespace sublift
