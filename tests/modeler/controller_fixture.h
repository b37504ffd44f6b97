#pragma once
// The controller under synthetic window events, without a window (picking is core math): the
// fixture the modeler's controller tests share.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "app/modeler/modeler_controller.h"
#include "core/edit/picking.h"
#include "core/multires/limit.h"
#include "render/net_renderer.h"
#include "render/viewport_renderer.h"

#ifndef SUBLIFT_ASSETS_DIR
#error "SUBLIFT_ASSETS_DIR must name the assets folder"
#endif

namespace sublift::testing {

constexpr float kViewX = 330.0f, kViewW = 800.0f, kViewH = 600.0f;

struct Fixture {
  ModelerController app{false};
  explicit Fixture(const std::string& file = "torus_quad.obj") {
    app.model.open(std::string(SUBLIFT_ASSETS_DIR) + "/" + file);
    app.set_view_rect(kViewX, 0.0f, kViewW, kViewH, 1.0f);
    app.camera.set_viewport(static_cast<int>(kViewW), static_cast<int>(kViewH));
    frame_bounds(app.camera, point_bounds(app.model.limit_positions()));
  }
  PickView view() const {
    return PickView{app.camera.projection() * app.camera.view(), app.camera.viewport_width,
                    app.camera.viewport_height};
  }
  // Window position of control point v of the edit level; false when it is off screen.
  bool window_position(unsigned v, double& x, double& y) const {
    const auto p = app.model.session().positions(app.model.level());
    glm::dvec2 s;
    double depth = 0.0;
    if (!project_point(view(), glm::dvec3(p[3 * v], p[3 * v + 1], p[3 * v + 2]), s, depth)) return false;
    x = s.x + kViewX;
    y = s.y;
    return true;
  }
  // The front-most control point: the one a click at its projection picks.
  unsigned visible_point() {
    PickIndex index;
    index.build(view(), app.model.session().positions(app.model.level()));
    const auto n = app.model.session().num_vertices(app.model.level());
    for (unsigned v = 0; v < n; ++v) {
      double x = 0, y = 0;
      if (window_position(v, x, y) && index.nearest(x - kViewX, y, 10.0, false) == v) return v;
    }
    return 0;
  }
  void send(WindowEvent::Type type, double x, double y, int button = 0, Modifiers mods = {}) {
    WindowEvent e;
    e.type = type;
    e.x = x;
    e.y = y;
    e.button = button;
    e.mods = mods;
    app.handle(e);
  }
  void key(Key k, Modifiers mods = {}) {
    WindowEvent e;
    e.type = WindowEvent::Type::Key;
    e.key = k;
    e.mods = mods;
    app.handle(e);
  }
  void click(double x, double y, Modifiers mods = {}) {
    send(WindowEvent::Type::Move, x, y, 0, mods);
    send(WindowEvent::Type::Press, x, y, 0, mods);
    send(WindowEvent::Type::Release, x, y, 0, mods);
  }
  std::vector<double> positions() const {
    const auto p = app.model.session().positions(app.model.level());
    return {p.begin(), p.end()};
  }
};

// What the viewport shows after the incremental updates equals a fresh evaluation.
inline void expect_shown_equals_fresh(const Fixture& f) {
  const Hierarchy& h = f.app.model.session().hierarchy();
  const int J = h.finest_level();
  const LimitStencils st = build_limit_stencils(h);
  const auto control = f.app.model.session().positions(J);
  std::vector<double> limit(control.size()), normals(control.size());
  eval_limit(st, control.data(), limit.data());
  limit_normals(st, h.levels[std::size_t(J)].faces, control.data(), limit.data(), normals.data());
  const auto shown = f.app.model.limit_positions();
  const auto shown_normals = f.app.model.limit_normals();
  ASSERT_EQ(shown.size(), limit.size());
  for (std::size_t i = 0; i < limit.size(); ++i) {
    EXPECT_NEAR(shown[i], limit[i], 1e-12) << i;
    EXPECT_NEAR(shown_normals[i], normals[i], 1e-12) << i;
  }
}

}  // namespace sublift::testing
