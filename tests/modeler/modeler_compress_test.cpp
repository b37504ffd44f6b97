// The modeler's compression view (docs/compression.md) on the controller, without a window: the
// slider shows the shape synthesised from that fraction of the wavelets (checked against
// keep_largest + synthesize + the limit stencils), the session is untouched, editing is refused
// while the view is on, Apply is one undoable edit, Off and 100% show the full shape, and the
// script commands.
#include <gtest/gtest.h>

#include "tests/test_shapes.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "app/modeler/modeler_controller.h"
#include "app/modeler/script_runner.h"
#include "core/analysis/compress.h"
#include "core/base/errors.h"
#include "core/multires/limit.h"
#include "core/io/project/project_io.h"
#include "tests/compress_fixture.h"

#ifndef SUBLIFT_ASSETS_DIR
#error "SUBLIFT_ASSETS_DIR must name the assets folder"
#endif

namespace sublift {
namespace {

using sublift::testing::max_abs_diff;

namespace fs = std::filesystem;

// A cubic torus project with real detail, written once per test into its own folder.
struct Fixture {
  fs::path dir;
  std::string project;
  Hierarchy h;
  ModelerController app{false};
  explicit Fixture(const std::vector<double>& gains = {}) {
    dir = fs::temp_directory_path() /
          ("sublift_modeler_compress_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    project = (dir / "detail.sublift").string();
    h = testing::detailed_hierarchy(std::string(SUBLIFT_ASSETS_DIR) + "/torus_quad.obj", Scheme::Cubic, 3);
    ProjectExtras extras;
    extras.gains = gains;
    write_project(project, h, extras);
    app.model.open(project);
  }
  ~Fixture() { fs::remove_all(dir); }
  void slider(double f) {
    ModelerPanelRequests r;
    r.compress_fraction = f;
    app.apply_panel_requests(r);
  }
  void button(bool apply) {
    ModelerPanelRequests r;
    (apply ? r.compress_apply : r.compress_off) = true;
    app.apply_panel_requests(r);
  }
  std::vector<double> limit() const { return app.model.limit_positions(); }
};

// The limit surface of finest control points `control` (the stencils of the session's hierarchy).
std::vector<double> limit_of(const Hierarchy& h, const std::vector<double>& control) {
  const LimitStencils st = build_limit_stencils(h);
  std::vector<double> out(control.size());
  eval_limit(st, control.data(), out.data());
  return out;
}

TEST(ModelerCompressTest, SliderShowsTheShapeOfThatFractionAndLeavesTheSessionAlone) {
  Fixture f;
  const std::vector<double> full_limit = f.limit();
  f.app.model.set_level(1);
  for (const double fraction : {0.01, 0.2}) {
    f.slider(fraction);
    ASSERT_TRUE(f.app.model.compression_on()) << f.app.error;
    // Independently: keep_largest on a copy of the hierarchy, synthesised, through the stencils.
    Hierarchy copy = f.h;
    const std::size_t kept = keep_largest(copy, fraction);
    EXPECT_LT(max_abs_diff(limit_of(copy, synthesize(copy, 3)), f.app.model.limit_positions()), 1e-12);
    EXPECT_LT(max_abs_diff(synthesize(copy, 1), f.app.model.net_positions()), 1e-12);
    CompressionPanelData d;
    f.app.fill_compression_data(d);
    EXPECT_TRUE(d.on);
    EXPECT_EQ(d.kept, kept);
    EXPECT_EQ(d.total, 6048u);
    EXPECT_DOUBLE_EQ(d.fraction, fraction);
    EXPECT_GT(d.l2_error, 0.0);
    EXPECT_GE(d.linf_error, d.l2_error);
    // Normals of the compressed limit surface, fresh.
    const LimitStencils st = build_limit_stencils(copy);
    const std::vector<double> control = synthesize(copy, 3);
    std::vector<double> lim(control.size()), normals(control.size());
    eval_limit(st, control.data(), lim.data());
    limit_normals(st, f.app.model.surface_faces(), control.data(), lim.data(), normals.data());
    EXPECT_LT(max_abs_diff(normals, f.app.model.limit_normals()), 1e-12);
  }
  // Non-destructive: the session's coefficients are the project's, bit for bit, and no history.
  EXPECT_EQ(f.app.model.session().hierarchy().coeffs, f.h.coeffs);
  EXPECT_TRUE(f.app.model.session().history().empty());
  // 100% is the full shape itself; Off too.
  f.slider(1.0);
  EXPECT_EQ(f.limit(), full_limit);
  f.slider(0.05);
  EXPECT_GT(max_abs_diff(full_limit, f.app.model.limit_positions()), 1e-3);
  f.button(false);
  EXPECT_FALSE(f.app.model.compression_on());
  EXPECT_EQ(f.limit(), full_limit);
  const auto net = f.app.model.session().positions(1);
  EXPECT_EQ(max_abs_diff({net.begin(), net.end()}, f.app.model.net_positions()), 0.0);
}

TEST(ModelerCompressTest, EditingIsRefusedWhileTheViewIsOn) {
  Fixture f;
  f.app.model.set_selection({3});
  const double d[3] = {0, 0.1, 0};
  f.app.model.begin_drag("Move");
  f.app.model.drag_to(d);
  f.app.model.end_drag();
  f.slider(0.3);
  ASSERT_TRUE(f.app.model.compression_on());
  EXPECT_THROW(f.app.model.begin_drag("Move"), Error);
  EXPECT_THROW(f.app.model.subdivide(), Error);
  EXPECT_THROW(f.app.model.undo(), Error);
  EXPECT_THROW(f.app.model.redo(), Error);
  EXPECT_THROW(f.app.model.set_scheme(Scheme::Linear), Error);
  EXPECT_THROW(f.app.model.begin_gain(0), Error);
  // Through the keys: Ctrl+Z shows why, and the edit is still there.
  WindowEvent e;
  e.type = WindowEvent::Type::Key;
  e.key = Key::Z;
  e.mods.ctrl = true;
  f.app.handle(e);
  EXPECT_NE(f.app.error.find("compression view is on"), std::string::npos) << f.app.error;
  EXPECT_EQ(f.app.model.session().undo_position(), 1u);
  // Levels and selection still work; the net shown follows the level.
  f.app.model.set_level(2);
  EXPECT_EQ(f.app.model.net_positions().size(), 3u * f.app.model.session().num_vertices(2));
  // The basis mode replaces the surface, so it turns the view off.
  BasisSettings b;
  b.on = true;
  b.request.index = 0;
  f.app.model.set_basis(b);
  EXPECT_FALSE(f.app.model.compression_on());
}

TEST(ModelerCompressTest, ApplyIsOneUndoableEdit) {
  Fixture f;
  const std::vector<double> full_limit = f.limit();
  f.slider(0.2);
  const std::vector<double> shown = f.limit();
  Hierarchy copy = f.h;
  keep_largest(copy, 0.2);
  f.button(true);
  ASSERT_FALSE(f.app.model.compression_on()) << f.app.error;
  const Session& s = f.app.model.session();
  ASSERT_EQ(s.history().size(), 1u);
  EXPECT_EQ(s.history().back().label, "Compress 20%");
  EXPECT_TRUE(s.dirty());
  // The session now holds the compressed shape: coefficients to round-off, removed ones ~0.
  double scale = 0;
  for (const double c : f.h.coeffs) scale = std::max(scale, std::abs(c));
  EXPECT_LT(max_abs_diff(copy.coeffs, s.hierarchy().coeffs), 1e-12 * scale);
  EXPECT_LT(max_abs_diff(shown, f.limit()), 1e-12 * scale);
  // Undo restores the project's coefficients bit for bit, redo the compressed ones.
  ASSERT_TRUE(f.app.model.undo());
  EXPECT_EQ(s.hierarchy().coeffs, f.h.coeffs);
  EXPECT_LT(max_abs_diff(full_limit, f.limit()), 1e-12 * scale);
  ASSERT_TRUE(f.app.model.redo());
  EXPECT_LT(max_abs_diff(copy.coeffs, s.hierarchy().coeffs), 1e-12 * scale);
  // Apply with the view off says so.
  f.button(true);
  EXPECT_NE(f.app.error.find("nothing to apply"), std::string::npos) << f.app.error;
}

TEST(ModelerCompressTest, GainsAreTheSessionsAndAMutedBandRefusesApply) {
  Fixture f({1.0, 0.0, 1.5});
  const std::vector<double> full_limit = f.limit();
  f.slider(1.0);
  EXPECT_EQ(f.limit(), full_limit);
  f.slider(0.1);
  // Against core with the same gains.
  CompressOptions o;
  o.gains = {1.0, 0.0, 1.5};
  const Compressor c(f.h, o);
  const Compression expect = c.evaluate(c.count_for_fraction(0.1));
  EXPECT_LT(max_abs_diff(limit_of(f.h, expect.finest), f.app.model.limit_positions()), 1e-12);
  EXPECT_DOUBLE_EQ(f.app.model.compression().l2_error, expect.l2_error);
  f.button(true);
  EXPECT_NE(f.app.error.find("gain of level 1 is 0"), std::string::npos) << f.app.error;
  EXPECT_TRUE(f.app.model.compression_on());  // nothing half-applied: the view stays
  EXPECT_TRUE(f.app.model.session().history().empty());
  EXPECT_EQ(f.app.model.session().hierarchy().coeffs, f.h.coeffs);
}

TEST(ModelerCompressTest, ScriptCommands) {
  Fixture f;
  ModelerState& state = f.app.model;
  ScriptRunner ok("ok", "compress keep 0.1\ncompress keep 0.25\ncompress apply\nundo\nredo\ncompress keep 0.5\ncompress off\n");
  EXPECT_EQ(ok.next(state).kind, ScriptStep::Kind::End);
  EXPECT_FALSE(state.compression_on());
  EXPECT_EQ(state.session().history().size(), 1u);
  EXPECT_EQ(state.session().history().back().label, "Compress 25%");
  struct Bad {
    std::string script, message;
  };
  for (const Bad& b : {Bad{"compress keep 2\n", "script:1: compress keep F needs F in 0..1"},
                       Bad{"compress keep half\n", "script:1: F must be a number"},
                       Bad{"compress\n", "script:1: usage: compress keep F | compress apply | compress off"},
                       Bad{"compress keep 0.5\nundo\n", "script:2: the compression view is on"},
                       Bad{"compress keep 0.5\nselect 1\nmove 0 1 0\n", "script:3: the compression view is on"},
                       Bad{"compress apply\n", "script:1: compression: nothing to apply"}}) {
    state.compression_off();
    ScriptRunner r("bad", b.script);
    const ScriptStep step = r.next(state);
    EXPECT_EQ(step.kind, ScriptStep::Kind::Error) << b.script;
    EXPECT_EQ(step.message.rfind(b.message, 0), 0u) << step.message;
  }
}

}  // namespace
}  // namespace sublift
