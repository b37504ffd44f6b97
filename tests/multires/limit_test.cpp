// Limit stencils and limit normals (core/multires/limit.h): exact rational masks where the scheme is a
// B-spline, eigenvector stencils elsewhere, checked against the engine's own refinement, against
// OpenSubdiv's limit stencils on a regular torus and against heavily refined normals.
#include <gtest/gtest.h>
#include <opensubdiv/far/stencilTable.h>
#include <opensubdiv/far/stencilTableFactory.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <map>
#include <memory>
#include <random>
#include <vector>

#include "core/complex/complex_build.h"
#include "core/multires/hierarchy.h"
#include "core/multires/limit.h"
#include "core/io/mesh/mesh_import.h"
#include "core/complex/shapes.h"
#include "tests/limit_convergence.h"
#include "tests/mesh_fixtures.h"

namespace sublift {
namespace {

using fixtures::Polygons;

Hierarchy surface(const Polygons& m, int levels, Scheme scheme = Scheme::Cubic) {
  Hierarchy h = make_hierarchy(complex_from_polygons(m.num_vertices, m.faces), levels, scheme, 3);
  set_base(h, m.positions);
  return h;
}

Complex with_adjacency(const Complex& c) {
  Complex copy = c;
  build_adjacency(copy);
  return copy;
}

std::map<std::uint32_t, double> row_of(const LimitStencils& s, std::uint32_t v) {
  std::map<std::uint32_t, double> r;
  for (std::uint32_t k = s.rows.offsets[v]; k < s.rows.offsets[v + 1]; ++k) r[s.rows.items[k]] += s.weights[k];
  return r;
}

std::map<std::uint32_t, double> row_of(const ProbedStencil& p) {
  std::map<std::uint32_t, double> r;
  for (std::size_t k = 0; k < p.vertices.size(); ++k) r[p.vertices[k]] += p.weights[k];
  return r;
}

double max_diff(const std::map<std::uint32_t, double>& a, const std::map<std::uint32_t, double>& b) {
  double d = 0;
  for (const auto& [v, w] : a) d = std::max(d, std::abs(w - (b.count(v) ? b.at(v) : 0.0)));
  for (const auto& [v, w] : b) d = std::max(d, std::abs(w - (a.count(v) ? a.at(v) : 0.0)));
  return d;
}

double dist(const double* a, const double* b) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

double angle(const double* a, const double* b) {
  const double d = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  const double c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  return std::atan2(std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]), d);
}

Polygons jittered(Polygons m, std::uint64_t seed, double amount) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-amount, amount);
  for (double& x : m.positions) x += u(rng);
  return m;
}

/// A pentagonal prism: two pentagons and five quads (valence-5 face points after one step).
Polygons pentagonal_prism() {
  Polygons m;
  m.num_vertices = 10;
  for (int z = 0; z < 2; ++z)
    for (int i = 0; i < 5; ++i) {
      const double a = 2 * 3.14159265358979323846 * i / 5;
      m.positions.insert(m.positions.end(), {std::cos(a), std::sin(a), double(z)});
    }
  fixtures::push_row(m.faces, {4, 3, 2, 1, 0});
  fixtures::push_row(m.faces, {5, 6, 7, 8, 9});
  for (std::uint32_t i = 0; i < 5; ++i) {
    const std::uint32_t j = (i + 1) % 5;
    fixtures::push_row(m.faces, {i, j, j + 5, i + 5});
  }
  return m;
}

// ---- exact stencils ----------------------------------------------------------------------------

