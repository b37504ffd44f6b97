// The modeler's session (issue 4): local resynthesis equals full resynthesis, undo/redo restore
// coefficients bit for bit, gains, local frames, subdivide.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "core/complex/complex_build.h"
#include "core/base/errors.h"
#include "core/multires/hierarchy.h"
#include "core/edit/session.h"
#include "core/io/lattice/shape_io.h"
#include "core/complex/shapes.h"
#include "tests/test_shapes.h"

namespace sublift {
namespace {

using sublift::testing::max_abs_diff;

// A hierarchy whose wavelets are not zero: the pure subdivision of `base` plus noise at the
// finest level, analysed.
Hierarchy noisy(const Complex& base, const std::vector<double>& xyz, int levels, Scheme scheme, double noise = 0.02) {
  Hierarchy h = make_hierarchy(base, levels, scheme, 3);
  set_base(h, xyz);
  std::vector<double> fine = synthesize(h, levels);
  const std::vector<double> r = testing::random_values(fine.size(), 7, -noise, noise);
  for (std::size_t i = 0; i < fine.size(); ++i) fine[i] += r[i];
  analyze(h, fine);
  return h;
}

Hierarchy torus(int levels, Scheme scheme) {
  const SurfaceMesh m = make_quad_torus(10, 7);
  return noisy(complex_from_surface_mesh(m), flatten_positions(m), levels, scheme);
}

Hierarchy from_asset(const std::string& name, int levels, Scheme scheme) {
  Shape s = read_shape(std::string(SUBLIFT_ASSETS_DIR) + "/" + name);
  return noisy(s.base, s.positions, levels, scheme);
}

bool same_bits(std::span<const double> a, std::span<const double> b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

void expect_sessions_equal(const Session& a, const Session& b, double tol) {
  for (int l = 0; l <= a.finest_level(); ++l)
    EXPECT_LT(max_abs_diff(a.positions(l), b.positions(l)), tol) << "level " << l;
  EXPECT_LT(max_abs_diff(a.hierarchy().coeffs, b.hierarchy().coeffs), tol) << "coefficients";
}

// The session's levels are the synthesis of its own coefficients.
void expect_consistent(const Session& s, double tol) {
  for (int l = 0; l <= s.finest_level(); ++l)
    EXPECT_LT(max_abs_diff(synthesize(s.hierarchy(), l), s.positions(l)), tol) << "level " << l;
}

struct Case {
  const char* name;
  Hierarchy (*make)();
};

class LocalEqualsFull : public ::testing::TestWithParam<Case> {};

TEST_P(LocalEqualsFull, EditsAtEveryLevel) {
  const Hierarchy h = GetParam().make();
  for (int level = 0; level <= h.finest_level(); ++level) {
    Session local(h), full(h);
    const std::uint32_t n = local.num_vertices(level);
    const std::vector<std::uint32_t> sel = {n / 3, n / 2, n - 1};
    const std::vector<double> w = {1.0, 0.5, 0.25};
    const double d[3] = {0.13, -0.07, 0.21};
    const OpReport r = local.move(level, sel, w, d);
    full.move_full(level, sel, w, d);
    SCOPED_TRACE(std::string(GetParam().name) + " level " + std::to_string(level));
    expect_sessions_equal(local, full, 1e-12);
    expect_consistent(local, 1e-12);
    EXPECT_FALSE(r.full);
    EXPECT_GT(r.vertices_updated, 0u);
    // Fold-back keeps the hierarchy consistent: a later coarse edit keeps the fine one.
    if (level > 0) {
      const double d0[3] = {0.0, 0.3, 0.0};
      const std::uint32_t v0[1] = {0};
      local.move(0, v0, {}, d0);
      full.move_full(0, v0, {}, d0);
      expect_sessions_equal(local, full, 1e-12);
      expect_consistent(local, 1e-12);
    }
  }
}

Hierarchy torus_cubic() { return torus(3, Scheme::Cubic); }
Hierarchy torus_linear() { return torus(3, Scheme::Linear); }
Hierarchy crease_cubic() { return from_asset("crease_loop.obj", 2, Scheme::Cubic); }
Hierarchy mixed_cubic() { return from_asset("mixed_polygons.obj", 3, Scheme::Cubic); }
Hierarchy boundary_cubic() { return from_asset("quad_grid_boundary.obj", 2, Scheme::Cubic); }
Hierarchy prism_ring_cubic() { return from_asset("prism_ring.lattice", 2, Scheme::Cubic); }
Hierarchy features_lattice_cubic() { return from_asset("feature_surface.lattice", 2, Scheme::Cubic); }
Hierarchy block_linear() {
  std::vector<double> xyz;
  const Complex c = make_hex_block(2, xyz);
  return noisy(c, xyz, 2, Scheme::Linear);
}
Hierarchy curve_cubic() { return from_asset("curves/curve.obj", 4, Scheme::Cubic); }
// sqrt2 (paper 001): explicit sparse transitions; odd finest levels keep their curves.
Hierarchy torus_sqrt2() { return torus(5, Scheme::Sqrt2); }
Hierarchy boundary_sqrt2() { return from_asset("quad_grid_boundary.obj", 3, Scheme::Sqrt2); }
Hierarchy crease_sqrt2() { return from_asset("crease_loop.obj", 4, Scheme::Sqrt2); }
Hierarchy dart_sqrt2() { return from_asset("crease_dart_flat.obj", 3, Scheme::Sqrt2); }
Hierarchy mixed_sqrt2() { return from_asset("mixed_polygons.obj", 4, Scheme::Sqrt2); }
// The triangle schemes (paper 004): the same explicit transitions; Loop adds its vertex rule
// (local in synthesis, a global solve in analysis). Butterfly on the creased grid is left out:
// its many boundary and crease neighbourhood types cost minutes under AddressSanitizer, and the
// sparse paths are the same code for the three schemes.
Hierarchy octa_butterfly() { return from_asset("octahedron.obj", 3, Scheme::Butterfly); }
Hierarchy octa_loop() { return from_asset("octahedron.obj", 3, Scheme::Loop); }
Hierarchy grid_loop() { return from_asset("tri_crease_grid.obj", 2, Scheme::Loop); }
Hierarchy grid_linear_tri() { return from_asset("tri_crease_grid.obj", 2, Scheme::LinearTri); }

INSTANTIATE_TEST_SUITE_P(Shapes, LocalEqualsFull,
                         ::testing::Values(Case{"torus_cubic", torus_cubic}, Case{"torus_linear", torus_linear},
                                           Case{"crease_cubic", crease_cubic}, Case{"mixed_cubic", mixed_cubic},
                                           Case{"boundary_cubic", boundary_cubic},
                                           Case{"prism_ring_cubic", prism_ring_cubic},
                                           Case{"features_lattice_cubic", features_lattice_cubic},
                                           Case{"block_linear", block_linear}, Case{"curve_cubic", curve_cubic},
                                           Case{"torus_sqrt2", torus_sqrt2}, Case{"boundary_sqrt2", boundary_sqrt2},
                                           Case{"crease_sqrt2", crease_sqrt2}, Case{"dart_sqrt2", dart_sqrt2},
                                           Case{"mixed_sqrt2", mixed_sqrt2}, Case{"octa_butterfly", octa_butterfly},
                                           Case{"octa_loop", octa_loop},
                                           Case{"grid_loop", grid_loop}, Case{"grid_linear_tri", grid_linear_tri}),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(Session, LocalFramesLocalEqualsFull) {
  for (Hierarchy (*make)() :
       {torus_cubic, crease_cubic, mixed_cubic, boundary_cubic, torus_sqrt2, crease_sqrt2, dart_sqrt2, mixed_sqrt2,
        octa_butterfly, grid_loop}) {
    const Hierarchy h = make();
    for (int level = 0; level <= h.finest_level(); ++level) {
      Session local(h), full(h);
      local.set_detail_frames(DetailFrames::Local);
      full.set_detail_frames(DetailFrames::Local);
      const std::uint32_t sel[2] = {1, local.num_vertices(level) / 2};
      const double d[3] = {0.2, 0.1, -0.15};
      local.move(level, sel, {}, d);
      full.move_full(level, sel, {}, d);
      SCOPED_TRACE("level " + std::to_string(level));
      expect_sessions_equal(local, full, 1e-12);
      expect_consistent(local, 1e-12);
    }
  }
}

TEST(Session, UndoRedoRestoreBitsAndOppositeEditIsIdentity) {
  for (const DetailFrames mode : {DetailFrames::World, DetailFrames::Local}) {
    Session s(torus_cubic());
    s.set_detail_frames(mode);
    const std::vector<double> c0 = s.hierarchy().coeffs;
    std::vector<std::vector<double>> p0;
    for (int l = 0; l <= s.finest_level(); ++l) p0.emplace_back(s.positions(l).begin(), s.positions(l).end());
    EXPECT_FALSE(s.dirty());
    // A drag: several moves in one history entry, at a fine level and then a coarse one.
    s.begin_edit("Drag");
    const std::uint32_t v[2] = {5, 40};
    const double d1[3] = {0.1, 0.0, 0.05}, d2[3] = {0.0, 0.2, 0.0};
    s.move(2, v, {}, d1);
    s.move(2, v, {}, d2);
    s.end_edit();
    const std::uint32_t v0[1] = {3};
    s.move(0, v0, {}, d1);
    ASSERT_EQ(s.history().size(), 2u);
    EXPECT_TRUE(s.dirty());
    const std::vector<double> c2 = s.hierarchy().coeffs;
    const std::vector<double> f2(s.positions(3).begin(), s.positions(3).end());
    ASSERT_TRUE(s.undo());
    ASSERT_TRUE(s.undo());
    EXPECT_FALSE(s.undo());
    EXPECT_TRUE(same_bits(s.hierarchy().coeffs, c0));
    for (int l = 0; l <= s.finest_level(); ++l) EXPECT_TRUE(same_bits(s.positions(l), p0[static_cast<std::size_t>(l)]));
    EXPECT_FALSE(s.dirty());
    ASSERT_TRUE(s.redo());
    ASSERT_TRUE(s.redo());
    EXPECT_FALSE(s.redo());
    EXPECT_TRUE(same_bits(s.hierarchy().coeffs, c2));
    EXPECT_TRUE(same_bits(s.positions(3), f2));
    // Edit then the opposite edit: the identity, to round-off.
    const double back[3] = {-0.1, 0.0, -0.05};
    s.move(0, v0, {}, back);
    s.undo();
    s.undo();
    s.undo();
    s.redo();
    s.redo();
    s.move(0, v0, {}, back);  // undoes move(0, d1) arithmetically
    const double back2[3] = {-0.1, -0.2, -0.05};
    s.move(2, v, {}, back2);
    EXPECT_LT(max_abs_diff(s.hierarchy().coeffs, c0), 1e-13);
    EXPECT_LT(max_abs_diff(s.positions(3), p0[3]), 1e-13);
  }
}

TEST(Session, CancelledEditLeavesNoTrace) {
  for (const DetailFrames mode : {DetailFrames::World, DetailFrames::Local}) {
    Session s(torus_cubic());
    s.set_detail_frames(mode);
    const std::uint32_t v0[1] = {3};
    const double d[3] = {0.1, 0.2, 0.3};
    s.move(0, v0, {}, d);
    const std::vector<double> c1 = s.hierarchy().coeffs;
    const std::vector<double> f1(s.positions(3).begin(), s.positions(3).end());
    s.begin_edit("Grab");
    const std::uint32_t v[2] = {7, 30};
    s.move(1, v, {}, d);
    s.move(1, v, {}, d);
    s.cancel_edit();
    EXPECT_FALSE(s.in_edit());
    EXPECT_TRUE(same_bits(s.hierarchy().coeffs, c1));
    EXPECT_TRUE(same_bits(s.positions(3), f1));
    EXPECT_EQ(s.history().size(), 1u);
    EXPECT_FALSE(s.can_redo());
    EXPECT_FALSE(s.changed(3).empty()) << "the viewport must redraw what the cancel restored";
  }
}

TEST(Session, GainOneIsIdentityAndGainZeroIsPureSubdivision) {
  Session s(torus_cubic());
  const std::uint32_t v0[2] = {3, 17};
  const double d[3] = {0.0, 0.4, 0.1};
  s.move(0, v0, {}, d);
  const std::vector<double> fine(s.positions(3).begin(), s.positions(3).end());
  const std::vector<double> coeffs = s.hierarchy().coeffs;
  s.set_gain(1, 1.0);
  EXPECT_EQ(s.history().size(), 1u) << "a gain that does not change is not an undo step";
  EXPECT_LT(max_abs_diff(s.positions(3), fine), 1e-13);
  s.set_gain(1, 2.0);
  EXPECT_GT(max_abs_diff(s.positions(3), fine), 1e-3);
  s.set_gain(1, 1.0);
  EXPECT_LT(max_abs_diff(s.positions(3), fine), 1e-13);
  EXPECT_TRUE(same_bits(s.hierarchy().coeffs, coeffs)) << "gains do not touch the stored coefficients";
  for (int l = 0; l < s.finest_level(); ++l) s.set_gain(l, 0.0);
  // Independently: a fresh hierarchy with the edited level 0 and no wavelets.
  Hierarchy pure = make_hierarchy(s.hierarchy().levels[0], 3, Scheme::Cubic, 3);
  set_base(pure, s.positions(0));
  EXPECT_LT(max_abs_diff(s.positions(3), synthesize(pure, 3)), 1e-13);
  // The noise was real: with gains 1 the shape differs from the pure subdivision.
  EXPECT_GT(max_abs_diff(fine, synthesize(pure, 3)), 1e-3);
  // Edits above a muted band are refused, edits at level 0 are not.
  const std::uint32_t v2[1] = {100};
  EXPECT_THROW(s.move(2, v2, {}, d), Error);
  EXPECT_NO_THROW(s.move(0, v0, {}, d));
  // Gain changes undo.
  for (int k = 0; k < 4; ++k) s.undo();  // the move, then gains 2, 1, 0 back to what they were
  EXPECT_EQ(s.gain(0), 1.0);
  EXPECT_EQ(s.gain(1), 1.0);
  EXPECT_EQ(s.gain(2), 1.0);
  s.undo();
  EXPECT_EQ(s.gain(1), 2.0);
  EXPECT_TRUE(same_bits(s.hierarchy().coeffs, coeffs));
}

// Rotate every level-0 control point by R (one move per point, one history entry).
void rotate_coarse(Session& s, double angle) {
  const double c = std::cos(angle), sn = std::sin(angle);
  const std::vector<double> p0(s.positions(0).begin(), s.positions(0).end());
  s.begin_edit("Rotate");
  for (std::uint32_t v = 0; v < s.num_vertices(0); ++v) {
    const double* p = &p0[3 * std::size_t(v)];
    const double q[3] = {c * p[0] - sn * p[2], p[1], sn * p[0] + c * p[2]};
    const double d[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
    s.move(0, std::span<const std::uint32_t>(&v, 1), {}, d);
  }
  s.end_edit();
}

TEST(Session, LocalFrameDetailFollowsRotation) {
  const double angle = 0.7, c = std::cos(angle), sn = std::sin(angle);
  for (const bool sqrt2 : {false, true})
  for (const DetailFrames mode : {DetailFrames::Local, DetailFrames::World}) {
    Session s(sqrt2 ? torus_sqrt2() : torus_cubic());
    SCOPED_TRACE(sqrt2 ? "sqrt2" : "cubic");
    s.set_detail_frames(mode);
    const int J = s.finest_level();
    const std::vector<double> fine(s.positions(J).begin(), s.positions(J).end());
    rotate_coarse(s, angle);
    std::vector<double> want(fine.size());
    for (std::size_t i = 0; i < fine.size(); i += 3) {
      want[i] = c * fine[i] - sn * fine[i + 2];
      want[i + 1] = fine[i + 1];
      want[i + 2] = sn * fine[i] + c * fine[i + 2];
    }
    if (mode == DetailFrames::Local) EXPECT_LT(max_abs_diff(s.positions(J), want), 1e-12);
    else EXPECT_GT(max_abs_diff(s.positions(J), want), 1e-3) << "world-coordinate detail only translates";
  }
}

TEST(Session, SubdivideAndUndo) {
  for (const Scheme scheme : {Scheme::Cubic, Scheme::Sqrt2}) {
  SCOPED_TRACE(scheme_name(scheme));
  Session s(torus(1, scheme));
  const std::uint32_t n1 = s.num_vertices(1);
  s.subdivide();
  ASSERT_EQ(s.finest_level(), 2);
  expect_consistent(s, 1e-12);
  const std::uint32_t v[1] = {n1 + 5};
  const double d[3] = {0.0, 0.0, 0.3};
  s.move(2, v, {}, d);
  const std::vector<double> c2 = s.hierarchy().coeffs;
  s.undo();
  s.undo();
  EXPECT_EQ(s.finest_level(), 1);
  EXPECT_EQ(s.hierarchy().coeffs.size(), std::size_t(n1) * 3);
  s.redo();
  s.redo();
  EXPECT_EQ(s.finest_level(), 2);
  EXPECT_TRUE(same_bits(s.hierarchy().coeffs, c2));
  EXPECT_THROW(s.subdivide(10.0), Error);
  }
}

// Issue 21: what the first edit after opening pays once (its buffers) is reported apart from the
// resynthesis, and only by the edits that size something.
TEST(Session, FirstEditReportsItsSetupApart) {
  Session s(torus(2, Scheme::Cubic));
  const std::uint32_t v[1] = {3};
  const double d[3] = {0.0, 0.1, 0.0};
  EXPECT_GT(s.move(0, v, {}, d).setup_ms, 0.0);
  EXPECT_EQ(s.move(0, v, {}, d).setup_ms, 0.0);
  EXPECT_EQ(s.move(1, v, {}, d).setup_ms, 0.0);
  s.subdivide();  // a new level's buffers are sized by the next edit
  EXPECT_GT(s.move(0, v, {}, d).setup_ms, 0.0);
  EXPECT_EQ(s.move(2, v, {}, d).setup_ms, 0.0);
  expect_consistent(s, 1e-12);
}

TEST(Session, BadInput) {
  Session s(torus_cubic());
  const double d[3] = {1, 0, 0};
  const std::uint32_t bad[1] = {s.num_vertices(1)};
  EXPECT_THROW(s.move(1, bad, {}, d), Error);
  EXPECT_THROW(s.move(9, bad, {}, d), Error);
  const double nan[3] = {NAN, 0, 0};
  const std::uint32_t ok[1] = {0};
  EXPECT_THROW(s.move(0, ok, {}, nan), Error);
  EXPECT_THROW(s.set_gain(3, 1.0), Error);
  EXPECT_TRUE(s.history().empty());
  Hierarchy lattice = prism_ring_cubic();
  Session l(lattice);
  EXPECT_THROW(l.set_detail_frames(DetailFrames::Local), Error);
  Hierarchy integer = make_hierarchy(s.hierarchy().levels[0], 1, Scheme::Cubic, 3, true);
  EXPECT_THROW(Session{integer}, Error);
}

TEST(SoftSelection, SmoothFalloff) {
  const std::vector<double> pos = {0, 0, 0, 0.5, 0, 0, 1, 0, 0, 2, 0, 0};
  const std::uint32_t sel[1] = {0};
  const SoftWeights w = soft_selection(pos, sel, 1.0);
  ASSERT_EQ(w.vertices, (std::vector<std::uint32_t>{0, 1}));
  EXPECT_EQ(w.weights[0], 1.0);
  EXPECT_DOUBLE_EQ(w.weights[1], 0.5);  // 1 - smoothstep(1/2)
  const SoftWeights none = soft_selection(pos, sel, 0.0);
  EXPECT_EQ(none.vertices.size(), 1u);
  const std::uint32_t bad[1] = {4};
  EXPECT_THROW(soft_selection(pos, bad, 1.0), Error);
}

}  // namespace
}  // namespace sublift
