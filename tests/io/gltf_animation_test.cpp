// Animations sampled into frames (core/io/model/animation.h, issue 22's input): glTF morph
// targets, skins and node transforms against closed forms and numbers read by hand from the
// shared samples (python3 over their JSON and buffers, quoted where used), frame sequences of OBJ
// files written here, and corrupted copies of the samples.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>

#include <nlohmann/json.hpp>

#include "core/io/lattice/shape_io.h"
#include "core/io/model/animation.h"
#include "tests/io_test_util.h"

namespace {

namespace fs = std::filesystem;
using namespace sublift;
using sublift::testing::input_error;
using sublift::testing::TempDir;

const fs::path kGltf = fs::path(SUBLIFT_SHARED_DATA) / "gltf";

#define SKIP_WITHOUT_SHARED_DATA()                                                                   \
  if (!fs::is_directory(kGltf)) GTEST_SKIP() << "glTF samples not found at " << kGltf \
                                             << " (../shared/data absent)"

// --- small helpers: JSON files, base64 buffers --------------------------------------------------

nlohmann::json read_json(const fs::path& p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in);
}

std::string write_json(const TempDir& dir, const std::string& name, const nlohmann::json& j) {
  const std::string path = dir.file(name);
  std::ofstream(path) << j.dump(1);
  return path;
}

constexpr char kB64[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

std::string base64_encode(const std::string& in) {
  std::string out;
  for (std::size_t i = 0; i < in.size(); i += 3) {
    const std::size_t n = std::min<std::size_t>(3, in.size() - i);
    std::uint32_t v = 0;
    for (std::size_t k = 0; k < 3; ++k) v = v << 8 | (k < n ? static_cast<unsigned char>(in[i + k]) : 0u);
    for (std::size_t k = 0; k < 4; ++k) out.push_back(k <= n ? kB64[(v >> (18 - 6 * k)) & 63] : '=');
  }
  return out;
}

std::string base64_decode(const std::string& in) {
  std::string out;
  std::uint32_t v = 0;
  int bits = 0;
  for (char c : in) {
    const char* at = std::strchr(kB64, c);
    if (c == '=' || !at || !c) break;
    v = v << 6 | std::uint32_t(at - kB64);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<char>((v >> bits) & 0xff));
    }
  }
  return out;
}

// The bytes of buffer `b` of a glTF whose buffers are data URIs, and back.
std::string buffer_bytes(const nlohmann::json& j, int b) {
  const std::string uri = j["buffers"][b]["uri"];
  return base64_decode(uri.substr(uri.find(',') + 1));
}
void set_buffer_bytes(nlohmann::json& j, int b, const std::string& bytes) {
  j["buffers"][b]["uri"] = "data:application/octet-stream;base64," + base64_encode(bytes);
  j["buffers"][b]["byteLength"] = bytes.size();
}
void put_f32(std::string& bytes, std::size_t at, float f) { std::memcpy(bytes.data() + at, &f, 4); }
std::string f32_bytes(std::initializer_list<float> v) {
  std::string s(4 * v.size(), '\0');
  std::size_t i = 0;
  for (float f : v) put_f32(s, 4 * i++, f);
  return s;
}

// Expects `work` to throw an InputError naming `file` and containing every needle.
void expect_error(const std::function<void()>& work, const std::string& file, std::initializer_list<const char*> needles) {
  const std::string e = input_error(work);
  ASSERT_FALSE(e.empty()) << "no InputError (expected one naming " << file << ")";
  EXPECT_NE(e.find(file), std::string::npos) << e;
  for (const char* n : needles) EXPECT_NE(e.find(n), std::string::npos) << "'" << n << "' not in: " << e;
}

double frame_value(const FrameSet& f, std::size_t frame, std::size_t v, int axis) { return f.frame(frame)[3 * v + std::size_t(axis)]; }

// --- morph targets: AnimatedMorphCube and box-morph -------------------------------------------

// Weights of animation 0 at some of its 127 keys, read from accessor 10 (times) and 11 (weights,
// 2 per key) of AnimatedMorphCube.bin with python3 (box-morph.gltf embeds the same buffer).
struct MorphKey {
  std::size_t key;
  double w1, w2;
};
constexpr MorphKey kMorphKeys[] = {{0, 0.0, 0.0},
                                   {24, 0.5000002384185791, 0.0},
                                   {48, 0.9999999403953552, 0.0},
                                   {72, 0.500000536441803, 0.499999463558197},
                                   {102, 3.814697180359872e-08, 1.0},
                                   {114, 0.0, 0.5000039935112},
                                   {126, 0.0, -1.5258788721439487e-07}};
constexpr double kMorphEnd = 4.199997425079346;  // accessor 10's last key (its "max": 4.19999743)

