// core/picking: projection against GLM, the pick index against brute force, view-plane moves.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "core/edit/picking.h"

namespace sublift {
namespace {

constexpr int kW = 640, kH = 480;

PickView perspective_view(const glm::dvec3& eye = {3.0, 2.0, 4.0}, const glm::dvec3& target = {0.0, 0.0, 0.0}) {
  const glm::dmat4 view = glm::lookAt(eye, target, glm::dvec3(0, 1, 0));
  const glm::dmat4 proj = glm::perspective(0.8, static_cast<double>(kW) / kH, 0.5, 20.0);
  return {proj * view, kW, kH};
}

// World (x, y) is the screen pixel (x right, y down); larger z is nearer (NDC z = -z / 10).
PickView pixel_view() {
  return {glm::ortho(0.0, double(kW), double(kH), 0.0, -10.0, 10.0), kW, kH};
}

std::vector<double> flatten(const std::vector<glm::dvec3>& points) {
  std::vector<double> xyz;
  for (const glm::dvec3& p : points) xyz.insert(xyz.end(), {p.x, p.y, p.z});
  return xyz;
}

TEST(ProjectPointTest, MatchesGlmProject) {
  const glm::dvec3 eye(3.0, 2.0, 4.0);
  const glm::dmat4 view = glm::lookAt(eye, glm::dvec3(0.0), glm::dvec3(0, 1, 0));
  const glm::dmat4 proj = glm::perspective(0.8, static_cast<double>(kW) / kH, 0.5, 20.0);
  const PickView v{proj * view, kW, kH};
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  for (int i = 0; i < 200; ++i) {
    const glm::dvec3 p(u(rng), u(rng), u(rng));
    glm::dvec2 s;
    double depth = 0.0;
    ASSERT_TRUE(project_point(v, p, s, depth));
    const glm::dvec3 win = glm::project(p, view, proj, glm::dvec4(0, 0, kW, kH));
    EXPECT_NEAR(s.x, win.x, 1e-9);
    EXPECT_NEAR(s.y, kH - win.y, 1e-9);  // top-left origin
    EXPECT_NEAR(depth, 2.0 * win.z - 1.0, 1e-12);
    const glm::dvec3 back = unproject_point(v, s.x, s.y, depth);
    EXPECT_NEAR(glm::distance(back, p), 0.0, 1e-9);
  }
}

TEST(ProjectPointTest, RejectsPointsBehindTheCameraOrOutside) {
  const PickView v = perspective_view();
  glm::dvec2 s;
  double depth = 0.0;
  EXPECT_FALSE(project_point(v, {6.0, 4.0, 8.0}, s, depth));    // behind the eye
  EXPECT_FALSE(project_point(v, {30.0, 0.0, -30.0}, s, depth));  // beside the frustum
  EXPECT_FALSE(project_point(v, {-30.0, -20.0, -40.0}, s, depth));  // beyond the far plane
  EXPECT_TRUE(project_point(v, {0.0, 0.0, 0.0}, s, depth));
  EXPECT_NEAR(s.x, kW / 2.0, 1e-9);
  EXPECT_NEAR(s.y, kH / 2.0, 1e-9);
}

TEST(PickIndexTest, NearestWithinTheRadiusAndTiesByDepth) {
  // Mouse at (100, 100): a at 5 px, b and c at 3 px (c nearer the eye), d at 3 px but masked out.
  const std::vector<glm::dvec3> pts = {
      {105, 100, 0}, {100, 103, -1}, {97, 100, 1}, {100, 97, 5}, {300, 300, 0}};
  const std::vector<std::uint8_t> visible = {1, 1, 1, 0, 1};
  PickIndex index;
  index.build(pixel_view(), flatten(pts), visible);
  EXPECT_EQ(index.size(), 4u);
  for (const bool xray : {false, true}) {
    EXPECT_EQ(index.nearest(100, 100, 10, xray), 2) << "tie at 3 px: the nearer one";
    EXPECT_EQ(index.nearest(100, 100, 2.9, xray), -1);
    EXPECT_EQ(index.nearest(104, 100, 1.0, xray), 0);
    EXPECT_EQ(index.nearest(110.1, 100, 5.0, xray), -1);
    EXPECT_EQ(index.nearest(110, 100, 5.0, xray), 0) << "the radius is inclusive";
    EXPECT_EQ(index.nearest(300, 300, 0.0, xray), 4);
    EXPECT_EQ(index.nearest(-50, -50, 20, xray), -1);
  }
  // A tie at equal depth goes to the smaller index.
  PickIndex tie;
  tie.build(pixel_view(), flatten({{10, 10, 0}, {12, 10, 0}, {8, 10, 0}}));
  EXPECT_EQ(tie.nearest(10, 10, 5, true), 0);
  EXPECT_EQ(tie.nearest(10.5, 10, 5, true), 0);
  EXPECT_EQ(tie.nearest(11, 10, 5, true), 0);  // 1 px from points 0 and 1: the smaller index
}

TEST(PickIndexTest, FrontMostClusterUnlessXray) {
  // p0 1 px from the mouse but 9 units behind p1, which is 3 px away; the radius 4 px is 4 world
  // units here, so without x-ray only the front point counts.
  const std::vector<glm::dvec3> pts = {{101, 100, -4}, {103, 100, 5}, {100, 102, 2}};
  PickIndex index;
  index.build(pixel_view(), flatten(pts));
  EXPECT_EQ(index.nearest(100, 100, 4, true), 0);
  EXPECT_EQ(index.nearest(100, 100, 4, false), 2) << "p2 is within 4 units of the front";
  EXPECT_EQ(index.nearest(100, 100, 2.5, false), 2) << "p2 the front; p0 6 units behind it";
  EXPECT_EQ(index.nearest(100, 100, 1.5, false), 0) << "alone in reach";
}

TEST(PickIndexTest, OcclusionDepthHidesPointsBehindTheSurface) {
  // A "surface" at window depth 0.5 (world z = 0) over the left half of the viewport.
  std::vector<float> depth(static_cast<std::size_t>(kW) * kH, 1.0f);
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW / 2; ++x) depth[static_cast<std::size_t>(y) * kW + x] = 0.5f;
  }
  const std::vector<glm::dvec3> pts = {{100, 100, -1}, {100, 110, 1}, {500, 100, -1}, {100, 120, 0}};
  PickIndex index;
  const OcclusionDepth occlusion{depth};
  index.build(pixel_view(), flatten(pts), {}, &occlusion);
  EXPECT_EQ(index.hidden_count(), 1u);
  EXPECT_EQ(index.nearest(100, 100, 3, false), -1) << "behind the surface";
  EXPECT_EQ(index.nearest(100, 100, 3, true), 0) << "x-ray sees it";
  EXPECT_EQ(index.nearest(500, 100, 3, false), 2) << "nothing in front there";
  EXPECT_EQ(index.nearest(100, 120, 3, false), 3) << "on the surface counts as visible";
  EXPECT_EQ(index.in_rect(0, 0, kW, kH, false), (std::vector<std::uint32_t>{1, 2, 3}));
  EXPECT_EQ(index.in_rect(0, 0, kW, kH, true), (std::vector<std::uint32_t>{0, 1, 2, 3}));
}

