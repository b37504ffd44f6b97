// render/net_renderer and render/limit_surface_renderer: headless renders of a bumped quad grid
// and a control net over it, checked where core/picking says the points project. PNGs of every
// case are written to the build folder (SUBLIFT_TEST_PNG_DIR) to look at.
#include <gtest/gtest.h>

#include <epoxy/gl.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "core/base/errors.h"
#include "core/edit/picking.h"
#include "render/camera.h"
#include "render/headless_context.h"
#include "render/limit_surface_renderer.h"
#include "render/net_renderer.h"
#include "render/offscreen_target.h"
#include "render/shader_program.h"
#include "render/viewport_renderer.h"

namespace sublift {
namespace {

constexpr int kW = 400, kH = 300;
const glm::vec3 kBackground{0.86f, 0.88f, 0.92f};

// ---- fixtures: a bump z = f(x, y) over [-1, 1]^2 and a 5x5 control net above it ----

double bump(double x, double y) { return 0.15 * std::exp(-3.0 * (x * x + y * y)); }

glm::dvec3 bump_normal(double x, double y) {
  const double fx = -6.0 * x * bump(x, y), fy = -6.0 * y * bump(x, y);
  return glm::normalize(glm::dvec3(-fx, -fy, 1.0));
}

struct Grid {
  int n = 0;  // quads per side
  std::vector<double> xyz, normals;
  std::vector<std::uint32_t> offsets{0}, corners;
  std::uint32_t id(int i, int j) const { return static_cast<std::uint32_t>(j * (n + 1) + i); }
  glm::dvec3 position(std::uint32_t v) const { return {xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]}; }
};

Grid make_surface(int n) {
  Grid g;
  g.n = n;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const double x = -1.0 + 2.0 * i / n, y = -1.0 + 2.0 * j / n;
      const glm::dvec3 nrm = bump_normal(x, y);
      g.xyz.insert(g.xyz.end(), {x, y, bump(x, y)});
      g.normals.insert(g.normals.end(), {nrm.x, nrm.y, nrm.z});
    }
  }
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      g.corners.insert(g.corners.end(), {g.id(i, j), g.id(i + 1, j), g.id(i + 1, j + 1), g.id(i, j + 1)});
      g.offsets.push_back(static_cast<std::uint32_t>(g.corners.size()));
    }
  }
  return g;
}

struct Net {
  int n = 4;
  std::vector<double> xyz;
  std::vector<std::uint32_t> edges;
  std::vector<std::uint8_t> edge_feature, vertex_feature;
  std::uint32_t id(int i, int j) const { return static_cast<std::uint32_t>(j * (n + 1) + i); }
  glm::dvec3 position(std::uint32_t v) const { return {xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]}; }
};

// 5x5 points 0.15 in front of the bump, except (0.5, -0.5), which sits 0.3 behind it. Boundary
// vertices and edges are creases, the four corners corners.
Net make_net() {
  Net net;
  const int n = net.n;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const double x = -1.0 + 2.0 * i / n, y = -1.0 + 2.0 * j / n;
      const double z = (i == 3 && j == 1) ? bump(x, y) - 0.3 : bump(x, y) + 0.15;
      net.xyz.insert(net.xyz.end(), {x, y, z});
      const bool bi = i == 0 || i == n, bj = j == 0 || j == n;
      net.vertex_feature.push_back(bi && bj ? 2 : (bi || bj ? 1 : 0));
    }
  }
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      if (i < n) {
        net.edges.insert(net.edges.end(), {net.id(i, j), net.id(i + 1, j)});
        net.edge_feature.push_back(j == 0 || j == n ? 1 : 0);
      }
      if (j < n) {
        net.edges.insert(net.edges.end(), {net.id(i, j), net.id(i, j + 1)});
        net.edge_feature.push_back(i == 0 || i == n ? 1 : 0);
      }
    }
  }
  return net;
}

// ---- image helpers ----

struct Rgb {
  int r, g, b;
};

struct Picture {
  std::vector<std::uint8_t> rgba;
  Rgb at(int x, int y) const {
    x = std::clamp(x, 0, kW - 1);
    y = std::clamp(y, 0, kH - 1);
    const std::size_t i = (static_cast<std::size_t>(y) * kW + x) * 4;
    return {rgba[i], rgba[i + 1], rgba[i + 2]};
  }
  Rgb at(const glm::dvec2& p) const { return at(static_cast<int>(p.x), static_cast<int>(p.y)); }
};