TEST(Limit, RegularQuadEigenvectorEqualsBicubic) {
  const Hierarchy h = surface(fixtures::torus(8, 6), 1);
  const LimitStencils s = build_limit_stencils(h);
  EXPECT_EQ(s.extraordinary, 0u);
  const Complex c = with_adjacency(h.levels.back());
  for (std::uint32_t v : {0u, 7u, h.num_vertices(0) + 3, h.num_vertices(1) - 1}) {
    const auto exact = row_of(s, v);
    ASSERT_EQ(exact.size(), 9u);
    EXPECT_EQ(exact.at(v), 16.0 / 36.0);
    int edges = 0, diagonals = 0;
    for (const auto& [u, w] : exact) {
      edges += w == 4.0 / 36.0;
      diagonals += w == 1.0 / 36.0;
    }
    EXPECT_EQ(edges, 4);
    EXPECT_EQ(diagonals, 4);
    const ProbedStencil p = probe_limit_stencil(c, v);
    ASSERT_TRUE(p.ok);
    EXPECT_LT(max_diff(exact, row_of(p)), 1e-14) << "vertex " << v;
    // Spectrum of the regular star: 1, 1/2, 1/2, 1/4, ...
    ASSERT_GE(p.spectrum.size(), 4u);
    EXPECT_NEAR(p.spectrum[0], 1.0, 1e-13);
    EXPECT_NEAR(p.spectrum[1], 0.5, 1e-13);
    EXPECT_NEAR(p.spectrum[2], 0.5, 1e-13);
    EXPECT_NEAR(p.spectrum[3], 0.25, 1e-13);
    // The eigen tangents span the same plane as the exact bicubic derivative masks.
    ASSERT_FALSE(p.du.empty());
    const std::vector<double> x = synthesize(h, 1);
    double eu[3] = {0, 0, 0}, ev[3] = {0, 0, 0}, pu[3] = {0, 0, 0}, pv[3] = {0, 0, 0};
    for (std::uint32_t k = s.tangent_rows.offsets[v]; k < s.tangent_rows.offsets[v + 1]; ++k)
      for (int d = 0; d < 3; ++d) {
        eu[d] += s.du[k] * x[3 * s.tangent_rows.items[k] + d];
        ev[d] += s.dv[k] * x[3 * s.tangent_rows.items[k] + d];
      }
    for (std::size_t k = 0; k < p.vertices.size(); ++k)
      for (int d = 0; d < 3; ++d) {
        pu[d] += p.du[k] * x[3 * p.vertices[k] + d];
        pv[d] += p.dv[k] * x[3 * p.vertices[k] + d];
      }
    auto cross = [](const double* a, const double* b, double* c) {
      c[0] = a[1] * b[2] - a[2] * b[1], c[1] = a[2] * b[0] - a[0] * b[2], c[2] = a[0] * b[1] - a[1] * b[0];
    };
    double ne[3], np[3];
    cross(eu, ev, ne);
    cross(pu, pv, np);
    const double a = angle(ne, np);
    EXPECT_LT(std::min(a, 3.14159265358979323846 - a), 1e-10);
  }
}

TEST(Limit, CurvesAreSixthTwoThirdsSixth) {
  std::vector<double> pos;
  Complex loop = make_curve_loop(12, pos);
  Hierarchy h = make_hierarchy(loop, 2, Scheme::Cubic, 3);
  set_base(h, pos);
  const LimitStencils s = build_limit_stencils(h);
  const Complex c = with_adjacency(h.levels.back());
  for (std::uint32_t v = 0; v < h.num_vertices(2); ++v) {
    const auto r = row_of(s, v);
    ASSERT_EQ(r.size(), 3u);
    for (const auto& [u, w] : r) EXPECT_EQ(w, u == v ? 2.0 / 3.0 : 1.0 / 6.0);
    EXPECT_EQ(s.tangent_rows.size(v), 0u);
  }
  EXPECT_EQ(s.extraordinary, 0u);
  // The eigen path agrees.
  const ProbedStencil p = probe_limit_stencil(c, 5);
  ASSERT_TRUE(p.ok);
  EXPECT_LT(max_diff(row_of(s, 5), row_of(p)), 1e-14);
  // Open polyline: the ends (dim 0) are interpolated, the rest is the curve rule.
  Csr line;
  line.items = {0, 1, 2, 3, 4};
  line.offsets.push_back(5);
  Hierarchy o = make_hierarchy(complex_from_polylines(5, line), 1, Scheme::Cubic, 3);
  const LimitStencils so = build_limit_stencils(o);
  EXPECT_EQ(row_of(so, 0), (std::map<std::uint32_t, double>{{0u, 1.0}}));
  EXPECT_EQ(row_of(so, 4), (std::map<std::uint32_t, double>{{4u, 1.0}}));
  EXPECT_EQ(row_of(so, 2).size(), 3u);
}

