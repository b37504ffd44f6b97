// Free-form deformation (issue 6): box lattices, binding a model into the finest level of a
// lattice hierarchy, deforming it fully and incrementally.
//
// Oracles: rest reconstruction (the model comes back where it was), affine invariance (an affine
// map of the level-0 lattice with zero details moves the model by the same map, because cubic
// subdivision and trilinear/barycentric coordinates both reproduce affine maps), locality against
// the session's own list of changed lattice vertices, trilinear weights of an axis-aligned box
// and barycentric coordinates of a tetrahedron computed here from their definitions.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "core/ffd/box_lattice.h"
#include "core/base/errors.h"
#include "core/ffd/ffd.h"
#include "core/multires/hierarchy.h"
#include "core/io/mesh/mesh_import.h"
#include "core/edit/session.h"
#include "core/io/lattice/shape_io.h"
#include "tests/test_lattices.h"

namespace sublift {
namespace {

using Vec = std::array<double, 3>;

struct Sample {
  std::string name;
  Complex base;
  std::vector<double> xyz;
};

std::vector<Sample> sample_lattices() {
  std::vector<Sample> out;
  for (const char* name : {"cube_cell", "feature_surface", "hex_block_4", "prism_ring", "pyramid_cell", "swept_quads",
                           "ffd/bent_tube", "ffd/pyramid_cap", "ffd/torus_ring", "ffd/crease_feature"}) {
    Shape s = read_shape(std::string(SUBLIFT_ASSETS_DIR) + "/" + name + ".lattice");
    out.push_back({name, std::move(s.base), std::move(s.positions)});
  }
  Shape box = make_box_lattice({-1.0, -0.5, 0.0}, {1.0, 0.5, 0.3}, 4, 3, 2, 0.1);
  out.push_back({"box", std::move(box.base), std::move(box.positions)});
  return out;
}

// The distinct vertices of finest cell k, from its faces.
std::vector<std::uint32_t> cell_vertices(const Complex& c, std::uint32_t k) {
  std::vector<std::uint32_t> vs;
  for (std::uint32_t f : c.cell_faces.row(k))
    for (std::uint32_t v : c.faces.row(f))
      if (std::find(vs.begin(), vs.end(), v) == vs.end()) vs.push_back(v);
  return vs;
}

double diagonal(const std::vector<double>& xyz) {
  const auto bb = bounding_box(xyz.data(), xyz.size() / 3);
  double d2 = 0;
  for (int a = 0; a < 3; ++a) d2 += (bb[1][a] - bb[0][a]) * (bb[1][a] - bb[0][a]);
  return std::sqrt(d2);
}

// Model points: finest lattice vertices (up to about 4000), random points near the middle of cells (random
// convex combinations of a cell's vertices pulled 10% toward its vertex mean), and points well
// outside the lattice's bounding box. `inside` counts the first two kinds (they come first).
struct Model {
  std::vector<double> xyz;
  std::size_t inside = 0;
};

Model sample_model(const Complex& fine, const std::vector<double>& x, std::uint64_t seed) {
  Model m;
  const std::size_t nv = x.size() / 3, stride = std::max<std::size_t>(1, nv / 4000);
  for (std::size_t v = 0; v < nv; v += stride) m.xyz.insert(m.xyz.end(), {x[3 * v], x[3 * v + 1], x[3 * v + 2]});
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(1e-9, 1.0);
  const std::uint32_t nc = fine.num_cells(), step = std::max<std::uint32_t>(1, nc / 1500);
  for (std::uint32_t k = 0; k < nc; k += step) {
    const auto vs = cell_vertices(fine, k);
    Vec mean{0, 0, 0};
    for (std::uint32_t v : vs)
      for (int a = 0; a < 3; ++a) mean[a] += x[3 * v + a] / double(vs.size());
    for (int rep = 0; rep < 2; ++rep) {
      std::vector<double> w(vs.size());
      double sum = 0;
      for (double& wi : w) sum += wi = std::pow(-std::log(u(rng)), 3.0);
      Vec p{0, 0, 0};
      for (std::size_t i = 0; i < vs.size(); ++i)
        for (int a = 0; a < 3; ++a) p[a] += w[i] / sum * x[3 * vs[i] + a];
      for (int a = 0; a < 3; ++a) m.xyz.push_back(mean[a] + 0.9 * (p[a] - mean[a]));
    }
  }
  m.inside = m.xyz.size() / 3;
  const auto bb = bounding_box(x.data(), x.size() / 3);
  for (int i = 0; i < 40; ++i)
    for (int a = 0; a < 3; ++a) {
      const double c = 0.5 * (bb[0][a] + bb[1][a]), h = 0.5 * (bb[1][a] - bb[0][a]) + 1e-3;
      const double dir = (i >> a & 1) ? 1.0 : -1.0;
      m.xyz.push_back(c + dir * h * (1.2 + 0.3 * u(rng)));
    }
  return m;
}

// A fixed affine map: rotation, shear and non-uniform scale, and a translation.
constexpr double kA[3][3] = {{1.2, 0.3, -0.4}, {-0.2, 0.9, 0.5}, {0.35, -0.1, 1.4}};
constexpr double kB[3] = {0.7, -1.3, 2.1};

std::vector<double> affine(const std::vector<double>& xyz) {
  std::vector<double> out(xyz.size());
  for (std::size_t i = 0; i < xyz.size(); i += 3)
    for (int r = 0; r < 3; ++r)
      out[i + r] = kA[r][0] * xyz[i] + kA[r][1] * xyz[i + 1] + kA[r][2] * xyz[i + 2] + kB[r];
  return out;
}

double max_dist(const std::vector<double>& a, const std::vector<double>& b, std::size_t from, std::size_t to) {
  double m = 0;
  for (std::size_t i = from; i < to; ++i) {
    double d2 = 0;
    for (int r = 0; r < 3; ++r) d2 += (a[3 * i + r] - b[3 * i + r]) * (a[3 * i + r] - b[3 * i + r]);
    m = std::max(m, std::sqrt(d2));
  }
  return m;
}

bool same_bits(const double* a, const double* b, std::size_t n) { return std::memcmp(a, b, n * sizeof(double)) == 0; }

Hierarchy two_levels(const Sample& s) {
  Hierarchy h = make_hierarchy(s.base, 2, Scheme::Cubic, 3);
  set_base(h, s.xyz);
  return h;
}

// ---- box lattices -------------------------------------------------------------------------

TEST(BoxLattice, CountsValidityAndCorners) {
  const int nx = 3, ny = 2, nz = 5;
  const Shape s = make_box_lattice({0, 0, 0}, {3, 4, 12}, nx, ny, nz, 0.25);
  EXPECT_NO_THROW(validate(s.base));
  EXPECT_EQ(s.base.dim, 3);
  EXPECT_EQ(s.base.num_vertices, std::uint32_t((nx + 1) * (ny + 1) * (nz + 1)));
  EXPECT_EQ(s.base.num_cells(), std::uint32_t(nx * ny * nz));
  EXPECT_EQ(s.base.num_faces(), std::uint32_t((nx + 1) * ny * nz + nx * (ny + 1) * nz + nx * ny * (nz + 1)));
  EXPECT_EQ(s.base.num_edges(), std::uint32_t(nx * (ny + 1) * (nz + 1) + (nx + 1) * ny * (nz + 1) + (nx + 1) * (ny + 1) * nz));
  for (std::uint32_t k = 0; k < s.base.num_cells(); ++k) {
    ASSERT_EQ(s.base.cell_faces.size(k), 6u);
    for (std::uint32_t f : s.base.cell_faces.row(k)) EXPECT_EQ(s.base.faces.size(f), 4u);
  }
  // Diagonal 13, margin 0.25 * 13 on every side; vertex (i, j, k) at (k * 3 + j) * 4 + i.
  const double m = 0.25 * 13.0;
  const auto bb = bounding_box(s.positions.data(), s.base.num_vertices);
  EXPECT_DOUBLE_EQ(bb[0][0], -m);
  EXPECT_DOUBLE_EQ(bb[1][2], 12 + m);
  const std::uint32_t v = (2 * 3 + 1) * 4 + 3;  // (3, 1, 2)
  EXPECT_DOUBLE_EQ(s.positions[3 * v], 3 + m);
  EXPECT_NEAR(s.positions[3 * v + 1], -m + (4 + 2 * m) / 2, 1e-12);
  EXPECT_NEAR(s.positions[3 * v + 2], -m + 2 * (12 + 2 * m) / 5, 1e-12);
}

TEST(BoxLattice, FlatAndPointBoxesGetThickness) {
  const Shape flat = make_box_lattice({0, 0, 1}, {2, 1, 1}, 2, 2, 1, 0.0);
  const auto bb = bounding_box(flat.positions.data(), flat.base.num_vertices);
  EXPECT_GT(bb[1][2] - bb[0][2], 0.1);
  EXPECT_NEAR(0.5 * (bb[0][2] + bb[1][2]), 1.0, 1e-12);
  const Shape point = make_box_lattice({5, 5, 5}, {5, 5, 5}, 1, 1, 1, 0.0);
  const auto pb = bounding_box(point.positions.data(), point.base.num_vertices);
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(pb[1][a] - pb[0][a], 1.0, 1e-12);
}

TEST(BoxLattice, BadInputThrows) {
  const double nan = std::nan("");
  EXPECT_THROW(make_box_lattice({0, 0, nan}, {1, 1, 1}, 2, 2, 2, 0.1), Error);
  EXPECT_THROW(make_box_lattice({0, 0, 0}, {1, INFINITY, 1}, 2, 2, 2, 0.1), Error);
  EXPECT_THROW(make_box_lattice({0, 0, 0}, {1, 1, 1}, 0, 2, 2, 0.1), Error);
  EXPECT_THROW(make_box_lattice({0, 0, 0}, {1, 1, 1}, 100, 100, 100, 0.1), Error);
  EXPECT_THROW(make_box_lattice({2, 0, 0}, {1, 1, 1}, 2, 2, 2, 0.1), Error);
  EXPECT_THROW(make_box_lattice({0, 0, 0}, {1, 1, 1}, 2, 2, 2, -0.1), Error);
}

// ---- weights against their definitions ------------------------------------------------------

TEST(FfdWeights, TrilinearInAxisAlignedBox) {
  const int n[3] = {3, 2, 4};
  const Shape s = make_box_lattice({0, 0, 0}, {3, 2, 4}, n[0], n[1], n[2], 0.0);  // unit cells
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.01, 0.99);
  std::vector<double> model;
  for (int i = 0; i < 200; ++i) model.insert(model.end(), {3 * u(rng), 2 * u(rng), 4 * u(rng)});
  const FfdBinding b = bind_model(s.base, s.positions, model);
  ASSERT_EQ(b.report.bound, 200u);
  EXPECT_EQ(b.report.tet_split, 0u);
  for (std::uint32_t i = 0; i < 200; ++i) {
    int c[3];
    double t[3];
    for (int a = 0; a < 3; ++a) c[a] = int(std::floor(model[3 * i + a])), t[a] = model[3 * i + a] - c[a];
    double sum = 0;
    for (int corner = 0; corner < 8; ++corner) {
      const int d[3] = {corner & 1, corner >> 1 & 1, corner >> 2 & 1};
      const std::uint32_t v = std::uint32_t(((c[2] + d[2]) * (n[1] + 1) + c[1] + d[1]) * (n[0] + 1) + c[0] + d[0]);
      double expect = 1;
      for (int a = 0; a < 3; ++a) expect *= d[a] ? t[a] : 1 - t[a];
      double got = 0;
      const auto row = b.stencil.row(i);
      for (std::size_t k = 0; k < row.size(); ++k)
        if (row[k] == v) got += b.weight[b.stencil.offsets[i] + k];
      EXPECT_NEAR(got, expect, 1e-12) << "point " << i << " corner " << corner;
      sum += got;
    }
    EXPECT_NEAR(sum, 1.0, 1e-12);
  }
}

TEST(FfdWeights, TetSplitOfATetrahedronIsBarycentric) {
  const Complex tet = testing::tetra_cell();
  const std::vector<double> x = {0.1, 0.0, 0.2, 2.0, 0.3, 0.0, 0.4, 1.8, 0.1, 0.5, 0.6, 1.5};
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> model;
  std::vector<std::array<double, 4>> bary;
  for (int i = 0; i < 100; ++i) {
    std::array<double, 4> l;
    double s = 0;
    for (double& li : l) s += li = -std::log(u(rng) + 1e-12);
    for (double& li : l) li /= s;
    bary.push_back(l);
    for (int a = 0; a < 3; ++a) model.push_back(l[0] * x[a] + l[1] * x[3 + a] + l[2] * x[6 + a] + l[3] * x[9 + a]);
  }
  const FfdBinding b = bind_model(tet, x, model);
  ASSERT_EQ(b.report.bound, 100u);
  EXPECT_EQ(b.report.tet_split, 100u);
  for (std::uint32_t i = 0; i < 100; ++i) {
    std::array<double, 4> got{0, 0, 0, 0};
    const auto row = b.stencil.row(i);
    for (std::size_t k = 0; k < row.size(); ++k) got[row[k]] += b.weight[b.stencil.offsets[i] + k];
    for (int v = 0; v < 4; ++v) EXPECT_NEAR(got[v], bary[i][v], 1e-12) << "point " << i << " vertex " << v;
  }
}

// ---- every sample lattice, two cubic levels -------------------------------------------------

TEST(Ffd, RestAffineAndOutsideOnSampleLattices) {
  std::vector<Sample> samples = sample_lattices();
  const std::string vtk = std::string(SUBLIFT_SHARED_DATA) + "/lattices/vtk/s01c_cube.vtk";
  if (std::filesystem::exists(vtk)) {
    Shape s = read_shape(vtk);
    samples.push_back({"s01c_cube.vtk", std::move(s.base), std::move(s.positions)});
  } else {
    std::printf("note: %s absent (SUBLIFT_SHARED_DATA); shared lattice skipped\n", vtk.c_str());
  }
  // Two cubic levels (the case), and level 0 itself, where tetrahedra, pyramids and
  // wedges of the samples are bound through the tet split.
  for (const int levels : {2, 0})
  for (const Sample& s : samples) {
    SCOPED_TRACE(s.name + ", levels " + std::to_string(levels));
    Hierarchy h = make_hierarchy(s.base, levels, Scheme::Cubic, 3);
    set_base(h, s.xyz);
    const std::vector<double> fine = synthesize(h, levels);
    const Complex& fc = h.levels[static_cast<std::size_t>(levels)];
    const Model m = sample_model(fc, fine, 17);
    const std::size_t n = m.xyz.size() / 3;
    const double size = diagonal(m.xyz);
    // Affine map of level 0 with zero details, synthesised independently of the binding.
    Hierarchy moved = make_hierarchy(s.base, levels, Scheme::Cubic, 3);
    set_base(moved, affine(s.xyz));
    const std::vector<double> moved_fine = synthesize(moved, levels);
    const std::vector<double> expect = affine(m.xyz);

    for (Outside mode : {Outside::Stay, Outside::Nearest}) {
      FfdOptions opt;
      opt.outside = mode;
      const FfdBinding b = bind_model(fc, fine, m.xyz, opt);
      ASSERT_EQ(b.num_model_vertices(), n);
      if (mode == Outside::Stay)
        std::printf("%-18s levels %d, finest cells %6u, model points %6zu: bound %zu (tet split %zu), outside %zu, %.1f ms\n",
                    s.name.c_str(), levels, fc.num_cells(), n, b.report.bound, b.report.tet_split, b.report.outside,
                    b.report.ms);
      // Lattice vertices and points near cell middles are inside; points beyond the lattice's
      // bounding box are not.
      for (std::size_t i = 0; i < n; ++i)
        ASSERT_EQ(b.placement[i] == Placement::Inside, i < m.inside) << "point " << i;
      EXPECT_EQ(b.report.bound, m.inside);
      EXPECT_EQ(b.report.outside, n - m.inside);
      EXPECT_EQ(b.report.nearest, mode == Outside::Nearest ? n - m.inside : 0u);
      for (std::size_t i = 0; i < n; ++i) {
        // Round-off grows with the weights' magnitudes: a point far outside a curved lattice
        // (the bent tube's) extrapolates a small finest cell with weights up to ~1e5.
        double sum = 0, abs_sum = 0;
        for (std::uint32_t o = b.stencil.offsets[i]; o < b.stencil.offsets[i + 1]; ++o)
          sum += b.weight[o], abs_sum += std::abs(b.weight[o]);
        if (b.placement[i] == Placement::Stay)
          EXPECT_EQ(b.stencil.size(i), 0u);
        else
          ASSERT_NEAR(sum, 1.0, 1e-12 * std::max(1.0, abs_sum)) << "point " << i;
      }

      // At rest every vertex comes back where it was.
      std::vector<double> out(m.xyz.size());
      deform(b, fine, out);
      EXPECT_LT(max_dist(out, m.xyz, 0, n), 1e-9 * size) << "rest";

      // Affine map of level 0 (zero details): the model follows by the same map; staying
      // vertices do not move at all.
      deform(b, moved_fine, out);
      EXPECT_LT(max_dist(out, expect, 0, m.inside), 1e-9 * size) << "affine, inside";
      if (mode == Outside::Nearest)
        EXPECT_LT(max_dist(out, expect, m.inside, n), 1e-9 * size) << "affine, outside following";
      else
        EXPECT_TRUE(same_bits(out.data() + 3 * m.inside, m.xyz.data() + 3 * m.inside, 3 * (n - m.inside)));
    }
  }
}

TEST(Ffd, Level0EditIsLocalAndIncrementalEqualsFull) {
  for (const Sample& s : sample_lattices()) {
    SCOPED_TRACE(s.name);
    Session session(two_levels(s));
    const int J = session.finest_level();
    const std::vector<double> rest_lattice(session.positions(J).begin(), session.positions(J).end());
    const Complex& fc = session.hierarchy().levels[2];
    const Model m = sample_model(fc, rest_lattice, 5);
    const std::size_t n = m.xyz.size() / 3;
    const FfdBinding b = bind_model(fc, rest_lattice, m.xyz);
    std::vector<double> before(m.xyz.size());
    deform(b, rest_lattice, before);

    const std::uint32_t v0 = 0;
    const double delta[3] = {0.13, -0.21, 0.17};
    session.move(0, std::span<const std::uint32_t>(&v0, 1), {}, delta);
    const auto changed = session.changed(J);
    std::vector<char> is_changed(rest_lattice.size() / 3, 0);
    for (std::uint32_t v : changed) is_changed[v] = 1;
    // The session's list is complete: every other lattice vertex kept its bits.
    const auto after_lattice = session.positions(J);
    for (std::size_t v = 0; v < is_changed.size(); ++v)
      if (!is_changed[v]) {
        ASSERT_TRUE(same_bits(&after_lattice[3 * v], &rest_lattice[3 * v], 3)) << "lattice " << v;
      }

    std::vector<double> full(m.xyz.size()), inc = before;
    deform(b, after_lattice, full);
    std::vector<std::uint32_t> touched;
    deform_changed(b, after_lattice, changed, inc, &touched);
    EXPECT_TRUE(same_bits(inc.data(), full.data(), full.size())) << "incremental differs from full";

    std::size_t outside_support = 0, moved = 0;
    std::vector<std::uint32_t> expect_touched;
    for (std::uint32_t i = 0; i < n; ++i) {
      bool uses = false;
      for (std::uint32_t v : b.stencil.row(i)) uses = uses || is_changed[v];
      if (uses) expect_touched.push_back(i);
      if (!uses) {
        ++outside_support;
        ASSERT_TRUE(same_bits(&full[3 * i], &before[3 * i], 3)) << "model vertex " << i << " outside the support moved";
      }
      moved += !same_bits(&full[3 * i], &before[3 * i], 3);
    }
    EXPECT_EQ(touched, expect_touched);
    EXPECT_GT(moved, 0u);
    if (s.name == "hex_block_4" || s.name == "box") {
      EXPECT_GT(outside_support, 0u);
    }

    // Undo through the session: the incremental update restores the rest deformation bit for bit.
    ASSERT_TRUE(session.undo());
    deform_changed(b, session.positions(J), session.changed(J), inc);
    EXPECT_TRUE(same_bits(inc.data(), before.data(), before.size())) << "after undo";
  }
}

// ---- a model in a lattice built around it ----------------------------------------------------

// assets/torus_quad.obj (12 x 8 vertices, vertex i * 8 + j at angle 2 pi i / 12 about the y axis)
// in assets/ffd/torus_ring.lattice (12 wedges, section m at the same angle as torus ring m).
TEST(Ffd, TorusModelInItsPrismRing) {
  const std::string dir(SUBLIFT_ASSETS_DIR);
  const LoadedMesh torus = import_surface_mesh(dir + "/torus_quad.obj");
  std::vector<double> model;
  for (const auto& p : torus.mesh.positions) model.insert(model.end(), {p.x, p.y, p.z});
  ASSERT_EQ(model.size(), 3u * 96u);
  const double size = diagonal(model);
  Shape ring = read_shape(dir + "/ffd/torus_ring.lattice");
  ASSERT_EQ(ring.base.num_cells(), 12u);
  Session session(two_levels({"torus_ring", std::move(ring.base), std::move(ring.positions)}));
  const int J = session.finest_level();
  const std::vector<double> rest_lattice(session.positions(J).begin(), session.positions(J).end());
  const FfdBinding b = bind_model(session.hierarchy().levels[2], rest_lattice, model);
  // The ring encloses the whole torus at two cubic levels (which round its triangles off).
  EXPECT_EQ(b.report.outside, 0u);
  EXPECT_EQ(b.report.bound, 96u);
  std::vector<double> before(model.size());
  deform(b, rest_lattice, before);
  EXPECT_LT(max_dist(before, model, 0, 96), 1e-9 * size) << "rest";

  // Move ring vertex 0 (section 0) at level 0: torus rings 11, 0 and 1 lie in its support, at
  // most 60 degrees away, rings 3 to 9 (90 degrees and more) cannot change at all.
  const std::uint32_t v0 = 0;
  const double delta[3] = {0.1, -0.15, 0.05};
  session.move(0, std::span<const std::uint32_t>(&v0, 1), {}, delta);
  std::vector<double> after = before;
  deform_changed(b, session.positions(J), session.changed(J), after);
  std::vector<double> full(model.size());
  deform(b, session.positions(J), full);
  EXPECT_TRUE(same_bits(after.data(), full.data(), full.size())) << "incremental differs from full";
  std::size_t moved = 0;
  for (std::uint32_t i = 0; i < 12; ++i)
    for (std::uint32_t j = 0; j < 8; ++j) {
      const std::uint32_t v = i * 8 + j;
      const bool same = same_bits(&after[3 * v], &before[3 * v], 3);
      moved += !same;
      if (i == 0 || i == 1 || i == 11) {
        EXPECT_FALSE(same) << "torus vertex " << v << " near the edit kept still";
      }
      if (i >= 3 && i <= 9) {
        EXPECT_TRUE(same) << "torus vertex " << v << " far from the edit moved";
      }
    }
  std::printf("torus in torus_ring: %zu of 96 vertices moved by a level-0 edit of ring vertex 0\n", moved);
}

// ---- orientation, degenerate cells, errors -------------------------------------------------

TEST(Ffd, MirroredLatticeBindsLikeTheOriginal) {
  Shape s = make_box_lattice({0, 0, 0}, {1, 1, 1}, 2, 2, 2, 0.0);
  for (std::size_t i = 0; i < s.positions.size(); i += 3) s.positions[i] = -s.positions[i];  // inverted cells
  std::vector<double> model;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.001, 0.999);
  for (int i = 0; i < 300; ++i) model.insert(model.end(), {-u(rng), u(rng), u(rng)});
  const FfdBinding b = bind_model(s.base, s.positions, model);
  EXPECT_EQ(b.report.bound, 300u);
  EXPECT_EQ(b.report.tet_split, 0u);
  std::vector<double> out(model.size());
  deform(b, s.positions, out);
  EXPECT_LT(max_dist(out, model, 0, 300), 1e-12);
}