int difference(const Rgb& a, const Rgb& b) {
  return std::max({std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b)});
}

Rgb to_rgb(const glm::vec3& c) {
  return {static_cast<int>(std::lround(c.r * 255)), static_cast<int>(std::lround(c.g * 255)),
          static_cast<int>(std::lround(c.b * 255))};
}

std::string describe(const Rgb& c) {
  return "(" + std::to_string(c.r) + ", " + std::to_string(c.g) + ", " + std::to_string(c.b) + ")";
}

// For failure messages: where near `p` the colour closest to `want` is.
std::string closest_offset(const Picture& img, const glm::dvec2& p, const Rgb& want) {
  int best = 1 << 30, bx = 0, by = 0;
  for (int dy = -8; dy <= 8; ++dy) {
    for (int dx = -8; dx <= 8; ++dx) {
      const int d = difference(img.at(static_cast<int>(p.x) + dx, static_cast<int>(p.y) + dy), want);
      if (d < best) best = d, bx = dx, by = dy;
    }
  }
  return "; closest colour (difference " + std::to_string(best) + ") at offset (" + std::to_string(bx) + ", " +
         std::to_string(by) + ") from " + std::to_string(p.x) + ", " + std::to_string(p.y);
}

void save(const Picture& p, const std::string& name) {
  std::filesystem::create_directories(SUBLIFT_TEST_PNG_DIR);
  write_png(std::string(SUBLIFT_TEST_PNG_DIR) + "/" + name + ".png", kW, kH, p.rgba);
}

// ---- the scene ----

class ModelerRenderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    surface_grid_ = make_surface(16);
    net_ = make_net();
    target_ = std::make_unique<OffscreenTarget>(kW, kH, 4);
    surface_ = std::make_unique<LimitSurfaceRenderer>();
    surface_->set_topology(surface_grid_.offsets, surface_grid_.corners, surface_grid_.xyz.size() / 3);
    surface_->set_positions_normals(surface_grid_.xyz, surface_grid_.normals);
    net_renderer_ = std::make_unique<NetRenderer>();
    net_renderer_->set_topology(net_.edges, net_.edge_feature, net_.vertex_feature, net_.xyz.size() / 3);
    net_renderer_->set_positions(net_.xyz);
    camera_.set_viewport(kW, kH);
    camera_.yaw = 0.35;
    camera_.pitch = 0.45;
    Bounds b = surface_->bounds();
    b.min = glm::min(b.min, net_renderer_->bounds().min);
    b.max = glm::max(b.max, net_renderer_->bounds().max);
    camera_.frame(b.min, b.max);
    view_ = {camera_.projection() * camera_.view(), kW, kH};
  }

  Picture draw(const SurfaceStyle* surface_style, const NetStyle* net_style,
               const NetRenderer* net = nullptr, const LimitSurfaceRenderer* surface = nullptr) {
    target_->bind();
    clear_framebuffer(kW, kH, kBackground);
    if (surface_style != nullptr) (surface ? surface : surface_.get())->draw(camera_, *surface_style);
    if (net_style != nullptr) (net ? net : net_renderer_.get())->draw(camera_, *net_style);
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
    return {target_->read_rgba()};
  }

  glm::dvec2 screen(const glm::dvec3& p) const {
    glm::dvec2 s;
    double depth = 0.0;
    EXPECT_TRUE(project_point(view_, p, s, depth));
    return s;
  }

  HeadlessContext context_;
  Grid surface_grid_;
  Net net_;
  std::unique_ptr<OffscreenTarget> target_;
  std::unique_ptr<LimitSurfaceRenderer> surface_;
  std::unique_ptr<NetRenderer> net_renderer_;
  OrbitCamera camera_;
  PickView view_;
};

