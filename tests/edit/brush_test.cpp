// core/edit/brush (issue 19): each brush's move on a flat grid, computed here by hand; the
// falloff curves; front faces only; and a dab in a session changes the dabbed level's control
// points only, with the finer levels resynthesised from the unchanged detail.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "core/base/errors.h"
#include "core/complex/complex_build.h"
#include "core/complex/shapes.h"
#include "core/edit/brush.h"
#include "core/edit/session.h"
#include "tests/edit_grid.h"
#include "tests/noisy_hierarchy.h"
#include "tests/test_shapes.h"

namespace sublift {
namespace {

// An n x n grid of unit quads in z = 0 centred on the origin, with its upward rows.
Complex flat_grid(int n, std::vector<double>& p) { return testing::quad_grid(n, n, p, -n / 2.0); }

TEST(Brush, FalloffCurves) {
  EXPECT_EQ(falloff_weight(Falloff::Smooth, 0.0), 1.0);
  EXPECT_EQ(falloff_weight(Falloff::Smooth, 0.5), 0.5);
  EXPECT_EQ(falloff_weight(Falloff::Linear, 0.25), 0.75);
  EXPECT_EQ(falloff_weight(Falloff::Sharp, 0.5), 0.25);
  EXPECT_EQ(falloff_weight(Falloff::Constant, 0.99), 1.0);
  for (const Falloff f : {Falloff::Smooth, Falloff::Linear, Falloff::Sharp, Falloff::Constant}) {
    EXPECT_EQ(falloff_weight(f, 1.0), 0.0);
    EXPECT_EQ(parse_falloff(falloff_name(f)), f);
  }
  EXPECT_THROW(parse_brush("clay"), Error);
}

TEST(Brush, EachKindOnAFlatGrid) {
  std::vector<double> p;
  const Complex c = flat_grid(8, p);  // vertex (i, j) at (i - 4, j - 4, 0); the centre (4, 4) is 40
  std::vector<std::uint32_t> vs;
  std::vector<double> d;
  BrushSettings b;
  b.radius = 1.5;
  b.strength = 0.8;
  b.falloff = Falloff::Linear;
  Dab dab;  // at the origin, seen from +z looking down
  dab.view_dir = {0, 0, -1};
  auto delta_of = [&](std::uint32_t v) {
    for (std::size_t k = 0; k < vs.size(); ++k)
      if (vs[k] == v) return glm::dvec3(d[3 * k], d[3 * k + 1], d[3 * k + 2]);
    return glm::dvec3(NAN);
  };
  // Draw: the 9 points within 1.5 (distances 0, 1, sqrt 2) move up by w r / 4.
  b.kind = BrushKind::Draw;
  brush_dab(b, dab, c, p, vs, d);
  ASSERT_EQ(vs.size(), 9u);
  EXPECT_EQ(delta_of(40), glm::dvec3(0, 0, 0.8 * 1.5 / 4));
  EXPECT_NEAR(delta_of(41).z, 0.8 * (1 - 1 / 1.5) * 1.5 / 4, 1e-15);
  EXPECT_NEAR(delta_of(50).z, 0.8 * (1 - std::sqrt(2.0) / 1.5) * 1.5 / 4, 1e-15);
  b.invert = true;
  brush_dab(b, dab, c, p, vs, d);
  EXPECT_EQ(delta_of(40), glm::dvec3(0, 0, -0.8 * 1.5 / 4));
  b.invert = false;
  // Seen from below with front faces only, nothing faces the viewer; without it all 9 move.
  dab.view_dir = {0, 0, 1};
  brush_dab(b, dab, c, p, vs, d);
  EXPECT_TRUE(vs.empty());
  b.front_faces_only = false;
  brush_dab(b, dab, c, p, vs, d);
  EXPECT_EQ(vs.size(), 9u);
  dab.view_dir = {0, 0, -1};
  // Grab: the motion times the weight.
  b.kind = BrushKind::Grab;
  dab.motion = {0.1, 0.2, 0.3};
  brush_dab(b, dab, c, p, vs, d);
  EXPECT_EQ(delta_of(40), glm::dvec3(0.1, 0.2, 0.3) * 0.8);
  // Pinch: towards the centre in the plane, by w / 2.
  b.kind = BrushKind::Pinch;
  brush_dab(b, dab, c, p, vs, d);
  EXPECT_NEAR(delta_of(41).x, -1.0 * 0.5 * 0.8 * (1 - 1 / 1.5), 1e-15);
  EXPECT_EQ(delta_of(41).z, 0.0);
  // Smooth and flatten on a bump: the centre raised by 1 goes down towards its neighbours'
  // mean (0) by w, and towards the area's mean plane.
  p[3 * 40 + 2] = 1.0;
  dab.center = {0, 0, 1};
  b.kind = BrushKind::Smooth;
  b.radius = 0.5;  // the centre alone
  brush_dab(b, dab, c, p, vs, d);
  ASSERT_EQ(vs, (std::vector<std::uint32_t>{40}));
  EXPECT_EQ(delta_of(40), glm::dvec3(0, 0, -0.8));
  b.kind = BrushKind::Flatten;
  b.radius = 1.5;
  brush_dab(b, dab, c, p, vs, d);
  EXPECT_LT(delta_of(40).z, 0.0);  // the bump comes down
  EXPECT_GT(delta_of(41).z, 0.0);  // its flat neighbours come up to the mean plane
  // Normals need a surface.
  std::vector<double> cp;
  Complex curve = make_curve_loop(8, cp);
  b.kind = BrushKind::Inflate;
  EXPECT_THROW(brush_dab(b, dab, curve, cp, vs, d), Error);
  b.kind = BrushKind::Smooth;
  EXPECT_NO_THROW(brush_dab(b, dab, curve, cp, vs, d));
  b.radius = 0.0;
  EXPECT_THROW(brush_dab(b, dab, c, p, vs, d), Error);
}

TEST(Brush, DabsAreSpacedAlongTheStroke) {
  const auto c = dab_centres_along({0, 0, 0}, {1, 0, 0}, 0.3);
  ASSERT_EQ(c.size(), 3u);  // at 0.3, 0.6, 0.9; the rest waits for the next move
  EXPECT_NEAR(c[0].x, 0.3, 1e-15);
  EXPECT_NEAR(c[2].x, 0.9, 1e-15);
  EXPECT_TRUE(dab_centres_along({0, 0, 0}, {0.2, 0, 0}, 0.3).empty());
  EXPECT_EQ(dab_centres_along({0, 0, 0}, {100, 0, 0}, 0.01, 64).size(), 64u);
  EXPECT_TRUE(dab_centres_along({0, 0, 0}, {1, 0, 0}, 0.0).empty());
}

TEST(Brush, RayHitFindsTheNearestFace) {
  std::vector<double> p;
  const Complex c = flat_grid(4, p);
  glm::dvec3 hit;
  ASSERT_TRUE(ray_hit(p, c.faces, {0.25, -0.5, 3.0}, {0, 0, -1}, hit));
  EXPECT_EQ(hit, glm::dvec3(0.25, -0.5, 0.0));
  EXPECT_FALSE(ray_hit(p, c.faces, {9.0, 0.0, 3.0}, {0, 0, -1}, hit));
  EXPECT_FALSE(ray_hit(p, c.faces, {0.0, 0.0, 3.0}, {0, 0, 1}, hit));  // pointing away
}

bool same_bits(std::span<const double> a, std::span<const double> b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

// A dab at level j moves level-j control points only: the detail of level j and finer (the
// wavelets on vertices of level j+1 and up) is untouched bit for bit, level j's other points
// are untouched, and the finer levels are the synthesis of the new level j with that detail.
TEST(Brush, ADabAtLevelJChangesOnlyLevelJAndWhatSynthesisDerives) {
  for (const int j : {0, 1, 2}) {
    SCOPED_TRACE(j);
    Session s(testing::noisy_torus(10, 8, 3, Scheme::Cubic, 4, 0.02));
    const std::vector<double> coeffs = s.hierarchy().coeffs;
    const std::vector<double> net(s.positions(j).begin(), s.positions(j).end());
    Complex c = s.hierarchy().levels[static_cast<std::size_t>(j)];
    build_adjacency(c);
    BrushSettings b;
    b.kind = BrushKind::Inflate;
    b.radius = 0.4;
    Dab dab;
    dab.center = {net[0], net[1], net[2]};
    dab.view_dir = glm::dvec3(0.0);
    std::vector<std::uint32_t> vs;
    std::vector<double> d;
    brush_dab(b, dab, c, net, vs, d);
    ASSERT_GT(vs.size(), 1u);
    s.move_each(j, vs, d);
    const std::size_t first_detail = 3 * std::size_t(s.num_vertices(j));
    EXPECT_TRUE(std::memcmp(s.hierarchy().coeffs.data() + first_detail, coeffs.data() + first_detail,
                            (coeffs.size() - first_detail) * sizeof(double)) == 0);
    std::vector<std::uint8_t> dabbed(s.num_vertices(j), 0);
    for (const std::uint32_t v : vs) dabbed[v] = 1;
    for (std::uint32_t v = 0; v < s.num_vertices(j); ++v)
      if (!dabbed[v]) {
        ASSERT_TRUE(same_bits(s.positions(j).subspan(3 * v, 3), std::span<const double>(net).subspan(3 * v, 3))) << v;
      }
    for (int l = 0; l <= s.finest_level(); ++l)
      EXPECT_LT(testing::max_abs_diff(synthesize(s.hierarchy(), l), s.positions(l)), 1e-11) << "level " << l;
    ASSERT_TRUE(s.undo());
    EXPECT_TRUE(same_bits(s.hierarchy().coeffs, coeffs));
  }
}

}  // namespace
}  // namespace sublift
