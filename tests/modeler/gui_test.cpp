// The `sublift` executable end to end: under Xvfb (a real GLFW window) and with no display at
// all (headless EGL fallback). Screenshots are checked by their content, with tolerances: the
// panel on the left, the mesh in clay with a dark wireframe in the light grey-blue viewport.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/gui_test_util.h"

#ifndef SUBLIFT_GUI_EXE
#error "SUBLIFT_GUI_EXE must name the sublift executable"
#endif
#ifndef SUBLIFT_ASSETS_DIR
#error "SUBLIFT_ASSETS_DIR must name the assets folder"
#endif

namespace {

namespace fs = std::filesystem;

// Must agree with ui/panels.h PanelLayout defaults.
constexpr int kPanelWidth = 330;
constexpr int kStatusHeight = 28;

using ProcessResult = sublift::testing::ShellResult;
using sublift::testing::load_png;
using sublift::testing::Png;
using sublift::testing::quote;

fs::path scratch_dir() {
  static const fs::path dir = [] {
    fs::path d = fs::temp_directory_path() / ("sublift_gui_test_" + std::to_string(::getpid()));
    fs::create_directories(d);
    return d;
  }();
  return dir;
}

// Runs a shell command with stderr captured; a hang is cut off by `timeout` inside `command`.
ProcessResult run_command(const std::string& command) {
  return sublift::testing::run_shell(command, scratch_dir() / "stderr.txt");
}

std::string sublift() { return quote(SUBLIFT_GUI_EXE); }
std::string sample() { return quote(std::string(SUBLIFT_ASSETS_DIR) + "/sample.obj"); }

std::string xvfb_prefix() {
  // -n spreads concurrent runs over server numbers so parallel ctest jobs do not collide.
  const int server = 100 + static_cast<int>(::getpid() % 400);
  return "timeout 90 xvfb-run -a -n " + std::to_string(server) +
         " -s '-screen 0 1280x800x24' ";
}

std::string headless_prefix() { return "env -u DISPLAY -u WAYLAND_DISPLAY "; }

struct Rgb {
  int r, g, b;
};

Rgb at(const Png& p, int x, int y) {
  const std::size_t i = (static_cast<std::size_t>(y) * p.width + x) * 4;
  return {p.rgba[i], p.rgba[i + 1], p.rgba[i + 2]};
}

int luminance(const Rgb& c) { return (299 * c.r + 587 * c.g + 114 * c.b) / 1000; }

bool is_clay(const Rgb& c) {
  const int l = luminance(c);
  return c.r > c.g && c.g > c.b && c.r - c.b > 25 && l > 60 && l < 245;
}

struct RegionStats {
  long pixels = 0, dark = 0, bright = 0, clay = 0, bluish_light = 0;
  double mean_luminance = 0.0;
};

RegionStats region(const Png& p, int x0, int y0, int x1, int y1) {
  RegionStats s;
  double sum = 0.0;
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) {
      const Rgb c = at(p, x, y);
      const int l = luminance(c);
      ++s.pixels;
      sum += l;
      s.dark += l < 70;
      s.bright += l > 180;
      s.clay += is_clay(c);
      s.bluish_light += c.b >= c.r && l > 120;
    }
  }
  s.mean_luminance = s.pixels > 0 ? sum / static_cast<double>(s.pixels) : 0.0;
  return s;
}

// What every GUI screenshot must show, whichever path drew it.
void expect_gui_screenshot(const Png& png, int width, int height) {
  ASSERT_EQ(png.width, width);
  ASSERT_EQ(png.height, height);
  const int view_x0 = kPanelWidth, view_y1 = height - kStatusHeight;

  // Viewport: light grey-blue background, clay mesh, dark wireframe.
  const RegionStats view = region(png, view_x0, 0, width, view_y1);
  const Rgb corner = at(png, width - 4, 4);
  EXPECT_GT(luminance(corner), 150) << "viewport background should be light";
  EXPECT_GE(corner.b, corner.r) << "viewport background should be grey-blue";
  EXPECT_GT(view.clay, view.pixels / 50) << "too few clay-coloured (mesh) pixels";
  EXPECT_GT(view.bluish_light, view.pixels / 5) << "too little background";
  EXPECT_GT(view.dark, 100) << "no dark wireframe pixels in the viewport";

  // Side panel: dark and unlike the viewport, with light text on it.
  const RegionStats panel = region(png, 0, 0, kPanelWidth, view_y1);
  EXPECT_LT(panel.mean_luminance, view.mean_luminance - 50);
  EXPECT_GT(panel.dark, panel.pixels / 2);
  EXPECT_GT(panel.bright, 500) << "panel text missing";

  // Status line: a dark strip with text across the bottom.
  const RegionStats status = region(png, 0, view_y1 + 2, width, height - 2);
  EXPECT_GT(status.dark, status.pixels / 2);
  EXPECT_GT(status.bright, 50) << "status line text missing";
}

TEST(GuiTest, XvfbWindowScreenshotShowsPanelMeshAndWireframe) {
  const fs::path png = scratch_dir() / "xvfb.png";
  fs::remove(png);
  const ProcessResult r = run_command(xvfb_prefix() + "timeout 60 " + sublift() + " " + sample() +
                    " --screenshot " + quote(png.string()) + " --frames 5");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("no display"), std::string::npos) << "Xvfb run fell back: " << r.err;
  expect_gui_screenshot(load_png(png), 1280, 800);
}