TEST(Limit, LinearSchemeIsIdentity) {
  const Hierarchy h = surface(fixtures::cube(), 2, Scheme::Linear);
  const LimitStencils s = build_limit_stencils(h);
  for (std::uint32_t v = 0; v < h.num_vertices(2); ++v)
    EXPECT_EQ(row_of(s, v), (std::map<std::uint32_t, double>{{v, 1.0}}));
  const std::vector<double> x = synthesize(h, 2);
  std::vector<double> lim(x.size());
  eval_limit(s, x.data(), lim.data());
  EXPECT_EQ(lim, x);
}

TEST(Limit, HexLatticeInteriorIsTricubic) {
  std::vector<double> pos;
  Hierarchy h = make_hierarchy(make_hex_block(2, pos), 1, Scheme::Cubic, 3);
  set_base(h, pos);
  const LimitStencils s = build_limit_stencils(h);
  const Complex c = with_adjacency(h.levels.back());
  // Vertex 13 is the block's centre (1, 1, 1); it keeps its index at level 1.
  const auto r = row_of(s, 13);
  ASSERT_EQ(r.size(), 27u);
  std::map<double, int> counts;
  for (const auto& [u, w] : r) ++counts[w];
  EXPECT_EQ(counts[64.0 / 216.0], 1);
  EXPECT_EQ(counts[16.0 / 216.0], 6);
  EXPECT_EQ(counts[4.0 / 216.0], 12);
  EXPECT_EQ(counts[1.0 / 216.0], 8);
  const ProbedStencil p = probe_limit_stencil(c, 13);
  ASSERT_TRUE(p.ok);
  EXPECT_LT(max_diff(r, row_of(p)), 1e-13);
  // Every interior vertex reproduces the (linear) grid; the limit of the whole block is finite.
  const std::vector<double> x = synthesize(h, 1);
  std::vector<double> lim(x.size());
  eval_limit(s, x.data(), lim.data());
  for (double v : lim) EXPECT_TRUE(std::isfinite(v));
  EXPECT_LT(dist(&lim[3 * 13], &x[3 * 13]), 1e-14);
  // Vertices on the block's boundary surface follow the surface rules on it: bicubic where the
  // boundary surface is a regular quad grid, the eigenvector stencil of a valence-3 surface vertex
  // at the eight block corners (whose edges are smooth dim-2 edges of the boundary surface).
  std::size_t regular = 0, corners = 0;
  for (std::uint32_t v = 0; v < h.num_vertices(1); ++v)
    if (c.vertex_dim[v] == 2) {
      const auto rb = row_of(s, v);
      if (c.vertex_cells.size(v) == 1) {
        ++corners;
        EXPECT_EQ(rb.size(), 7u);
        const ProbedStencil pc = probe_limit_stencil(c, v);
        EXPECT_LT(max_diff(rb, row_of(pc)), 1e-15);
      } else {
        ++regular;
        EXPECT_EQ(rb.size(), 9u);
        EXPECT_EQ(rb.at(v), 16.0 / 36.0);
      }
    }
  EXPECT_EQ(corners, 8u);
  EXPECT_EQ(regular, 6u * 9u + 12u * 3u);
  EXPECT_EQ(s.extraordinary, 8u);
  EXPECT_EQ(s.configurations, 1u);
  // The boundary-surface corner rule is the surface rule: the same stencil as a cube's corner.
  const Hierarchy cube = surface(fixtures::cube(), 1);
  const ProbedStencil cs = probe_limit_stencil(with_adjacency(cube.levels.back()), 0);
  ASSERT_TRUE(cs.ok);
  std::vector<double> a = cs.weights, b = probe_limit_stencil(c, 0).weights;
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) EXPECT_NEAR(a[k], b[k], 1e-15);
}

