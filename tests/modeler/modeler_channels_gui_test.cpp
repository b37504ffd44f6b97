// A model's attribute channel shown as colour, end to end: `sublift --script` under Xvfb (a real
// window) opens the shared BoxVertexColors, whose COLOR_0 comes in as the channels red, green,
// blue and alpha, and screenshots it in clay, coloured by red and coloured by blue. Each colouring
// must change the box's pixels, and red and blue must differ from each other. PNGs are kept in
// the build directory (modeler_channels_gui_out/).
#include <gtest/gtest.h>

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
using sublift::testing::kGuiWidth;
using sublift::testing::load_png;
using sublift::testing::Png;

TEST(ModelerChannelsGuiTest, XvfbColourByChannel) {
  const fs::path box = fs::path(SUBLIFT_SHARED_DATA) / "gltf" / "BoxVertexColors" / "BoxVertexColors.glb";
  if (!fs::exists(box)) GTEST_SKIP() << box << " not found (../shared/data absent)";
  const fs::path dir = sublift::testing::fresh_dir(fs::path(SUBLIFT_TEST_OUT_DIR) / "xvfb");
  std::ofstream(dir / "channels.txt") << "open " << box.string() << "\n"
                                      << "display net off\n"
                                         "screenshot clay.png\n"
                                         "colour channel red\n"
                                         "screenshot red.png\n"
                                         "colour channel blue\n"
                                         "screenshot blue.png\n"
                                         "colour off\n"
                                         "screenshot off.png\n";
  const auto r = sublift::testing::run_gui_script(SUBLIFT_GUI_EXE, dir, "channels.txt");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Png clay = load_png(dir / "clay.png"), red = load_png(dir / "red.png"), blue = load_png(dir / "blue.png"), off = load_png(dir / "off.png");
  for (const Png* p : {&clay, &red, &blue, &off}) ASSERT_EQ(p->width, kGuiWidth);
  EXPECT_GT(changed_viewport_pixels(clay, red, 40), 5000) << "colouring by red changed nothing";
  EXPECT_GT(changed_viewport_pixels(red, blue, 40), 2000) << "red and blue look the same";
  EXPECT_LT(changed_viewport_pixels(clay, off, 24), 20) << "colour off does not bring the clay back";
}

// A textured model is drawn with its texture (the Display section's Texture switch, `display
// texture on|off`), and the texture follows a drag: BoxTextured textured, in clay, then with a
// base corner moved.
TEST(ModelerChannelsGuiTest, XvfbTexturedModel) {
  const fs::path box = fs::path(SUBLIFT_SHARED_DATA) / "gltf" / "BoxTextured" / "BoxTextured.glb";
  if (!fs::exists(box)) GTEST_SKIP() << box << " not found (../shared/data absent)";
  const fs::path dir = sublift::testing::fresh_dir(fs::path(SUBLIFT_TEST_OUT_DIR) / "xvfb_texture");
  std::ofstream(dir / "texture.txt") << "open " << box.string() << "\n"
                                     << "display net off\n"
                                        "screenshot textured.png\n"
                                        "display texture off\n"
                                        "screenshot clay.png\n"
                                        "display texture on\n"
                                        "level 0\n"
                                        "select 0\n"
                                        "move 0 0.3 0\n"
                                        "screenshot moved.png\n";
  const auto r = sublift::testing::run_gui_script(SUBLIFT_GUI_EXE, dir, "texture.txt");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Png textured = load_png(dir / "textured.png"), clay = load_png(dir / "clay.png"), moved = load_png(dir / "moved.png");
  for (const Png* p : {&textured, &clay, &moved}) ASSERT_EQ(p->width, kGuiWidth);
  EXPECT_GT(changed_viewport_pixels(clay, textured, 40), 10000) << "the texture is not drawn";
  EXPECT_GT(changed_viewport_pixels(textured, moved, 40), 500) << "the drag did not move the textured surface";
}

}  // namespace