class MorphCube : public ::testing::TestWithParam<const char*> {};

// Closed form. The node rotates by q = (0, 0.7071067, -0.7071068, 0) and scales by 100: R maps
// mesh (x, y, z) to world (-x, -z, -y), so a vertex of rest world position r has mesh y = -r.z /
// 100 and mesh z = -r.y / 100. Target 0 ("thin") moves every vertex of mesh y = -0.01 by
// +0.0189325 in mesh y; target 1 ("angle") those of mesh y = -0.01 and z = -0.01 by +0.0198908
// (accessors 4 and 7, read with python3). Mesh +y is world -z.
TEST_P(MorphCube, FramesAtKeysAreBasePlusWeightedTargets) {
  SKIP_WITHOUT_SHARED_DATA();
  const std::string path = (kGltf / GetParam()).string();
  const FrameSet f = sample_gltf_animation(path, 0, 127, false);
  const Shape shape = read_shape(path);
  ASSERT_EQ(f.num_vertices, shape.base.num_vertices);
  EXPECT_EQ(f.num_vertices, 8u);  // 24 file vertices, the cube's 8 corners
  EXPECT_EQ(f.rest_positions, shape.positions);
  EXPECT_EQ(f.faces.offsets, shape.base.faces.offsets);
  EXPECT_EQ(f.faces.items, shape.base.faces.items);
  ASSERT_EQ(f.num_frames(), 127u);
  ASSERT_EQ(f.positions.size(), 127u * 8 * 3);
  for (std::size_t i = 0; i < 127; ++i) EXPECT_EQ(f.times[i], 0.0 + double(i) * (kMorphEnd - 0.0) / 126.0) << i;
  for (const MorphKey& k : kMorphKeys) {
    SCOPED_TRACE("key " + std::to_string(k.key));
    for (std::size_t v = 0; v < 8; ++v) {
      const double* r = &f.rest_positions[3 * v];
      const double my = -r[2] / 100, mz = -r[1] / 100;
      ASSERT_NEAR(std::abs(my), 0.01, 1e-6);
      const double offset = (my < 0 ? k.w1 * 0.01893253 : 0.0) + (my < 0 && mz < 0 ? k.w2 * 0.0198908355 : 0.0);
      // Frame i's time is within 1e-6 s of key i (the keys are float sums of 1/30); the weights
      // move at most 1 per second, so 2e-5 covers it.
      EXPECT_NEAR(frame_value(f, k.key, v, 0), r[0], 2e-5);
      EXPECT_NEAR(frame_value(f, k.key, v, 1), r[1], 2e-5);
      EXPECT_NEAR(frame_value(f, k.key, v, 2), r[2] - 100 * offset, 2e-5) << "vertex " << v;
    }
  }
  // The bottom (world z = +1) moves by 100 * 0.0189 at key 48: motion is real.
  double most = 0;
  for (std::size_t v = 0; v < 8; ++v) most = std::max(most, std::abs(frame_value(f, 48, v, 2) - f.rest_positions[3 * v + 2]));
  EXPECT_NEAR(most, 1.893253, 1e-4);
}

// Vertices 0, 8 and 23 of box-morph share a position (python3: (-0.01, 0.01, 0.01)) and weld
// into one. Target 0 given an offset of +0.01 in mesh y on vertex 8 alone (its y at byte
// 1248 + 8 * 12 + 4 of the buffer, bufferView 4) makes that copy part from vertex 0 by 100 * 0.01
// * w1, most at key 48 (w1 = 0.99999994): a note says so, and the welded vertex keeps vertex 0's
// motion, so the frames are the unchanged file's.
TEST(GltfAnimation, WeldedCopiesThatPartAreNamed) {
  SKIP_WITHOUT_SHARED_DATA();
  TempDir dir("sublift_anim_parting");
  nlohmann::json j = read_json(kGltf / "misc/box-morph.gltf");
  std::string bytes = buffer_bytes(j, 0);
  put_f32(bytes, 1248 + 8 * 12 + 4, 0.01f);
  set_buffer_bytes(j, 0, bytes);
  const std::string path = write_json(dir, "parting.gltf", j);
  const FrameSet parted = sample_gltf_animation(path, 0, 127, false);
  const FrameSet plain = sample_gltf_animation((kGltf / "misc/box-morph.gltf").string(), 0, 127, false);
  EXPECT_EQ(parted.positions, plain.positions);
  std::string all;
  for (const std::string& n : parted.notes) all += n + "\n";
  EXPECT_NE(all.find("1 welded copies do not move with the vertex they were welded to (largest gap 1 at frame 48)"), std::string::npos) << all;
  for (const std::string& n : plain.notes) EXPECT_EQ(n.find("welded copies"), std::string::npos) << n;
  EXPECT_NE(std::find_if(plain.notes.begin(), plain.notes.end(), [](const std::string& n) { return n.find("other than POSITION") != std::string::npos; }),
            plain.notes.end()) << "the targets' NORMAL and TANGENT are named as not read";
}