TEST_F(ModelerRenderTest, NetPointsShowStateAndFeatureColours) {
  const std::uint32_t selected = net_.id(1, 1), hover = net_.id(2, 3), soft = net_.id(2, 2);
  const std::uint32_t ordinary = net_.id(3, 2), crease = net_.id(0, 2), corner = net_.id(4, 4);
  std::vector<std::uint8_t> state(net_.xyz.size() / 3, 0);
  std::vector<float> weight(state.size(), 0.0f);
  state[selected] = 2;
  state[hover] = 1;
  weight[soft] = 1.0f;
  weight[selected] = 1.0f;
  net_renderer_->set_state(state, weight);
  const SurfaceStyle surface_style;
  const NetStyle style;
  const Picture img = draw(&surface_style, &style);
  save(img, "net_states");

  const NetColors& k = style.colors;
  struct Expect {
    std::uint32_t v;
    glm::vec3 color;
    const char* what;
  };
  for (const Expect& e : {Expect{selected, k.selected, "selected"}, Expect{hover, k.hover, "hover"},
                          Expect{soft, k.soft, "soft weight 1"}, Expect{ordinary, k.point, "ordinary"},
                          Expect{crease, k.crease, "crease"}, Expect{corner, k.corner, "corner"}}) {
    const glm::dvec2 at = screen(net_.position(e.v));
    const Rgb got = img.at(at);
    EXPECT_LE(difference(got, to_rgb(e.color)), 40)
        << e.what << " point is " << describe(got) << closest_offset(img, at, to_rgb(e.color));
  }
}

TEST_F(ModelerRenderTest, XrayShowsNetPointsBehindTheSurface) {
  const std::uint32_t hidden = net_.id(3, 1);
  std::vector<std::uint8_t> state(net_.xyz.size() / 3, 0);
  state[hidden] = 2;
  net_renderer_->set_state(state, {});
  const SurfaceStyle surface_style;
  NetStyle style;
  const Picture plain = draw(&surface_style, &style);
  style.xray = true;
  const Picture xray = draw(&surface_style, &style);
  const Picture surface_only = draw(&surface_style, nullptr);
  save(plain, "net_hidden_point");
  save(xray, "net_xray");

  const glm::dvec2 s = screen(net_.position(hidden));
  const Rgb clay = surface_only.at(s), p = plain.at(s), x = xray.at(s);
  EXPECT_LE(difference(p, clay), 12) << "hidden without x-ray: " << describe(p) << " vs " << describe(clay);
  EXPECT_GE(difference(x, clay), 40) << "x-ray shows it: " << describe(x);
  EXPECT_LT(x.b, clay.b - 30) << "tinted towards the orange selection colour";
  // A point in front of the surface looks the same either way.
  const glm::dvec2 front = screen(net_.position(net_.id(1, 3)));
  EXPECT_LE(difference(plain.at(front), xray.at(front)), 12);

  // Picking agrees when given the surface's depth buffer: hidden unless x-ray.
  OffscreenTarget single(kW, kH, 0);
  single.bind();
  clear_framebuffer(kW, kH, kBackground);
  surface_->draw(camera_, surface_style);
  std::vector<float> depth(static_cast<std::size_t>(kW) * kH);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, kW, kH, GL_DEPTH_COMPONENT, GL_FLOAT, depth.data());
  ASSERT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  PickIndex index;
  const OcclusionDepth occlusion{depth};
  index.build(view_, net_.xyz, {}, &occlusion);
  EXPECT_EQ(index.hidden_count(), 1u);
  EXPECT_EQ(index.nearest(s.x, s.y, 6, true), hidden);
  EXPECT_NE(index.nearest(s.x, s.y, 6, false), static_cast<std::int64_t>(hidden));
  EXPECT_EQ(index.nearest(front.x + 2, front.y - 1, 6, false), net_.id(1, 3));
}

