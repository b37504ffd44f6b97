// render/: triangulation and edge lists without GL, then real headless renders checked against
// what the camera math predicts. Headless GL is a requirement here: if EGL is missing the tests
// fail (the exception fails them), they never skip.
#include <gtest/gtest.h>

#include <stb_image.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <numbers>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <unistd.h>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "core/base/errors.h"
#include "core/base/surface_mesh.h"
#include "render/camera.h"
#include "render/headless_context.h"
#include "render/headless_render.h"
#include "render/mesh_buffers.h"
#include "render/offscreen_target.h"
#include "render/render_errors.h"
#include "render/shader_program.h"

namespace sublift {
namespace {

// ---- fixtures ----

SurfaceMesh make_mesh(std::vector<glm::dvec3> positions,
                      const std::vector<std::vector<std::uint32_t>>& faces) {
  SurfaceMesh mesh;
  mesh.positions = std::move(positions);
  for (const auto& f : faces) mesh.add_face(f);
  return mesh;
}

// Axis-aligned cube [-h,h]^3 + offset, quads oriented outwards.
SurfaceMesh make_cube(double h = 1.0, glm::dvec3 offset = glm::dvec3(0.0)) {
  std::vector<glm::dvec3> p;
  for (int i = 0; i < 8; ++i) {
    p.push_back(offset + glm::dvec3(i & 4 ? h : -h, i & 2 ? h : -h, i & 1 ? h : -h));
  }
  // index = 4*(x>0) + 2*(y>0) + (z>0)
  return make_mesh(p, {{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1},
                       {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}});
}

SurfaceMesh make_front_quad() {
  return make_mesh({{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}}, {{0, 1, 2, 3}});
}

// ---- image helpers ----

struct Rgb {
  int r, g, b;
};

Rgb pixel(const Image& img, int x, int y) {
  const std::size_t i = (static_cast<std::size_t>(y) * img.width + x) * 4;
  return {img.rgba[i], img.rgba[i + 1], img.rgba[i + 2]};
}

int luminance(const Rgb& c) { return (299 * c.r + 587 * c.g + 114 * c.b) / 1000; }

int difference(const Rgb& a, const Rgb& b) {
  return std::max({std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b)});
}

struct Coverage {
  long pixels = 0;
  int min_x = 1 << 30, min_y = 1 << 30, max_x = -1, max_y = -1;
};

// Pixels where `img` differs from the bare background `bg`.
Coverage covered(const Image& img, const Image& bg, int threshold = 12) {
  Coverage c;
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      if (difference(pixel(img, x, y), pixel(bg, x, y)) > threshold) {
        ++c.pixels;
        c.min_x = std::min(c.min_x, x);
        c.max_x = std::max(c.max_x, x);
        c.min_y = std::min(c.min_y, y);
        c.max_y = std::max(c.max_y, y);
      }
    }
  }
  return c;
}

// Projects a world point to image pixels (x right, y down) with the renderer's camera.
glm::dvec2 project(const OrbitCamera& camera, const glm::dvec3& p) {
  const glm::dvec4 c = camera.projection() * camera.view() * glm::dvec4(p, 1.0);
  return {(c.x / c.w + 1.0) * 0.5 * camera.viewport_width,
          (1.0 - c.y / c.w) * 0.5 * camera.viewport_height};
}