TEST(GuiTest, NoDisplayFallsBackToHeadlessScreenshot) {
  const fs::path png = scratch_dir() / "headless.png";
  fs::remove(png);
  const ProcessResult r = run_command(headless_prefix() + "timeout 60 " + sublift() + " " + sample() +
                    " --screenshot " + quote(png.string()) + " --size 960x640");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("sublift: no display available; rendering the same view headless to " +
                       png.string()),
            std::string::npos)
      << r.err;
  expect_gui_screenshot(load_png(png), 960, 640);
}

TEST(GuiTest, NoDisplayWithoutScreenshotWritesTheDefaultFile) {
  const fs::path dir = scratch_dir() / "default_name";
  fs::create_directories(dir);
  const ProcessResult r = run_command("cd " + quote(dir.string()) + " && " + headless_prefix() + "timeout 60 " +
                    sublift() + " " + sample() + " --size 640x480");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("sublift-screenshot.png"), std::string::npos) << r.err;
  expect_gui_screenshot(load_png(dir / "sublift-screenshot.png"), 640, 480);
}

TEST(GuiTest, WindowAndHeadlessPathsDrawTheSameFrame) {
  const fs::path window_png = scratch_dir() / "same_window.png";
  const fs::path headless_png = scratch_dir() / "same_headless.png";
  const std::string args = " " + sample() + " --size 800x600 --frames 3 --screenshot ";
  ASSERT_EQ(run_command(xvfb_prefix() + "timeout 60 " + sublift() + args + quote(window_png.string()))
                .exit_code,
            0);
  ASSERT_EQ(run_command(headless_prefix() + "timeout 60 " + sublift() + args +
                quote(headless_png.string()))
                .exit_code,
            0);
  const Png a = load_png(window_png), b = load_png(headless_png);
  ASSERT_EQ(a.width, b.width);
  ASSERT_EQ(a.height, b.height);
  // Anti-aliasing may differ along edges and the status line shows a measured time: compare
  // everything above the status line and allow a thin fringe of differing pixels.
  long differing = 0, total = 0;
  for (int y = 0; y < a.height - kStatusHeight; ++y) {
    for (int x = 0; x < a.width; ++x) {
      const Rgb p = at(a, x, y), q = at(b, x, y);
      differing += std::max({std::abs(p.r - q.r), std::abs(p.g - q.g), std::abs(p.b - q.b)}) > 40;
      ++total;
    }
  }
  EXPECT_LT(differing, total / 50) << differing << " of " << total << " pixels differ";
}

TEST(GuiTest, UnreadableFileExitsOneNamingTheFile) {
  const fs::path missing = scratch_dir() / "no_such_mesh.obj";
  const ProcessResult r = run_command(headless_prefix() + "timeout 60 " + sublift() + " " +
                    quote(missing.string()) + " --screenshot " +
                    quote((scratch_dir() / "never.png").string()));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find(missing.string()), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(scratch_dir() / "never.png"));
}

TEST(GuiTest, BadUsageExitsTwo) {
  for (const std::string args : {"--frames", "--frames 0", "--size 12", "--size 800x",
                                 "--bogus", "a.obj b.obj", "--screenshot"}) {
    const ProcessResult r = run_command(headless_prefix() + "timeout 60 " + sublift() + " " + args);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.err;
    EXPECT_NE(r.err.find("usage: sublift"), std::string::npos) << args;
  }
}

// `sublift --script FILE --json --headless`: one JSON line per command on stdout, the exit code
// of the script (issue 19); --json without --script is a usage error.
TEST(GuiTest, ScriptJsonPrintsOneLinePerCommand) {
  const fs::path script = scratch_dir() / "json.script";
  { std::ofstream(script) << "open " << SUBLIFT_ASSETS_DIR << "/cube.obj\nsubdivide\nlevel 3\nbogus\n"; }
  const fs::path out = scratch_dir() / "json.out";
  const ProcessResult r = run_command(headless_prefix() + "timeout 60 " + sublift() + " --script " +
                                      quote(script.string()) + " --json --headless --size 320x240 >" + quote(out.string()));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  std::vector<std::string> lines;
  std::ifstream in(out);
  for (std::string l; std::getline(in, l);)
    if (!l.empty()) lines.push_back(l);
  ASSERT_EQ(lines.size(), 4u) << r.err;
  EXPECT_EQ(lines[0].rfind("{\"command\":\"open\",\"finest_level\":2,", 0), 0u) << lines[0];
  EXPECT_NE(lines[2].find("\"level\":3"), std::string::npos) << lines[2];
  EXPECT_NE(lines[3].find("\"ok\":false"), std::string::npos) << lines[3];
  EXPECT_NE(lines[3].find("unknown command 'bogus'"), std::string::npos) << lines[3];
  const ProcessResult bad = run_command("timeout 60 " + sublift() + " --json");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("--json goes with --script"), std::string::npos) << bad.err;
}

TEST(GuiTest, HelpExitsZero) {
  const ProcessResult r = run_command("timeout 60 " + sublift() + " --help >/dev/null");
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

}  // namespace