TEST_P(MorphCube, CyclicLeavesOutTheEnd) {
  SKIP_WITHOUT_SHARED_DATA();
  const std::string path = (kGltf / GetParam()).string();
  const FrameSet open = sample_gltf_animation(path, -1, 127, false);
  const FrameSet loop = sample_gltf_animation(path, 0, 126, true);
  ASSERT_EQ(loop.num_frames(), 126u);
  for (std::size_t i = 0; i < 126; ++i) EXPECT_EQ(loop.times[i], double(i) * kMorphEnd / 126.0);
  EXPECT_EQ(open.times.back(), kMorphEnd);
  EXPECT_LT(loop.times.back(), kMorphEnd);
  // Same times, same frames.
  EXPECT_TRUE(std::equal(loop.positions.begin(), loop.positions.end(), open.positions.begin()));
  // Two frames: the start and the end; cyclic: the start and the middle.
  const FrameSet two = sample_gltf_animation(path, 0, 2, false), two_loop = sample_gltf_animation(path, 0, 2, true);
  EXPECT_EQ(two.times, (std::vector<double>{0.0, kMorphEnd}));
  EXPECT_EQ(two_loop.times, (std::vector<double>{0.0, kMorphEnd / 2}));
}

TEST_P(MorphCube, ListsItsAnimation) {
  SKIP_WITHOUT_SHARED_DATA();
  const auto list = gltf_animations((kGltf / GetParam()).string());
  ASSERT_EQ(list.size(), 1u);
  EXPECT_EQ(list[0].index, 0);
  EXPECT_EQ(list[0].name, "Square");
  EXPECT_EQ(list[0].start, 0.0);
  EXPECT_EQ(list[0].end, kMorphEnd);
  EXPECT_EQ(list[0].channels, 1);
  EXPECT_TRUE(list[0].morph_weights);
  EXPECT_FALSE(list[0].node_transforms);
}

INSTANTIATE_TEST_SUITE_P(GltfAnimation, MorphCube,
                         ::testing::Values("AnimatedMorphCube/AnimatedMorphCube.gltf", "misc/box-morph.gltf"),
                         [](const auto& info) { return std::string(info.index == 0 ? "AnimatedMorphCube" : "BoxMorph"); });

// --- skins: SimpleSkin -------------------------------------------------------------------------

// SimpleSkin.gltf, read with python3: 10 vertices (x in {0, 1}, y in {0, 0.5, 1, 1.5, 2}); joint 0
// is node 1 (translation (0, 1, 0)), joint 1 its child node 2 (rotation animated); both
// inverseBindMatrices are the translation (-0.5, -1, 0); WEIGHTS_0 of a vertex at height y is
// (1 - y / 2) on joint 0 and y / 2 on joint 1 (JOINTS_0 = 0 1 0 0). Animation 0 rotates node 2
// about z, keys every 0.5 s from 0 to 5.5 with quaternions (0, 0, qz, qw):
constexpr double kSkinKeys[12][2] = {{0, 1},         {0.383, 0.924}, {0.707, 0.707},   {0.707, 0.707},
                                     {0.383, 0.924}, {0, 1},         {0, 1},           {-0.383, 0.924},
                                     {-0.707, 0.707}, {-0.707, 0.707}, {-0.383, 0.924}, {0, 1}};

// The skin at angle `theta` about z by hand: joint 0's matrix is T(0, 1, 0) T(-0.5, -1, 0) =
// T(-0.5, 0, 0); joint 1's is T(0, 1, 0) Rz(theta) T(-0.5, -1, 0).
std::array<double, 3> simple_skin(const double* p, double theta, double w1 = -1) {
  if (w1 < 0) w1 = p[1] / 2;
  const double w0 = 1 - w1;
  const double x = p[0] - 0.5, y = p[1] - 1;
  const double c = std::cos(theta), s = std::sin(theta);
  return {w0 * (p[0] - 0.5) + w1 * (c * x - s * y), w0 * p[1] + w1 * (s * x + c * y + 1), p[2]};
}