TEST(Ffd, DegenerateCellsGiveNoNaN) {
  Shape s = make_box_lattice({0, 0, 0}, {2, 1, 1}, 2, 1, 1, 0.0);
  // Collapse the right cell (x in [1, 2]) onto the plane x = 1 and fold a corner of the left one.
  for (std::size_t v = 0; v < s.base.num_vertices; ++v)
    if (s.positions[3 * v] > 1.5) s.positions[3 * v] = 1.0;
  s.positions[0] = 1.7;
  std::vector<double> model;
  for (int i = 0; i <= 20; ++i)
    for (int j = 0; j <= 4; ++j) model.insert(model.end(), {0.1 * i, 0.25 * j, 0.5});
  for (Outside mode : {Outside::Stay, Outside::Nearest}) {
    FfdOptions opt;
    opt.outside = mode;
    const FfdBinding b = bind_model(s.base, s.positions, model, opt);
    EXPECT_EQ(b.report.bound + b.report.outside, model.size() / 3);
    std::vector<double> out(model.size());
    deform(b, s.positions, out);
    for (double x : out) ASSERT_TRUE(std::isfinite(x));
    for (double w : b.weight) ASSERT_TRUE(std::isfinite(w));
    EXPECT_LT(max_dist(out, model, 0, model.size() / 3), 1e-9);
  }
}

TEST(Ffd, BadInputThrows) {
  const Shape s = make_box_lattice({0, 0, 0}, {1, 1, 1}, 1, 1, 1, 0.0);
  const std::vector<double> model = {0.5, 0.5, 0.5};
  std::vector<double> short_lattice(s.positions.begin(), s.positions.end() - 3);
  EXPECT_THROW(bind_model(s.base, short_lattice, model), Error);
  EXPECT_THROW(bind_model(s.base, s.positions, std::vector<double>{0.5, 0.5}), Error);
  EXPECT_THROW(bind_model(s.base, s.positions, std::vector<double>{0.5, std::nan(""), 0.5}), Error);
  Complex surface = s.base;
  surface.dim = 2;
  EXPECT_THROW(bind_model(surface, s.positions, model), Error);
  const FfdBinding b = bind_model(s.base, s.positions, model);
  std::vector<double> out(3);
  EXPECT_THROW(deform(b, short_lattice, out), Error);
  const std::uint32_t bad = 8;
  EXPECT_THROW(deform_changed(b, s.positions, std::span<const std::uint32_t>(&bad, 1), out), Error);
}

}  // namespace
}  // namespace sublift
