// Perfect reconstruction for every scheme, dimension and feature mix: analysis then synthesis
// returns the input (float: relative error < 1e-12; integer mode: bit-exact), and analysing a
// pure subdivision gives zero wavelet coefficients.
#include <gtest/gtest.h>

#include <cmath>

#include "core/analysis/compress.h"
#include "core/complex/complex_build.h"
#include "core/multires/hierarchy.h"
#include "core/io/mesh/mesh_import.h"
#include "core/complex/shapes.h"
#include "tests/test_lattices.h"
#include "tests/test_shapes.h"

using namespace sublift;
using namespace sublift::testing;

namespace {

struct Case {
  std::string name;
  Complex base;
  int levels;
};

std::vector<Case> cases() {
  std::vector<Case> out;
  std::vector<double> pos;
  out.push_back({"closed curve", make_curve_loop(7, pos), 4});
  Csr lines;
  lines.items = {0, 1, 2, 3, 4, 1, 5};  // open polyline crossing itself at vertex 1 (a cusp)
  lines.offsets.push_back(static_cast<std::uint32_t>(lines.items.size()));
  out.push_back({"open curve with junction", complex_from_polylines(6, lines), 4});
  out.push_back({"torus", complex_from_surface_mesh(make_quad_torus(5, 4)), 3});
  const std::string dir = SUBLIFT_ASSETS_DIR;
  for (const char* f : {"mixed_polygons.obj", "quad_grid_boundary.obj", "crease_loop.obj", "pyramid.obj"})
    out.push_back({f, complex_from_surface_mesh(import_surface_mesh(dir + "/" + f).mesh), 3});
  SurfaceMesh tagged = import_surface_mesh(dir + "/mixed_polygons.obj").mesh;
  tagged.tags.push_back({"crease", {5, 6, 7}, {1.0}, {}, 0});  // crease chain ending in a dart
  tagged.tags.push_back({"corner", {10}, {1.0}, {}, 0});
  out.push_back({"mixed with crease, dart and corner", complex_from_surface_mesh(tagged), 3});
  Complex block = make_hex_block(2, pos);
  FeatureTags tags;  // vertex (i, j, k) of the 2 x 2 x 2 block is (k * 3 + j) * 3 + i
  tags.feature_faces.push_back({1, 4, 13, 10});  // an inner face on the plane x = 1
  tags.crease_edges.push_back({13, 14});         // centre to the x = 2 side: a dart inside
  tags.corner_vertices.push_back(0);
  assign_feature_dims(block, tags);
  EXPECT_EQ(block.vertex_dim[13], 0);  // rim of the inner patch (2 curve edges) plus the crease
  EXPECT_EQ(block.vertex_dim[4], 1);   // rim of the inner patch meeting the boundary surface
  out.push_back({"hex block with features", block, 2});
  out.push_back({"pyramid cell (type-4 cells)", pyramid_cell(), 3});
  out.push_back({"prism cell", prism_cell(), 3});
  out.push_back({"tetrahedron", tetra_cell(), 3});
  return out;
}

double max_abs(const std::vector<double>& v) {
  double m = 0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

}  // namespace

TEST(Reconstruction, FloatIsPerfectForEverySchemeAndDimension) {
  std::uint64_t seed = 100;
  for (const Case& c : cases())
    for (Scheme s : {Scheme::Linear, Scheme::Cubic})
      for (int channels : {3, 5}) {
        SCOPED_TRACE(c.name + " " + scheme_name(s) + " channels " + std::to_string(channels));
        Hierarchy h = make_hierarchy(c.base, c.levels, s, channels);
        const std::vector<double> fine = random_values(h.coeffs.size(), ++seed, -100, 100);
        analyze(h, fine);
        const std::vector<double> back = synthesize(h, c.levels);
        double err = 0;
        for (std::size_t i = 0; i < fine.size(); ++i) err = std::max(err, std::abs(back[i] - fine[i]));
        EXPECT_LT(err / max_abs(fine), 1e-12);
        EXPECT_GT(level_stats(h).back().wavelet_max, 1.0);  // random data has real detail
      }
}

TEST(Reconstruction, IntegerModeIsBitExact) {
  std::uint64_t seed = 200;
  for (const Case& c : cases())
    for (Scheme s : {Scheme::Linear, Scheme::Cubic}) {
      SCOPED_TRACE(c.name + " " + scheme_name(s));
      Hierarchy h = make_hierarchy(c.base, c.levels, s, 3, /*integer=*/true);
      std::vector<double> fine = random_values(h.coeffs.size(), ++seed, -1000, 1000);
      for (double& x : fine) x = std::round(x);
      analyze(h, fine);
      for (double x : h.coeffs) ASSERT_EQ(x, std::round(x)) << "coefficients stay integers";
      EXPECT_EQ(synthesize(h, c.levels), fine);
      // And a pure integer subdivision analyses back to the base with all wavelets exactly 0.
      std::vector<double> base(std::size_t(h.num_vertices(0)) * 3);
      for (std::size_t i = 0; i < base.size(); ++i) base[i] = double(int(i * 37 % 201) - 100);
      set_base(h, base);
      const std::vector<double> sub = synthesize(h, c.levels);
      analyze(h, sub);
      EXPECT_TRUE(std::equal(base.begin(), base.end(), h.coeffs.begin()));
      EXPECT_TRUE(std::all_of(h.coeffs.begin() + base.size(), h.coeffs.end(), [](double x) { return x == 0.0; }));
    }
}

TEST(Reconstruction, PureSubdivisionHasZeroWavelets) {
  std::uint64_t seed = 300;
  for (const Case& c : cases())
    for (Scheme s : {Scheme::Linear, Scheme::Cubic}) {
      SCOPED_TRACE(c.name + " " + scheme_name(s));
      Hierarchy h = make_hierarchy(c.base, c.levels, s, 3);
      const std::vector<double> base = random_values(std::size_t(h.num_vertices(0)) * 3, ++seed);
      set_base(h, base);
      const std::vector<double> fine = synthesize(h, c.levels);
      analyze(h, fine);
      for (std::size_t i = 0; i < base.size(); ++i) EXPECT_NEAR(h.coeffs[i], base[i], 1e-13);
      for (const LevelStats& st : level_stats(h)) EXPECT_LT(st.wavelet_max, 1e-13) << "level " << st.level;
    }
}

TEST(Reconstruction, KeepLargestZeroIsPureSubdivisionAndOneIsExact) {
  Hierarchy h = make_hierarchy(complex_from_surface_mesh(make_quad_torus(6, 4)), 3, Scheme::Cubic, 3);
  const std::vector<double> fine = random_values(h.coeffs.size(), 7);
  analyze(h, fine);
  Hierarchy all = h, none = h, half = h;
  EXPECT_EQ(keep_largest(all, 1.0), h.coeffs.size() / 3 - h.num_vertices(0));
  EXPECT_EQ(synthesize(all, 3), synthesize(h, 3));
  EXPECT_EQ(keep_largest(none, 0.0), 0u);
  Hierarchy pure = h;
  std::vector<double> base(h.coeffs.begin(), h.coeffs.begin() + std::size_t(h.num_vertices(0)) * 3);
  set_base(pure, base);
  EXPECT_EQ(synthesize(none, 3), synthesize(pure, 3));
  // Keeping half is in between: error smaller than dropping everything.
  keep_largest(half, 0.5);
  auto err = [&](const Hierarchy& x) {
    const auto v = synthesize(x, 3);
    double e = 0;
    for (std::size_t i = 0; i < v.size(); ++i) e += (v[i] - fine[i]) * (v[i] - fine[i]);
    return e;
  };
  EXPECT_LT(err(half), err(none));
  EXPECT_GT(err(half), 0.0);
}