TEST(PickIndexTest, InRectMatchesBruteForce) {
  const PickView v = perspective_view();
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  std::vector<double> xyz(3 * 5000);
  for (double& c : xyz) c = u(rng);
  PickIndex index;
  index.build(v, xyz);
  const double x0 = 400, y0 = 300, x1 = 150.5, y1 = 90.25;  // corners in any order
  std::vector<std::uint32_t> expected;
  for (std::uint32_t i = 0; i < 5000; ++i) {
    glm::dvec2 s;
    double depth = 0.0;
    if (!project_point(v, {xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]}, s, depth)) continue;
    const float fx = static_cast<float>(s.x), fy = static_cast<float>(s.y);  // the index's precision
    if (fx >= x1 && fx <= x0 && fy >= y1 && fy <= y0) expected.push_back(i);
  }
  EXPECT_GT(expected.size(), 100u);
  EXPECT_EQ(index.in_rect(x0, y0, x1, y1, true), expected);
  EXPECT_EQ(index.in_rect(x0, y0, x1, y1, false), expected) << "no occlusion given";
}

TEST(PickIndexTest, NearestMatchesBruteForceOnRandomPoints) {
  const PickView v = perspective_view();
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  const std::uint32_t n = 20000;
  std::vector<double> xyz(3 * n);
  for (double& c : xyz) c = u(rng);
  std::vector<glm::dvec3> screen(n);  // x, y, visible
  for (std::uint32_t i = 0; i < n; ++i) {
    glm::dvec2 s;
    double depth = 0.0;
    const bool in = project_point(v, {xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]}, s, depth);
    screen[i] = {s.x, s.y, in ? 1.0 : 0.0};
  }
  PickIndex index;
  index.build(v, xyz);
  std::uniform_real_distribution<double> mx(-10, kW + 10), my(-10, kH + 10);
  int found = 0;
  for (int q = 0; q < 500; ++q) {
    const double x = mx(rng), y = my(rng), r = 6.0;
    double best = 1e300;
    for (std::uint32_t i = 0; i < n; ++i) {
      if (screen[i].z == 0.0) continue;
      const double d2 = std::pow(float(screen[i].x) - x, 2) + std::pow(float(screen[i].y) - y, 2);
      if (d2 <= r * r) best = std::min(best, d2);
    }
    const std::int64_t got = index.nearest(x, y, r, true);
    if (best == 1e300) {
      EXPECT_EQ(got, -1);
      continue;
    }
    ++found;
    ASSERT_GE(got, 0);
    const double d2 = std::pow(float(screen[got].x) - x, 2) + std::pow(float(screen[got].y) - y, 2);
    EXPECT_NEAR(d2, best, 1e-6);
    const std::int64_t front = index.nearest(x, y, r, false);
    ASSERT_GE(front, 0);
    EXPECT_LE(std::hypot(screen[front].x - x, screen[front].y - y), r + 1e-3);
  }
  EXPECT_GT(found, 100);
}

