// Space-time lattices (core/anim/spacetime.h): the sweep's counts and validity, the vertex map
// against refine.h's numbering, perfect reconstruction, a static animation's zero time
// wavelets, and the fit of the finest layers to the frames.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>

#include "core/anim/spacetime.h"
#include "core/base/errors.h"
#include "core/complex/complex_build.h"
#include "tests/mesh_fixtures.h"
#include "tests/test_shapes.h"

namespace {

using namespace sublift;
namespace fx = sublift::fixtures;

Complex surface_of(const fx::Polygons& m) { return complex_from_polygons(m.num_vertices, m.faces); }

// The octahedron with positions (its 6 unit axis points), a closed triangle mesh.
fx::Polygons octahedron_xyz() {
  fx::Polygons m = fx::octahedron();
  m.positions = {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1};
  return m;
}

// A 3 x 2 quad grid (open, boundary all round) with a triangle and a pentagon glued on.
fx::Polygons open_patch() {
  fx::Polygons m = fx::mixed_patch();
  m.positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 2, 0, 0.2, 2.5, 1, 0.1, 1.5, 1.8, 0};
  return m;
}

// Frame t of a moving animation: the base positions bent and translated as t goes on.
std::vector<double> moving_frames(const std::vector<double>& base, int frames) {
  std::vector<double> out;
  for (int t = 0; t < frames; ++t) {
    const double s = double(t) / (frames - 1);
    for (std::size_t i = 0; i < base.size(); i += 3) {
      const double x = base[i], y = base[i + 1], z = base[i + 2];
      out.insert(out.end(), {x + 0.3 * s + 0.1 * std::sin(3 * s + y), y * (1 + 0.2 * s * s), z + 0.4 * s * x});
    }
  }
  return out;
}

std::vector<double> repeated(const std::vector<double>& base, int frames) {
  std::vector<double> out;
  for (int t = 0; t < frames; ++t) out.insert(out.end(), base.begin(), base.end());
  return out;
}

TEST(SweepLattice, CountsAndCellShapes) {
  const fx::Polygons torus = fx::torus(5, 4);  // 20 quads, 40 edges
  const Complex s = surface_of(torus);
  const Complex open = sweep_lattice(s, 3, false);
  EXPECT_EQ(open.dim, 3);
  EXPECT_EQ(open.num_vertices, 4u * 20);
  EXPECT_EQ(open.num_cells(), 3u * 20);
  EXPECT_EQ(open.num_faces(), 4u * 20 + 3u * 40);  // layer faces + side faces
  EXPECT_EQ(open.num_edges(), 4u * 40 + 3u * 20);  // layer edges + time edges
  for (std::uint32_t k = 0; k < open.num_cells(); ++k) EXPECT_EQ(open.cell_faces.size(k), 6u) << "cell " << k;  // hexahedra

  const Complex cyc = sweep_lattice(s, 3, true);
  EXPECT_EQ(cyc.num_vertices, 3u * 20);
  EXPECT_EQ(cyc.num_faces(), 3u * 20 + 3u * 40);
  EXPECT_EQ(cyc.num_edges(), 3u * 40 + 3u * 20);

  const Complex prisms = sweep_lattice(surface_of(fx::octahedron()), 2, false);
  for (std::uint32_t k = 0; k < prisms.num_cells(); ++k) EXPECT_EQ(prisms.cell_faces.size(k), 5u);  // prisms

  const Complex mixed = sweep_lattice(surface_of(fx::mixed_patch()), 1, false);
  EXPECT_EQ(mixed.cell_faces.size(1), 7u);  // the pentagon's prism: 2 caps + 5 sides
}

