// The modeler's animation mode (issue 22) on ModelerState, without a window: the frame shown and
// its blend between layers, the edit level's layer as the net (other layers hidden and not
// pickable), a drag at a frame moving that layer's point and spreading over its time support,
// undo, tools refused with a reason, export, playback and the script commands.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "app/modeler/modeler_state.h"
#include "app/modeler/script_runner.h"
#include "core/base/errors.h"
#include "core/io/model/animation.h"

namespace sublift {
namespace {

namespace fs = std::filesystem;

// A unit cube of quads per frame, moved and stretched as f goes on.
std::string cube_frame(double s) {
  std::string out;
  for (int i = 0; i < 8; ++i)
    out += "v " + std::to_string((i & 1) + s) + " " + std::to_string((i >> 1) & 1) + " " + std::to_string(((i >> 2) & 1) * (1 + s)) + "\n";
  return out + "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";
}

struct Fixture {
  fs::path dir = fs::temp_directory_path() / ("sublift_modeler_animation_" + std::to_string(::getpid()));
  std::vector<std::string> files;
  ModelerState state;
  explicit Fixture(int frames = 17) {
    fs::remove_all(dir);
    fs::create_directories(dir);
    for (int f = 0; f < frames; ++f) {
      files.push_back((dir / ("cube" + std::to_string(f) + ".obj")).string());
      std::ofstream(files.back()) << cube_frame(0.05 * f);
    }
    AnimationOptions o;
    o.levels = 2;
    state.open_animation(files, o);
  }
  ~Fixture() { fs::remove_all(dir); }
  const SpaceTime& st() const { return state.animation()->anim.st; }
  std::uint32_t vertex(int level, int layer, std::uint32_t point) const {
    return st().layer_vertices[std::size_t(level)][std::size_t(layer) * st().surface_vertices(level) + point];
  }
};

double max_diff(std::span<const double> a, std::span<const double> b) {
  double m = 0;
  for (std::size_t i = 0; i < a.size(); ++i) m = std::max(m, std::abs(a[i] - b[i]));
  return m;
}

TEST(ModelerAnimation, ShowsTheFrameAndTheLevelsNearestLayer) {
  Fixture f;
  ModelerState& s = f.state;
  ASSERT_TRUE(s.animation_on());
  EXPECT_EQ(s.animation()->frames(), 17);
  const int J = f.st().levels();
  const std::vector<double> finest(s.session().positions(J).begin(), s.session().positions(J).end());
  EXPECT_EQ(s.limit_positions(), layer_positions(f.st(), finest, J, 0));
  EXPECT_EQ(s.surface_faces().rows(), f.st().surface_levels.levels[std::size_t(J)].faces.rows());
  s.set_frame(6);
  EXPECT_EQ(s.limit_positions(), layer_positions(f.st(), finest, J, 6));
  EXPECT_EQ(s.animation()->layer, 2);  // level 0 has layers every 4 frames: 6 rounds to 8
  s.set_frame(5.25);
  const std::vector<double> a = layer_positions(f.st(), finest, J, 5), b = layer_positions(f.st(), finest, J, 6);
  for (std::size_t i = 0; i < a.size(); ++i) ASSERT_NEAR(s.limit_positions()[i], 0.75 * a[i] + 0.25 * b[i], 1e-12);
  EXPECT_EQ(s.animation()->layer, 1);
  // The net: the layer's 8 points and 12 edges; every other point hidden and not pickable.
  const auto mask = s.net_pick_mask();
  EXPECT_EQ(std::count(mask.begin(), mask.end(), 1), 8);
  EXPECT_EQ(s.net_edges().size(), 2u * 12);
  for (std::uint32_t v : s.net_edges()) EXPECT_TRUE(mask[v]);
  for (std::size_t v = 0; v < mask.size(); ++v) EXPECT_EQ(s.net_state()[v] == 3, mask[v] == 0) << v;
  s.set_level(1);  // layers every 2 frames: 5.25 rounds to frame 6
  EXPECT_EQ(s.animation()->layer, 3);
  EXPECT_EQ(std::count(s.net_pick_mask().begin(), s.net_pick_mask().end(), 1), int(f.st().surface_vertices(1)));
  s.set_frame(-3);
  EXPECT_EQ(s.animation()->frame, 0.0);  // an open animation clamps
  s.set_frame(99);
  EXPECT_EQ(s.animation()->frame, 16.0);
}

TEST(ModelerAnimation, ADragMovesTheLayersPointAndSpreadsOverItsTimeSupport) {
  Fixture f;
  ModelerState& s = f.state;
  const int J = f.st().levels();
  s.set_frame(4);  // level 0, layer 1
  const std::vector<double> before0(s.session().positions(0).begin(), s.session().positions(0).end());
  const std::vector<double> before(s.session().positions(J).begin(), s.session().positions(J).end());
  const std::uint32_t v = f.vertex(0, 1, 7);
  s.set_selection({v, f.vertex(0, 3, 7)});  // a point of another layer is dropped
  ASSERT_EQ(s.selection(), std::vector<unsigned>{v});
  s.set_soft_radius(10.0);  // reaches every point in space: still this layer's only
  s.begin_drag("Grab");
  const double t[3] = {0, 0, 0.5};
  s.drag_to(t);
  s.end_drag();
  const auto after0 = s.session().positions(0);
  for (std::uint32_t u = 0; u < s.session().num_vertices(0); ++u) {
    const bool on_layer = s.net_pick_mask()[u] != 0;
    const double moved = std::abs(after0[3 * u + 2] - before0[3 * u + 2]);
    if (u == v) {
      EXPECT_NEAR(moved, 0.5, 1e-12);
    }
    if (!on_layer) {
      EXPECT_EQ(moved, 0.0) << "point " << u << " of another layer moved";
    }
  }
  const std::vector<double> after(s.session().positions(J).begin(), s.session().positions(J).end());
  for (int frame = 0; frame < 17; ++frame) {
    const double d = max_diff(layer_positions(f.st(), before, J, frame), layer_positions(f.st(), after, J, frame));
    // The cubic's level-2 reach: 6 frames; the first frame is the lattice's boundary.
    if (frame == 0 || frame >= 4 + 7) EXPECT_EQ(d, 0.0) << "frame " << frame;
    else EXPECT_GT(d, 1e-3) << "frame " << frame;
  }
  EXPECT_NE(s.limit_positions(), layer_positions(f.st(), before, J, 4)) << "the frame shown follows the drag";
  ASSERT_TRUE(s.undo());
  EXPECT_EQ(max_diff(s.session().positions(J), before), 0.0);
  EXPECT_EQ(s.limit_positions(), layer_positions(f.st(), before, J, 4));
}

TEST(ModelerAnimation, ToolsThatDoNotApplySaySo) {
  Fixture f;
  ModelerState& s = f.state;
  EXPECT_THROW(s.subdivide(), Error);
  EXPECT_THROW(s.set_scheme(Scheme::Linear), Error);
  EXPECT_THROW(s.set_compression(0.5), Error);
  EXPECT_THROW(s.set_symmetry(0, true), Error);
  EXPECT_THROW(s.begin_stroke(), Error);
  try {
    s.subdivide();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("not available on an animation"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(s.dragging());
  EXPECT_THROW(s.set_ghosts(9), Error);
  s.set_ghosts(2);
  EXPECT_EQ(s.animation()->ghost_edges.size(), 2u * 48 * 2);  // frames 4 and 8 (-4, -8 are out); level 1 of the cube has 48 edges
}

// Saved as a project (and so in its recovery file), an animation opens again as the animation:
// the same frames, edits and edit level.
TEST(ModelerAnimation, TheProjectReopensAsTheAnimation) {
  Fixture f;
  ModelerState& s = f.state;
  s.set_frame(4);
  s.set_selection({f.vertex(0, 1, 7)});
  s.begin_drag("Grab");
  const double t[3] = {0.1, 0, 0.3};
  s.drag_to(t);
  s.end_drag();
  s.set_level(1);
  const std::string path = (f.dir / "anim.sublift").string();
  s.save_project(path);
  EXPECT_FALSE(s.session().dirty());
  const std::vector<double> before(s.session().positions(2).begin(), s.session().positions(2).end());
  ModelerState again;
  again.open(path);
  ASSERT_TRUE(again.animation_on());
  EXPECT_EQ(again.animation()->frames(), 17);
  EXPECT_EQ(again.level(), 1);
  EXPECT_EQ(again.project_path(), path);
  // The coefficients bit for bit; the shown positions to rounding (the drag's local resynthesis
  // and the reopened session's full synthesis add in another order).
  EXPECT_EQ(again.session().hierarchy().coeffs, s.session().hierarchy().coeffs);
  EXPECT_LT(max_diff(again.session().positions(2), before), 1e-12);
  EXPECT_EQ(again.animation()->anim.times, s.animation()->anim.times);
}

TEST(ModelerAnimation, ExportsEveryFrameAndPlays) {
  Fixture f;
  ModelerState& s = f.state;
  const std::vector<std::string> files = s.export_animation((f.dir / "out_##.obj").string());
  ASSERT_EQ(files.size(), 17u);
  EXPECT_EQ(fs::path(files.back()).filename(), "out_16.obj");
  ASSERT_EQ(s.export_animation((f.dir / "out.glb").string()).size(), 1u);
  const FrameSet back = sample_gltf_animation((f.dir / "out.glb").string(), 0, 17, false);
  EXPECT_EQ(back.num_frames(), 17u);
  s.set_playing(true);
  s.advance(4.0 / 24);  // four frames at the sequence's 24 fps
  EXPECT_NEAR(s.animation()->frame, 4.0, 1e-9);
  s.advance(10.0);
  EXPECT_EQ(s.animation()->frame, 16.0);
  EXPECT_FALSE(s.animation()->playing) << "an open animation stops at its last frame";
}

TEST(ModelerAnimation, ScriptCommands) {
  Fixture f;
  ModelerState& s = f.state;
  std::string open = "animation open levels 2";
  for (const std::string& file : f.files) open += " " + file;
  ScriptRunner ok("ok", open + "\nanimation frame 8\nselect 3\nmove 0 0.25 0\nanimation ghosts 1\nanimation export " +
                            (f.dir / "s.glb").string() + "\n");
  const ScriptStep step = ok.next(s);
  ASSERT_EQ(step.kind, ScriptStep::Kind::End) << step.message;
  EXPECT_EQ(s.selection(), std::vector<unsigned>{f.vertex(0, 2, 3)});
  EXPECT_EQ(s.session().history().size(), 1u);
  EXPECT_TRUE(fs::exists(f.dir / "s.glb"));
  struct Bad {
    std::string script, message;
  };
  for (const Bad& b : {Bad{"animation frame x\n", "script:1: F must be a number"},
                       Bad{"animation spin\n", "script:1: usage: animation open"},
                       Bad{"select 8\n", "script:1: vertex 8 is outside 0..7 of level 0's layer shown"},
                       Bad{"animation open levels 2 " + f.files[0] + " " + f.files[1] + " " + f.files[2] + "\n",
                           "script:1: " + f.files[0] + ": 3 files do not fit 2 levels"}}) {
    ScriptRunner r("bad", b.script);
    const ScriptStep e = r.next(s);
    EXPECT_EQ(e.kind, ScriptStep::Kind::Error) << b.script;
    EXPECT_EQ(e.message.rfind(b.message, 0), 0u) << e.message;
  }
  EXPECT_TRUE(s.animation_on()) << "a failed open keeps the animation open";
}

}  // namespace
}  // namespace sublift