TEST_F(ModelerRenderTest, ClipPlaneRemovesTheClippedHalf) {
  SurfaceStyle surface_style;
  surface_style.clip = true;
  surface_style.clip_plane = {1, 0, 0, 0};  // keeps x >= 0
  NetStyle style;
  style.clip = true;
  style.clip_plane = surface_style.clip_plane;
  std::vector<std::uint8_t> state(net_.xyz.size() / 3, 2);  // everything selected: easy to see
  net_renderer_->set_state(state, {});
  const Picture img = draw(&surface_style, &style);
  const Picture full = draw(&surface_style, nullptr);
  save(img, "clip_x_positive");
  const Rgb bg = to_rgb(kBackground);
  for (const double y : {-0.35, 0.15, 0.65}) {
    const glm::dvec3 left(-0.6, y, bump(-0.6, y)), right(0.6, y, bump(0.6, y));
    EXPECT_LE(difference(img.at(screen(left)), bg), 6) << "clipped surface at y = " << y;
    EXPECT_GE(difference(img.at(screen(right)), bg), 40) << "kept surface at y = " << y;
    EXPECT_LE(difference(full.at(screen(right)), img.at(screen(right))), 6);
  }
  for (int j = 0; j <= net_.n; ++j) {
    const glm::dvec2 gone = screen(net_.position(net_.id(1, j)));   // x = -0.5
    const glm::dvec2 kept = screen(net_.position(net_.id(3, j)));   // x = 0.5
    EXPECT_GT(difference(img.at(gone), to_rgb(style.colors.selected)), 60) << "clipped point, row " << j;
    if (j != 1) {  // (0.5, -0.5) is behind the surface
      EXPECT_LE(difference(img.at(kept), to_rgb(style.colors.selected)), 40) << "kept point, row " << j;
    }
  }
}

// Pixels that differ between a and b, and their bounding box.
struct Changed {
  long count = 0;
  int min_x = kW, min_y = kH, max_x = -1, max_y = -1;
};
Changed changed_pixels(const Picture& a, const Picture& b) {
  Changed c;
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      if (difference(a.at(x, y), b.at(x, y)) > 0) {
        ++c.count;
        c.min_x = std::min(c.min_x, x);
        c.max_x = std::max(c.max_x, x);
        c.min_y = std::min(c.min_y, y);
        c.max_y = std::max(c.max_y, y);
      }
    }
  }
  return c;
}

void expect_inside(const Changed& c, const std::vector<glm::dvec2>& region, double margin) {
  double x0 = 1e9, y0 = 1e9, x1 = -1e9, y1 = -1e9;
  for (const glm::dvec2& p : region) {
    x0 = std::min(x0, p.x), y0 = std::min(y0, p.y), x1 = std::max(x1, p.x), y1 = std::max(y1, p.y);
  }
  EXPECT_GE(c.min_x, x0 - margin);
  EXPECT_GE(c.min_y, y0 - margin);
  EXPECT_LE(c.max_x, x1 + margin);
  EXPECT_LE(c.max_y, y1 + margin);
}

TEST_F(ModelerRenderTest, UpdatingOneNetVertexChangesPixelsOnlyNearIt) {
  const NetStyle style;
  const Picture before = draw(nullptr, &style);
  const std::uint32_t v = net_.id(2, 2);
  const glm::dvec3 old_p = net_.position(v);
  std::vector<double> moved = net_.xyz;
  moved[3 * v] += 0.2;
  moved[3 * v + 1] += 0.1;
  const std::uint32_t changed[] = {v};
  net_renderer_->update_positions(moved, changed);
  const Picture after = draw(nullptr, &style);
  save(before, "net_update_before");
  save(after, "net_update_after");

  const Changed c = changed_pixels(before, after);
  EXPECT_GT(c.count, 30);
  // The point and its four edges move: all changes within the box of the old and new point and
  // its neighbours (plus the point radius).
  std::vector<glm::dvec2> region = {screen(old_p), screen(old_p + glm::dvec3(0.2, 0.1, 0.0))};
  for (const std::uint32_t u : {net_.id(1, 2), net_.id(3, 2), net_.id(2, 1), net_.id(2, 3)}) {
    region.push_back(screen(net_.position(u)));
  }
  expect_inside(c, region, 6.0);

  // The same as uploading everything (the bounds, so the centre, did not change).
  NetRenderer fresh;
  fresh.set_topology(net_.edges, net_.edge_feature, net_.vertex_feature, net_.xyz.size() / 3);
  fresh.set_positions(moved);
  const Picture reference = draw(nullptr, &style, &fresh);
  EXPECT_EQ(changed_pixels(after, reference).count, 0);
}

