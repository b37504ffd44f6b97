// Rebuilding a hierarchy from a mesh subdivided elsewhere (core/multires/rebuild.h): the
// analysis reproduces the input, bilinear data has zero linear wavelets, a coarse edit carries
// the detail as on a project made in engine order, and the project keeps the input order.
#include "core/complex/feature_tags.h"
#include "core/multires/rebuild.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <numeric>
#include <random>

#include "core/base/errors.h"
#include "core/complex/complex_build.h"
#include "core/io/project/project_io.h"
#include "tests/mesh_fixtures.h"
#include "tests/test_shapes.h"

namespace sublift {
namespace {

using fixtures::Polygons;
using testing::random_coefficients;

struct Input {
  Polygons mesh;                    // shuffled
  std::vector<double> xyz;          // positions in the shuffled order
  std::vector<std::uint32_t> perm;  // original fine vertex -> input vertex
  Hierarchy original;               // the engine-order hierarchy the input came from
};

// `base` refined `levels` times by `scheme` from base positions (plus `detail` random wavelets
// when nonzero), written out in a shuffled vertex and face order.
Input make_input(const Polygons& base, int levels, Scheme scheme, double detail, unsigned seed, bool integer = false) {
  Input in;
  in.original = make_hierarchy(complex_from_polygons(base.num_vertices, base.faces), levels, scheme, 3, integer);
  Hierarchy& h = in.original;
  std::vector<double> b = random_coefficients(3 * std::size_t(base.num_vertices), seed, integer);
  set_base(h, b);
  if (detail != 0)
    for (std::size_t i = b.size(); i < h.coeffs.size(); ++i) h.coeffs[i] = detail * random_coefficients(1, seed + unsigned(i), integer)[0];
  const std::vector<double> x = synthesize(h, levels);
  const Complex& fine = h.levels.back();
  in.mesh = fixtures::shuffled({fine.num_vertices, fine.faces, x}, seed, &in.perm);
  in.xyz = std::move(in.mesh.positions);
  return in;
}

double relative(std::span<const double> a, std::span<const double> b) {
  double scale = 0;
  for (double v : b) scale = std::max(scale, std::abs(v));
  return testing::max_abs_diff(a, b) / scale;
}

std::vector<double> finest_in_input_order(const Rebuilt& r) {
  InputOrder o;
  o.level = r.hierarchy.finest_level();
  o.engine_vertex = r.engine_vertex;
  return in_input_order(o, synthesize(r.hierarchy, o.level), 3);
}

TEST(Rebuild, BilinearDataHasZeroLinearWaveletsAndItsBase) {
  // The regular torus: its connectivity has four equally good coarsenings; the positions pick
  // the one whose edge points are midpoints.
  for (const Polygons& base : {fixtures::cube(), fixtures::mixed_patch(), fixtures::torus(3, 5)}) {
    const Input in = make_input(base, 3, Scheme::Linear, 0.0, 5);
    const Rebuilt r = rebuild_hierarchy(in.mesh.num_vertices, in.mesh.faces, in.xyz, Scheme::Linear, -1);
    ASSERT_EQ(r.hierarchy.finest_level(), 3) << r.detected.stop;
    const std::size_t n0 = 3 * std::size_t(r.hierarchy.num_vertices(0));
    double worst = 0;
    for (std::size_t i = n0; i < r.hierarchy.coeffs.size(); ++i) worst = std::max(worst, std::abs(r.hierarchy.coeffs[i]));
    EXPECT_LE(worst, 1e-14);
    // Base coefficients are the original base positions (base vertex b is fine vertex b).
    std::vector<std::uint32_t> inv(in.perm.size());
    for (std::uint32_t v = 0; v < in.perm.size(); ++v) inv[in.perm[v]] = v;
    for (std::uint32_t v = 0; v < r.hierarchy.num_vertices(0); ++v) {
      const std::uint32_t b = inv[r.detected.steps.front().input_vertex[v]];
      ASSERT_LT(b, base.num_vertices);
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(r.hierarchy.coeffs[3 * v + k], in.original.coeffs[3 * b + k], 1e-14);
    }
    EXPECT_LE(relative(finest_in_input_order(r), in.xyz), 1e-14);
  }
}

TEST(Rebuild, AnalysisReproducesTheInputForEveryScheme) {
  struct Case {
    Polygons base;
    Scheme scheme;
    double tolerance;
  };
  const Case cases[] = {{fixtures::cube(), Scheme::Cubic, 1e-12},
                        {fixtures::cube(), Scheme::Sqrt2, 1e-12},
                        {fixtures::torus(3, 5), Scheme::Sqrt2, 1e-12},
                        {fixtures::mixed_patch(), Scheme::Sqrt2, 1e-12},
                        {fixtures::mixed_patch(), Scheme::Cubic, 1e-12},
                        {fixtures::octahedron(), Scheme::LinearTri, 1e-12},
                        {fixtures::octahedron(), Scheme::Butterfly, 1e-12},
                        {fixtures::octahedron(), Scheme::Loop, 1e-12}};
  for (const Case& c : cases) {
    SCOPED_TRACE(scheme_name(c.scheme));
    const Input in = make_input(c.base, 3, c.scheme, 0.05, 9);
    const Rebuilt r = rebuild_hierarchy(in.mesh.num_vertices, in.mesh.faces, in.xyz, c.scheme, 3);
    EXPECT_LE(relative(finest_in_input_order(r), in.xyz), c.tolerance);
  }
}

TEST(Rebuild, IntegerModeIsBitExact) {
  const Input in = make_input(fixtures::cube(), 3, Scheme::Cubic, 0.0, 13, true);
  std::vector<double> xyz = in.xyz;
  for (double& v : xyz) v = std::round(v * 7.0) + 0.0;  // any integer shape
  const Rebuilt r = rebuild_hierarchy(in.mesh.num_vertices, in.mesh.faces, xyz, Scheme::Cubic, 3, true);
  const std::vector<double> back = finest_in_input_order(r);
  ASSERT_EQ(back.size(), xyz.size());
  EXPECT_EQ(std::memcmp(back.data(), xyz.data(), xyz.size() * sizeof(double)), 0);
}

TEST(Rebuild, CoarseEditCarriesTheDetailAsInEngineOrder) {
  const Input in = make_input(fixtures::mixed_patch(), 3, Scheme::Cubic, 0.05, 17);
  Rebuilt r = rebuild_hierarchy(in.mesh.num_vertices, in.mesh.faces, in.xyz, Scheme::Cubic, 3);
  Hierarchy original = in.original;
  // The same coarse edit: move base vertex b (the original's numbering) by d in both.
  std::vector<std::uint32_t> inv(in.perm.size());
  for (std::uint32_t v = 0; v < in.perm.size(); ++v) inv[in.perm[v]] = v;
  const double d[3] = {0.3, -0.2, 0.1};
  for (std::uint32_t v = 0; v < r.hierarchy.num_vertices(0); ++v) {
    const std::uint32_t b = inv[r.detected.steps.front().input_vertex[v]];
    if (b != 2) continue;
    for (int k = 0; k < 3; ++k) {
      r.hierarchy.coeffs[3 * v + k] += d[k];
      original.coeffs[3 * b + k] += d[k];
    }
  }
  const std::vector<double> ours = finest_in_input_order(r), x = synthesize(original, 3);
  std::vector<double> want(x.size());
  for (std::uint32_t v = 0; v < in.perm.size(); ++v)
    for (int k = 0; k < 3; ++k) want[3 * std::size_t(in.perm[v]) + k] = x[3 * std::size_t(v) + k];
  EXPECT_LE(relative(ours, want), 1e-12);
  EXPECT_GT(relative(ours, in.xyz), 1e-3);  // the edit did move the shape
}

TEST(Rebuild, AskingForMoreLevelsThanTheMeshHoldsSaysWhere) {
  const Input in = make_input(fixtures::cube(), 2, Scheme::Cubic, 0.0, 3);
  try {
    rebuild_hierarchy(in.mesh.num_vertices, in.mesh.faces, in.xyz, Scheme::Cubic, 3);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("holds 2 levels"), std::string::npos) << e.what();
  }
  // Two sqrt(2) steps make the quad split's connectivity: the same mesh holds 4 sqrt(2) levels
  // of the cube, and one more of the tetrahedron the cube is a sqrt(2) step of.
  EXPECT_EQ(rebuild_hierarchy(in.mesh.num_vertices, in.mesh.faces, in.xyz, Scheme::Sqrt2, -1).hierarchy.finest_level(), 5);
  EXPECT_EQ(rebuild_auto_scheme(in.mesh.faces), Scheme::Cubic);
  EXPECT_EQ(rebuild_auto_scheme(fixtures::octahedron().faces), Scheme::Loop);
}

TEST(Rebuild, ProjectKeepsTheInputOrder) {
  const Input in = make_input(fixtures::mixed_patch(), 2, Scheme::Cubic, 0.05, 23);
  Rebuilt r = rebuild_hierarchy(in.mesh.num_vertices, in.mesh.faces, in.xyz, Scheme::Cubic, -1);
  ProjectExtras extras;
  extras.input_order.level = r.hierarchy.finest_level();
  extras.input_order.engine_vertex = r.engine_vertex;
  extras.input_order.faces = in.mesh.faces;
  const std::string path = (std::filesystem::temp_directory_path() / "sublift_rebuild_test.sublift").string();
  write_project(path, r.hierarchy, extras);
  ProjectExtras back;
  const Hierarchy h = read_project(path, &back);
  EXPECT_EQ(back.input_order.level, extras.input_order.level);
  EXPECT_EQ(back.input_order.engine_vertex, extras.input_order.engine_vertex);
  EXPECT_EQ(back.input_order.faces.items, in.mesh.faces.items);
  EXPECT_EQ(back.input_order.faces.offsets, in.mesh.faces.offsets);
  EXPECT_LE(relative(in_input_order(back.input_order, synthesize(h, h.finest_level()), 3), in.xyz), 1e-12);
  // An order that is no permutation is refused on save.
  ProjectExtras bad = extras;
  bad.input_order.engine_vertex[0] = bad.input_order.engine_vertex[1];
  EXPECT_THROW(write_project(path, r.hierarchy, bad), Error);
  // A face list that is not the level's faces too.
  bad = extras;
  std::swap(bad.input_order.faces.items[0], bad.input_order.faces.items[5]);
  EXPECT_THROW(write_project(path, r.hierarchy, bad), Error);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace sublift

namespace sublift {
namespace {

// Creases and corners of the fine mesh come down to the base; what cannot is named.
TEST(Rebuild, CreasesAndCornersAreCarriedToTheBase) {
  const fixtures::Polygons cube = fixtures::cube();
  FeatureTags tags;
  tags.crease_edges = {{0, 2}, {2, 3}};  // two edges of face 0
  tags.corner_vertices = {7};
  Hierarchy h = make_hierarchy(complex_from_polygons(cube.num_vertices, cube.faces, tags), 2, Scheme::Cubic, 3);
  set_base(h, cube.positions);
  const std::vector<double> x = synthesize(h, 2);
  Complex fine = h.levels.back();
  build_adjacency(fine);
  const FeatureTags fine_tags = derive_feature_tags(fine);
  EXPECT_EQ(fine_tags.crease_edges.size(), 8u);  // each crease halved twice
  EXPECT_EQ(fine_tags.corner_vertices.size(), 1u);
  Rebuilt r = rebuild_hierarchy(fine.num_vertices, fine.faces, x, Scheme::Cubic, 2, false, 2, fine_tags);
  EXPECT_TRUE(r.features.dropped.empty());
  EXPECT_EQ(r.features.base.crease_edges.size(), 2u);
  EXPECT_EQ(r.features.base.corner_vertices.size(), 1u);
  // The rebuilt levels have the input's features: its finest edges of dim 1 are the input's.
  Complex again = r.hierarchy.levels.back();
  build_adjacency(again);
  EXPECT_EQ(derive_feature_tags(again).crease_edges.size(), 8u);
  // A crease across a coarse face (from a face point to an edge point) cannot come down.
  FeatureTags odd = fine_tags;
  // Level-2 face 0 is (v, e, f, e') of level-1 face 0 (refine.h): corners 1 and 2 are an edge
  // point and the face point.
  odd.crease_edges.emplace_back(fine.faces.row(0)[1], fine.faces.row(0)[2]);
  Rebuilt d = rebuild_hierarchy(fine.num_vertices, fine.faces, x, Scheme::Cubic, 2, false, 2, odd);
  ASSERT_EQ(d.features.dropped.size(), 1u);
  EXPECT_NE(d.features.dropped[0].find("runs inside a face"), std::string::npos) << d.features.dropped[0];
}

}  // namespace
}  // namespace sublift

namespace sublift {
namespace {

// Lattices: trilinear data (the linear scheme's pure subdivision of a block with random
// corners) has zero linear wavelets; any data comes back exactly; the vertex order is kept.
TEST(Rebuild, LatticesAnalyseAndComeBack) {
  const fixtures::Cells b = fixtures::hex_block(2);
  for (Scheme scheme : {Scheme::Linear, Scheme::Cubic}) {
    SCOPED_TRACE(scheme_name(scheme));
    Hierarchy h = make_hierarchy(complex_from_cells(b.num_vertices, b.face_loops, b.cell_faces), 2, scheme, 3);
    set_base(h, random_coefficients(3 * std::size_t(b.num_vertices), 4, false));
    if (scheme == Scheme::Cubic)
      for (std::size_t i = 3 * std::size_t(b.num_vertices); i < h.coeffs.size(); ++i) h.coeffs[i] = 0.01 * std::sin(double(i));
    const std::vector<double> x = synthesize(h, 2);
    Complex fine = h.levels.back();
    build_adjacency(fine);
    const Rebuilt r = rebuild_volume_hierarchy(fine, x, scheme, 2);
    ASSERT_EQ(r.hierarchy.finest_level(), 2);
    InputOrder o;
    o.level = 2;
    o.engine_vertex = r.engine_vertex;
    EXPECT_LE(relative(in_input_order(o, synthesize(r.hierarchy, 2), 3), x), 1e-12);
    if (scheme == Scheme::Linear) {
      double worst = 0;
      for (std::size_t i = 3 * std::size_t(r.hierarchy.num_vertices(0)); i < r.hierarchy.coeffs.size(); ++i)
        worst = std::max(worst, std::abs(r.hierarchy.coeffs[i]));
      EXPECT_LE(worst, 1e-14);
    }
  }
  Complex fine = make_hierarchy(complex_from_cells(b.num_vertices, b.face_loops, b.cell_faces), 1, Scheme::Cubic, 3).levels.back();
  build_adjacency(fine);
  EXPECT_THROW(rebuild_volume_hierarchy(fine, std::vector<double>(3 * fine.num_vertices), Scheme::Loop, -1), Error);
}

}  // namespace
}  // namespace sublift