TEST(GltfAnimation, SimpleSkinMatchesTheSkinByHand) {
  SKIP_WITHOUT_SHARED_DATA();
  const std::string path = (kGltf / "SimpleSkin/SimpleSkin.gltf").string();
  const FrameSet f = sample_gltf_animation(path, 0, 12, false);
  const Shape shape = read_shape(path);
  ASSERT_EQ(f.num_vertices, 10u);
  EXPECT_EQ(f.rest_positions, shape.positions);
  ASSERT_EQ(f.num_frames(), 12u);
  for (std::size_t i = 0; i < 12; ++i) {
    EXPECT_EQ(f.times[i], 0.5 * double(i));  // t_i = 5.5 i / 11, exact
    const double theta = 2 * std::atan2(kSkinKeys[i][0], kSkinKeys[i][1]);
    for (std::size_t v = 0; v < 10; ++v) {
      const auto want = simple_skin(&f.rest_positions[3 * v], theta);
      for (int a = 0; a < 3; ++a) EXPECT_NEAR(frame_value(f, i, v, a), want[std::size_t(a)], 1e-6) << "frame " << i << " vertex " << v;
    }
  }
  // The first key is the identity: every vertex at its stored position moved by the bind
  // matrices' -0.5 in x, exactly.
  for (std::size_t v = 0; v < 10; ++v) {
    EXPECT_EQ(frame_value(f, 0, v, 0), f.rest_positions[3 * v] - 0.5);
    EXPECT_EQ(frame_value(f, 0, v, 1), f.rest_positions[3 * v + 1]);
  }
  for (double x : f.positions) EXPECT_TRUE(std::isfinite(x));
}

// Between keys a rotation is the spec's slerp: a quarter of the way from the identity to key 1
// is a quarter of its angle (normalised lerp would give 0.0972 rad of the 0.3927, not 0.0982).
TEST(GltfAnimation, SimpleSkinSlerpsBetweenKeys) {
  SKIP_WITHOUT_SHARED_DATA();
  const std::string path = (kGltf / "SimpleSkin/SimpleSkin.gltf").string();
  const FrameSet f = sample_gltf_animation(path, 0, 45, false);  // t_i = 5.5 i / 44 = 0.125 i
  ASSERT_EQ(f.times[1], 0.125);
  const double theta = 0.25 * 2 * std::atan2(double(0.383f), double(0.924f));  // the file's floats
  for (std::size_t v = 0; v < 10; ++v) {
    const auto want = simple_skin(&f.rest_positions[3 * v], theta);
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(frame_value(f, 1, v, a), want[std::size_t(a)], 1e-9) << "vertex " << v;
  }
}

// Normalised unsigned byte WEIGHTS_0 are glTF (sec. 3.7.3.1): the same weights as bytes, 191 and
// 64 of 255 for a vertex at height 0.5, 128 and 127 at 1, ...; without "normalized" refused.
TEST(GltfAnimation, SimpleSkinTakesNormalisedByteWeights) {
  SKIP_WITHOUT_SHARED_DATA();
  TempDir dir("sublift_anim_ubyte_weights");
  nlohmann::json j = read_json(kGltf / "SimpleSkin/SimpleSkin.gltf");
  const unsigned char w1_of_row[5] = {0, 64, 127, 191, 255};  // joint 1's byte by height row
  std::string bytes;
  for (int v = 0; v < 10; ++v) bytes += std::string{char(255 - w1_of_row[v / 2]), char(w1_of_row[v / 2]), 0, 0};
  j["buffers"].push_back({{"byteLength", 40}, {"uri", "data:application/octet-stream;base64," + base64_encode(bytes)}});
  j["bufferViews"].push_back({{"buffer", 4}, {"byteLength", 40}});
  j["accessors"].push_back({{"bufferView", 5}, {"componentType", 5121}, {"normalized", true}, {"count", 10}, {"type", "VEC4"}});
  j["meshes"][0]["primitives"][0]["attributes"]["WEIGHTS_0"] = 7;
  const std::string path = write_json(dir, "ubyte.gltf", j);
  const FrameSet f = sample_gltf_animation(path, 0, 12, false);
  const double theta = 2 * std::atan2(double(0.707f), double(0.707f));
  for (std::size_t v = 0; v < 10; ++v) {
    const auto want = simple_skin(&f.rest_positions[3 * v], theta, w1_of_row[v / 2] / 255.0);
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(frame_value(f, 2, v, a), want[std::size_t(a)], 1e-6) << "vertex " << v;
  }
  j["accessors"][7].erase("normalized");
  const std::string plain = write_json(dir, "plain.gltf", j);
  expect_error([&] { sample_gltf_animation(plain, 0, 12, false); }, plain, {"accessor 7", "WEIGHTS_0", "normalized"});
}

// --- node transforms: Fox ------------------------------------------------------------------------