TEST(ViewPlaneDeltaTest, MovesTheProjectionByExactlyThePixelOffset) {
  const PickView persp = perspective_view({6.0, 4.0, 8.0}, {1.0, 0.5, -2.0});
  const PickView ortho{glm::ortho(-4.0, 4.0, -3.0, 3.0, 0.1, 100.0) *
                           glm::lookAt(glm::dvec3(5, 6, 7), glm::dvec3(0.0), glm::dvec3(0, 1, 0)),
                       kW, kH};
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-2.0, 2.0), d(-80.0, 80.0);
  for (const PickView& v : {persp, ortho}) {
    const glm::dvec3 forward = glm::normalize(unproject_point(v, kW / 2.0, kH / 2.0, 1.0) -
                                              unproject_point(v, kW / 2.0, kH / 2.0, -1.0));
    for (int i = 0; i < 100; ++i) {
      const glm::dvec3 anchor(u(rng), u(rng), u(rng));
      const double dx = d(rng), dy = d(rng);
      glm::dvec2 s0, s1;
      double z0 = 0.0, z1 = 0.0;
      ASSERT_TRUE(project_point(v, anchor, s0, z0));
      const glm::dvec3 delta = view_plane_delta(v, anchor, dx, dy);
      project_point(v, anchor + delta, s1, z1);
      EXPECT_NEAR(s1.x, s0.x + dx, 1e-6);
      EXPECT_NEAR(s1.y, s0.y + dy, 1e-6);
      EXPECT_NEAR(glm::dot(delta, forward), 0.0, 1e-9) << "stays in the view plane";
    }
  }
  EXPECT_EQ(view_plane_delta(persp, {60.0, 40.0, 80.0}, 5, 5), glm::dvec3(0.0)) << "behind the eye";
}

TEST(PixelRayTest, PointsOnTheRayProjectToThePixel) {
  const PickView v = perspective_view();
  glm::dvec3 origin, dir;
  pixel_ray(v, 123.25, 321.5, origin, dir);
  EXPECT_NEAR(glm::length(dir), 1.0, 1e-12);
  for (const double t : {0.0, 1.0, 5.0, 10.0}) {
    glm::dvec2 s;
    double depth = 0.0;
    project_point(v, origin + t * dir, s, depth);
    EXPECT_NEAR(s.x, 123.25, 1e-6);
    EXPECT_NEAR(s.y, 321.5, 1e-6);
  }
  glm::dvec2 s;
  double depth = 0.0;
  project_point(v, origin, s, depth);
  EXPECT_NEAR(depth, -1.0, 1e-9) << "the origin is on the near plane";
  glm::dvec2 s_far;
  project_point(v, origin + 1.0 * dir, s_far, depth);
  EXPECT_GT(depth, -1.0) << "the direction points away from the eye";
}

TEST(PickIndexTest, TimingOnTwoMillionPoints) {
  const std::uint32_t n = 2'000'000;
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  std::vector<double> xyz(3 * static_cast<std::size_t>(n));
  for (double& c : xyz) c = u(rng);
  const PickView v{perspective_view().view_proj, 1920, 1080};
  PickIndex index;
  const auto t0 = std::chrono::steady_clock::now();
  index.build(v, xyz);
  const auto t1 = std::chrono::steady_clock::now();
  std::int64_t sum = 0;
  std::uniform_real_distribution<double> mx(0, 1920), my(0, 1080);
  for (int q = 0; q < 1000; ++q) sum += index.nearest(mx(rng), my(rng), 8.0, q % 2 == 0);
  const auto t2 = std::chrono::steady_clock::now();
  const std::size_t rect = index.in_rect(500, 300, 900, 700, true).size();
  const auto t3 = std::chrono::steady_clock::now();
  const auto ms = [](auto a, auto b) { return std::chrono::duration<double, std::milli>(b - a).count(); };
  std::printf("[timing] 2M points: build %.1f ms, nearest %.4f ms/query (r = 8 px), "
              "in_rect 400x400 %.1f ms (%zu points); %zu indexed\n",
              ms(t0, t1), ms(t1, t2) / 1000.0, ms(t2, t3), rect, index.size());
  EXPECT_GT(index.size(), n / 2);
  EXPECT_NE(sum, 0);
}

}  // namespace
}  // namespace sublift
