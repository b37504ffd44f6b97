// OrbitCamera: framing, orbit, pan, zoom and view presets as properties of the matrices.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include "render/camera.h"

namespace sublift {
namespace {

constexpr double kEps = 1e-9;

std::array<glm::dvec3, 8> corners(const glm::dvec3& lo, const glm::dvec3& hi) {
  std::array<glm::dvec3, 8> out;
  for (int i = 0; i < 8; ++i) {
    out[i] = {i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z};
  }
  return out;
}

glm::dvec4 clip(const OrbitCamera& camera, const glm::dvec3& p) {
  return camera.projection() * camera.view() * glm::dvec4(p, 1.0);
}

bool inside_frustum(const OrbitCamera& camera, const glm::dvec3& p) {
  const glm::dvec4 c = clip(camera, p);
  return c.w > 0.0 && std::abs(c.x) <= c.w && std::abs(c.y) <= c.w && std::abs(c.z) <= c.w;
}

void expect_near(const glm::dvec3& a, const glm::dvec3& b, double eps = kEps) {
  EXPECT_NEAR(a.x, b.x, eps);
  EXPECT_NEAR(a.y, b.y, eps);
  EXPECT_NEAR(a.z, b.z, eps);
}

TEST(CameraTest, BasisIsOrthonormalAndRightHanded) {
  OrbitCamera camera;
  for (const UpAxis axis : {UpAxis::Y, UpAxis::Z}) {
    for (double yaw : {-2.5, -0.3, 0.0, 0.7, 3.0}) {
      for (double pitch : {-std::numbers::pi / 2, -0.4, 0.0, 1.1, std::numbers::pi / 2}) {
        camera.up_axis = axis;
        camera.yaw = yaw;
        camera.pitch = pitch;
        const glm::dvec3 r = camera.right(), u = camera.up(), f = camera.forward();
        EXPECT_NEAR(glm::length(r), 1.0, kEps);
        EXPECT_NEAR(glm::length(u), 1.0, kEps);
        EXPECT_NEAR(glm::length(f), 1.0, kEps);
        EXPECT_NEAR(glm::dot(r, u), 0.0, kEps);
        EXPECT_NEAR(glm::dot(r, f), 0.0, kEps);
        // Looking down -Z of the eye frame: right x up = backward.
        expect_near(glm::cross(r, u), -f);
      }
    }
  }
}

TEST(CameraTest, ViewMatrixMapsEyeToOriginAndTargetDownMinusZ) {
  OrbitCamera camera;
  camera.target = {1.0, -2.0, 3.0};
  camera.distance = 7.0;
  const glm::dvec4 eye = camera.view() * glm::dvec4(camera.eye(), 1.0);
  const glm::dvec4 target = camera.view() * glm::dvec4(camera.target, 1.0);
  expect_near(glm::dvec3(eye), glm::dvec3(0.0));
  expect_near(glm::dvec3(target), glm::dvec3(0.0, 0.0, -7.0));
}

TEST(CameraTest, FramingPutsEveryBoxCornerInsideTheFrustum) {
  const std::array<std::pair<glm::dvec3, glm::dvec3>, 4> boxes = {{
      {{-1, -1, -1}, {1, 1, 1}},
      {{0, 0, 0}, {10, 0.1, 0.1}},           // a long thin bar
      {{-3, 5, 100}, {-2, 9, 100.5}},        // off the origin
      {{1e5, 1e5, 1e5}, {1e5 + 2, 1e5 + 1, 1e5 + 3}},
  }};
  const std::array<ViewPreset, 7> views = {ViewPreset::ThreeQuarter, ViewPreset::Front,
                                           ViewPreset::Back,         ViewPreset::Right,
                                           ViewPreset::Left,         ViewPreset::Top,
                                           ViewPreset::Bottom};
  for (const auto& [lo, hi] : boxes) {
    for (const ViewPreset view : views) {
      for (const auto& [w, h] : {std::pair{800, 600}, {300, 900}, {1000, 200}}) {
        for (const bool ortho : {false, true}) {
          OrbitCamera camera;
          camera.up_axis = ortho ? UpAxis::Z : UpAxis::Y;  // both axes, without another loop
          camera.set_viewport(w, h);
          camera.set_view(view);
          camera.orthographic = ortho;
          camera.frame(lo, hi);
          expect_near(camera.target, 0.5 * (lo + hi), 1e-9 * (1.0 + glm::length(lo)));
          for (const glm::dvec3& p : corners(lo, hi)) {
            EXPECT_TRUE(inside_frustum(camera, p))
                << "corner " << p.x << "," << p.y << "," << p.z << " view "
                << static_cast<int>(view) << " size " << w << "x" << h << " ortho " << ortho;
          }
        }
      }
    }
  }
}

TEST(CameraTest, FramingFillsTheViewRatherThanShrinkingTheModel) {
  // A cube seen from the front: its front face should span most of the viewport height.
  OrbitCamera camera;
  camera.set_viewport(800, 800);
  camera.set_view(ViewPreset::Front);
  camera.frame(glm::dvec3(-1.0), glm::dvec3(1.0));
  const glm::dvec4 top = clip(camera, {0.0, 1.0, 1.0});
  EXPECT_GT(top.y / top.w, 0.7);
  EXPECT_LT(top.y / top.w, 1.0);
}

TEST(CameraTest, DegenerateBoxStillGivesAUsableCamera) {
  OrbitCamera camera;
  camera.set_viewport(640, 480);
  camera.frame(glm::dvec3(2.0), glm::dvec3(2.0));
  EXPECT_GT(camera.distance, 0.0);
  EXPECT_TRUE(std::isfinite(camera.distance));
  EXPECT_TRUE(inside_frustum(camera, glm::dvec3(2.0)));
}

TEST(CameraTest, OrbitKeepsTargetAndDistance) {
  OrbitCamera camera;
  camera.target = {0.5, 1.5, -2.0};
  camera.distance = 4.0;
  for (const auto& [dx, dy] : {std::pair{30.0, 0.0}, {0.0, -45.0}, {-120.0, 80.0}, {500.0, 500.0}}) {
    camera.orbit(dx, dy);
    EXPECT_NEAR(glm::length(camera.eye() - camera.target), 4.0, kEps);
    expect_near(camera.target, {0.5, 1.5, -2.0});
  }
}

TEST(CameraTest, OrbitDirectionsFollowTheTurntableConvention) {
  OrbitCamera camera;
  camera.set_view(ViewPreset::Front);
  camera.orbit(50.0, 0.0);  // drag right: the eye swings to the model's left (-X)
  EXPECT_LT(camera.eye().x, 0.0);
  camera.set_view(ViewPreset::Front);
  camera.orbit(0.0, 50.0);  // drag down: the eye rises, the top comes into view
  EXPECT_GT(camera.eye().y, 0.0);
}

TEST(CameraTest, PitchIsClampedAtThePoles) {
  OrbitCamera camera;
  camera.orbit(0.0, 1e6);
  EXPECT_NEAR(camera.pitch, std::numbers::pi / 2, kEps);
  camera.orbit(0.0, -1e6);
  EXPECT_NEAR(camera.pitch, -std::numbers::pi / 2, kEps);
}

TEST(CameraTest, PanMovesTargetPerpendicularToTheViewDirection) {
  OrbitCamera camera;
  camera.set_viewport(800, 600);
  camera.target = {1.0, 2.0, 3.0};
  camera.distance = 10.0;
  const glm::dvec3 forward = camera.forward();
  const glm::dvec3 before = camera.target;
  camera.pan(40.0, -25.0);
  const glm::dvec3 moved = camera.target - before;
  EXPECT_GT(glm::length(moved), 0.0);
  EXPECT_NEAR(glm::dot(moved, forward), 0.0, kEps);
  EXPECT_NEAR(camera.distance, 10.0, kEps);
  expect_near(camera.forward(), forward);
}

TEST(CameraTest, PanKeepsThePointUnderTheCursorUnderTheCursor) {
  // A point at the target's depth must move on screen by exactly the drag, in pixels.
  for (const bool ortho : {false, true}) {
    OrbitCamera camera;
    camera.set_viewport(800, 600);
    camera.orthographic = ortho;
    camera.frame(glm::dvec3(-1.0), glm::dvec3(1.0));
    const glm::dvec3 anchor = camera.target;
    auto to_pixels = [&camera](const glm::dvec3& p) {
      const glm::dvec4 c = clip(camera, p);
      return glm::dvec2((c.x / c.w + 1.0) * 400.0, (1.0 - c.y / c.w) * 300.0);  // y down
    };
    const glm::dvec2 before = to_pixels(anchor);
    camera.pan(37.0, -21.0);
    const glm::dvec2 after = to_pixels(anchor);
    EXPECT_NEAR(after.x - before.x, 37.0, 1e-6);
    EXPECT_NEAR(after.y - before.y, -21.0, 1e-6);
  }
}

TEST(CameraTest, ZoomScalesDistanceAndInverts) {
  OrbitCamera camera;
  camera.distance = 8.0;
  camera.zoom(1.0);
  EXPECT_LT(camera.distance, 8.0);
  camera.zoom(-1.0);
  EXPECT_NEAR(camera.distance, 8.0, 1e-12);
  camera.zoom(-3.0);
  EXPECT_GT(camera.distance, 8.0);
  const glm::dvec3 target = camera.target;
  camera.zoom(2.5);
  expect_near(camera.target, target);
}

TEST(CameraTest, PresetViewsLookAlongTheAxes) {
  OrbitCamera camera;
  struct Case {
    ViewPreset view;
    glm::dvec3 forward, up;
  };
  const Case cases[] = {
      {ViewPreset::Front, {0, 0, -1}, {0, 1, 0}}, {ViewPreset::Back, {0, 0, 1}, {0, 1, 0}},
      {ViewPreset::Right, {-1, 0, 0}, {0, 1, 0}}, {ViewPreset::Left, {1, 0, 0}, {0, 1, 0}},
      {ViewPreset::Top, {0, -1, 0}, {0, 0, -1}},  {ViewPreset::Bottom, {0, 1, 0}, {0, 0, 1}},
  };
  for (const Case& c : cases) {
    camera.set_view(c.view);
    expect_near(camera.forward(), c.forward);
    expect_near(camera.up(), c.up);
  }
}

TEST(CameraTest, ZUpPresetsMatchBlender) {
  // Blender: numpad 1 looks along +Y, 3 along -X, 7 down -Z with +Y up on screen; Z is up.
  OrbitCamera camera;
  camera.up_axis = UpAxis::Z;
  struct Case {
    ViewPreset view;
    glm::dvec3 forward, up;
  };
  const Case cases[] = {
      {ViewPreset::Front, {0, 1, 0}, {0, 0, 1}},  {ViewPreset::Back, {0, -1, 0}, {0, 0, 1}},
      {ViewPreset::Right, {-1, 0, 0}, {0, 0, 1}}, {ViewPreset::Left, {1, 0, 0}, {0, 0, 1}},
      {ViewPreset::Top, {0, 0, -1}, {0, 1, 0}},   {ViewPreset::Bottom, {0, 0, 1}, {0, -1, 0}},
  };
  for (const Case& c : cases) {
    camera.set_view(c.view);
    expect_near(camera.forward(), c.forward);
    expect_near(camera.up(), c.up);
    expect_near(camera.right(), glm::cross(c.forward, c.up));
  }
  expect_near(camera.world_up(), {0, 0, 1});
}

TEST(CameraTest, OrbitingTurnsAboutTheWorldUpAxis) {
  // Horizontal drags keep the eye's height along the up axis (turntable), for both axes.
  for (const UpAxis axis : {UpAxis::Y, UpAxis::Z}) {
    OrbitCamera camera;
    camera.up_axis = axis;
    camera.target = {0.3, -0.2, 0.5};
    const double height = glm::dot(camera.eye() - camera.target, camera.world_up());
    camera.orbit(123.0, 0.0);
    EXPECT_NEAR(glm::dot(camera.eye() - camera.target, camera.world_up()), height, kEps);
    EXPECT_NEAR(glm::dot(camera.right(), camera.world_up()), 0.0, kEps);
  }
}

TEST(CameraTest, OrthographicScaleMatchesPerspectiveAtTheTarget) {
  // Toggling the projection keeps the model's size at the target depth.
  OrbitCamera camera;
  camera.set_viewport(640, 480);
  camera.frame(glm::dvec3(-1.0), glm::dvec3(1.0));
  const glm::dvec3 p = camera.target + 0.8 * camera.up();
  const glm::dvec4 persp = clip(camera, p);
  camera.orthographic = true;
  const glm::dvec4 ortho = clip(camera, p);
  EXPECT_NEAR(persp.y / persp.w, ortho.y / ortho.w, 1e-9);
}

}  // namespace
}  // namespace sublift
