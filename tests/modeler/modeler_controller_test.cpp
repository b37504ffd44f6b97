// ModelerController: clicks, Shift+clicks, box selection, drags and the grab tool on a real
// session, with synthetic window events and no GL context (picking is core math).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <unistd.h>
#include <span>
#include <string>
#include <vector>

#include "app/modeler/modeler_controller.h"
#include "app/modeler/modeler_view.h"
#include "tests/modeler/controller_fixture.h"
#include "app/modeler/script_runner.h"
#include "core/multires/basis.h"
#include "core/base/errors.h"
#include "core/io/model/model.h"
#include "core/multires/limit.h"
#include "core/edit/picking.h"
#include "render/headless_context.h"
#include "render/net_renderer.h"
#include "render/viewport_renderer.h"

#ifndef SUBLIFT_ASSETS_DIR
#error "SUBLIFT_ASSETS_DIR must name the assets folder"
#endif

namespace sublift {
namespace {

using testing::Fixture;
using testing::expect_shown_equals_fresh;
using testing::kViewX;
using testing::kViewW;
using testing::kViewH;

TEST(ModelerControllerTest, ClickShiftClickAndClickOnEmptySpace) {
  Fixture f;
  const unsigned v = f.visible_point();
  double x = 0, y = 0;
  ASSERT_TRUE(f.window_position(v, x, y));
  f.click(x, y);
  EXPECT_EQ(f.app.model.selection(), (std::vector<unsigned>{v}));
  f.click(x, y, Modifiers{true, false, false});  // Shift on a selected point toggles it off
  EXPECT_TRUE(f.app.model.selection().empty());
  f.click(x, y);
  f.click(kViewX + 5, 5);  // empty corner: clears
  EXPECT_TRUE(f.app.model.selection().empty());
  EXPECT_TRUE(f.app.model.session().history().empty()) << "selection is not an undo step";
}

// With the surface's depth (the app's ModelerView::surface_depth), a click at a control point
// hidden behind the surface does not pick it; with x-ray it does. Needs a GL context (EGL).
TEST(ModelerControllerTest, ClicksSkipPointsBehindTheSurfaceUnlessXray) {
  HeadlessContext context;
  Fixture f;
  ModelerView view;
  view.sync(f.app.model);
  const int w = f.app.camera.viewport_width, h = f.app.camera.viewport_height;
  const std::vector<float> depth = view.surface_depth(f.app.camera, w, h, f.app.display);
  ASSERT_EQ(depth.size(), std::size_t(w) * std::size_t(h));
  // A point the depth-less front-cluster rule would pick, but that lies behind the surface.
  PickIndex plain;
  plain.build(f.view(), f.app.model.session().positions(0));
  const auto p = f.app.model.session().positions(0);
  int hidden = -1;
  for (unsigned v = 0; v < f.app.model.session().num_vertices(0) && hidden < 0; ++v) {
    glm::dvec2 s;
    double ndc = 0.0;
    if (!project_point(f.view(), glm::dvec3(p[3 * v], p[3 * v + 1], p[3 * v + 2]), s, ndc)) continue;
    const int px = static_cast<int>(s.x), py = h - 1 - static_cast<int>(s.y);
    if (px < 0 || py < 0 || px >= w || py >= h) continue;
    const double surface = depth[std::size_t(py) * std::size_t(w) + std::size_t(px)];
    if (surface < 0.5 * (ndc + 1.0) - 0.01 && plain.nearest(s.x, s.y, 10.0, false) == v) hidden = int(v);
  }
  ASSERT_GE(hidden, 0) << "no control point of the torus is hidden behind its surface from this view";
  f.app.set_depth_source([&view](const OrbitCamera& c, int dw, int dh, const ModelerDisplay& d) {
    return view.surface_depth(c, dw, dh, d);
  });
  double x = 0, y = 0;
  ASSERT_TRUE(f.window_position(unsigned(hidden), x, y));
  f.click(x, y);
  EXPECT_NE(f.app.model.selection(), (std::vector<unsigned>{unsigned(hidden)}));
  f.app.display.xray = true;
  f.click(x, y);
  EXPECT_EQ(f.app.model.selection(), (std::vector<unsigned>{unsigned(hidden)}));
  f.app.set_depth_source({});
}

TEST(ModelerControllerTest, BoxSelectAndSelectAllNone) {
  Fixture f;
  f.send(WindowEvent::Type::Move, kViewX + 2, 2);
  f.send(WindowEvent::Type::Press, kViewX + 2, 2);
  f.send(WindowEvent::Type::Move, kViewX + kViewW - 2, kViewH - 2);
  f.send(WindowEvent::Type::Release, kViewX + kViewW - 2, kViewH - 2);
  EXPECT_EQ(f.app.model.selection().size(), f.app.model.session().num_vertices(0));
  f.key(Key::A, Modifiers{false, false, true});
  EXPECT_TRUE(f.app.model.selection().empty());
  f.key(Key::A);
  EXPECT_EQ(f.app.model.selection().size(), f.app.model.session().num_vertices(0));
}

TEST(ModelerControllerTest, DragMovesTheSelectionAsOneUndoStep) {
  Fixture f;
  const unsigned v = f.visible_point();
  double x = 0, y = 0;
  ASSERT_TRUE(f.window_position(v, x, y));
  f.click(x, y);
  const std::vector<double> before = f.positions();
  f.send(WindowEvent::Type::Press, x, y);
  for (int i = 1; i <= 5; ++i) f.send(WindowEvent::Type::Move, x + 8 * i, y - 4 * i);
  f.send(WindowEvent::Type::Release, x + 40, y - 20);
  ASSERT_EQ(f.app.model.session().history().size(), 1u);
  EXPECT_FALSE(f.app.model.dragging());
  // The point now projects where the mouse let go.
  double nx = 0, ny = 0;
  ASSERT_TRUE(f.window_position(v, nx, ny));
  EXPECT_NEAR(nx, x + 40, 1.0);
  EXPECT_NEAR(ny, y - 20, 1.0);
  // Only the selected point moved on its level.
  const std::vector<double> after = f.positions();
  for (std::size_t i = 0; i < after.size(); ++i) {
    if (i / 3 != v) {
      EXPECT_EQ(after[i], before[i]) << i;
    }
  }
  f.key(Key::Z, Modifiers{false, true, false});
  EXPECT_EQ(f.positions(), before);
  f.key(Key::Z, Modifiers{true, true, false});
  EXPECT_EQ(f.positions(), after);
  expect_shown_equals_fresh(f);
}

// Boundaries and creases take face-based normals, which also depend on the neighbours.
TEST(ModelerControllerTest, DragOnBoundaryAndCreaseKeepsTheShownLimitExact) {
  for (const char* file : {"quad_grid_boundary.obj", "crease_loop.obj"}) {
    Fixture f(file);
    for (unsigned v = 0; v < f.app.model.session().num_vertices(0); v += 3) {
      double x = 0, y = 0;
      if (!f.window_position(v, x, y)) continue;
      f.app.model.set_selection({v});
      f.app.model.begin_drag("Drag");
      const double total[3] = {0.05, 0.1, -0.02};
      f.app.model.drag_to(total);
      f.app.model.end_drag();
    }
    SCOPED_TRACE(file);
    expect_shown_equals_fresh(f);
  }
}


TEST(ModelerControllerTest, GrabWithAxisAndTypedDistanceAndCancel) {
  Fixture f;
  const unsigned v = f.visible_point();
  double x = 0, y = 0;
  ASSERT_TRUE(f.window_position(v, x, y));
  f.click(x, y);
  const std::vector<double> before = f.positions();
  f.key(Key::G);
  ASSERT_TRUE(f.app.grabbing());
  f.send(WindowEvent::Type::Move, x + 30, y + 10);
  EXPECT_NE(f.positions(), before);
  f.key(Key::Escape);  // cancel restores exactly and leaves no redo-able change behind
  EXPECT_FALSE(f.app.grabbing());
  EXPECT_EQ(f.positions(), before);
  EXPECT_FALSE(f.app.model.session().can_redo());
  EXPECT_TRUE(f.app.model.session().history().empty());

  f.key(Key::G);
  f.key(Key::Y);
  f.key(Key::Digit0);
  f.key(Key::Period);
  f.key(Key::Digit5);
  f.key(Key::Enter);
  const std::vector<double> after = f.positions();
  EXPECT_DOUBLE_EQ(after[3 * v + 0], before[3 * v + 0]);
  EXPECT_NEAR(after[3 * v + 1], before[3 * v + 1] + 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(after[3 * v + 2], before[3 * v + 2]);
  EXPECT_EQ(f.app.model.session().undo_position(), 1u);
  EXPECT_EQ(f.app.model.session().history().size(), 1u);
}

TEST(ModelerControllerTest, SoftRadiusLevelsAndSubdivideKeys) {
  Fixture f;
  WindowEvent wheel;
  wheel.type = WindowEvent::Type::Wheel;
  wheel.x = kViewX + 100;
  wheel.y = 100;
  wheel.wheel = 1.0;
  wheel.mods.ctrl = true;
  f.app.handle(wheel);
  EXPECT_NEAR(f.app.model.soft_radius(), f.app.model.default_soft_radius(), 1e-12);
  EXPECT_EQ(f.app.model.level(), 0);
  f.key(Key::PageUp);
  EXPECT_EQ(f.app.model.level(), 1);
  f.key(Key::D, Modifiers{true, false, false});
  EXPECT_EQ(f.app.model.level(), 0);
  const int finest = f.app.model.session().finest_level();
  f.key(Key::D, Modifiers{false, true, false});
  EXPECT_EQ(f.app.model.session().finest_level(), finest + 1);
  f.key(Key::Z, Modifiers{false, true, false});
  EXPECT_EQ(f.app.model.session().finest_level(), finest);
}

TEST(ModelerControllerTest, AutosaveRecoveryAndQuitPrompt) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("sublift_recovery_test_" + std::to_string(::getpid()));
  ::setenv("SUBLIFT_RECOVERY_DIR", dir.c_str(), 1);
  const std::filesystem::path file = dir / "recovery.sublift";
  EXPECT_EQ(ModelerController::recovery_path(), file.string());
  {
    ModelerController app(true);
    app.model.open(std::string(SUBLIFT_ASSETS_DIR) + "/torus_quad.obj");
    EXPECT_TRUE(app.request_quit()) << "a clean session quits at once";
    app.tick(0.0);
    app.model.set_selection({1});
    app.model.begin_drag("Move");
    const double d[3] = {0.0, 0.1, 0.0};
    app.model.drag_to(d);
    app.tick(200.0);  // never during a drag
    EXPECT_FALSE(std::filesystem::exists(file));
    app.model.end_drag();
    app.tick(100.0);  // not yet two minutes since the first tick
    EXPECT_FALSE(std::filesystem::exists(file));
    app.tick(200.0);
    EXPECT_TRUE(std::filesystem::exists(file));
    EXPECT_FALSE(app.request_quit()) << "unsaved changes must be asked about";
    // The autosave reopens to the edited shape.
    {
      ModelerState copy;
      copy.open(file.string());
      const auto a = copy.session().positions(0), b = app.model.session().positions(0);
      EXPECT_TRUE(std::equal(a.begin(), a.end(), b.begin(), b.end()));
    }
    app.clean_exit();
    EXPECT_FALSE(std::filesystem::exists(file));
  }
  {
    ModelerController scripted(false);  // scripts and screenshots never autosave
    scripted.model.open(std::string(SUBLIFT_ASSETS_DIR) + "/torus_quad.obj");
    scripted.model.subdivide();
    scripted.tick(0.0);
    scripted.tick(500.0);
    EXPECT_FALSE(std::filesystem::exists(file));
    EXPECT_TRUE(scripted.request_quit());
  }
  std::filesystem::remove_all(dir);
  ::unsetenv("SUBLIFT_RECOVERY_DIR");
}

// A Basis-section request for the edit level: on, kind (0 scaling, 1 wavelet), index.
BasisSettings basis_request(int kind, long long index) {
  BasisSettings q;
  q.on = true;
  q.request.kind = kind == 0 ? BasisKind::Scaling : BasisKind::Wavelet;
  q.request.index = static_cast<std::uint32_t>(index);
  return q;
}

// Basis mode (issue 5): the panel's request for the selected point computes the same function
// as a direct basis_function call on the edit level, with the support outline around the point;
// wavelets, duals, bad indices, level changes and edits.
TEST(ModelerControllerTest, BasisModeComputesTheSelectedScalingFunctionAndWavelet) {
  Fixture f;
  ModelerState& m = f.app.model;
  m.set_level(1);
  const unsigned v = 2;
  m.set_selection({v});
  const Session& s = m.session();
  const Complex& c1 = s.hierarchy().levels[1];

  ModelerPanelRequests req;
  req.basis = basis_request(0, static_cast<long long>(m.selection().front()));
  f.app.apply_panel_requests(req);
  ASSERT_TRUE(f.app.error.empty()) << f.app.error;
  ASSERT_TRUE(m.basis_on());
  EXPECT_TRUE(m.take_view_update().basis);

  BasisRequest r;
  r.level = 1;
  r.index = v;
  const BasisFunction direct = basis_function(c1, s.hierarchy().scheme, r, s.positions(1));
  const BasisFunction& got = m.basis().function;
  EXPECT_EQ(got.extra_levels, direct.extra_levels);
  EXPECT_EQ(got.support, direct.support);
  EXPECT_EQ(got.support_per_level, direct.support_per_level);
  EXPECT_DOUBLE_EQ(got.integral, direct.integral);
  EXPECT_DOUBLE_EQ(got.max, direct.max);
  EXPECT_GT(got.integral, 0.0);
  ASSERT_GE(got.support_per_level.size(), 2u);
  EXPECT_EQ(got.support_per_level[0], 1u);  // the unit coefficient itself at level j
  // Cubic on a quad torus: the limit function is non-zero on the 2-ring of faces around v.
  const std::size_t nfinest = got.values.size();
  EXPECT_GT(got.support.size(), 10u);
  EXPECT_LT(got.support.size(), nfinest / 4);
  const BasisDisplay& d = m.basis();
  EXPECT_EQ(d.colour.size(), nfinest);
  EXPECT_EQ(d.faces.rows(), got.finest.num_faces());
  EXPECT_FALSE(d.symmetric);
  EXPECT_FLOAT_EQ(*std::max_element(d.colour.begin(), d.colour.end()), 1.0f);
  bool outline_at_v = false;
  for (const std::uint32_t e : d.support_edges) outline_at_v |= e == v;
  EXPECT_TRUE(outline_at_v);
  EXPECT_LT(d.support_edges.size() / 2, c1.num_edges() / 4);

  // Height field: displaced only where the function is non-zero.
  req.basis->height = true;
  f.app.apply_panel_requests(req);
  std::size_t moved = 0;
  for (std::size_t i = 0; i < d.positions.size(); ++i) moved += d.positions[i] != d.base_positions[i];
  EXPECT_GT(moved, 0u);
  EXPECT_EQ(m.basis().function.integral, direct.integral);  // not recomputed

  // The edge wavelet at the selected point, and its dual.
  const long long w = edge_wavelet_at(c1, v);
  ASSERT_GE(w, static_cast<long long>(c1.num_vertices));
  req.basis = basis_request(1, w);
  f.app.apply_panel_requests(req);
  ASSERT_TRUE(m.basis_on()) << f.app.error;
  r.kind = BasisKind::Wavelet;
  r.index = static_cast<std::uint32_t>(w);
  const BasisFunction wd = basis_function(c1, s.hierarchy().scheme, r, s.positions(1));
  EXPECT_EQ(m.basis().function.support, wd.support);
  EXPECT_NEAR(m.basis().function.integral, wd.integral, 1e-15);
  EXPECT_TRUE(m.basis().symmetric);
  req.basis->request.dual = true;
  f.app.apply_panel_requests(req);
  ASSERT_TRUE(m.basis_on());
  EXPECT_FALSE(m.basis().function.limit);

  // A wavelet index on a v vertex fails like other actions and leaves the mode off.
  req.basis = basis_request(1, 0);
  f.app.apply_panel_requests(req);
  EXPECT_FALSE(m.basis_on());
  EXPECT_NE(f.app.error.find("Basis: "), std::string::npos);

  // An edit of the level recomputes (moments follow the geometry); the function keeps its level
  // when another level is edited.
  f.app.error.clear();
  req.basis = basis_request(0, v);
  f.app.apply_panel_requests(req);
  const double before = m.basis().function.moment[1];
  m.begin_drag("Move");
  const double t[3] = {0.0, 0.3, 0.0};
  m.drag_to(t);
  m.end_drag();
  ASSERT_TRUE(m.basis_on());
  EXPECT_NE(m.basis().function.moment[1], before);
  const auto support = m.basis().function.support;
  m.set_level(0);
  ASSERT_TRUE(m.basis_on());
  EXPECT_EQ(m.basis().level, 1);
  EXPECT_EQ(m.basis().function.support, support);
}

// Follow: selecting an e/f/c point of the level j+1 net shows its level-j wavelet; a vertex
// point shows the edge wavelet on its first edge at the edit level; scaling mode the point's
// own scaling function. Each matches a direct basis_function call.
TEST(ModelerControllerTest, BasisFollowPicksWaveletsOnTheNextLevelNet) {
  Fixture f;
  ModelerState& m = f.app.model;
  m.set_level(1);
  const Hierarchy& h = m.session().hierarchy();
  const std::uint32_t nv0 = h.levels[0].num_vertices;
  ModelerPanelRequests req;
  req.basis = basis_request(1, h.levels[1].num_vertices);  // the first edge wavelet of level 1
  req.basis->follow = true;
  f.app.apply_panel_requests(req);
  ASSERT_TRUE(m.basis_on()) << f.app.error;
  auto direct = [&](int level, BasisKind kind, std::uint32_t index) {
    BasisRequest r;
    r.level = level;
    r.kind = kind;
    r.index = index;
    return basis_function(h.levels[static_cast<std::size_t>(level)], h.scheme, r, m.session().positions(level));
  };
  const std::uint32_t face_point = nv0 + h.levels[0].num_edges() + 3;  // a face child of level 0
  m.set_selection({face_point});
  ASSERT_TRUE(m.basis_on());
  EXPECT_EQ(m.basis().level, 0);
  EXPECT_EQ(m.basis().settings.request.index, face_point);
  EXPECT_EQ(m.basis().function.support, direct(0, BasisKind::Wavelet, face_point).support);
  m.set_selection({5});  // a vertex point: the edge wavelet of level 1 on its first edge
  const long long w = edge_wavelet_at(h.levels[1], 5);
  EXPECT_EQ(m.basis().level, 1);
  EXPECT_EQ(m.basis().settings.request.index, static_cast<std::uint32_t>(w));
  EXPECT_EQ(m.basis().function.support, direct(1, BasisKind::Wavelet, static_cast<std::uint32_t>(w)).support);
  // Scaling mode follows too; without follow nothing changes on a click.
  req.basis = basis_request(0, 0);
  req.basis->follow = true;
  f.app.apply_panel_requests(req);
  m.set_selection({face_point});
  EXPECT_EQ(m.basis().level, 1);
  EXPECT_EQ(m.basis().settings.request.index, face_point);
  EXPECT_EQ(m.basis().function.integral, direct(1, BasisKind::Scaling, face_point).integral);
  req.basis->follow = false;
  req.basis->request.index = 7;
  f.app.apply_panel_requests(req);
  m.set_selection({9});
  EXPECT_EQ(m.basis().settings.request.index, 7u);
}

// Pinning keeps a copy of the function across index and scheme changes (linear vs cubic) and
// the panel shows both readouts.
TEST(ModelerControllerTest, BasisPinKeepsAFunctionForComparison) {
  Fixture f;
  ModelerState& m = f.app.model;
  ModelerPanelRequests req;
  req.basis = basis_request(0, 4);
  f.app.apply_panel_requests(req);
  ASSERT_TRUE(m.basis_on());
  const double cubic_max = m.basis().function.max;
  ModelerPanelRequests pin;
  pin.pin_basis = true;
  f.app.apply_panel_requests(pin);
  ASSERT_NE(m.pinned(), nullptr);
  m.set_scheme(Scheme::Linear);
  EXPECT_FALSE(m.basis_on());
  f.app.apply_panel_requests(req);
  ASSERT_TRUE(m.basis_on());
  ASSERT_NE(m.pinned(), nullptr);
  EXPECT_EQ(m.pinned()->function.max, cubic_max);
  EXPECT_DOUBLE_EQ(m.basis().function.max, 1.0);  // the linear hat peaks at its own vertex
  EXPECT_LT(cubic_max, 1.0);                        // the cubic one (limit values) does not
  BasisPanelData data;
  f.app.fill_basis_data(data);
  EXPECT_TRUE(data.pinned && data.computed);
  EXPECT_EQ(data.pin.max, cubic_max);
  EXPECT_NE(data.current.title.find("scaling 4 of level 0"), std::string::npos) << data.current.title;
  ModelerPanelRequests clear;
  clear.clear_pin = true;
  f.app.apply_panel_requests(clear);
  EXPECT_EQ(m.pinned(), nullptr);
  ModelerPanelRequests off;
  off.basis = BasisSettings{};
  f.app.apply_panel_requests(off);
  f.app.apply_panel_requests(pin);  // nothing to pin: an error, not a crash
  EXPECT_NE(f.app.error.find("nothing to pin"), std::string::npos) << f.app.error;
}

// Lattices: a slice plane lies in its plane and is coloured by the function; an iso-surface
// carries the iso value's colour; both are view settings (the function is not recomputed).
TEST(ModelerControllerTest, BasisLatticeSlicesAndIsoSurfaces) {
  Fixture f("hex_block_4.lattice");
  ModelerState& m = f.app.model;
  ModelerPanelRequests req;
  req.basis = basis_request(0, 62);  // the block's centre vertex (0, 0, 0)
  f.app.apply_panel_requests(req);
  ASSERT_TRUE(m.basis_on()) << f.app.error;
  const BasisDisplay& d = m.basis();
  const std::size_t boundary_faces = d.faces.rows();
  EXPECT_EQ(d.faces.rows(), d.boundary.rows());
  req.basis->slice_axis = 2;
  req.basis->slice_pos = 0.5f;
  f.app.apply_panel_requests(req);
  const BasisDisplay& s = m.basis();
  ASSERT_GT(s.faces.rows(), 0u);
  EXPECT_EQ(s.faces.items.size(), 3 * s.faces.rows());
  double zlo = 1e300, zhi = -1e300;
  for (std::size_t v = 0; v < d.base_positions.size() / 3; ++v) {
    zlo = std::min(zlo, d.base_positions[3 * v + 2]), zhi = std::max(zhi, d.base_positions[3 * v + 2]);
  }
  for (std::size_t v = 0; v < s.positions.size() / 3; ++v) EXPECT_NEAR(s.positions[3 * v + 2], 0.5 * (zlo + zhi), 1e-12);
  // The centre vertex lies in that plane: the slice's brightest colour is the function's max.
  EXPECT_FLOAT_EQ(*std::max_element(s.colour.begin(), s.colour.end()), 1.0f);
  const double integral = s.function.integral;
  req.basis->slice_axis = -1;
  req.basis->iso = true;
  req.basis->iso_level = 0.5f;
  f.app.apply_panel_requests(req);
  const BasisDisplay& iso = m.basis();
  ASSERT_GT(iso.faces.rows(), 0u);
  EXPECT_EQ(iso.function.integral, integral);
  const float expected = basis_colour(iso, 0.5 * iso.function.max);
  for (const float c : iso.colour) EXPECT_NEAR(c, expected, 1e-6);
  req.basis->iso = false;
  f.app.apply_panel_requests(req);
  EXPECT_EQ(m.basis().faces.rows(), boundary_faces);
}

// Curves: the plot runs along the curve over the support with zero margins, and its peak is
// the function's maximum.
TEST(ModelerControllerTest, BasisCurvePlot) {
  Fixture f("curves/curve.obj");
  ModelerState& m = f.app.model;
  ModelerPanelRequests req;
  req.basis = basis_request(0, m.session().num_vertices(0) / 2);
  f.app.apply_panel_requests(req);
  ASSERT_TRUE(m.basis_on()) << f.app.error;
  const std::vector<float>& plot = m.basis().plot;
  ASSERT_GT(plot.size(), 8u);
  EXPECT_EQ(plot.front(), 0.0f);
  EXPECT_EQ(plot.back(), 0.0f);
  EXPECT_FLOAT_EQ(*std::max_element(plot.begin(), plot.end()), static_cast<float>(m.basis().function.max));
  std::size_t nonzero = 0;
  for (const float x : plot) nonzero += x != 0.0f;
  EXPECT_EQ(nonzero, m.basis().function.support.size());  // the whole support, in one piece
}

// Each (script, message) case stops with an error whose message contains the expected text.
void expect_script_errors(ModelerState& m, std::span<const std::pair<std::string, std::string>> cases) {
  for (const auto& [text, expect] : cases) {
    ScriptRunner bad("bad", text);
    const ScriptStep step = bad.next(m);
    EXPECT_EQ(step.kind, ScriptStep::Kind::Error) << text;
    EXPECT_NE(step.message.find(expect), std::string::npos) << step.message;
  }
}

// The scheme menu's third entry (issue 7): the hierarchy is rebuilt as sqrt2 at the same finest
// resolution (2 levels per 1-to-4 level), drags stay exact on the shown surface (the limit of an
// interpolatory scheme is its control net), the scaling function of a clicked point peaks at
// exactly 1 there, and lattices refuse the scheme with a message.
TEST(ModelerControllerTest, Sqrt2SchemeFromTheMenu) {
  Fixture f("quad_grid_boundary.obj");
  ModelerState& m = f.app.model;
  const int cubic_levels = m.session().finest_level();
  const std::uint32_t finest = m.session().num_vertices(cubic_levels);
  ModelerPanelRequests req;
  req.scheme = 2;
  f.app.apply_panel_requests(req);
  ASSERT_EQ(m.session().hierarchy().scheme, Scheme::Sqrt2);
  EXPECT_EQ(m.session().finest_level(), 2 * cubic_levels);
  EXPECT_EQ(m.session().num_vertices(m.session().finest_level()), finest);  // Catmull-Clark topology
  for (int level : {1, 2}) {
    m.set_level(level);
    m.set_selection({5});
    m.begin_drag("Drag");
    const double total[3] = {0.05, 0.1, -0.02};
    m.drag_to(total);
    m.end_drag();
    expect_shown_equals_fresh(f);
  }
  // The shown surface passes through the finest control points.
  const auto net = m.session().positions(m.session().finest_level());
  const auto shown = m.limit_positions();
  ASSERT_EQ(shown.size(), net.size());
  for (std::size_t i = 0; i < net.size(); ++i) ASSERT_EQ(shown[i], net[i]) << i;
  ModelerPanelRequests basis;
  basis.basis = basis_request(0, 7);
  f.app.apply_panel_requests(basis);
  ASSERT_TRUE(m.basis_on());
  EXPECT_EQ(m.basis().function.values[7], 1.0);
  EXPECT_EQ(m.basis().function.max, 1.0);
  // Back to cubic: the resolution comes back too.
  ModelerPanelRequests back;
  back.scheme = 1;
  f.app.apply_panel_requests(back);  // at once: undo brings the sqrt2 session back
  EXPECT_EQ(m.session().hierarchy().scheme, Scheme::Cubic);
  EXPECT_EQ(m.session().finest_level(), cubic_levels);
  ASSERT_TRUE(m.undo());
  EXPECT_EQ(m.session().hierarchy().scheme, Scheme::Sqrt2);
  EXPECT_EQ(m.session().history().size(), 2u);  // the two drags, undoable as before
  ASSERT_TRUE(m.redo());
  EXPECT_EQ(m.session().hierarchy().scheme, Scheme::Cubic);

  Fixture lattice("cube_cell.lattice");
  EXPECT_THROW(lattice.app.model.set_scheme(Scheme::Sqrt2), Error);
  ModelerPanelRequests to_sqrt2;
  to_sqrt2.scheme = 2;
  lattice.app.apply_panel_requests(to_sqrt2);
  EXPECT_NE(lattice.app.error.find("surfaces only"), std::string::npos) << lattice.app.error;
  EXPECT_EQ(lattice.app.model.session().hierarchy().scheme, Scheme::Cubic);
}

// The Scheme menu builds the new levels on a worker thread with progress (a dense mesh's take a
// while under the triangle schemes); the result installs itself, undoable; a cancelled change
// leaves the session as it was; the same scheme again starts nothing.
TEST(ModelerControllerTest, SchemeChangeRunsAsAJobWithCancel) {
  Fixture f;
  f.app.set_background_jobs(true);
  ModelerState& m = f.app.model;
  const std::uint64_t serial = m.serial();
  const std::vector<double> shown(m.limit_positions().begin(), m.limit_positions().end());
  ModelerPanelRequests to_linear;
  to_linear.scheme = static_cast<int>(Scheme::Linear);
  f.app.apply_panel_requests(to_linear);
  EXPECT_TRUE(f.app.job_running());
  EXPECT_EQ(m.serial(), serial);  // nothing installed until the job is polled
  EXPECT_TRUE(f.app.poll_job(true));
  EXPECT_EQ(m.session().hierarchy().scheme, Scheme::Linear);
  EXPECT_NE(f.app.message.find("Rebuilt with the linear scheme"), std::string::npos) << f.app.message << f.app.error;
  ASSERT_TRUE(m.undo());
  EXPECT_EQ(m.session().hierarchy().scheme, Scheme::Cubic);
  EXPECT_EQ(std::vector<double>(m.limit_positions().begin(), m.limit_positions().end()), shown);
  // Cancelled from the window: nothing changes. Five levels (98 k quads, ten sqrt(2) levels
  // to build) keep the job running well past the cancel that follows it at once.
  while (m.session().finest_level() < 5) m.subdivide();
  const std::vector<double> fine(m.limit_positions().begin(), m.limit_positions().end());
  ModelerPanelRequests to_sqrt2;
  to_sqrt2.scheme = static_cast<int>(Scheme::Sqrt2);
  f.app.apply_panel_requests(to_sqrt2);
  ASSERT_TRUE(f.app.job_running());
  f.app.cancel_job();
  EXPECT_TRUE(f.app.poll_job(true));
  EXPECT_EQ(m.session().hierarchy().scheme, Scheme::Cubic);
  EXPECT_EQ(m.session().finest_level(), 5);
  EXPECT_NE(f.app.message.find("Changing the scheme cancelled; nothing changed"), std::string::npos) << f.app.message;
  EXPECT_EQ(std::vector<double>(m.limit_positions().begin(), m.limit_positions().end()), fine);
  // The scheme it already has: no job.
  ModelerPanelRequests same;
  same.scheme = static_cast<int>(Scheme::Cubic);
  f.app.apply_panel_requests(same);
  EXPECT_FALSE(f.app.job_running());
}

// The triangle schemes of paper 004 from the Scheme menu: drags keep the shown surface equal
// to a fresh evaluation, butterfly shows its finest net (it interpolates), Loop its limit
// masks; a quad mesh refuses them with the face named.
TEST(ModelerControllerTest, TriangleSchemesFromTheMenu) {
  Fixture f("octahedron.obj");
  ModelerState& m = f.app.model;
  for (int choice : {4, 5, 3}) {  // butterfly, loop, linear-tri
    ModelerPanelRequests req;
    req.scheme = choice;
    f.app.apply_panel_requests(req);
    if (m.session().hierarchy().scheme != static_cast<Scheme>(choice)) m.set_scheme(static_cast<Scheme>(choice));
    ASSERT_EQ(m.session().hierarchy().scheme, static_cast<Scheme>(choice)) << f.app.error;
    for (int level : {0, 1}) {
      m.set_level(level);
      m.set_selection({2});
      m.begin_drag("Drag");
      const double total[3] = {0.05, 0.1, -0.02};
      m.drag_to(total);
      m.end_drag();
      expect_shown_equals_fresh(f);
    }
    const auto net = m.session().positions(m.session().finest_level());
    const auto shown = m.limit_positions();
    ASSERT_EQ(shown.size(), net.size());
    double differs = 0;
    for (std::size_t i = 0; i < net.size(); ++i) differs = std::max(differs, std::abs(shown[i] - net[i]));
    if (static_cast<Scheme>(choice) == Scheme::Loop) {
      EXPECT_GT(differs, 1e-3);
    } else {
      EXPECT_EQ(differs, 0.0);
    }
  }
  Fixture quads("quad_grid_boundary.obj");
  ModelerPanelRequests to_loop;
  to_loop.scheme = 5;
  quads.app.apply_panel_requests(to_loop);
  EXPECT_NE(quads.app.error.find("needs a triangle mesh; face 0 has 4 corners"), std::string::npos) << quads.app.error;
  EXPECT_EQ(quads.app.model.session().hierarchy().scheme, Scheme::Cubic);
}

TEST(ModelerControllerTest, BasisScriptCommands) {
  ModelerState m;
  const std::string torus = std::string(SUBLIFT_ASSETS_DIR) + "/torus_quad.obj";
  ScriptRunner ok("ok", "open " + torus + "\nlevel 1\nbasis scaling 5\nbasis height 0.1\nbasis wavelet 400 dual\n");
  EXPECT_EQ(ok.next(m).kind, ScriptStep::Kind::End);
  ASSERT_TRUE(m.basis_on());
  EXPECT_EQ(m.basis_settings().request.kind, BasisKind::Wavelet);
  EXPECT_TRUE(m.basis_settings().request.dual);
  EXPECT_TRUE(m.basis_settings().height);
  EXPECT_EQ(m.basis().function.finest.num_vertices, m.basis().function.values.size());
  ScriptRunner off("off", "basis off\n");
  EXPECT_EQ(off.next(m).kind, ScriptStep::Kind::End);
  EXPECT_FALSE(m.basis_on());
  const std::pair<std::string, std::string> cases[] = {
      {"basis wavelet 3\n", "script:1: wavelet index 3 is outside 384.."},
      {"basis scaling 384\n", "script:1: scaling index 384 is outside 0..383"},
      {"basis scaling 1 primal\n", "script:1: basis takes 'dual'"},
      {"basis\n", "script:1: usage: basis scaling|wavelet"},
      {"basis height 0.2\n", "script:1: basis height needs the basis mode on"},
  };
  expect_script_errors(m, cases);
}

}  // namespace
}  // namespace sublift