double cross2(const glm::dvec2& o, const glm::dvec2& a, const glm::dvec2& b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

// Area of the convex hull (monotone chain), i.e. a convex solid's silhouette area.
double hull_area(std::vector<glm::dvec2> pts) {
  std::sort(pts.begin(), pts.end(),
            [](const glm::dvec2& a, const glm::dvec2& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  std::vector<glm::dvec2> hull(2 * pts.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    while (k >= 2 && cross2(hull[k - 2], hull[k - 1], pts[i]) <= 0) --k;
    hull[k++] = pts[i];
  }
  for (std::size_t i = pts.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross2(hull[k - 2], hull[k - 1], pts[i]) <= 0) --k;
    hull[k++] = pts[i];
  }
  hull.resize(k - 1);
  double area = 0.0;
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const glm::dvec2& a = hull[i];
    const glm::dvec2& b = hull[(i + 1) % hull.size()];
    area += a.x * b.y - b.x * a.y;
  }
  return std::abs(area) / 2.0;
}

const Image& background_image(int w, int h) {
  static std::vector<Image> cache;
  for (const Image& img : cache) {
    if (img.width == w && img.height == h) return img;
  }
  cache.push_back(render_mesh_headless(SurfaceMesh{}, w, h));
  return cache.back();
}

// ---- mesh buffers (no GL) ----

TEST(MeshBuffersTest, FanTrianglesAndUniqueEdgesWithoutDiagonals) {
  // A quad, a triangle and a pentagon sharing edges.
  const SurfaceMesh mesh = make_mesh(
      {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}, {2, 1, 0}, {3, 2, 0}, {1.5, 2, 0}},
      {{0, 1, 2, 3}, {1, 4, 2}, {4, 5, 6, 7, 2}});
  const MeshBuffers b = build_mesh_buffers(mesh);
  EXPECT_EQ(b.corners.size(), 12u);
  EXPECT_EQ(b.triangles.size(), 3u * (2 + 1 + 3));

  std::set<std::pair<std::uint32_t, std::uint32_t>> expected;
  for (std::size_t f = 0; f < mesh.num_faces(); ++f) {
    const auto c = mesh.face(f);
    for (std::size_t i = 0; i < c.size(); ++i) {
      const std::uint32_t a = c[i], d = c[(i + 1) % c.size()];
      expected.emplace(std::min(a, d), std::max(a, d));
    }
  }
  std::set<std::pair<std::uint32_t, std::uint32_t>> got;
  ASSERT_EQ(b.edges.size() % 2, 0u);
  for (std::size_t i = 0; i < b.edges.size(); i += 2) got.emplace(b.edges[i], b.edges[i + 1]);
  EXPECT_EQ(got.size(), b.edges.size() / 2) << "an edge is listed twice";
  EXPECT_EQ(got, expected);
  EXPECT_EQ(got.count({0, 2}), 0u) << "the quad's fan diagonal must not be a wireframe edge";
}

TEST(MeshBuffersTest, NewellNormalOfConcaveAndTiltedPolygons) {
  // L-shaped (concave) hexagon in z = 0, counter-clockwise: normal +Z, length 2 * area (3).
  const SurfaceMesh l_shape = make_mesh(
      {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}}, {{0, 1, 2, 3, 4, 5}});
  const glm::dvec3 n = newell_normal(l_shape, l_shape.face(0));
  EXPECT_NEAR(n.x, 0.0, 1e-12);
  EXPECT_NEAR(n.y, 0.0, 1e-12);
  EXPECT_NEAR(n.z, 6.0, 1e-12);

  // The same square in the plane x + y + z = const, far from the origin.
  const glm::dvec3 o(1e6, -2e6, 3e6);
  const glm::dvec3 u = glm::normalize(glm::dvec3(1, -1, 0));
  const glm::dvec3 v = glm::normalize(glm::dvec3(1, 1, -2));
  const SurfaceMesh tilted = make_mesh({o, o + u, o + u + v, o + v}, {{0, 1, 2, 3}});
  const glm::dvec3 t = glm::normalize(newell_normal(tilted, tilted.face(0)));
  const glm::dvec3 expected = glm::normalize(glm::cross(u, v));
  EXPECT_NEAR(glm::dot(t, expected), 1.0, 1e-9);

  const MeshBuffers b = build_mesh_buffers(tilted);
  for (const CornerVertex& c : b.corners) {
    EXPECT_NEAR(glm::dot(glm::dvec3(c.normal), expected), 1.0, 1e-6);
  }
}

TEST(MeshBuffersTest, PositionsAreRelativeToTheBoundsCentre) {
  const SurfaceMesh cube = make_cube(0.5, glm::dvec3(1e7, -3e7, 5e6));
  const MeshBuffers b = build_mesh_buffers(cube);
  EXPECT_EQ(b.center, glm::dvec3(1e7, -3e7, 5e6));
  for (const glm::vec3& p : b.vertex_positions) {
    EXPECT_FLOAT_EQ(std::abs(p.x), 0.5f);
    EXPECT_FLOAT_EQ(std::abs(p.y), 0.5f);
    EXPECT_FLOAT_EQ(std::abs(p.z), 0.5f);
  }
}