// Fox.glb, read with python3: animations Survey, Walk, Run, 21 channels each (rotation and
// translation, LINEAR), keys from 0 to these ends; one skinned mesh of 1728 vertices.
TEST(GltfAnimation, FoxSamplesEachAnimation) {
  SKIP_WITHOUT_SHARED_DATA();
  const std::string path = (kGltf / "Fox/Fox.glb").string();
  const auto list = gltf_animations(path);
  ASSERT_EQ(list.size(), 3u);
  const char* names[] = {"Survey", "Walk", "Run"};
  const double ends[] = {3.4166667461395264, 0.7083333134651184, 1.1583333015441895};
  const Shape shape = read_shape(path);
  ASSERT_EQ(shape.base.num_vertices, 290u);
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (std::size_t i = 0; i < shape.positions.size(); ++i) lo[i % 3] = std::min(lo[i % 3], shape.positions[i]), hi[i % 3] = std::max(hi[i % 3], shape.positions[i]);
  const double diag = std::hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
  const double centre[3] = {(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2};
  for (int a = 0; a < 3; ++a) {
    SCOPED_TRACE(names[a]);
    EXPECT_EQ(list[std::size_t(a)].name, names[a]);
    EXPECT_EQ(list[std::size_t(a)].start, 0.0);
    EXPECT_EQ(list[std::size_t(a)].end, ends[a]);
    EXPECT_EQ(list[std::size_t(a)].channels, 21);
    EXPECT_TRUE(list[std::size_t(a)].node_transforms);
    EXPECT_FALSE(list[std::size_t(a)].morph_weights);
    const FrameSet f = sample_gltf_animation(path, a, 16, true);
    ASSERT_EQ(f.num_vertices, 290u);
    ASSERT_EQ(f.num_frames(), 16u);
    EXPECT_EQ(f.times[15], 15 * ends[a] / 16);
    // read_shape's vertices in read_shape's order (its bind-pose positions), and its faces.
    EXPECT_EQ(f.rest_positions, shape.positions);
    EXPECT_EQ(f.faces.offsets, shape.base.faces.offsets);
    EXPECT_EQ(f.faces.items, shape.base.faces.items);
    double motion = 0, reach = 0;
    for (std::size_t fr = 0; fr < 16; ++fr)
      for (std::size_t v = 0; v < 290; ++v) {
        const double* p = &f.frame(fr)[3 * v];
        const double* q = &f.frame(0)[3 * v];
        ASSERT_TRUE(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]));
        motion = std::max(motion, std::hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]));
        reach = std::max(reach, std::hypot(p[0] - centre[0], p[1] - centre[1], p[2] - centre[2]));
      }
    EXPECT_GT(motion, 0.01 * diag) << "the animation moves the fox";
    EXPECT_LT(reach, 3 * diag) << "the posed fox stays near its bind pose";
  }
}

// --- STEP and CUBICSPLINE: a triangle translated in x ----------------------------------------

// A glTF built here: one triangle (0,0,0) (1,0,0) (0,1,0) on node 0, keys at 0, 1 and 3 s.
// Animation 0, STEP: x = 0, 2, 2 and y = 0, 0, 4. Animation 1, CUBICSPLINE on x: values 0, 1, 5
// with (in, out) tangents (0, 0), (0, 2), (2, 0) per second, so x(t) = 3t^2 - 2t^3 on [0, 1] (the
// smoothstep: zero slopes) and the line x = 2t - 1 on [1, 3] (Hermite reproduces a line when
// both slopes are its slope; only if tangents are scaled by the 2 s interval).
std::string translated_triangle(const TempDir& dir) {
  const std::string bytes = f32_bytes({0, 0, 0, 1, 0, 0, 0, 1, 0,                     // positions, 36
                                       0, 1, 3,                                        // times, 12
                                       0, 0, 0, 2, 0, 0, 2, 4, 0,                      // STEP, 36
                                       0, 0, 0, 0, 0, 0, 0, 0, 0,                      // cubic key 0: in, value, out
                                       0, 0, 0, 1, 0, 0, 2, 0, 0,                      // key 1
                                       2, 0, 0, 5, 0, 0, 0, 0, 0});                    // key 2
  nlohmann::json j = {
      {"asset", {{"version", "2.0"}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}}}}}}},
      {"buffers", {{{"byteLength", bytes.size()}, {"uri", "data:application/octet-stream;base64," + base64_encode(bytes)}}}},
      {"bufferViews", {{{"buffer", 0}, {"byteLength", 36}}, {{"buffer", 0}, {"byteOffset", 36}, {"byteLength", 12}},
                       {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 36}}, {{"buffer", 0}, {"byteOffset", 84}, {"byteLength", 108}}}},
      {"accessors", {{{"bufferView", 0}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}, {"min", {0, 0, 0}}, {"max", {1, 1, 0}}},
                     {{"bufferView", 1}, {"componentType", 5126}, {"count", 3}, {"type", "SCALAR"}, {"min", {0}}, {"max", {3}}},
                     {{"bufferView", 2}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}},
                     {{"bufferView", 3}, {"componentType", 5126}, {"count", 9}, {"type", "VEC3"}}}},
      {"animations",
       {{{"name", "step"},
         {"samplers", {{{"input", 1}, {"output", 2}, {"interpolation", "STEP"}}}},
         {"channels", {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "translation"}}}}}}},
        {{"name", "cubic"},
         {"samplers", {{{"input", 1}, {"output", 3}, {"interpolation", "CUBICSPLINE"}}}},
         {"channels", {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "translation"}}}}}}}}}};
  return write_json(dir, "triangle.gltf", j);
}