TEST_F(ModelerRenderTest, UpdatingOneSurfaceVertexChangesPixelsOnlyNearItsFaces) {
  SurfaceStyle style;
  style.wireframe = true;
  const Picture before = draw(&style, nullptr);
  const int i = 12, j = 12;  // (0.5, 0.5)
  const std::uint32_t v = surface_grid_.id(i, j);
  std::vector<double> xyz = surface_grid_.xyz, normals = surface_grid_.normals;
  xyz[3 * v + 2] += 0.25;
  normals[3 * v] = 0.6;  // tilt its normal too
  const std::uint32_t changed[] = {v};
  surface_->update(xyz, normals, changed);
  const Picture after = draw(&style, nullptr);
  save(after, "surface_update");
  const Changed c = changed_pixels(before, after);
  EXPECT_GT(c.count, 50);
  std::vector<glm::dvec2> region;
  for (int dj = -1; dj <= 1; ++dj) {
    for (int di = -1; di <= 1; ++di) region.push_back(screen(surface_grid_.position(surface_grid_.id(i + di, j + dj))));
  }
  region.push_back(screen(surface_grid_.position(v) + glm::dvec3(0.0, 0.0, 0.25)));
  expect_inside(c, region, 2.0);

  LimitSurfaceRenderer fresh;
  fresh.set_topology(surface_grid_.offsets, surface_grid_.corners, surface_grid_.xyz.size() / 3);
  fresh.set_positions_normals(xyz, normals);
  // The fresh one is centred on the grown bounds: sub-pixel differences at most.
  const Changed vs_fresh = changed_pixels(after, draw(&style, nullptr, nullptr, &fresh));
  EXPECT_LT(vs_fresh.count, 40);
}

TEST_F(ModelerRenderTest, ColourMapFlatShadingAndDepthCue) {
  std::vector<float> value(surface_grid_.xyz.size() / 3);
  for (std::size_t v = 0; v < value.size(); ++v) value[v] = static_cast<float>(0.5 * (surface_grid_.xyz[3 * v] + 1.0));
  surface_->set_scalar(value);
  SurfaceStyle style;
  const Picture clay = draw(&style, nullptr);
  style.color_map = true;
  const Picture mapped = draw(&style, nullptr);
  style.smooth = false;
  style.wireframe = true;
  const Picture flat = draw(&style, nullptr);
  save(clay, "surface_clay");
  save(mapped, "surface_viridis");
  save(flat, "surface_viridis_flat_wire");

  const Rgb low = mapped.at(screen({-0.85, 0.1, bump(-0.85, 0.1)}));
  const Rgb high = mapped.at(screen({0.85, 0.1, bump(0.85, 0.1)}));
  EXPECT_GT(low.b, low.g) << "viridis starts dark purple: " << describe(low);
  EXPECT_LT(low.r + low.g + low.b, 330) << describe(low);
  EXPECT_GT(high.r, 150) << "and ends yellow: " << describe(high);
  EXPECT_GT(high.g, 150) << describe(high);
  EXPECT_LT(high.b, 110) << describe(high);
  const glm::dvec2 middle = screen({0.0, 0.1, bump(0.0, 0.1)});
  EXPECT_GT(difference(clay.at(middle), mapped.at(middle)), 40);
  // Flat shading: faces differ from the smooth rendering somewhere on the bump.
  EXPECT_GT(changed_pixels(mapped, flat).count, 1000);

  // Depth cue on a 4x4x4 lattice: the farthest corner is lighter (fogged) than the nearest.
  Net lattice;
  lattice.n = 3;
  lattice.xyz.clear();
  for (int k = 0; k < 4; ++k) {
    for (int j = 0; j < 4; ++j) {
      for (int i = 0; i < 4; ++i) lattice.xyz.insert(lattice.xyz.end(), {-0.9 + 0.6 * i, -0.9 + 0.6 * j, -0.9 + 0.6 * k});
    }
  }
  const auto lid = [](int i, int j, int k) { return static_cast<std::uint32_t>(16 * k + 4 * j + i); };
  for (int k = 0; k < 4; ++k) {
    for (int j = 0; j < 4; ++j) {
      for (int i = 0; i < 4; ++i) {
        if (i < 3) lattice.edges.insert(lattice.edges.end(), {lid(i, j, k), lid(i + 1, j, k)});
        if (j < 3) lattice.edges.insert(lattice.edges.end(), {lid(i, j, k), lid(i, j + 1, k)});
        if (k < 3) lattice.edges.insert(lattice.edges.end(), {lid(i, j, k), lid(i, j, k + 1)});
      }
    }
  }
  NetRenderer cube;
  cube.set_topology(lattice.edges, {}, {}, 64);
  cube.set_positions(lattice.xyz);
  NetStyle cue;
  cue.depth_cue = true;
  cue.point_size = 8;
  const Picture cued = draw(nullptr, &cue, &cube);
  cue.depth_cue = false;
  const Picture uncued = draw(nullptr, &cue, &cube);
  save(cued, "lattice_depth_cue");
  save(uncued, "lattice_plain");
  // The eye looks from +z (yaw 0.35, pitch 0.45): (0.9, 0.9, 0.9) is nearest, (-0.9, -0.9, -0.9) farthest.
  const Rgb near_point = cued.at(screen({0.9, 0.9, 0.9})), far_point = cued.at(screen({-0.9, -0.9, -0.9}));
  EXPECT_LE(difference(near_point, uncued.at(screen({0.9, 0.9, 0.9}))), 30) << "the front is hardly fogged";
  EXPECT_GT(far_point.r, near_point.r + 60) << describe(far_point) << " vs " << describe(near_point);
}