// ---- convergence at extraordinary vertices ------------------------------------------------------

// Refines `m` (finest level `base_levels`) `more` further levels with zero detail and checks that
// the control points of `vertex` approach the predicted limit geometrically.
// Convergence of the extraordinary stencils: tests/limit_convergence.h, 20 % a level at least.
void expect_converges(const Polygons& m, int base_levels, std::uint32_t vertex, int more, double final_tol) {
  testing::expect_converges(m, base_levels, vertex, more, {.min_first = 1e-4, .rate = 0.8, .final_tol = final_tol, .last_ratio = 1e-2});
}

TEST(Limit, ConvergesAtValenceThreeCubeCorner) {
  const Polygons cube = jittered(fixtures::cube(), 7, 0.1);
  const Hierarchy h = surface(cube, 1);
  const LimitStencils s = build_limit_stencils(h);
  EXPECT_EQ(s.extraordinary, 8u);
  EXPECT_EQ(s.configurations, 1u);  // all eight corners share one cached configuration
  expect_converges(cube, 1, 0, 8, 1e-4);
  expect_converges(cube, 1, 5, 8, 1e-4);
}

TEST(Limit, ConvergesAtValenceFiveAndAtPentagonsOfTheBase) {
  const Polygons prism = jittered(pentagonal_prism(), 3, 0.05);
  {
    const Hierarchy h = surface(prism, 1);
    const Complex c = with_adjacency(h.levels.back());
    const std::uint32_t centre = h.num_vertices(0) + h.levels[0].num_edges() + 0;  // pentagon 0's point
    ASSERT_EQ(c.vertex_edges.size(centre), 5u);
    const ProbedStencil p = probe_limit_stencil(c, centre);
    ASSERT_TRUE(p.ok);
    ASSERT_GE(p.spectrum.size(), 4u);
    EXPECT_NEAR(p.spectrum[1], p.spectrum[2], 1e-12);  // double subdominant eigenvalue
    EXPECT_GT(p.spectrum[2], p.spectrum[3] + 1e-6);
    EXPECT_FALSE(p.du.empty());
    expect_converges(prism, 1, centre, 7, 1e-3);
    expect_converges(prism, 1, 0, 7, 1e-3);
  }
  // The finest level is the base itself (pentagons in the star): the stencil composes the first
  // refinement with the eigenvector of the refined star.
  expect_converges(prism, 0, 0, 8, 1e-3);
}

TEST(Limit, ConvergesOnAssetsWithCreasesBoundariesAndCorners) {
  // Every finest vertex's control point approaches its predicted limit under further zero-detail
  // refinement: extraordinary vertices, n-gons, boundary curves, tagged creases and corners, darts.
  for (const char* name : {"mixed_polygons.obj", "crease_loop.obj", "quad_grid_boundary.obj", "pyramid.obj"}) {
    SCOPED_TRACE(name);
    LoadedMesh lm = import_surface_mesh(std::string(SUBLIFT_ASSETS_DIR) + "/" + name);
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> jitter(-0.02, 0.02);
    for (auto& p : lm.mesh.positions) p += glm::dvec3(jitter(rng), jitter(rng), jitter(rng));
    const std::vector<double> base = flatten_positions(lm.mesh);
    const Complex c = complex_from_surface_mesh(lm.mesh);
    Hierarchy h = make_hierarchy(c, 1, Scheme::Cubic, 3);
    set_base(h, base);
    const LimitStencils s = build_limit_stencils(h);
    EXPECT_EQ(s.unsolved, 0u);
    const std::vector<double> x = synthesize(h, 1);
    std::vector<double> lim(x.size());
    eval_limit(s, x.data(), lim.data());
    Hierarchy deep = make_hierarchy(c, 7, Scheme::Cubic, 3);
    set_base(deep, base);
    const std::vector<double> x7 = synthesize(deep, 7);
    const std::vector<double> x6 = synthesize(deep, 6);
    for (std::uint32_t v = 0; v < h.num_vertices(1); ++v) {
      const double e6 = dist(&x6[3 * v], &lim[3 * v]), e7 = dist(&x7[3 * v], &lim[3 * v]);
      EXPECT_LT(e7, 2e-3) << "vertex " << v;
      EXPECT_LE(e7, 0.8 * e6 + 1e-12) << "vertex " << v;
    }
  }
}