TEST(GltfAnimation, StepAndCubicSplineTranslations) {
  TempDir dir("sublift_anim_triangle");
  const std::string path = translated_triangle(dir);
  const auto list = gltf_animations(path);
  ASSERT_EQ(list.size(), 2u);
  EXPECT_EQ(list[1].name, "cubic");
  EXPECT_EQ(list[1].end, 3.0);
  const FrameSet step = sample_gltf_animation(path, 0, 13, false);  // t = 0, 0.25, ..., 3
  const FrameSet cubic = sample_gltf_animation(path, 1, 13, false);
  ASSERT_EQ(step.num_vertices, 3u);
  EXPECT_EQ(step.rest_positions, (std::vector<double>{0, 0, 0, 1, 0, 0, 0, 1, 0}));
  for (std::size_t i = 0; i < 13; ++i) {
    const double t = 0.25 * double(i);
    ASSERT_EQ(step.times[i], t);
    const double sx = t < 1 ? 0 : 2, sy = t < 3 ? 0 : 4;
    const double cx = t <= 1 ? 3 * t * t - 2 * t * t * t : 2 * t - 1;
    for (std::size_t v = 0; v < 3; ++v) {
      EXPECT_EQ(frame_value(step, i, v, 0), step.rest_positions[3 * v] + sx) << "t " << t;
      EXPECT_EQ(frame_value(step, i, v, 1), step.rest_positions[3 * v + 1] + sy) << "t " << t;
      EXPECT_NEAR(frame_value(cubic, i, v, 0), cubic.rest_positions[3 * v] + cx, 1e-12) << "t " << t;
      EXPECT_EQ(frame_value(cubic, i, v, 1), cubic.rest_positions[3 * v + 1]);
    }
  }
}

// --- frame sequences ---------------------------------------------------------------------------

std::string write_text(const TempDir& dir, const std::string& name, const std::string& text) {
  std::ofstream(dir.file(name)) << text;
  return dir.file(name);
}

// A square of two triangles, its top edge raised by `h`.
std::string square(double h, const std::string& last_face = "f 1 3 4") {
  return "v 0 0 0\nv 1 0 0\nv 1 1 " + std::to_string(h) + "\nv 0 1 " + std::to_string(h) + "\nf 1 2 3\n" + last_face + "\n";
}

TEST(FrameSequence, ReadsObjFramesBackExactly) {
  TempDir dir("sublift_anim_sequence");
  const std::vector<std::string> paths = {write_text(dir, "frame0.obj", square(0)), write_text(dir, "frame1.obj", square(0.5)),
                                          write_text(dir, "frame2.obj", square(1.25))};
  const FrameSet f = read_frame_sequence(paths, 24);
  EXPECT_EQ(f.source, paths[0]);
  ASSERT_EQ(f.num_vertices, 4u);
  ASSERT_EQ(f.num_frames(), 3u);
  EXPECT_EQ(f.times, (std::vector<double>{0.0, 1.0 / 24, 2.0 / 24}));
  EXPECT_EQ(f.faces.offsets, (std::vector<std::uint32_t>{0, 3, 6}));
  EXPECT_EQ(f.faces.items, (std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3}));
  const double h[3] = {0, 0.5, 1.25};
  for (std::size_t fr = 0; fr < 3; ++fr)
    EXPECT_EQ(std::vector<double>(f.frame(fr).begin(), f.frame(fr).end()),
              (std::vector<double>{0, 0, 0, 1, 0, 0, 1, 1, h[fr], 0, 1, h[fr]}));
  EXPECT_EQ(f.rest_positions, std::vector<double>(f.frame(0).begin(), f.frame(0).end()));
}

