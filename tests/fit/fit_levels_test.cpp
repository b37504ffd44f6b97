// Fitting levels to any surface (core/fit/fit_levels.h, issue 17): the fitted finest level lies
// on the input and covers it, reconstructs exactly, and a level-0 edit moves the detail with it.
#include "core/fit/fit_levels.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <optional>
#include <filesystem>

#include "core/analysis/sphere_resample.h"
#include "core/base/bounds.h"
#include "core/base/errors.h"
#include "core/base/parallel.h"
#include "core/base/triangle_bvh.h"
#include "core/io/mesh/mesh_import.h"
#include "core/schemes/registry.h"
#include "tests/mesh_fixtures.h"
#include "tests/test_shapes.h"

namespace sublift {
namespace {

struct Input {
  std::uint32_t n = 0;
  Csr faces;
  std::vector<double> xyz;
};

Input sphere(int level = 6) {
  const GeodesicSphere g = geodesic_sphere(level);  // 16,386 vertices on the unit sphere at level 6
  Input in{g.fine.num_vertices, g.fine.faces, {}};
  for (const auto& d : g.directions) in.xyz.insert(in.xyz.end(), {d.x, d.y, d.z});
  return in;
}

Input torus() {
  const fixtures::Polygons t = fixtures::torus(96, 48);
  Input in{t.num_vertices, {}, t.positions};
  for (std::size_t f = 0; f < t.faces.rows(); ++f) {
    const auto q = t.faces.row(f);
    fixtures::push_row(in.faces, {q[0], q[1], q[2]});
    fixtures::push_row(in.faces, {q[0], q[2], q[3]});
  }
  return in;
}

// A triangulated sheet with a boundary: a 120 x 80 height field z = 0.1 sin(3x) cos(2y).
Input sheet() {
  const std::uint32_t nx = 120, ny = 80;
  Input in{nx * ny, {}, {}};
  for (std::uint32_t j = 0; j < ny; ++j)
    for (std::uint32_t i = 0; i < nx; ++i) {
      const double x = double(i) / (nx - 1), y = double(j) / (ny - 1) * 0.7;
      in.xyz.insert(in.xyz.end(), {x, y, 0.1 * std::sin(3 * x) * std::cos(2 * y)});
    }
  for (std::uint32_t j = 0; j + 1 < ny; ++j)
    for (std::uint32_t i = 0; i + 1 < nx; ++i) {
      const std::uint32_t a = j * nx + i;
      fixtures::push_row(in.faces, {a, a + 1, a + nx + 1});
      fixtures::push_row(in.faces, {a, a + nx + 1, a + nx});
    }
  return in;
}

// A closed surface of genus `holes`: the boundary of a plate of voxels (2 holes + 1 wide,
// 3 deep, 1 thick; every other voxel of the middle row removed), each square split into 8 x 8
// pairs of triangles and smoothed (so its edges round off below the feature angle).
Input voxel_plate(int holes) {
  const int W = 2 * holes + 1, H = 3;
  const auto filled = [&](int i, int j, int k) {
    return i >= 0 && i < W && j >= 0 && j < H && k == 0 && !(j == 1 && i % 2 == 1);
  };
  const int s = 8;  // grid points per voxel edge
  std::map<std::array<int, 3>, std::uint32_t> id;
  Input in;
  const auto vertex = [&](std::array<int, 3> g) {
    const auto [it, fresh] = id.emplace(g, in.n);
    if (fresh) {
      in.xyz.insert(in.xyz.end(), {double(g[0]) / s, double(g[1]) / s, double(g[2]) / s});
      ++in.n;
    }
    return it->second;
  };
  for (int i = -1; i <= W; ++i)
    for (int j = -1; j <= H; ++j)
      for (int k = -1; k <= 1; ++k)
        for (int axis = 0; axis < 3; ++axis) {
          // The square between voxel (i, j, k) and its neighbour along +axis, when one is filled.
          std::array<int, 3> b = {i, j, k};
          ++b[static_cast<std::size_t>(axis)];
          const bool here = filled(i, j, k), there = filled(b[0], b[1], b[2]);
          if (here == there) continue;
          const int u = (axis + 1) % 3, v = (axis + 2) % 3;
          for (int p = 0; p < s; ++p)
            for (int q = 0; q < s; ++q) {
              std::array<std::array<int, 3>, 4> c;
              for (int corner = 0; corner < 4; ++corner) {
                std::array<int, 3> g = {s * i, s * j, s * k};
                g[static_cast<std::size_t>(axis)] += s;
                g[static_cast<std::size_t>(u)] += p + (corner == 1 || corner == 2);
                g[static_cast<std::size_t>(v)] += q + (corner >= 2);
                c[static_cast<std::size_t>(corner)] = g;
              }
              std::uint32_t r[4];
              for (int corner = 0; corner < 4; ++corner) r[corner] = vertex(c[static_cast<std::size_t>(corner)]);
              if (here) {  // outward along +axis: (u, v) turns counterclockwise seen from outside
                fixtures::push_row(in.faces, {r[0], r[1], r[2]});
                fixtures::push_row(in.faces, {r[0], r[2], r[3]});
              } else {
                fixtures::push_row(in.faces, {r[0], r[2], r[1]});
                fixtures::push_row(in.faces, {r[0], r[3], r[2]});
              }
            }
        }
  // Smooth: the mean of the neighbours, 30 times.
  std::vector<std::vector<std::uint32_t>> nb(in.n);
  for (std::size_t f = 0; f < in.faces.rows(); ++f) {
    const auto row = in.faces.row(f);
    for (int k = 0; k < 3; ++k) nb[row[k]].push_back(row[(k + 1) % 3]), nb[row[(k + 1) % 3]].push_back(row[k]);
  }
  for (int it = 0; it < 30; ++it) {
    std::vector<double> next(in.xyz.size());
    for (std::uint32_t a = 0; a < in.n; ++a)
      for (int d = 0; d < 3; ++d) {
        double m = 0;
        for (std::uint32_t b : nb[a]) m += in.xyz[3 * std::size_t(b) + d];
        next[3 * std::size_t(a) + d] = 0.5 * in.xyz[3 * std::size_t(a) + d] + 0.5 * m / double(nb[a].size());
      }
    in.xyz.swap(next);
  }
  return in;
}

// Largest distance from the input's vertices to the fitted finest net, over the diagonal.
double input_to_fit(const Input& in, const Fitted& f) {
  const Complex& fine = f.hierarchy.levels.back();
  const TriangleBvh index(f.finest, fine.faces);
  double worst = 0;
  for (std::uint32_t v = 0; v < in.n; ++v)
    worst = std::max(worst, index.closest({in.xyz[3 * std::size_t(v)], in.xyz[3 * std::size_t(v) + 1], in.xyz[3 * std::size_t(v) + 2]}).distance);
  return worst / bbox_diagonal(in.xyz);
}

// Generated surfaces of genus 0, 1 and 3 and an open sheet, fitted from bases of about 1/50 of
// their vertices to a finest level with about as many: the fitted surface (Loop's limit
// surface; butterfly's finest net, which it interpolates) within 0.5 % of the input's diagonal
// both ways and 0.1 % RMS, no folded face, the input's Euler characteristic and boundary loops.
// One test per surface and scheme: together they take minutes under the sanitizers, so each
// gets its own timeout and ctest spreads them over the cores.
struct GeneratedCase {
  const char* name;
  Input (*make)();
  long long euler;
  std::size_t loops;
  Scheme scheme;
};

const GeneratedCase kGenerated[] = {
    {"sphere", [] { return sphere(5); }, 2, 0, Scheme::Loop},
    {"torus", [] { return torus(); }, 0, 0, Scheme::Loop},
    {"genus3", [] { return voxel_plate(3); }, -4, 0, Scheme::Loop},
    {"sheet", [] { return sheet(); }, 1, 1, Scheme::Loop},
    {"torus_butterfly", [] { return torus(); }, 0, 0, Scheme::Butterfly},
    // the polygon schemes, from quad-dominant bases
    {"torus_cubic", [] { return torus(); }, 0, 0, Scheme::Cubic},
    {"genus3_cubic", [] { return voxel_plate(3); }, -4, 0, Scheme::Cubic},
    {"sheet_cubic", [] { return sheet(); }, 1, 1, Scheme::Cubic},
    {"torus_sqrt2", [] { return torus(); }, 0, 0, Scheme::Sqrt2},
    {"sheet_linear", [] { return sheet(); }, 1, 1, Scheme::Linear}};

// The input's base of about `base_vertices` for scheme s (quads where the scheme refines them)
// and the options that fit it three splits deep.
struct ThreeSplits {
  BaseMesh base;
  FitOptions o;
};
ThreeSplits three_splits(const Input& in, Scheme s, std::uint32_t base_vertices) {
  BaseMeshOptions bo;
  bo.target_vertices = base_vertices;
  bo.quads = fit_base_quads(s);
  ThreeSplits t{decimate_to_base(in.n, in.faces, in.xyz, bo), {}};
  t.o.scheme = s;
  t.o.levels = 3 * scheme_levels_per_split(s);
  return t;
}

class GeneratedSurfaces : public ::testing::TestWithParam<int> {};

TEST_P(GeneratedSurfaces, FitBothWays) {
  const GeneratedCase& k = kGenerated[GetParam()];
  {
    const Input in = k.make();
    SCOPED_TRACE(k.name);
    const auto [base, o] = three_splits(in, k.scheme, std::max<std::uint32_t>(60, in.n / 50));
    EXPECT_EQ(base.euler_after, k.euler);
    EXPECT_EQ(base.boundary_loops_after, k.loops);
    const Fitted f = fit_levels(base, in.faces, in.xyz, o);
    ASSERT_EQ(f.levels.size(), std::size_t(o.levels));
    for (const FitLevelReport& r : f.levels)
      std::printf("%s level %d: %u vertices, net->input %.4f %% rms %.4f %% max, input->net %.4f %% rms %.4f %% max, %u folded, %.1f ms\n",
                  k.name, r.level, r.vertices, 100 * r.rms, 100 * r.max, 100 * r.back_rms, 100 * r.back_max, r.folded, r.ms);
    std::printf("%s limit: ->input %.4f %% rms %.4f %% max, input-> %.4f %% rms %.4f %% max, %u folded\n", k.name, 100 * f.limit_rms,
                100 * f.limit_max, 100 * f.limit_back_rms, 100 * f.limit_back_max, f.limit_folded);
    const FitLevelReport& r = f.levels.back();
    EXPECT_EQ(r.folded, 0u);
    EXPECT_EQ(f.limit_folded, 0u);
    if (scheme_info(k.scheme).limit == LimitRule::ControlNet) {
      EXPECT_LT(r.max, 0.005);
      EXPECT_LT(r.back_max, 0.005);
      EXPECT_LT(r.rms, 0.001);
      EXPECT_LT(r.back_rms, 0.001);
    } else {
      EXPECT_LT(f.limit_max, 0.005);
      EXPECT_LT(f.limit_back_max, 0.005);
      EXPECT_LT(f.limit_rms, 0.001);
      EXPECT_LT(f.limit_back_rms, 0.001);
    }
    // An independent check of the report's input->net distance.
    EXPECT_NEAR(input_to_fit(in, f), r.back_max, 1e-12);
    // Feature lines: only the sheet has one (its boundary), kept by the fitted boundary.
    EXPECT_EQ(f.feature_lines, k.loops);
    if (k.loops) {
      EXPECT_LT(f.feature_max, 0.001) << "the boundary's limit curve strays from the sheet's";
    }
  }
}

INSTANTIATE_TEST_SUITE_P(FitLevels, GeneratedSurfaces, ::testing::Range(0, int(std::size(kGenerated))),
                         [](const ::testing::TestParamInfo<int>& i) { return std::string(kGenerated[i.param].name); });

TEST(FitLevels, PerfectReconstructionAndCoarseEditsCarryTheDetail) {
  const Input in = sphere();
  for (Scheme s : {Scheme::Loop, Scheme::Cubic, Scheme::Sqrt2}) {
    SCOPED_TRACE(scheme_name(s));
    const auto [base, o] = three_splits(in, s, 80);
    const Fitted f = fit_levels(base, in.faces, in.xyz, o);
    const int J = f.hierarchy.finest_level();
    ASSERT_EQ(J, o.levels);
    EXPECT_LE(testing::max_abs_diff(synthesize(f.hierarchy, J), f.finest), 1e-12);
    // World frames: a level-0 move changes the finest level by the pure subdivision of the move.
    Hierarchy edited = f.hierarchy, delta = f.hierarchy;
    std::fill(delta.coeffs.begin(), delta.coeffs.end(), 0.0);
    const double d[3] = {0.2, -0.1, 0.05};
    for (int k = 0; k < 3; ++k) edited.coeffs[k] += d[k], delta.coeffs[k] = d[k];
    const std::vector<double> a = synthesize(edited, J), b = synthesize(delta, J);
    std::vector<double> moved(a.size());
    for (std::size_t i = 0; i < a.size(); ++i) moved[i] = a[i] - f.finest[i];
    EXPECT_LE(testing::max_abs_diff(moved, b), 1e-12);
    EXPECT_GT(*std::max_element(b.begin(), b.end()), 0.01);  // the edit reached the finest level
  }
}

// A fit is the same to the bit on one thread and on two: every parallel sum (the solve's dot
// products among them) is taken in an order fixed by the data. The sheet (a boundary, four
// corners) with cubic, whose finest level solves under its limit surface, and with sqrt(2);
// their finest nets have more than 4,096 points, so the solve's sums span several blocks.
TEST(FitLevels, SameBitsOnOneThreadAndTwo) {
  const Input in = sheet();
  const int threads_before = parallel_threads();
  for (Scheme s : {Scheme::Cubic, Scheme::Sqrt2}) {
    SCOPED_TRACE(scheme_name(s));
    const auto [base, o] = three_splits(in, s, 120);
    std::vector<Fitted> fits;
    for (const int threads : {1, 2}) {
      set_parallel_threads(threads);
      fits.push_back(fit_levels(base, in.faces, in.xyz, o));
    }
    set_parallel_threads(threads_before);
    ASSERT_GT(fits[0].finest.size(), 3u * 4096);
    ASSERT_EQ(fits[0].finest.size(), fits[1].finest.size());
    EXPECT_EQ(std::memcmp(fits[0].finest.data(), fits[1].finest.data(), fits[0].finest.size() * sizeof(double)), 0);
    ASSERT_EQ(fits[0].hierarchy.coeffs.size(), fits[1].hierarchy.coeffs.size());
    EXPECT_EQ(std::memcmp(fits[0].hierarchy.coeffs.data(), fits[1].hierarchy.coeffs.data(), fits[0].hierarchy.coeffs.size() * sizeof(double)), 0);
    EXPECT_EQ(fits[0].limit_max, fits[1].limit_max);
    EXPECT_EQ(fits[0].limit_back_max, fits[1].limit_back_max);
  }
}

// fit_mesh, which indexes the input on another thread while the base is decimated, fits as the
// two steps in turn do, to the bit, and takes the default levels for the base it made; a cancel
// during the decimation comes out as Cancelled (the index thread joined), nothing returned.
TEST(FitLevels, FitMeshIsTheBaseThenTheLevels) {
  const Input in = torus();
  BaseMeshOptions bo;
  bo.quads = fit_base_quads(Scheme::Loop);
  FitOptions o;
  o.scheme = Scheme::Loop;
  o.levels = -1;
  const MeshFit m = fit_mesh(in.n, in.faces, in.xyz, bo, o);
  const BaseMesh base = decimate_to_base(in.n, in.faces, in.xyz, bo);
  EXPECT_EQ(m.base.positions, base.positions);
  EXPECT_EQ(m.base.input_vertex, base.input_vertex);
  o.levels = default_fit_levels(in.n, base.num_vertices, Scheme::Loop);
  EXPECT_GE(o.levels, 2);
  EXPECT_EQ(m.fitted.hierarchy.finest_level(), o.levels);
  const Fitted f = fit_levels(base, in.faces, in.xyz, o);
  ASSERT_EQ(m.fitted.finest.size(), f.finest.size());
  EXPECT_EQ(std::memcmp(m.fitted.finest.data(), f.finest.data(), f.finest.size() * sizeof(double)), 0);
  EXPECT_EQ(m.fitted.limit_max, f.limit_max);
  EXPECT_GT(m.base_ms, 0.0);
  std::vector<std::string> stages;
  for (const auto& [stage, ms] : m.fitted.stage_ms) stages.push_back(stage);
  EXPECT_EQ(stages, (std::vector<std::string>{"indexing", "hierarchy", "levels", "analysis", "report"}));

  bo.progress = [](double done) { return done < 0.3; };
  EXPECT_THROW(fit_mesh(in.n, in.faces, in.xyz, bo, o), Cancelled);
}

// A shared scan (../shared/data/scans), or none when the data is absent.
std::optional<Input> load_scan(const char* name) {
  const std::filesystem::path path = std::filesystem::path(SUBLIFT_SHARED_DATA) / "scans" / name;
  if (!std::filesystem::exists(path)) return std::nullopt;
  const LoadedMesh lm = import_surface_mesh(path.string());
  Input in{static_cast<std::uint32_t>(lm.mesh.num_vertices()), {}, {}};
  in.faces.offsets = lm.mesh.face_offsets;
  in.faces.items = lm.mesh.face_indices;
  for (const auto& p : lm.mesh.positions) in.xyz.insert(in.xyz.end(), {p.x, p.y, p.z});
  return in;
}

// Issue 17's distance and fold goals on three shared scans, with defaults (base 1/64 of the
// scan, the levels that bring it to about the scan's count): the genus-1 rocker arm, the
// stanford bunny (5 holes) and fandisk (creases) fitted by sqrt(2) lie within 0.5 % of the
// diagonal both ways and 0.1 % RMS, with no folded face and the scan's Euler characteristic and
// boundary loops (docs/fit.md has every scheme; fandisk's feature lines are not yet within 0.2 %).
TEST(FitLevels, ThreeScansMeetTheGoalsWithSqrt2) {
  for (const char* name : {"rocker-arm.obj", "stanford-bunny.obj", "fandisk.off"}) {
    SCOPED_TRACE(name);
    const std::optional<Input> scan = load_scan(name);
    if (!scan) GTEST_SKIP() << "no third-party data at " << SUBLIFT_SHARED_DATA << " (SUBLIFT_SHARED_DATA)";
    BaseMeshOptions bo;
    bo.quads = fit_base_quads(Scheme::Sqrt2);
    const BaseMesh base = decimate_to_base(scan->n, scan->faces, scan->xyz, bo);
    EXPECT_EQ(base.euler_after, base.euler_before);
    EXPECT_EQ(base.boundary_loops_after, base.boundary_loops_before);
    FitOptions o;
    o.scheme = Scheme::Sqrt2;
    o.levels = default_fit_levels(scan->n, base.num_vertices, Scheme::Sqrt2);
    const Fitted f = fit_levels(base, scan->faces, scan->xyz, o);
    const FitLevelReport& r = f.levels.back();
    std::printf("%s: %u -> %u vertices, %d levels; %.4f / %.4f %% to the scan, %.4f / %.4f %% back (RMS / max), %u folded\n", name,
                base.num_vertices, r.vertices, o.levels, 100 * r.rms, 100 * r.max, 100 * r.back_rms, 100 * r.back_max, r.folded);
    EXPECT_GT(r.vertices, scan->n / 2);
    EXPECT_LT(r.max, 0.005);
    EXPECT_LT(r.back_max, 0.005);
    EXPECT_LT(r.rms, 0.001);
    EXPECT_LT(r.back_rms, 0.001);
    EXPECT_EQ(r.folded, 0u);
    EXPECT_EQ(f.limit_folded, 0u);
  }
}

// A real scan, the npm bunny, with every triangle scheme: its decimated base is so coarse around
// the ears that faces' patches meet themselves there (once refused: docs/fit.md). The fit
// reconstructs exactly, and each level covers the scan better.
TEST(FitLevels, BunnyBaseFitsWithEveryTriangleScheme) {
  const std::optional<Input> scan = load_scan("bunny_npm_lowres.obj");
  if (!scan) GTEST_SKIP() << "no third-party data at " << SUBLIFT_SHARED_DATA << " (SUBLIFT_SHARED_DATA)";
  const Input& in = *scan;
  const BaseMesh base = decimate_to_base(in.n, in.faces, in.xyz, {30});
  for (Scheme s : {Scheme::LinearTri, Scheme::Loop, Scheme::Butterfly}) {
    SCOPED_TRACE(scheme_name(s));
    FitOptions o;
    o.scheme = s;
    o.levels = 2;
    const Fitted f = fit_levels(base, in.faces, in.xyz, o);
    EXPECT_LE(testing::max_abs_diff(synthesize(f.hierarchy, 2), f.finest), 1e-12);
    // Each level covers the scan better than the one above (docs/fit.md has the numbers).
    EXPECT_LT(f.levels[1].back_max, f.levels[0].back_max);
    EXPECT_LT(f.levels[1].back_rms, f.levels[0].back_rms);
  }
}

}  // namespace
}  // namespace sublift
