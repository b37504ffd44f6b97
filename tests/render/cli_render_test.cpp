// sublift-cli render on every kind of input (issue 19, CLI parity): a mesh, a lattice (its
// outward boundary) and a project (its finest limit surface with the saved gains). Each PNG is
// decoded and must show the shape: enough pixels away from the background's colour, and a
// project with gain 0 on its detail renders differently from the same project with gain 1.
#include <gtest/gtest.h>

#include <stb_image.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "core/complex/complex_build.h"
#include "core/complex/shapes.h"
#include "core/io/project/project_io.h"
#include "core/multires/hierarchy.h"
#include "tests/cli_run.h"
#include "tests/io_test_util.h"
#include "tests/test_shapes.h"
#include "tests/test_util.h"

namespace sublift {
namespace {

struct Png {
  int w = 0, h = 0;
  std::vector<unsigned char> rgba;
};

Png load(const std::string& path) {
  Png p;
  int n = 0;
  unsigned char* data = stbi_load(path.c_str(), &p.w, &p.h, &n, 4);
  if (!data) return p;
  p.rgba.assign(data, data + std::size_t(p.w) * p.h * 4);
  stbi_image_free(data);
  return p;
}

// Fraction of pixels that differ from the first pixel of their row (the background gradient is
// vertical, and the framed shape never reaches the left edge).
double shape_fraction(const Png& p) {
  std::size_t shape = 0;
  for (int y = 0; y < p.h; ++y)
    for (int x = 0; x < p.w; ++x) {
      const unsigned char* q = &p.rgba[(std::size_t(y) * p.w + x) * 4];
      const unsigned char* b = &p.rgba[std::size_t(y) * p.w * 4];
      if (std::abs(q[0] - b[0]) + std::abs(q[1] - b[1]) + std::abs(q[2] - b[2]) > 24) ++shape;
    }
  return double(shape) / (double(p.w) * p.h);
}

TEST(CliRender, MeshLatticeAndProject) {
  testing::TempDir dir("sublift_cli_render");
  const Hierarchy h = [] {
    const SurfaceMesh m = make_quad_torus(10, 6);
    Hierarchy t = make_hierarchy(complex_from_surface_mesh(m), 2, Scheme::Cubic, 3);
    set_base(t, flatten_positions(m));
    std::vector<double> fine = synthesize(t, 2);
    for (std::size_t i = 0; i < fine.size(); i += 7) fine[i] += 0.15;  // visible bumps
    analyze(t, fine);
    return t;
  }();
  ProjectExtras muted;
  muted.gains = {0.0, 0.0};
  write_project(dir.file("t.sublift"), h);
  write_project(dir.file("muted.sublift"), h, muted);
  const std::string assets = SUBLIFT_ASSETS_DIR;
  std::vector<std::vector<unsigned char>> images;
  for (const std::string& in : {assets + "/cube.obj", assets + "/hex_block_4.lattice", assets + "/prism_ring.lattice",
                                dir.file("t.sublift"), dir.file("muted.sublift")}) {
    SCOPED_TRACE(in);
    const std::string png = dir.file("r.png");
    std::filesystem::remove(png);
    const testing::ProcessResult r = testing::run_cli({"render", in, "-o", png, "--size", "160x120"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const Png p = load(png);
    ASSERT_EQ(p.w, 160);
    ASSERT_EQ(p.h, 120);
    EXPECT_GT(shape_fraction(p), 0.05);
    images.push_back(p.rgba);
  }
  EXPECT_NE(images[3], images[4]);  // the gains are honoured
}

// --colour L: a project's surface through viridis by the magnitude of level L's wavelets. Viridis
// is saturated (blue-purple to yellow-green) where clay and the grey background are not, and
// detail on one half only colours that half.
TEST(CliRender, ColourByWaveletMagnitude) {
  testing::TempDir dir("sublift_cli_render_colour");
  const SurfaceMesh m = make_quad_torus(12, 8);
  Hierarchy t = make_hierarchy(complex_from_surface_mesh(m), 2, Scheme::Cubic, 3);
  set_base(t, flatten_positions(m));
  std::vector<double> fine = synthesize(t, 2);
  for (std::size_t v = 0; 3 * v < fine.size(); ++v)
    if (fine[3 * v] > 0.0) fine[3 * v + 1] += 0.02 * std::sin(7.0 * fine[3 * v + 2]);  // detail where x > 0
  analyze(t, fine);
  write_project(dir.file("t.sublift"), t);
  auto saturated = [](const Png& p) {
    std::size_t n = 0;
    for (std::size_t i = 0; i + 3 < p.rgba.size(); i += 4) {
      const int r = p.rgba[i], g = p.rgba[i + 1], b = p.rgba[i + 2];
      if (std::max({r, g, b}) - std::min({r, g, b}) > 60) ++n;
    }
    return double(n) / (double(p.w) * p.h);
  };
  const testing::ProcessResult plain = testing::run_cli({"render", dir.file("t.sublift"), "-o", dir.file("plain.png")});
  const testing::ProcessResult coloured =
      testing::run_cli({"render", dir.file("t.sublift"), "--colour", "1", "-o", dir.file("c.png"), "--json"});
  if (plain.exit_code != 0 && plain.err.find("EGL") != std::string::npos) GTEST_SKIP() << "no headless GL: " << plain.err;
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  ASSERT_EQ(coloured.exit_code, 0) << coloured.err;
  EXPECT_NE(coloured.out.find("\"colour_level\": 1"), std::string::npos) << coloured.out;
  const Png a = load(dir.file("plain.png")), c = load(dir.file("c.png"));
  ASSERT_EQ(c.w, 800);
  EXPECT_LT(saturated(a), 0.01);
  EXPECT_GT(saturated(c), 0.08) << "the surface is not coloured";  // it covers about an eighth of the image
  // The large wavelets (along the step of the detail at x = 0) in viridis' green and yellow.
  std::size_t high = 0;
  for (std::size_t i = 0; i + 3 < c.rgba.size(); i += 4)
    if (c.rgba[i + 1] > 140 && c.rgba[i + 1] > c.rgba[i + 2] + 20) ++high;
  EXPECT_GT(high, 100u);
  // --level 0: the base's limit surface (the modeler's viewport level): smoother, so another picture.
  const testing::ProcessResult coarse =
      testing::run_cli({"render", dir.file("t.sublift"), "--level", "0", "--colour", "0", "-o", dir.file("l0.png")});
  ASSERT_EQ(coarse.exit_code, 0) << coarse.err;
  const Png l0 = load(dir.file("l0.png"));
  ASSERT_EQ(l0.w, 800);
  EXPECT_GT(saturated(l0), 0.08);
  for (const auto& args : std::vector<std::vector<std::string>>{
           {"render", dir.file("t.sublift"), "--level", "5", "-o", dir.file("x.png")},
           {"render", dir.file("t.sublift"), "--colour", "2", "-o", dir.file("x.png")},  // the finest has no wavelets
           {"render", dir.file("t.sublift"), "--colour", "x", "-o", dir.file("x.png")},
       }) {
    const testing::ProcessResult bad = testing::run_cli(args);
    EXPECT_EQ(bad.exit_code, 2) << bad.err;
  }
}

// Issue 20: a textured asset subdivides and still maps its texture. BoxTextured is drawn with its
// texture before and after three levels of linear subdivision (written as .glb, the texture
// embedded): the two pictures agree pixel for pixel but for a thin line of rasterisation
// differences, while the same box drawn without the texture, or with its UVs through the image
// upside down, differs from them over much of the box (so the comparison can see a wrong map).
TEST(CliRender, TexturedBoxBeforeAndAfterSubdivision) {
  const std::filesystem::path box = std::filesystem::path(SUBLIFT_SHARED_DATA) / "gltf" / "BoxTextured" / "BoxTextured.gltf";
  if (!std::filesystem::exists(box)) GTEST_SKIP() << box << " not found (../shared/data absent)";
  testing::TempDir dir("sublift_cli_render_textured");
  const std::string fine = dir.file("fine.glb");
  auto r = testing::run_cli({"subdivide", box.string(), "--scheme", "linear", "--levels", "3", "-o", fine});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto render = [&](const std::string& in, const std::string& png, std::vector<std::string> extra) {
    std::vector<std::string> args{"render", in, "-o", dir.file(png), "--size", "320x240"};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto rr = testing::run_cli(args);
    EXPECT_EQ(rr.exit_code, 0) << rr.err;
    return load(dir.file(png));
  };
  // Flat shading: the welded box's corner normals are averages, which light its few big faces
  // differently from the many small ones after subdivision.
  const Png before = render(box.string(), "before.png", {"--textured", "--flat"});
  const Png after = render(fine, "after.png", {"--textured", "--flat"});
  const Png clay = render(box.string(), "clay.png", {});
  // The box's own texture upside down, put where the UVs look.
  {
    int w = 0, h = 0, n = 0;
    unsigned char* t = stbi_load((box.parent_path() / "CesiumLogoFlat.png").string().c_str(), &w, &h, &n, 4);
    ASSERT_TRUE(t);
    std::vector<unsigned char> flipped(std::size_t(w) * h * 4);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) std::copy_n(t + (std::size_t(y) * w + x) * 4, 4, &flipped[(std::size_t(h - 1 - y) * w + x) * 4]);
    stbi_image_free(t);
    ASSERT_TRUE(stbi_write_png(dir.file("mirrored.png").c_str(), w, h, 4, flipped.data(), w * 4));
  }
  const Png mirrored = render(fine, "mirrored_render.png", {"--texture", dir.file("mirrored.png"), "--flat"});
  ASSERT_EQ(before.rgba.size(), after.rgba.size());
  ASSERT_FALSE(before.rgba.empty());
  const auto differing = [](const Png& a, const Png& b) {  // fraction of the picture's pixels that differ visibly
    std::size_t diff = 0;
    for (std::size_t i = 0; i < a.rgba.size(); i += 4)
      diff += std::abs(a.rgba[i] - b.rgba[i]) + std::abs(a.rgba[i + 1] - b.rgba[i + 1]) + std::abs(a.rgba[i + 2] - b.rgba[i + 2]) > 48;
    return double(diff) / double(a.rgba.size() / 4);
  };
  const double shape = shape_fraction(before);
  ASSERT_GT(shape, 0.15) << "the box should fill a good part of the picture";
  const double same = differing(before, after), untextured = differing(before, clay), wrong = differing(after, mirrored);
  EXPECT_LT(same, 0.01 * shape) << "subdivided box renders differently: " << same;
  EXPECT_GT(untextured, 0.25 * shape) << "texture not visible? " << untextured;
  EXPECT_GT(wrong, 0.25 * shape) << "an upside-down texture should show: " << wrong;
  std::cerr << "box " << shape << " of the picture; differing pixels: after subdivision " << same << ", untextured " << untextured
            << ", upside-down texture " << wrong << "\n";
}

}  // namespace
}  // namespace sublift