TEST_F(ModelerRenderTest, TopologyCountsAndErrors) {
  // A quad, a triangle and a pentagon: 2 + 1 + 3 triangles, 4 + 3 + 5 - 2 shared edges.
  const std::vector<std::uint32_t> offsets = {0, 4, 7, 12};
  const std::vector<std::uint32_t> corners = {0, 1, 2, 3, 1, 4, 2, 4, 5, 6, 7, 2};
  LimitSurfaceRenderer r;
  r.set_topology(offsets, corners, 8);
  EXPECT_EQ(r.num_triangles(), 6u);
  EXPECT_EQ(r.num_edges(), 10u);
  const std::vector<std::uint32_t> bad = {0, 1, 2, 9};
  const std::vector<std::uint32_t> bad_offsets = {0, 4};
  EXPECT_THROW(r.set_topology(bad_offsets, bad, 8), TopologyError);
  EXPECT_THROW(r.set_topology(offsets, bad, 8), TopologyError);
  const std::vector<double> three(9, 0.0);
  EXPECT_THROW(r.set_positions_normals(three, three), Error);

  NetRenderer net;
  const std::vector<std::uint32_t> edges = {0, 1, 1, 5};
  EXPECT_THROW(net.set_topology(edges, {}, {}, 5), TopologyError);
  EXPECT_NO_THROW(net.set_topology(edges, {}, {}, 6));
  EXPECT_NO_THROW(ShaderProgram("net.vert", "net.frag"));
  EXPECT_NO_THROW(ShaderProgram("limit.vert", "limit.frag"));
}

TEST(UploadRangesTest, MergesNearbyIndicesAndCapsTheRangeCount) {
  using Ranges = std::vector<std::pair<std::uint32_t, std::uint32_t>>;
  const std::vector<std::uint32_t> a = {10, 3, 4, 5, 200, 11, 4};
  EXPECT_EQ(upload_ranges(a, 0, 64), (Ranges{{3, 6}, {10, 12}, {200, 201}}));
  EXPECT_EQ(upload_ranges(a, 4, 64), (Ranges{{3, 12}, {200, 201}}));
  EXPECT_EQ(upload_ranges(a, 0, 2), (Ranges{{3, 12}, {200, 201}})) << "the largest gap splits";
  EXPECT_EQ(upload_ranges(a, 0, 1), (Ranges{{3, 201}}));
  EXPECT_TRUE(upload_ranges({}, 0, 4).empty());
  // Many scattered indices: at most max_ranges ranges, covering all of them.
  std::vector<std::uint32_t> many;
  for (std::uint32_t i = 0; i < 5000; ++i) many.push_back((i * 7919u) % 100000u);
  const Ranges r = upload_ranges(many, 8, 16);
  EXPECT_LE(r.size(), 16u);
  for (const std::uint32_t v : many) {
    EXPECT_TRUE(std::any_of(r.begin(), r.end(), [v](const auto& x) { return x.first <= v && v < x.second; }));
  }
}

}  // namespace
}  // namespace sublift