TEST(MeshBuffersTest, PolylineSegmentsFollowThePolylines) {
  SurfaceMesh mesh = make_front_quad();
  mesh.positions.push_back({2, 0, 0});
  mesh.positions.push_back({3, 1, 5});
  const std::vector<std::uint32_t> open = {1, 4, 5};
  const std::vector<std::uint32_t> closed = {0, 3, 5, 0};
  mesh.add_polyline(open);
  mesh.add_polyline(closed);
  const MeshBuffers b = build_mesh_buffers(mesh);
  EXPECT_EQ(b.polyline_segments,
            (std::vector<std::uint32_t>{1, 4, 4, 5, 0, 3, 3, 5, 5, 0}));
  EXPECT_EQ(b.edges.size(), 8u) << "polylines are not polygon edges";
  const Bounds bounds = drawn_bounds(mesh);
  EXPECT_EQ(bounds.max, glm::dvec3(3, 1, 5)) << "polyline vertices are drawn, so framed";
}

TEST(MeshBuffersTest, BoundsIgnoreIsolatedVertices) {
  SurfaceMesh mesh = make_front_quad();
  mesh.positions.push_back({100.0, 100.0, 100.0});  // used by no face
  const Bounds bounds = drawn_bounds(mesh);
  EXPECT_FALSE(bounds.empty);
  EXPECT_EQ(bounds.max, glm::dvec3(1.0, 1.0, 0.0));
  EXPECT_TRUE(drawn_bounds(SurfaceMesh{}).empty);
}

// ---- headless rendering ----

TEST(HeadlessRenderTest, EglSurfacelessContextIsAvailable) {
  HeadlessContext context;  // throws (and so fails) when EGL/Mesa is missing
  EXPECT_FALSE(context.renderer().empty());
}

TEST(HeadlessRenderTest, RejectsBadSizes) {
  const SurfaceMesh cube = make_cube();
  EXPECT_THROW(render_mesh_headless(cube, 0, 10), RenderError);
  EXPECT_THROW(render_mesh_headless(cube, 10, -1), RenderError);
  EXPECT_THROW(render_mesh_headless(cube, 100000, 10), RenderError);
}

TEST(HeadlessRenderTest, ImageIsNotBlankAndShowsTheBackgroundGradient) {
  const Image img = render_mesh_headless(make_cube(), 160, 120);
  ASSERT_EQ(img.width, 160);
  ASSERT_EQ(img.height, 120);
  ASSERT_EQ(img.rgba.size(), 160u * 120u * 4u);
  std::set<std::uint32_t> colours;
  for (std::size_t i = 0; i < img.rgba.size(); i += 4) {
    EXPECT_EQ(img.rgba[i + 3], 255);
    colours.insert(img.rgba[i] << 16 | img.rgba[i + 1] << 8 | img.rgba[i + 2]);
  }
  EXPECT_GT(colours.size(), 20u);
  // Light grey-blue gradient: lighter at the top, blue the strongest channel.
  const Rgb top = pixel(img, 2, 2), bottom = pixel(img, 2, 117);
  EXPECT_GT(luminance(top), luminance(bottom) + 20);
  EXPECT_GE(top.b, top.r);
  EXPECT_GT(luminance(bottom), 110);
}