TEST(SweepLattice, BoundaryIsTheFirstAndLastFramesAndTheSurfaceBoundarySwept) {
  const fx::Polygons torus = fx::torus(5, 4);
  const Complex s = surface_of(torus);
  const Complex open = sweep_lattice(s, 2, false);
  std::uint32_t boundary = 0;
  for (std::uint32_t f = 0; f < open.num_faces(); ++f) boundary += open.face_cells.size(f) == 1;
  EXPECT_EQ(boundary, 2u * 20) << "a closed surface's open sweep is bounded by its first and last layers";
  for (std::uint32_t f = 0; f < open.num_faces(); ++f) {
    const bool first_or_last = f < 20 || (f >= 40 && f < 60);
    EXPECT_EQ(open.face_dim[f], first_or_last ? 2 : 3) << "face " << f;
  }
  const Complex cyc = sweep_lattice(s, 3, true);
  for (std::uint32_t f = 0; f < cyc.num_faces(); ++f) EXPECT_EQ(cyc.face_cells.size(f), 2u) << "a cyclic sweep of a closed surface has no boundary";

  const Complex patch = sweep_lattice(surface_of(fx::mixed_patch()), 1, false);
  std::uint32_t sides = 0;
  for (std::uint32_t f = 0; f < patch.num_faces(); ++f) sides += patch.face_cells.size(f) == 1;
  EXPECT_EQ(sides, 2u * 3 + 6u) << "both caps (3 faces each) and the 6 boundary edges swept";
}

TEST(SweepLattice, RefusesWhatCannotBeSwept) {
  const Complex s = surface_of(fx::torus(5, 4));
  EXPECT_THROW(sweep_lattice(s, 0, false), Error);
  EXPECT_THROW(sweep_lattice(s, 2, true), Error);  // two time edges would join the same vertices
  EXPECT_NO_THROW(sweep_lattice(s, 3, true));
  EXPECT_THROW(make_space_time(s, 2, false, 1, Scheme::Loop), Error);
}

TEST(SpaceTimeFrames, CountsForLevels) {
  EXPECT_EQ(space_time_frames(4, 3, false), 33);
  EXPECT_EQ(space_time_frames(4, 3, true), 32);
  EXPECT_EQ(space_time_base_steps(33, 3, false), 4);
  EXPECT_EQ(space_time_base_steps(32, 3, true), 4);
  EXPECT_FALSE(space_time_base_steps(30, 3, false).has_value());
  EXPECT_FALSE(space_time_base_steps(16, 3, true).has_value());  // K = 2 < 3
  EXPECT_EQ(space_time_base_steps(24, 3, true), 3);
}

// The map says level j's vertex at (layer t, surface vertex p); check it against geometry: the
// lattice synthesised with the *linear* scheme from base layers at heights z = t and the surface's
// own xy, where linear synthesis with zero wavelets interpolates, lands every vertex of level j
// on the surface's level-j point in xy and at height t / 2^j.
void check_map(const fx::Polygons& m, int steps, int levels) {
  const Complex s = surface_of(m);
  SpaceTime st = make_space_time(s, steps, false, levels, Scheme::Linear);
  const std::uint32_t nv0 = m.num_vertices;
  std::vector<double> base(3 * std::size_t(st.lattice.num_vertices(0)));
  for (int t = 0; t < st.layers(0); ++t)
    for (std::uint32_t p = 0; p < nv0; ++p) {
      double* x = &base[3 * (std::size_t(t) * nv0 + p)];
      x[0] = m.positions[3 * p], x[1] = m.positions[3 * p + 1], x[2] = t;
    }
  set_base(st.lattice, base);
  std::vector<double> flat(3 * std::size_t(nv0));
  for (std::uint32_t p = 0; p < nv0; ++p) flat[3 * p] = m.positions[3 * p], flat[3 * p + 1] = m.positions[3 * p + 1];
  for (int j = 0; j <= levels; ++j) {
    const std::vector<double> x = synthesize(st.lattice, j), sx = subdivide_frame(st, flat, j);
    const std::uint32_t nvs = st.surface_vertices(j);
    std::set<std::uint32_t> seen;
    for (int t = 0; t < st.layers(j); ++t)
      for (std::uint32_t p = 0; p < nvs; ++p) {
        const std::uint32_t v = st.layer_vertices[std::size_t(j)][std::size_t(t) * nvs + p];
        seen.insert(v);
        ASSERT_NEAR(x[3 * v + 2], double(t) / (1 << j), 1e-12) << "level " << j << " layer " << t << " point " << p;
        ASSERT_NEAR(x[3 * v], sx[3 * p], 1e-12) << "level " << j << " layer " << t << " point " << p;
        ASSERT_NEAR(x[3 * v + 1], sx[3 * p + 1], 1e-12) << "level " << j << " layer " << t << " point " << p;
      }
    EXPECT_EQ(seen.size(), st.lattice.num_vertices(j)) << "the map is one to one at level " << j;
  }
}