// ---- peer: OpenSubdiv's limit stencils on a regular torus ----------------------------------

TEST(Limit, MatchesOpenSubdivLimitStencilsOnRegularTorus) {
  namespace Far = OpenSubdiv::Far;
  namespace Sdc = OpenSubdiv::Sdc;
  const std::uint32_t nu = 10, nvv = 7;
  const Polygons m = fixtures::torus(nu, nvv);
  const Hierarchy h = surface(m, 0);
  const LimitStencils s = build_limit_stencils(h);
  std::vector<double> lim(m.positions.size()), nrm(m.positions.size());
  eval_limit(s, m.positions.data(), lim.data());
  limit_normals(s, m.faces, m.positions.data(), lim.data(), nrm.data());

  std::vector<int> sizes(m.faces.rows(), 4);
  const std::vector<Far::Index> corners(m.faces.items.begin(), m.faces.items.end());
  Far::TopologyDescriptor desc;
  desc.numVertices = static_cast<int>(m.num_vertices);
  desc.numFaces = static_cast<int>(sizes.size());
  desc.numVertsPerFace = sizes.data();
  desc.vertIndicesPerFace = corners.data();
  using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
  std::unique_ptr<Far::TopologyRefiner> r(Factory::Create(desc, Factory::Options(Sdc::SCHEME_CATMARK, Sdc::Options())));
  ASSERT_TRUE(r);
  r->RefineAdaptive(Far::TopologyRefiner::AdaptiveOptions(2));
  // Face f = j * nu + i has vertex f as its corner 0, i.e. at (s, t) = (0, 0) of ptex face f.
  const double zero = 0.0;
  typename Far::LimitStencilTableFactoryReal<double>::LocationArrayVec locs(m.num_vertices);
  for (std::uint32_t v = 0; v < m.num_vertices; ++v) {
    ASSERT_EQ(m.faces.row(v)[0], v);
    locs[v].ptexIdx = static_cast<int>(v);
    locs[v].numLocations = 1;
    locs[v].s = &zero;
    locs[v].t = &zero;
  }
  std::unique_ptr<const Far::LimitStencilTableReal<double>> table(
      Far::LimitStencilTableFactoryReal<double>::Create(*r, locs));
  ASSERT_TRUE(table);
  ASSERT_EQ(table->GetNumStencils(), int(m.num_vertices));
  const auto& sz = table->GetSizes();
  const auto& off = table->GetOffsets();
  const auto& idx = table->GetControlIndices();
  const auto& w = table->GetWeights();
  const auto& du = table->GetDuWeights();
  const auto& dv = table->GetDvWeights();
  double worst = 0, worst_angle = 0;
  for (std::uint32_t v = 0; v < m.num_vertices; ++v) {
    double p[3] = {0, 0, 0}, tu[3] = {0, 0, 0}, tv[3] = {0, 0, 0};
    for (int k = off[v]; k < off[v] + sz[v]; ++k)
      for (int d = 0; d < 3; ++d) {
        p[d] += w[k] * m.positions[3 * idx[k] + d];
        tu[d] += du[k] * m.positions[3 * idx[k] + d];
        tv[d] += dv[k] * m.positions[3 * idx[k] + d];
      }
    worst = std::max(worst, dist(p, &lim[3 * v]));
    const double n[3] = {tu[1] * tv[2] - tu[2] * tv[1], tu[2] * tv[0] - tu[0] * tv[2], tu[0] * tv[1] - tu[1] * tv[0]};
    worst_angle = std::max(worst_angle, angle(n, &nrm[3 * v]));
  }
  EXPECT_LT(worst, 1e-12);
  EXPECT_LT(worst_angle, 1e-10);
}