TEST(FrameSequence, ColoursAreNamedAsNotKept) {
  TempDir dir("sublift_anim_sequence_colours");
  const std::string coloured = "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 1 1 0 0 0 1\nv 0 1 0 1 1 1\nf 1 2 3\nf 1 3 4\n";
  const std::vector<std::string> paths = {write_text(dir, "a0.obj", coloured), write_text(dir, "a1.obj", coloured)};
  const FrameSet f = read_frame_sequence(paths, 30);
  std::string all;
  for (const std::string& n : f.notes) all += n + "\n";
  EXPECT_NE(all.find("not kept"), std::string::npos) << all;
  EXPECT_NE(all.find("red"), std::string::npos) << all;
  EXPECT_NE(all.find("and 1 other files"), std::string::npos) << all;
}

TEST(FrameSequence, DifferentConnectivityIsNamed) {
  TempDir dir("sublift_anim_sequence_bad");
  const std::string f0 = write_text(dir, "frame0.obj", square(0)), f1 = write_text(dir, "frame1.obj", square(0.5));
  const std::string other_face = write_text(dir, "frame2.obj", square(1, "f 2 4 3"));
  const std::string five = write_text(dir, "frame3.obj", square(1) + "v 2 2 2\nf 2 5 3\n");
  const std::string fewer = write_text(dir, "frame4.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\n");
  {
    const std::vector<std::string> p = {f0, f1, other_face};
    expect_error([&] { read_frame_sequence(p, 24); }, other_face, {"face 1 is 1 3 2 here but 0 2 3 in frame0.obj"});
  }
  {
    const std::vector<std::string> p = {f0, five};
    expect_error([&] { read_frame_sequence(p, 24); }, five, {"5 vertices here but 4 in frame0.obj"});
  }
  {
    const std::vector<std::string> p = {f0, fewer};
    expect_error([&] { read_frame_sequence(p, 24); }, fewer, {"1 faces here but 2 in frame0.obj"});
  }
  const std::vector<std::string> one = {f0}, two = {f0, f1};
  expect_error([&] { read_frame_sequence(one, 24); }, f0, {"at least 2 files, not 1"});
  expect_error([&] { read_frame_sequence({}, 24); }, "frame sequence", {"at least 2 files, not 0"});
  for (double fps : {0.0, -1.0, std::nan(""), std::numeric_limits<double>::infinity()}) expect_error([&] { read_frame_sequence(two, fps); }, f0, {"frames per second"});
}

// --- bad inputs ----------------------------------------------------------------------------------

class BadAnimation : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::is_directory(kGltf)) GTEST_SKIP() << "glTF samples not found at " << kGltf << " (../shared/data absent)";
    morph = read_json(kGltf / "misc/box-morph.gltf");
    skin = read_json(kGltf / "SimpleSkin/SimpleSkin.gltf");
  }
  // Writes `j` and expects sampling it to throw naming the copy and every needle.
  void expect_refused(const nlohmann::json& j, const std::string& name, std::initializer_list<const char*> needles, int frames = 8) {
    SCOPED_TRACE(name);
    const std::string path = write_json(dir, name, j);
    expect_error([&] { sample_gltf_animation(path, 0, frames, false); }, path, needles);
  }
  // One folder per test: ctest runs them in parallel.
  TempDir dir{std::string("sublift_anim_bad_") + ::testing::UnitTest::GetInstance()->current_test_info()->name()};
  nlohmann::json morph, skin;
};

TEST_F(BadAnimation, SamplerInputs) {
  // box-morph's keys live at byte 2760 of its buffer (bufferView 10): key 5 moved before key 4.
  nlohmann::json j = morph;
  std::string bytes = buffer_bytes(j, 0);
  put_f32(bytes, 2760 + 4 * 5, 0.1f);
  set_buffer_bytes(j, 0, bytes);
  expect_refused(j, "decreasing.gltf", {"animation 0 sampler 0", "not strictly increasing", "key 5"});
  bytes = buffer_bytes(morph, 0);
  put_f32(bytes, 2760 + 4 * 7, NAN);
  set_buffer_bytes(j, 0, bytes);
  expect_refused(j, "nan_key.gltf", {"accessor 10", "input of animation 0 sampler 0", "element 7", "not finite"});
  j = morph;
  j["accessors"][10]["componentType"] = 5123;  // unsigned short keys: 254 bytes, fit in the view
  expect_refused(j, "short_keys.gltf", {"accessor 10", "input of animation 0 sampler 0", "componentType 5123"});
  j = morph;
  j["accessors"][10]["type"] = "VEC2";
  j["accessors"][10]["count"] = 63;
  expect_refused(j, "vec2_keys.gltf", {"accessor 10", "input of animation 0 sampler 0", "type is VEC2"});
  j = morph;
  j["animations"][0]["samplers"][0]["interpolation"] = "SMOOTH";
  expect_refused(j, "smooth.gltf", {"animation 0 sampler 0", "SMOOTH"});
}