TEST(HeadlessRenderTest, FrontQuadCoversExactlyItsProjectedSquare) {
  const int w = 320, h = 240;
  HeadlessRenderSettings settings;
  settings.view = ViewPreset::Front;
  settings.orthographic = true;
  const SurfaceMesh quad = make_front_quad();
  const Image img = render_mesh_headless(quad, w, h, settings);
  const OrbitCamera camera = headless_camera(quad, w, h, settings);
  const glm::dvec2 lo = project(camera, {-1, 1, 0});  // top-left on screen
  const glm::dvec2 hi = project(camera, {1, -1, 0});
  const double predicted = (hi.x - lo.x) * (hi.y - lo.y);
  ASSERT_GT(predicted, 0.25 * w * h) << "framing should make the quad large";

  const Coverage c = covered(img, background_image(w, h));
  EXPECT_NEAR(static_cast<double>(c.pixels), predicted, 0.02 * predicted);
  EXPECT_NEAR(c.min_x, lo.x, 1.5);
  EXPECT_NEAR(c.max_x + 1, hi.x, 1.5);
  EXPECT_NEAR(c.min_y, lo.y, 1.5);
  EXPECT_NEAR(c.max_y + 1, hi.y, 1.5);

  // Clay-coloured inside (warm: red > green > blue), and facing the light: not dark.
  const Rgb centre = pixel(img, w / 2, h / 2);
  EXPECT_GT(centre.r, centre.g);
  EXPECT_GT(centre.g, centre.b);
  EXPECT_GT(centre.r - centre.b, 25);
  EXPECT_GT(luminance(centre), 110);
}

TEST(HeadlessRenderTest, WireframeDrawsDarkLinesAlongThePolygonEdges) {
  // A 2x2 grid of quads seen head-on: its 12 edges are lines, its fan diagonals are not.
  const int w = 301, h = 221;
  HeadlessRenderSettings settings;
  settings.view = ViewPreset::Front;
  settings.orthographic = true;
  std::vector<glm::dvec3> grid;
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 3; ++i) grid.emplace_back(i - 1.0, j - 1.0, 0.0);
  }
  const SurfaceMesh quads =
      make_mesh(grid, {{0, 1, 4, 3}, {1, 2, 5, 4}, {3, 4, 7, 6}, {4, 5, 8, 7}});
  const OrbitCamera camera = headless_camera(quads, w, h, settings);
  const Image wire = render_mesh_headless(quads, w, h, settings);
  settings.display.wireframe = false;
  const Image plain = render_mesh_headless(quads, w, h, settings);

  // "Dark" is well below the shaded clay; a line only half covering a pixel still counts.
  const int clay = luminance(pixel(plain, w / 2 + 20, h / 2 + 20));
  auto is_dark = [clay](const Rgb& c) { return luminance(c) < clay - 40; };
  long dark_wire = 0, dark_plain = 0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      dark_wire += is_dark(pixel(wire, x, y));
      dark_plain += is_dark(pixel(plain, x, y));
    }
  }
  EXPECT_EQ(dark_plain, 0);
  const glm::dvec2 lo = project(camera, {-1, 1, 0});
  const glm::dvec2 hi = project(camera, {1, -1, 0});
  const double line_length = 3.0 * ((hi.x - lo.x) + (hi.y - lo.y));
  EXPECT_GT(static_cast<double>(dark_wire), 0.8 * line_length);

  auto dark_near = [&](glm::dvec2 p) {
    for (int dy = -2; dy <= 1; ++dy) {
      for (int dx = -2; dx <= 1; ++dx) {
        const int x = std::clamp(static_cast<int>(p.x) + dx, 0, w - 1);
        const int y = std::clamp(static_cast<int>(p.y) + dy, 0, h - 1);
        if (is_dark(pixel(wire, x, y))) return true;
      }
    }
    return false;
  };
  for (const glm::dvec3& edge_midpoint :
       {glm::dvec3(-0.5, 1, 0), glm::dvec3(0.5, -1, 0), glm::dvec3(-1, 0.5, 0),
        glm::dvec3(1, -0.5, 0), glm::dvec3(0, 0.5, 0), glm::dvec3(0, -0.5, 0),
        glm::dvec3(0.5, 0, 0), glm::dvec3(-0.5, 0, 0)}) {
    EXPECT_TRUE(dark_near(project(camera, edge_midpoint)))
        << "no line at " << edge_midpoint.x << "," << edge_midpoint.y;
  }
  // Quad centres lie on both possible fan diagonals: never drawn.
  for (const glm::dvec3& centre : {glm::dvec3(-0.5, -0.5, 0), glm::dvec3(0.5, -0.5, 0),
                                   glm::dvec3(-0.5, 0.5, 0), glm::dvec3(0.5, 0.5, 0)}) {
    EXPECT_FALSE(dark_near(project(camera, centre)))
        << "diagonal drawn at " << centre.x << "," << centre.y;
  }
}