namespace sublift {
namespace {

// FFD mode (issue 6): a model loaded with no lattice open is wrapped in a 4x4x4 box lattice and
// bound; a lattice drag moves it exactly as core/ffd/ffd.h's deform of the same binding does, undo
// brings it back bit for bit, an unbound model stays put, topology changes are refused while
// bound, and a dirty surface is not replaced.
TEST(ModelerFfdTest, ModelFollowsLatticeEditsAndUndo) {
  ModelerState m;
  const std::string torus = std::string(SUBLIFT_ASSETS_DIR) + "/torus_quad.obj";
  m.load_model(torus);
  ASSERT_TRUE(m.has_session());
  ASSERT_NE(m.ffd(), nullptr);
  EXPECT_EQ(m.dim(), 3);
  EXPECT_EQ(m.session().num_vertices(0), 125u);
  EXPECT_TRUE(m.ffd()->bound);
  EXPECT_EQ(m.ffd()->binding.report.bound, 96u);
  EXPECT_TRUE(m.take_view_update().model_topology);
  const std::vector<double> rest = m.ffd()->positions;

  m.set_selection({62});  // the box's centre point
  m.begin_drag("Move");
  const double t[3] = {0.0, 0.0, 0.2};
  m.drag_to(t);
  m.end_drag();
  EXPECT_TRUE(m.take_view_update().model);
  const int J = m.session().finest_level();
  std::vector<double> expected(rest.size());
  deform(m.ffd()->binding, m.session().positions(J), expected);
  EXPECT_EQ(m.ffd()->positions, expected);
  EXPECT_NE(m.ffd()->positions, rest);
  EXPECT_GT(m.ffd()->last_moved, 0u);

  m.undo();
  EXPECT_EQ(m.ffd()->positions, rest);  // bit for bit
  m.redo();
  EXPECT_EQ(m.ffd()->positions, expected);

  EXPECT_THROW(m.subdivide(), Error);
  EXPECT_THROW(m.set_scheme(Scheme::Linear), Error);
  m.unbind_model();
  m.set_selection({0});
  m.begin_drag("Move");
  m.drag_to(t);
  m.end_drag();
  EXPECT_EQ(m.ffd()->positions, expected);  // unbound: the model stays
  EXPECT_NO_THROW(m.subdivide());
  // Bound again to the lattice as it is: the model does not jump.
  m.bind_model();
  EXPECT_EQ(m.ffd()->positions, expected);
  EXPECT_EQ(m.session().finest_level(), 3);

  // Export and read back: the model as it is now.
  const std::string out = (std::filesystem::temp_directory_path() / "sublift_ffd_state.obj").string();
  m.export_model(out);
  const Model back = import_model(out);
  ASSERT_EQ(back.positions.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) EXPECT_NEAR(back.positions[i], expected[i], 1e-12);
  std::filesystem::remove(out);
}

TEST(ModelerFfdTest, LoadBindsToAnOpenLatticeAndRefusesToDropADirtySurface) {
  ModelerState m;
  m.open(std::string(SUBLIFT_ASSETS_DIR) + "/hex_block_4.lattice");
  m.load_model(std::string(SUBLIFT_ASSETS_DIR) + "/torus_quad.obj");
  EXPECT_EQ(m.session().num_vertices(0), 125u);  // the open lattice, not a box
  EXPECT_TRUE(m.ffd()->bound);
  EXPECT_EQ(m.ffd()->binding.report.bound + m.ffd()->binding.report.outside, 96u);

  ModelerState s;
  s.open(std::string(SUBLIFT_ASSETS_DIR) + "/torus_quad.obj");
  s.set_selection({3});
  s.begin_drag("Move");
  const double t[3] = {0.0, 0.1, 0.0};
  s.drag_to(t);
  s.end_drag();
  EXPECT_THROW(s.load_model(std::string(SUBLIFT_ASSETS_DIR) + "/cube.obj"), Error);
  EXPECT_EQ(s.dim(), 2);
  EXPECT_EQ(s.ffd(), nullptr);
  EXPECT_THROW(s.load_model("/nonexistent/model.obj"), Error);
}

TEST(ModelerFfdTest, ScriptCommands) {
  ModelerState m;
  const std::string torus = std::string(SUBLIFT_ASSETS_DIR) + "/torus_quad.obj";
  ScriptRunner ok("ok", "model " + torus + "\nffd box 2 2 2 0.1\nffd bind nearest\nselect 13\nmove 0 0.3 0\n");
  EXPECT_EQ(ok.next(m).kind, ScriptStep::Kind::End);
  ASSERT_NE(m.ffd(), nullptr);
  EXPECT_EQ(m.session().num_vertices(0), 27u);
  EXPECT_EQ(m.ffd()->outside, Outside::Nearest);
  EXPECT_NE(m.ffd()->positions, m.ffd()->model.positions);
  const std::pair<std::string, std::string> cases[] = {
      {"ffd box 2 0 2\n", "script:1: cell counts must be 1..64"},
      {"ffd bind far\n", "script:1: ffd bind takes 'nearest'"},
      {"ffd\n", "script:1: usage: ffd box"},
      {"subdivide\n", "not possible while a model is bound"},
  };
  expect_script_errors(m, cases);
}

}  // namespace
}  // namespace sublift