TEST_F(BadAnimation, OutputCounts) {
  nlohmann::json j = morph;
  j["accessors"][11]["count"] = 253;
  expect_refused(j, "count.gltf", {"animation 0 channel 0", "sampler 0", "accessor 11", "253 weights for 127 keys"});
  j = morph;
  j["animations"][0]["samplers"][0]["interpolation"] = "CUBICSPLINE";
  expect_refused(j, "cubic.gltf", {"animation 0 channel 0", "254 weights for 127 keys", "CUBICSPLINE"});
  j = skin;
  j["accessors"][6]["count"] = 11;
  expect_refused(j, "rotation_count.gltf", {"animation 0 sampler 0", "accessor 6", "11 elements for 12 keys"});
}

TEST_F(BadAnimation, Channels) {
  nlohmann::json j = morph;
  j["animations"][0]["channels"][0]["target"]["node"] = 5;
  expect_refused(j, "node.gltf", {"animation 0 channel 0", "target node 5 does not exist"});
  j = morph;
  j["animations"][0]["channels"][0]["sampler"] = 3;
  expect_refused(j, "sampler.gltf", {"animation 0 channel 0", "sampler 3 does not exist"});
  j = morph;
  j["animations"][0]["channels"].push_back(j["animations"][0]["channels"][0]);
  expect_refused(j, "twice.gltf", {"animation 0 channel 1", "earlier channel"});
  // The mesh keeps one of its two targets: the channel's 2 weights per key no longer match.
  j = morph;
  j["meshes"][0]["primitives"][0]["targets"].erase(1);
  j["meshes"][0]["weights"] = {0};
  expect_refused(j, "weights_count.gltf", {"animation 0 channel 0", "2 per key", "1 morph targets"});
  j = morph;
  j["meshes"][0]["primitives"][0].erase("targets");
  j["meshes"][0].erase("weights");
  expect_refused(j, "no_targets.gltf", {"animation 0 channel 0", "no mesh with morph targets"});
  j = skin;
  j["nodes"][2]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  j["nodes"][2].erase("rotation");
  expect_refused(j, "matrix.gltf", {"animation 0 channel 0", "node 2 has a matrix"});
}

TEST_F(BadAnimation, Skins) {
  nlohmann::json j = skin;
  j["skins"][0]["joints"] = {1};  // JOINTS_0 names joint 1 of a skin of one joint
  expect_refused(j, "joints.gltf", {"accessor 2", "JOINTS_0 of mesh 0 primitive 0", "element 0 names joint 1", "1 joints"});
  // WEIGHTS_0 sit at byte 160 of buffer 1: vertex 0's (1, 0, 0, 0) becomes all zero.
  j = skin;
  std::string bytes = buffer_bytes(j, 1);
  put_f32(bytes, 160, 0.0f);
  set_buffer_bytes(j, 1, bytes);
  expect_refused(j, "zero_weights.gltf", {"accessor 3", "WEIGHTS_0", "element 0 sum to 0"});
  put_f32(bytes, 160, INFINITY);
  set_buffer_bytes(j, 1, bytes);
  expect_refused(j, "inf_weights.gltf", {"accessor 3", "not finite"});
  j = skin;
  j["accessors"][4]["count"] = 1;
  expect_refused(j, "bind.gltf", {"accessor 4", "inverseBindMatrices of skin 0", "1 matrices for 2 joints"});
  j = skin;
  j["accessors"][2]["componentType"] = 5126;  // float joints: 160 bytes, fit in the view
  expect_refused(j, "float_joints.gltf", {"accessor 2", "JOINTS_0", "not unsigned byte or unsigned short"});
}

TEST_F(BadAnimation, AnimationAndFrames) {
  nlohmann::json j = morph;
  j.erase("animations");
  expect_refused(j, "none.gltf", {"has no animation"});
  const std::string path = (kGltf / "misc/box-morph.gltf").string();
  expect_error([&] { sample_gltf_animation(path, 1, 8, false); }, path, {"animation 1 does not exist", "the file has 1"});
  expect_error([&] { sample_gltf_animation(path, -2, 8, false); }, path, {"animation -2 does not exist"});
  expect_error([&] { sample_gltf_animation(path, 0, 1, false); }, path, {"2 frames or more, not 1"});
  j = morph;
  j["accessors"][10]["count"] = 1;  // one key: no time to sample
  j["accessors"][11]["count"] = 2;
  expect_refused(j, "one_key.gltf", {"animation 0", "span no time"});
  // gltf_animations validates as sampling does.
  j = morph;
  j["accessors"][11]["count"] = 253;
  const std::string bad = write_json(dir, "listed.gltf", j);
  expect_error([&] { gltf_animations(bad); }, bad, {"animation 0 channel 0", "253 weights"});
}

}  // namespace
