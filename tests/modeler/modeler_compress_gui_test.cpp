// The compression view end to end: `sublift --script` under Xvfb (a real window) on a project
// with detail at every scale, screenshots at 1%, 20% and 100% of the wavelets, Off, Apply and
// Undo. 1% must visibly lose detail, 20% less so, 100% and Off must be the full shape, Apply must
// show what the 20% view showed and Undo the full shape again. PNGs are kept in the build
// directory (modeler_compress_gui_out/).
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/io/project/project_io.h"
#include "tests/compress_fixture.h"
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

TEST(ModelerCompressGuiTest, XvfbSliderFractionsOffApplyAndUndo) {
  const fs::path dir = sublift::testing::fresh_dir(fs::path(SUBLIFT_TEST_OUT_DIR) / "xvfb");
  // The sample torus (24 x 12 quads), 2 cubic levels, waves of three lengths at 1.5 times the
  // fixture's amplitude and visible roughness; the net hidden, so that only the surface shows.
  const sublift::Hierarchy h = sublift::testing::detailed_hierarchy(std::string(SUBLIFT_ASSETS_DIR) + "/sample.obj",
                                                                    sublift::Scheme::Cubic, 2, 1.5, 0.002);
  sublift::write_project((dir / "detail.sublift").string(), h);
  const std::string script =
      "open detail.sublift\n"
      "display net off\n"
      "screenshot full.png\n"
      "compress keep 0.01\n"
      "screenshot keep01.png\n"
      "compress keep 0.2\n"
      "screenshot keep20.png\n"
      "compress keep 1\n"
      "screenshot keep100.png\n"
      "compress off\n"
      "screenshot off.png\n"
      "compress keep 0.2\n"
      "compress apply\n"
      "screenshot applied.png\n"
      "undo\n"
      "screenshot undone.png\n";
  std::ofstream(dir / "compress.txt") << script;
  const auto r = sublift::testing::run_gui_script(SUBLIFT_GUI_EXE, dir, "compress.txt");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Png full = load_png(dir / "full.png"), k01 = load_png(dir / "keep01.png"), k20 = load_png(dir / "keep20.png"),
            k100 = load_png(dir / "keep100.png"), off = load_png(dir / "off.png"),
            applied = load_png(dir / "applied.png"), undone = load_png(dir / "undone.png");
  for (const Png* p : {&full, &k01, &k20, &k100, &off, &applied, &undone}) ASSERT_EQ(p->width, kGuiWidth);
  const long lost01 = changed_viewport_pixels(full, k01, 40), lost20 = changed_viewport_pixels(full, k20, 40);
  EXPECT_GT(lost01, 2000) << "1% of the wavelets looks like the full shape";
  EXPECT_GT(lost20, 100) << "20% of the wavelets looks exactly like the full shape";
  EXPECT_LT(lost20, lost01 / 2) << "20% is not closer to the full shape than 1%";
  EXPECT_LT(changed_viewport_pixels(full, k100, 24), 20) << "100% is not the full shape";
  EXPECT_LT(changed_viewport_pixels(full, off, 24), 20) << "Off does not restore the full shape";
  EXPECT_LT(changed_viewport_pixels(k20, applied, 24), 40) << "Apply does not keep what the 20% view showed";
  EXPECT_LT(changed_viewport_pixels(full, undone, 24), 20) << "Undo does not restore the full shape";
}

}  // namespace