// ---- normals -------------------------------------------------------------------------------

TEST(Limit, TorusNormalsMatchHeavyRefinementAndPointOutward) {
  const Polygons m = fixtures::torus(8, 6);
  const Hierarchy h = surface(m, 1);
  const LimitStencils s = build_limit_stencils(h);
  const std::vector<double> x = synthesize(h, 1);
  std::vector<double> lim(x.size()), nrm(x.size());
  eval_limit(s, x.data(), lim.data());
  const Csr& faces = h.levels[1].faces;
  limit_normals(s, faces, x.data(), lim.data(), nrm.data());
  const int deep_levels = 7;
  const Hierarchy deep = surface(m, deep_levels);
  const std::vector<double> xd = synthesize(deep, deep_levels);
  const Csr& fd = deep.levels.back().faces;
  const Csr vf = transpose(fd, deep.num_vertices(deep_levels));
  double worst = 0;
  for (std::uint32_t v = 0; v < h.num_vertices(1); ++v) {
    double ref[3] = {0, 0, 0};
    for (std::uint32_t f : vf.row(v)) {
      const auto q = fd.row(f);
      const double* a = &xd[3 * q[0]];
      const double* b = &xd[3 * q[1]];
      const double* c = &xd[3 * q[2]];
      const double* d = &xd[3 * q[3]];
      const double e1[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]}, e2[3] = {d[0] - b[0], d[1] - b[1], d[2] - b[2]};
      ref[0] += e1[1] * e2[2] - e1[2] * e2[1];
      ref[1] += e1[2] * e2[0] - e1[0] * e2[2];
      ref[2] += e1[0] * e2[1] - e1[1] * e2[0];
    }
    worst = std::max(worst, angle(ref, &nrm[3 * v]));
    // Outward: away from the tube's centre circle (radius 2 in the xy plane).
    const double* p = &lim[3 * v];
    const double rho = std::hypot(p[0], p[1]);
    const double out[3] = {p[0] - 2 * p[0] / rho, p[1] - 2 * p[1] / rho, p[2]};
    EXPECT_GT(out[0] * nrm[3 * v] + out[1] * nrm[3 * v + 1] + out[2] * nrm[3 * v + 2], 0) << "vertex " << v;
    EXPECT_NEAR(std::hypot(nrm[3 * v], nrm[3 * v + 1], nrm[3 * v + 2]), 1.0, 1e-14);
  }
  EXPECT_LT(worst, 2e-3);
}