#include <fstream>

#include "tests/io_test_util.h"
#include <sstream>

#include "core/complex/complex_build.h"
#include "core/io/lattice/shape_io.h"
#include "core/io/project/project_io.h"
#include "tests/mesh_fixtures.h"

namespace sublift {
namespace {

// The vertex numbers of each OBJ face line (normal and texture indices dropped).
std::vector<std::vector<long>> obj_faces(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::vector<long>> faces;
  for (std::string l; std::getline(in, l);) {
    if (l.rfind("f ", 0) != 0) continue;
    std::istringstream s(l.substr(2));
    faces.emplace_back();
    for (std::string corner; s >> corner;) faces.back().push_back(std::stol(corner.substr(0, corner.find('/'))));
  }
  return faces;
}

// Issue 16: a mesh subdivided elsewhere is recognised on open; "rebuild" (script or the
// Hierarchy button's request) finds its base, opens at level 0 with the detail as wavelets, and
// saves and exports in the file's order.
TEST(ModelerRebuildTest, OpeningASubdividedMeshOffersToRebuildItsLevels) {
  const auto dir = std::filesystem::temp_directory_path() / "sublift_modeler_rebuild";
  std::filesystem::create_directories(dir);
  const std::string fine = (dir / "fine.obj").string(), project = (dir / "p.sublift").string(), out = (dir / "out.obj").string();
  const fixtures::Polygons cube = fixtures::cube();
  Hierarchy h = make_hierarchy(complex_from_polygons(cube.num_vertices, cube.faces), 2, Scheme::Cubic, 3);
  set_base(h, cube.positions);
  write_shape(fine, h.levels.back(), synthesize(h, 2));

  ModelerController app{false};
  app.model.open(fine);
  EXPECT_EQ(app.model.rebuild_offer().levels, 2);
  EXPECT_EQ(app.model.rebuild_offer().scheme, Scheme::Cubic);
  EXPECT_EQ(app.model.session().finest_level(), ModelerState::kDefaultLevels);  // opened as today: the dense mesh is level 0
  EXPECT_NE(app.model.rebuild_offer().stop.find("the mesh 2 levels down"), std::string::npos) << app.model.rebuild_offer().stop;
  // "Show where": the vertex near where the split stops, selected on the file's own level.
  ModelerPanelRequests show;
  show.rebuild_show_stop = true;
  app.apply_panel_requests(show);
  ASSERT_EQ(app.model.selection().size(), 1u);
  EXPECT_EQ(app.model.selection()[0], app.model.rebuild_offer().stop_vertex);
  EXPECT_EQ(app.model.level(), 0);
  ModelerPanelRequests r;
  r.rebuild = true;
  app.apply_panel_requests(r);
  EXPECT_NE(app.message.find("Rebuilt 2 levels"), std::string::npos) << app.message << app.error;
  ModelerState& m = app.model;
  EXPECT_EQ(m.session().finest_level(), 2);
  EXPECT_EQ(m.level(), 0);
  EXPECT_EQ(m.session().num_vertices(0), 8u);
  EXPECT_EQ(m.rebuild_offer().levels, 0);
  const Shape file = read_shape(fine);
  const auto finest = m.session().positions(2);
  const std::vector<double> back = in_input_order(m.input_order(), finest, 3);
  ASSERT_EQ(back.size(), file.positions.size());
  double worst = 0;
  for (std::size_t i = 0; i < back.size(); ++i) worst = std::max(worst, std::abs(back[i] - file.positions[i]));
  EXPECT_LE(worst, 1e-9);  // OBJ keeps 17 digits; the analysis reproduces them
  m.save_project(project);
  ProjectExtras extras;
  read_project(project, &extras);
  EXPECT_EQ(extras.input_order.level, 2);
  m.set_level(2);
  m.export_shape(out, false);
  EXPECT_EQ(obj_faces(out), obj_faces(fine));
  EXPECT_EQ(obj_faces(fine).size(), 96u);
  // The script command; refused on a project.
  ModelerState s;
  ScriptRunner ok("ok", "open " + fine + "\nrebuild max\nlevel 0\n");
  EXPECT_EQ(ok.next(s).kind, ScriptStep::Kind::End);
  EXPECT_EQ(s.session().finest_level(), 2);
  ModelerState p;
  ScriptRunner bad("bad", "open " + project + "\nrebuild\n");
  const ScriptStep step = bad.next(p);
  EXPECT_EQ(step.kind, ScriptStep::Kind::Error);

  // In the window the rebuild runs on a worker thread with progress; its result is installed
  // when it ends. A cancelled rebuild changes nothing.
  ModelerController bg{false};
  bg.set_background_jobs(true);
  bg.model.open(fine);
  ModelerPanelRequests go;
  go.rebuild = true;
  bg.apply_panel_requests(go);
  EXPECT_TRUE(bg.job_running());
  EXPECT_TRUE(bg.poll_job(true));
  EXPECT_FALSE(bg.job_running());
  EXPECT_EQ(bg.model.session().finest_level(), 2);
  EXPECT_NE(bg.message.find("Rebuilt 2 levels"), std::string::npos) << bg.message << bg.error;
  std::vector<std::string> stages;
  EXPECT_THROW(ModelerState::prepare_rebuild(fine, {}, -1,
                                             [&](const char* stage, double) {
                                               stages.push_back(stage);
                                               return stages.size() < 2;
                                             }),
               Cancelled);
  EXPECT_EQ(stages.size(), 2u);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace sublift

namespace sublift {
namespace {

// A mesh with a loose vertex (the stanford bunny has 1,113) opens: level detection refuses
// it, and says why instead of failing the open.
TEST(ModelerOpenTest, LooseVerticesStillOpen) {
  const testing::TempDir dir("sublift_modeler_loose");
  const std::string path = dir.file("loose.obj");
  std::ofstream(path) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 5 5\nf 1 2 3\n";
  ModelerState m;
  m.open(path);
  ASSERT_TRUE(m.has_session());
  EXPECT_EQ(m.rebuild_offer().levels, 0);
  EXPECT_NE(m.rebuild_offer().stop.find("in no face"), std::string::npos) << m.rebuild_offer().stop;
}

// A dense mesh opens with fewer added levels, so its finest level stays within
// kMaxOpenVertices (a 180 k-vertex torus: one level, 720 k vertices, not two, 2.9 M).
TEST(ModelerOpenTest, DenseMeshesOpenWithFewerLevels) {
  const auto dir = std::filesystem::temp_directory_path() / "sublift_modeler_dense";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "dense.obj").string();
  const fixtures::Polygons t = fixtures::torus(600, 300);
  Complex c = complex_from_polygons(t.num_vertices, t.faces);
  write_shape(path, c, t.positions);
  ModelerState m;
  m.open(path);
  EXPECT_EQ(m.session().finest_level(), 1);
  EXPECT_LE(double(m.session().num_vertices(1)), ModelerState::kMaxOpenVertices);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace sublift

#include "core/analysis/sphere_resample.h"

namespace sublift {
namespace {

// Issue 17 (a first version): the script command `fit` gives any triangle mesh a coarse base
// and fitted levels, opened at level 0; a thin scan fits; a failed fit changes nothing.
TEST(ModelerFitTest, FitScriptCommand) {
  const auto dir = std::filesystem::temp_directory_path() / "sublift_modeler_fit";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "sphere.obj").string();
  const GeodesicSphere g = geodesic_sphere(5);
  std::vector<double> xyz;
  for (const auto& d : g.directions) xyz.insert(xyz.end(), {d.x, d.y, d.z});
  write_shape(path, g.fine, xyz);
  ModelerState m;
  ScriptRunner ok("ok", "open " + path + "\nfit 100 2\n");  // 2 levels; 0 or none: to about the mesh's count
  EXPECT_EQ(ok.next(m).kind, ScriptStep::Kind::End);
  EXPECT_EQ(m.session().num_vertices(0), 100u);
  EXPECT_EQ(m.session().finest_level(), 2);
  EXPECT_EQ(m.level(), 0);
  {  // the base-to-mesh map rides with the project: saved, reopened, saved again
    ASSERT_EQ(m.fit_source().base_vertex.size(), 100u);
    EXPECT_EQ(m.fit_source().mesh_vertices, g.fine.num_vertices);
    const std::string saved = (dir / "fitted.sublift").string(), again = (dir / "again.sublift").string();
    m.save_project(saved);
    ModelerState r;
    r.open(saved);
    EXPECT_EQ(r.fit_source().base_vertex, m.fit_source().base_vertex);
    r.save_project(again);
    ProjectExtras x;
    read_project(again, &x);
    EXPECT_EQ(x.fit_source.base_vertex, m.fit_source().base_vertex);
    EXPECT_EQ(x.fit_source.mesh, m.fit_source().mesh);
    r.open(path);  // a mesh, not a fit
    EXPECT_TRUE(r.fit_source().empty());
  }
  // Any scheme: the polygon schemes from a quad-dominant base (fewer faces than the 2 V - 4
  // triangles of a genus-0 triangle base).
  ModelerState mc;
  ScriptRunner cubic("cubic", "open " + path + "\nfit 100 1 cubic\n");
  EXPECT_EQ(cubic.next(mc).kind, ScriptStep::Kind::End);
  EXPECT_EQ(mc.session().hierarchy().scheme, Scheme::Cubic);
  EXPECT_EQ(mc.session().num_vertices(0), 100u);
  EXPECT_LT(mc.session().hierarchy().levels[0].faces.rows(), 2u * 100 - 4);
  const std::pair<std::string, std::string> cases[] = {
      {"fit 100 7 loop\n", "script:1: fit LEVELS needs 0 (to about the mesh's vertex count) to 6"},
      {"fit 100 13\n", "script:1: fit LEVELS needs 0 (to about the mesh's vertex count) to 12"},  // sqrt(2), the default
      {"fit 100 1 quintic\n", "script:1: unknown scheme 'quintic' (linear, cubic, sqrt2, linear-tri, butterfly or loop)"}};
  expect_script_errors(m, cases);
  const std::filesystem::path scan = std::filesystem::path(SUBLIFT_SHARED_DATA) / "scans/bunny_npm_lowres.obj";
  if (std::filesystem::exists(scan)) {
    ModelerState b;
    b.open(scan.string());
    const std::uint32_t before = b.session().num_vertices(0);
    EXPECT_THROW(b.fit_base({5000, 60.0, 3}), Error);  // a base larger than the scan
    EXPECT_EQ(b.session().num_vertices(0), before);  // nothing changed
    // The default base is so coarse at the ears that faces' patches meet themselves: it fits.
    b.fit_base({0, 60.0, 3});
    // About 1/64 of its 1,839 vertices: the decimation stops at 30 free vertices, and the
    // corners it may not collapse (where its creases end) come on top.
    EXPECT_GE(b.session().num_vertices(0), 28u);
    EXPECT_LE(b.session().num_vertices(0), 40u);
    EXPECT_EQ(b.session().finest_level(), 3);
  }
  // The Fit section: a preview of the base (drawn over the mesh), then the fit on a worker
  // thread with progress; a cancelled fit changes nothing.
  ModelerController app{false};
  app.set_background_jobs(true);
  app.model.open(path);
  ASSERT_TRUE(app.model.can_fit());
  FitRequest q;
  q.base_vertices = 80;
  ModelerPanelRequests preview;
  preview.fit_preview = q;
  app.apply_panel_requests(preview);  // a job too: a large mesh's decimation takes seconds
  EXPECT_TRUE(app.job_running());
  EXPECT_TRUE(app.poll_job(true));
  ASSERT_NE(app.model.fit_preview(), nullptr) << app.error;
  EXPECT_EQ(app.model.fit_preview()->vertices, 80u);
  // A sphere's: V - E + F = 2 (quads and triangles, for the default sqrt(2)).
  EXPECT_EQ(app.model.fit_preview()->edges.size() / 2, 80u + app.model.fit_preview()->faces - 2);
  EXPECT_LT(app.model.fit_preview()->faces, 2u * 80 - 4);  // fewer than a triangle base's
  EXPECT_TRUE(app.model.take_view_update().fit_preview);
  EXPECT_NE(app.message.find("80 vertices"), std::string::npos) << app.message;
  ModelerPanelRequests go;
  go.fit = q;
  app.apply_panel_requests(go);
  EXPECT_TRUE(app.job_running());
  EXPECT_TRUE(app.poll_job(true));
  EXPECT_EQ(app.model.session().num_vertices(0), 80u);
  EXPECT_EQ(app.model.session().finest_level(), default_fit_levels(g.fine.num_vertices, 80, kDefaultFitScheme));
  EXPECT_EQ(app.model.level(), 0);
  EXPECT_EQ(app.model.fit_preview(), nullptr);  // the preview goes with the fit
  EXPECT_EQ(app.model.file_vertices(), g.fine.num_vertices);  // the Fit section still counts the file's
  EXPECT_NE(app.message.find("Fitted a base of 80 vertices"), std::string::npos) << app.message << app.error;
  std::vector<std::string> stages;
  ModelerState::FitSettings settings;
  settings.base_vertices = 80;
  EXPECT_THROW(ModelerState::prepare_fit(path, settings,
                                         [&](const char* stage, double) {
                                           stages.push_back(stage);
                                           return stages.size() < 4;
                                         }),
               Cancelled);
  EXPECT_EQ(stages.size(), 4u);
  // Cancel while the base is decimated (the progress reaches into OpenMesh's decimater).
  std::vector<double> base_progress;
  EXPECT_THROW(ModelerState::prepare_fit(path, settings,
                                         [&](const char* stage, double f) {
                                           if (std::string(stage) != "the base mesh") return true;
                                           base_progress.push_back(f);
                                           return f < 0.3;
                                         }),
               Cancelled);
  ASSERT_GE(base_progress.size(), 3u);
  EXPECT_GE(base_progress.back(), 0.3);
  EXPECT_LT(base_progress.back(), 0.5) << "the decimation went on after Cancel";
  // Cancel from the window: the session stays as it was.
  ModelerController c2{false};
  c2.set_background_jobs(true);
  c2.model.open(path);
  const std::uint32_t opened = c2.model.session().num_vertices(0);
  c2.apply_panel_requests(go);
  c2.cancel_job();
  EXPECT_TRUE(c2.poll_job(true));
  EXPECT_EQ(c2.model.session().num_vertices(0), opened);
  EXPECT_NE(c2.message.find("Fitting cancelled; nothing changed"), std::string::npos) << c2.message << c2.error;
  // The file's crease and corner tags do not come along (the fit makes its own): said by name.
  ModelerState tagged;
  tagged.open(std::string(SUBLIFT_ASSETS_DIR) + "/tri_crease_grid.obj");
  tagged.fit_base({24, 60.0, 1});
  bool said = false;
  for (const std::string& w : tagged.import_warnings()) said |= w.find("not kept by the fit: the file's") != std::string::npos;
  EXPECT_TRUE(said);
  // Script: fit-preview and its errors.
  ModelerState sp;
  ScriptRunner pv("pv", "open " + path + "\nfit-preview 60 45\n");
  EXPECT_EQ(pv.next(sp).kind, ScriptStep::Kind::End);
  ASSERT_NE(sp.fit_preview(), nullptr);
  EXPECT_EQ(sp.fit_preview()->vertices, 60u);
  const std::pair<std::string, std::string> bad_preview[] = {{"fit-preview 60 200\n", "script:1: fit-preview FEATURE_ANGLE needs degrees in (0, 180)"}};
  expect_script_errors(sp, bad_preview);
  std::filesystem::remove_all(dir);
}

// A scripted fit or base preview shows its settings in the Fit panel's form (before, the form
// kept its own scheme after `fit ... cubic`); what is typed there stays until a script asks again.
TEST(ModelerFitTest, ScriptedFitSettingsShowInTheFitPanel) {
  const testing::TempDir dir("sublift_modeler_fit_form");
  const std::string path = dir.file("sphere.obj");
  const GeodesicSphere g = geodesic_sphere(5);
  std::vector<double> xyz;
  for (const auto& d : g.directions) xyz.insert(xyz.end(), {d.x, d.y, d.z});
  write_shape(path, g.fine, xyz);
  ModelerController c{false};
  c.sync_fit_form();
  EXPECT_EQ(c.fields.fit.scheme, static_cast<int>(kDefaultFitScheme));  // nothing asked yet
  ScriptRunner preview("preview", "open " + path + "\nfit-preview 60 45 loop\n");
  EXPECT_EQ(preview.next(c.model).kind, ScriptStep::Kind::End);
  c.sync_fit_form();
  EXPECT_EQ(c.fields.fit.scheme, static_cast<int>(Scheme::Loop));
  EXPECT_EQ(c.fields.fit.base_vertices, 60);
  EXPECT_EQ(c.fields.fit.feature_angle_deg, 45.0f);
  EXPECT_EQ(c.fields.fit.levels, 0);
  c.fields.fit.scheme = static_cast<int>(Scheme::Sqrt2);  // typed in the panel
  c.sync_fit_form();
  EXPECT_EQ(c.fields.fit.scheme, static_cast<int>(Scheme::Sqrt2));
  ScriptRunner fit("fit", "fit 100 1 cubic\n");
  EXPECT_EQ(fit.next(c.model).kind, ScriptStep::Kind::End);
  c.sync_fit_form();
  EXPECT_EQ(c.fields.fit.scheme, static_cast<int>(Scheme::Cubic));
  EXPECT_EQ(c.fields.fit.base_vertices, 100);
  EXPECT_EQ(c.fields.fit.levels, 1);
  EXPECT_EQ(c.fields.fit.feature_angle_deg, 60.0f);  // the script's default
}

// Issue 20: a glTF opens in the modeler as a welded surface; a PLY's colours open as channels
// beside the session (tests/modeler/modeler_channels_test.cpp), so nothing is named as dropped.
TEST(ModelerOpenTest, GltfOpensWeldedAndColoursAreKept) {
  const std::filesystem::path box = std::filesystem::path(SUBLIFT_SHARED_DATA) / "gltf/BoxVertexColors/BoxVertexColors.glb";
  if (!std::filesystem::exists(box)) GTEST_SKIP() << box << " not found (../shared/data is absent)";
  ModelerState m;
  m.open(box.string());
  ASSERT_TRUE(m.has_session());
  EXPECT_EQ(m.session().num_vertices(0), 8u);
  std::string all;
  for (const std::string& w : m.import_warnings()) all += w + "\n";
  EXPECT_NE(all.find("welded by position: 24 into 8"), std::string::npos) << all;
  const testing::TempDir dir("sublift_modeler_colours");
  const std::string ply = dir.file("c.ply");
  std::ofstream(ply) << "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                        "property uchar red\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                        "0 0 0 255\n1 0 0 0\n0 1 0 9\n3 0 1 2\n";
  m.open(ply);
  all.clear();
  for (const std::string& w : m.import_warnings()) all += w + "\n";
  EXPECT_EQ(all.find("vertex attributes"), std::string::npos) << all;
  m.save_project(dir.file("c.sublift"));
  EXPECT_EQ(read_project(dir.file("c.sublift")).channels, 4);  // x, y, z and red
}

}  // namespace
}  // namespace sublift