TEST(HeadlessRenderTest, CubeSilhouetteMatchesTheDefaultCamera) {
  const int w = 320, h = 240;
  const SurfaceMesh cube = make_cube();
  const Image img = render_mesh_headless(cube, w, h);
  const OrbitCamera camera = headless_camera(cube, w, h);

  std::vector<glm::dvec2> projected;
  glm::dvec2 lo(1e9), hi(-1e9);
  for (const glm::dvec3& p : cube.positions) {
    projected.push_back(project(camera, p));
    lo = glm::min(lo, projected.back());
    hi = glm::max(hi, projected.back());
  }
  const double predicted = hull_area(projected);
  const Coverage c = covered(img, background_image(w, h));
  EXPECT_NEAR(static_cast<double>(c.pixels), predicted, 0.03 * predicted);
  EXPECT_NEAR(c.min_x, lo.x, 2.0);
  EXPECT_NEAR(c.max_x + 1, hi.x, 2.0);
  EXPECT_NEAR(c.min_y, lo.y, 2.0);
  EXPECT_NEAR(c.max_y + 1, hi.y, 2.0);
  // The whole cube is inside the image with some margin (the camera framed it).
  EXPECT_GT(c.min_x, 2);
  EXPECT_GT(c.min_y, 2);
  EXPECT_LT(c.max_x, w - 3);
  EXPECT_LT(c.max_y, h - 3);
}

TEST(HeadlessRenderTest, FlatShadingGivesTheThreeVisibleFacesDistinctClayTones) {
  const int w = 320, h = 240;
  const SurfaceMesh cube = make_cube();
  HeadlessRenderSettings settings;
  settings.display.wireframe = false;
  const Image img = render_mesh_headless(cube, w, h, settings);
  const OrbitCamera camera = headless_camera(cube, w, h, settings);
  // The default 3/4 view sees the +X, +Y and +Z faces.
  const std::array<glm::dvec3, 3> centres = {glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0),
                                             glm::dvec3(0, 0, 1)};
  std::array<Rgb, 3> tones{};
  for (int i = 0; i < 3; ++i) {
    const glm::dvec2 p = project(camera, centres[i]);
    tones[i] = pixel(img, static_cast<int>(p.x), static_cast<int>(p.y));
    EXPECT_GT(tones[i].r, tones[i].b) << "face " << i << " is not clay-coloured";
    // Flat: the face's colour is the same a few pixels away from its centre.
    const Rgb beside = pixel(img, static_cast<int>(p.x) + 3, static_cast<int>(p.y) + 2);
    EXPECT_LE(difference(tones[i], beside), 3);
  }
  EXPECT_GT(difference(tones[0], tones[1]), 10);
  EXPECT_GT(difference(tones[1], tones[2]), 10);
  EXPECT_GT(difference(tones[0], tones[2]), 10);
  // Lit from above: the top face is the brightest.
  EXPECT_GT(luminance(tones[1]), luminance(tones[0]));
  EXPECT_GT(luminance(tones[1]), luminance(tones[2]));
}

TEST(HeadlessRenderTest, FarFromTheOriginRendersLikeAtTheOrigin) {
  // Single-precision world coordinates near 1e7 are a unit apart; centring keeps the cube exact.
  const int w = 200, h = 150;
  const Image here = render_mesh_headless(make_cube(1.0), w, h);
  const Image far = render_mesh_headless(make_cube(1.0, glm::dvec3(1e7, -1e7, 1e7)), w, h);
  long differing = 0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) differing += difference(pixel(here, x, y), pixel(far, x, y)) > 24;
  }
  EXPECT_LT(differing, w * h / 200);
}

TEST(HeadlessRenderTest, BackFacesAreShadedToo) {
  // Seen from behind, the quad still shows (two-sided lighting), in the cooler back tint.
  const int w = 160, h = 120;
  HeadlessRenderSettings settings;
  settings.view = ViewPreset::Back;
  settings.display.wireframe = false;
  const Image img = render_mesh_headless(make_front_quad(), w, h, settings);
  const Coverage c = covered(img, background_image(w, h));
  EXPECT_GT(c.pixels, w * h / 4);
  const Rgb centre = pixel(img, w / 2, h / 2);
  EXPECT_GT(centre.b, centre.r);
}