TEST(Limit, ExtraordinaryNormalsFromEigenTangents) {
  // Cube at level 2: the corner normals are exact (eigen tangents) and, by symmetry, diagonal.
  const Hierarchy h = surface(fixtures::cube(), 2);
  const LimitStencils s = build_limit_stencils(h);
  const std::vector<double> x = synthesize(h, 2);
  std::vector<double> lim(x.size()), nrm(x.size());
  eval_limit(s, x.data(), lim.data());
  limit_normals(s, h.levels[2].faces, x.data(), lim.data(), nrm.data());
  for (std::uint32_t v = 0; v < 8; ++v) {
    EXPECT_GT(s.tangent_rows.size(v), 0u);
    const double diag[3] = {(v & 1) ? 1.0 : -1.0, (v & 2) ? 1.0 : -1.0, (v & 4) ? 1.0 : -1.0};
    EXPECT_LT(angle(diag, &nrm[3 * v]), 1e-12) << "corner " << v;
  }
  // A jittered prism: eigen normals at the valence-5 points agree with heavily refined faces.
  const Polygons prism = jittered(pentagonal_prism(), 5, 0.05);
  const Hierarchy hp = surface(prism, 1);
  const LimitStencils sp = build_limit_stencils(hp);
  const std::vector<double> xp = synthesize(hp, 1);
  std::vector<double> lp(xp.size()), np(xp.size());
  eval_limit(sp, xp.data(), lp.data());
  limit_normals(sp, hp.levels[1].faces, xp.data(), lp.data(), np.data());
  const Hierarchy deep = surface(prism, 8);
  const std::vector<double> xd = synthesize(deep, 8);
  const Csr& fd = deep.levels.back().faces;
  const Csr vf = transpose(fd, deep.num_vertices(8));
  const std::uint32_t first_face_point = hp.num_vertices(0) + hp.levels[0].num_edges();
  for (std::uint32_t v : {first_face_point, first_face_point + 1, 0u, 7u}) {
    EXPECT_GT(sp.tangent_rows.size(v), 0u);
    double ref[3] = {0, 0, 0};
    for (std::uint32_t f : vf.row(v)) {
      const auto q = fd.row(f);
      const double *a = &xd[3 * q[0]], *b = &xd[3 * q[1]], *c = &xd[3 * q[2]], *d = &xd[3 * q[3]];
      const double e1[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]}, e2[3] = {d[0] - b[0], d[1] - b[1], d[2] - b[2]};
      ref[0] += e1[1] * e2[2] - e1[2] * e2[1];
      ref[1] += e1[2] * e2[0] - e1[0] * e2[2];
      ref[2] += e1[0] * e2[1] - e1[1] * e2[0];
    }
    EXPECT_LT(angle(ref, &np[3 * v]), 1e-2) << "vertex " << v;
  }
}

// ---- incremental evaluation ----------------------------------------------------------------

// A drag's frames move the same control points: the second call replays the limit vertices the
// first found (LimitStencils::subset_plan), with the same lists and values as a fresh search.
TEST(Limit, RepeatedSubsetEvaluationReplaysItsRows) {
  const Hierarchy h = surface(jittered(pentagonal_prism(), 9, 0.05), 2);
  const LimitStencils s = build_limit_stencils(h);
  std::vector<double> x = synthesize(h, 2), lim(x.size()), full(x.size());
  eval_limit(s, x.data(), lim.data());
  const std::vector<std::uint32_t> moved = {0, 3, 17, 40};
  std::vector<std::vector<std::uint32_t>> lists;
  for (int frame = 0; frame < 3; ++frame) {
    for (std::uint32_t u : moved) x[3 * u] += 0.05 * (frame + 1);
    std::vector<std::uint32_t> changed{41};
    eval_limit_subset(s, x.data(), moved, lim.data(), changed);
    lists.push_back(changed);
    eval_limit(s, x.data(), full.data());
    EXPECT_EQ(lim, full) << "frame " << frame;
  }
  EXPECT_EQ(s.subset_plan.replays, 2u);
  EXPECT_EQ(lists[1], lists[0]);
  EXPECT_EQ(lists[2], lists[0]);
  // Another list is searched afresh, and so is the same list with another changed_limit.
  const LimitStencils fresh = build_limit_stencils(h);
  for (const std::vector<std::uint32_t>& other : {std::vector<std::uint32_t>{5, 6}, moved}) {
    x[3 * other[0] + 1] += 0.25;
    std::vector<std::uint32_t> a, b;
    eval_limit_subset(s, x.data(), other, lim.data(), a);
    eval_limit_subset(fresh, x.data(), other, full.data(), b);
    EXPECT_EQ(a, b);
    EXPECT_EQ(lim, full);
  }
  EXPECT_EQ(s.subset_plan.replays, 2u);
}