TEST(SpaceTimeMap, AgreesWithLinearSynthesis) {
  check_map(fx::torus(5, 4), 2, 3);
  check_map(octahedron_xyz(), 1, 3);
  check_map(open_patch(), 3, 2);
}

class SpaceTimeFit : public ::testing::TestWithParam<std::tuple<Scheme, bool>> {};

TEST_P(SpaceTimeFit, FinestLayersAreTheFilledFramesAndReconstructPerfectly) {
  const auto [scheme, cyclic] = GetParam();
  const fx::Polygons shapes[] = {fx::torus(6, 4), octahedron_xyz(), open_patch()};
  for (std::size_t shape = 0; shape < 3; ++shape) {
    const fx::Polygons& m = shapes[shape];
    const int levels = 2, steps = cyclic ? 3 : 2;
    SpaceTime st = make_space_time(surface_of(m), steps, cyclic, levels, scheme);
    const int n = st.layers(levels);
    const std::vector<double> frames = moving_frames(m.positions, n);
    const std::vector<double> filled = fill_layers(st, frames);
    const FitReport r = fit_frames(st, frames);
    EXPECT_LT(r.max_error, 1e-12);
    const std::vector<double> x = synthesize(st.lattice, levels);
    for (std::size_t i = 0; i < x.size(); ++i) ASSERT_NEAR(x[i], filled[i], 1e-12) << "value " << i;
    // Each layer is its frame as the lattice refines it: on the torus (quads, every vertex
    // regular) the volume rule is the product of the surface's and time's, so the layer is the
    // frame's own surface subdivision; elsewhere it stays close to it.
    if (shape == 0 || scheme == Scheme::Linear) EXPECT_LT(r.max_surface_gap, 1e-12);
    else EXPECT_LT(r.max_surface_gap, 0.02);
    // A moving animation has time detail.
    double time_detail = 0;
    const std::vector<std::uint8_t> flags = time_wavelet_flags(st);
    const std::uint32_t nv0 = st.lattice.num_vertices(0);
    for (std::size_t i = 0; i < flags.size(); ++i)
      if (flags[i]) time_detail = std::max(time_detail, std::abs(st.lattice.coeffs[3 * (nv0 + i)]));
    EXPECT_GT(time_detail, 1e-6);
  }
}

// A static animation: every layer the same frame. Its space-time lattice is the frame's own
// refinement, so analysis leaves no wavelet at all, in time or in space. Long sweeps fill their
// ends and interior from different helpers: 8 steps checks the seam.
TEST_P(SpaceTimeFit, StaticAnimationHasZeroTimeWavelets) {
  const auto [scheme, cyclic] = GetParam();
  for (const int steps : {cyclic ? 3 : 2, 8})
    for (const fx::Polygons& m : {fx::torus(6, 4), octahedron_xyz(), open_patch()}) {
      const int levels = steps == 8 ? 3 : 2;
      SpaceTime st = make_space_time(surface_of(m), steps, cyclic, levels, scheme);
      fit_frames(st, repeated(m.positions, st.layers(levels)));
      const std::vector<std::uint8_t> flags = time_wavelet_flags(st);
      const std::uint32_t nv0 = st.lattice.num_vertices(0);
      std::size_t time_wavelets = 0;
      double largest_time = 0, largest_space = 0;
      for (std::size_t i = 0; i < flags.size(); ++i) {
        const double* w = &st.lattice.coeffs[3 * (nv0 + i)];
        const double mag = std::max({std::abs(w[0]), std::abs(w[1]), std::abs(w[2])});
        double& largest = flags[i] ? largest_time : largest_space;
        largest = std::max(largest, mag);
        time_wavelets += flags[i];
      }
      EXPECT_GT(time_wavelets, 0u);
      EXPECT_LT(largest_time, 1e-12) << scheme_name(scheme) << (cyclic ? " cyclic " : " open ") << steps << " steps";
      EXPECT_LT(largest_space, 1e-12) << scheme_name(scheme) << (cyclic ? " cyclic " : " open ") << steps << " steps";
    }
}

INSTANTIATE_TEST_SUITE_P(Schemes, SpaceTimeFit,
                         ::testing::Combine(::testing::Values(Scheme::Linear, Scheme::Cubic), ::testing::Bool()),
                         [](const auto& info) {
                           return scheme_name(std::get<0>(info.param)) + (std::get<1>(info.param) ? "_cyclic" : "_open");
                         });

}  // namespace