TEST(HeadlessRenderTest, PolylinesAreDrawnWithoutFacesOrWireframe) {
  // A closed zigzag curve, no faces: drawn as solid blue lines and framed like a surface.
  const int w = 241, h = 181;
  SurfaceMesh curve;
  std::vector<std::uint32_t> loop;
  for (int i = 0; i < 12; ++i) {
    const double a = 2.0 * std::numbers::pi * i / 12.0;
    const double r = i % 2 == 0 ? 1.0 : 0.6;
    curve.positions.emplace_back(r * std::cos(a), r * std::sin(a), 0.0);
    loop.push_back(static_cast<std::uint32_t>(i));
  }
  loop.push_back(0);
  curve.add_polyline(loop);
  HeadlessRenderSettings settings;
  settings.view = ViewPreset::Front;
  settings.display.wireframe = false;
  const Image img = render_mesh_headless(curve, w, h, settings);
  const OrbitCamera camera = headless_camera(curve, w, h, settings);

  const Coverage c = covered(img, background_image(w, h));
  EXPECT_GT(c.pixels, 300);
  EXPECT_NEAR(c.min_x, project(camera, {-1, 0, 0}).x, 2.0);
  EXPECT_NEAR(c.max_x + 1, project(camera, {1, 0, 0}).x, 2.0);
  // Midway along the first segment the line is blue, far darker than the background.
  const glm::dvec2 mid = 0.5 * (project(camera, curve.positions[0]) +
                                project(camera, curve.positions[1]));
  bool blue = false;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      const Rgb p = pixel(img, static_cast<int>(mid.x) + dx, static_cast<int>(mid.y) + dy);
      blue = blue || (p.b > p.r + 30 && luminance(p) < 110);
    }
  }
  EXPECT_TRUE(blue);
}

TEST(ShaderProgramTest, AllEmbeddedShadersCompileAndUnknownOnesFailByName) {
  HeadlessContext context;
  EXPECT_NO_THROW(ShaderProgram("mesh.vert", "mesh.frag"));
  EXPECT_NO_THROW(ShaderProgram("lines.vert", "lines.frag"));
  EXPECT_NO_THROW(ShaderProgram("background.vert", "background.frag"));
  try {
    ShaderProgram program("no_such_shader.vert", "mesh.frag");
    FAIL() << "expected ShaderError";
  } catch (const ShaderError& e) {
    EXPECT_NE(std::string(e.what()).find("no_such_shader.vert"), std::string::npos) << e.what();
  }
}

// ---- PNG output ----

TEST(WritePngTest, RoundTripsThroughStbImageAndLeavesNoTemporaryFile) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("sublift_png_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "out.png").string();
  const int w = 7, h = 5;
  std::vector<std::uint8_t> rgba(w * h * 4);
  for (std::size_t i = 0; i < rgba.size(); ++i) rgba[i] = static_cast<std::uint8_t>(i * 37 + 11);
  write_png(path, w, h, rgba);
  write_png(path, w, h, rgba);  // replacing an existing file works too

  int rw = 0, rh = 0, channels = 0;
  stbi_uc* data = stbi_load(path.c_str(), &rw, &rh, &channels, 4);
  ASSERT_NE(data, nullptr);
  EXPECT_EQ(rw, w);
  EXPECT_EQ(rh, h);
  EXPECT_TRUE(std::equal(rgba.begin(), rgba.end(), data));
  stbi_image_free(data);

  int files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 1);
  std::filesystem::remove_all(dir);
}

TEST(WritePngTest, FailuresAreIoErrorsNamingTheFile) {
  const std::vector<std::uint8_t> rgba(4 * 4 * 4, 0);
  try {
    write_png("/nonexistent-dir/x.png", 4, 4, rgba);
    FAIL() << "expected IoError";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-dir/x.png"), std::string::npos);
  }
  EXPECT_THROW(write_png("/tmp/never.png", 5, 4, rgba), IoError);  // size mismatch
}

}  // namespace
}  // namespace sublift