TEST(Limit, SubsetEvaluationEqualsFullEvaluation) {
  const Hierarchy h = surface(jittered(pentagonal_prism(), 9, 0.05), 2);
  const LimitStencils s = build_limit_stencils(h);
  std::vector<double> x = synthesize(h, 2);
  std::vector<double> lim(x.size()), nrm(x.size());
  eval_limit(s, x.data(), lim.data());
  const Csr& faces = h.levels[2].faces;
  limit_normals(s, faces, x.data(), lim.data(), nrm.data());
  // The same stencils with their tangent orientation recorded from the unmoved shape.
  LimitStencils oriented = s;
  orient_tangents(oriented, faces, x.data(), lim.data());
  std::size_t signed_vertices = 0;
  for (const std::int8_t g : oriented.tangent_sign) signed_vertices += g != 0;
  EXPECT_GT(signed_vertices, h.num_vertices(2) / 2);
  std::vector<double> nrm_oriented = nrm;
  const std::vector<std::uint32_t> moved = {0, 3, 17, 40, 41};
  for (std::uint32_t u : moved)
    for (int d = 0; d < 3; ++d) x[3 * u + d] += 0.1 * (d + 1);
  std::vector<std::uint32_t> changed{41};  // already listed: must not be appended again
  eval_limit_subset(s, x.data(), moved, lim.data(), changed);
  std::vector<double> full(x.size()), full_n(x.size());
  eval_limit(s, x.data(), full.data());
  EXPECT_EQ(lim, full);
  std::vector<std::uint32_t> sorted = changed;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(std::adjacent_find(sorted.begin(), sorted.end()), sorted.end());
  EXPECT_LT(changed.size(), h.num_vertices(2) / 2);
  // Normals: recompute around the changed limit vertices (their faces' corners).
  const Csr vf = transpose(faces, h.num_vertices(2));
  std::vector<std::uint32_t> around;
  for (std::uint32_t v : changed)
    for (std::uint32_t f : vf.row(v))
      for (std::uint32_t c : faces.row(f)) around.push_back(c);
  std::sort(around.begin(), around.end());
  around.erase(std::unique(around.begin(), around.end()), around.end());
  limit_normals_subset(s, faces, vf, x.data(), lim.data(), around, nrm.data());
  limit_normals_subset(oriented, faces, vf, x.data(), lim.data(), around, nrm_oriented.data());
  limit_normals(s, faces, x.data(), full.data(), full_n.data());
  for (std::size_t i = 0; i < nrm.size(); ++i) EXPECT_NEAR(nrm[i], full_n[i], 1e-14) << i;
  for (std::size_t i = 0; i < nrm.size(); ++i) EXPECT_NEAR(nrm_oriented[i], full_n[i], 1e-14) << i;
}

// ---- timing (not asserted; run with --gtest_also_run_disabled_tests) ------------------------

TEST(Limit, DISABLED_TimingMillionVertexTorus) {
  const SurfaceMesh t = make_quad_torus(512, 512);
  Hierarchy h = make_hierarchy(complex_from_surface_mesh(t), 1, Scheme::Cubic, 3);
  set_base(h, flatten_positions(t));
  const std::vector<double> x = synthesize(h, 1);
  using clock = std::chrono::steady_clock;
  auto t0 = clock::now();
  const std::clock_t c0 = std::clock();
  const LimitStencils s = build_limit_stencils(h);
  const std::clock_t c1 = std::clock();
  auto t1 = clock::now();
  std::vector<double> lim(x.size()), nrm(x.size());
  eval_limit(s, x.data(), lim.data());
  auto t2 = clock::now();
  limit_normals(s, h.levels[1].faces, x.data(), lim.data(), nrm.data());
  auto t3 = clock::now();
  auto ms = [](auto a, auto b) { return std::chrono::duration<double, std::milli>(b - a).count(); };
  std::printf("vertices %u: build %.1f ms (cpu %.1f ms), eval_limit %.1f ms, limit_normals %.1f ms\n",
              h.num_vertices(1), ms(t0, t1), 1000.0 * double(c1 - c0) / CLOCKS_PER_SEC, ms(t1, t2), ms(t2, t3));
}

}  // namespace
}  // namespace sublift
