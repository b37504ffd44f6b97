// The modeler's animation mode under Xvfb (`sublift --script`, issue 22): the Fox's walk opened
// as a space-time lattice, shown at frames 0 and 8, with ghosts, a level-0 point dragged at frame
// 8; the screenshots (in modeler_animation_gui_out/) show the walk move, the ghosts appear, the
// drag change frame 8 and leave frame 16 (beyond its time support) as it was.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "tests/gui_test_util.h"

#ifndef SUBLIFT_GUI_EXE
#error "SUBLIFT_GUI_EXE must name the sublift executable"
#endif
#ifndef SUBLIFT_TEST_OUT_DIR
#error "SUBLIFT_TEST_OUT_DIR must name a folder for the screenshots"
#endif

namespace {

namespace fs = std::filesystem;

using sublift::testing::changed_viewport_pixels;
using sublift::testing::kGuiHeight;
using sublift::testing::kGuiPanelWidth;
using sublift::testing::kGuiStatusHeight;
using sublift::testing::kGuiWidth;
using sublift::testing::load_png;
using sublift::testing::Png;

// Viewport pixels of the ghosts' blue (NetRenderer edges 0.25, 0.45, 0.85 blended at 0.35 over
// the background or the surface): clearly bluer than red.
long blue_pixels(const Png& p) {
  long n = 0;
  for (int y = 0; y < kGuiHeight - kGuiStatusHeight; ++y)
    for (int x = kGuiPanelWidth; x < kGuiWidth; ++x) n += p.channel(x, y, 2) > p.channel(x, y, 0) + 40;
  return n;
}

TEST(ModelerAnimationGuiTest, XvfbFoxWalkFramesGhostsAndADrag) {
  const fs::path fox = fs::path(SUBLIFT_SHARED_DATA) / "gltf" / "Fox" / "Fox.glb";
  if (!fs::exists(fox)) GTEST_SKIP() << fox << " not found (../shared/data absent)";
  const fs::path dir = sublift::testing::fresh_dir(fs::path(SUBLIFT_TEST_OUT_DIR) / "xvfb");
  const std::string script = "animation open clip 1 frames 17 levels 2 " + fox.string() + "\n"
                             "view left\n"
                             "screenshot f0.png\n"
                             "animation frame 16\n"
                             "screenshot f16.png\n"
                             "animation frame 8\n"
                             "screenshot f8.png\n"
                             "animation ghosts 2\n"
                             "screenshot ghosts.png\n"
                             "animation ghosts 0\n"
                             "select 100\n"
                             "move 0 40 0\n"
                             "screenshot moved.png\n"
                             "animation frame 16\n"
                             "select none\n"
                             "screenshot f16_after.png\n";
  std::ofstream(dir / "animation.txt") << script;
  const auto r = sublift::testing::run_gui_script(SUBLIFT_GUI_EXE, dir, "animation.txt");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Png f0 = load_png(dir / "f0.png"), f16 = load_png(dir / "f16.png"), f8 = load_png(dir / "f8.png"),
            ghosts = load_png(dir / "ghosts.png"), moved = load_png(dir / "moved.png"), f16_after = load_png(dir / "f16_after.png");
  for (const Png* p : {&f0, &f16, &f8, &ghosts, &moved, &f16_after}) ASSERT_EQ(p->width, kGuiWidth);
  EXPECT_GT(changed_viewport_pixels(f0, f8, 40), 1500) << "the walk does not move between frames 0 and 8";
  EXPECT_GT(blue_pixels(ghosts), blue_pixels(f8) + 1000) << "no ghost frames drawn";
  EXPECT_GT(changed_viewport_pixels(f8, moved, 40), 300) << "the drag at frame 8 changed nothing on screen";
  EXPECT_LT(changed_viewport_pixels(f16, f16_after, 24), 20) << "frame 16 is beyond the drag's time support but changed";
}

}  // namespace
