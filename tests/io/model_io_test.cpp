// Model import/export for FFD (core/io/model/model.h): glTF round trips on the shared sample models
// (deform by a known map, export, re-import: positions moved, everything else unchanged, checked
// against the test's own reading of the files with plain tinygltf), the invalid and hostile glTF
// corpus, the file-access lock-down, refusals, and OBJ/PLY/OFF rewrites of the original bytes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <tiny_gltf.h>

#include "core/base/errors.h"
#include "core/base/file_io.h"
#include "core/io/model/model.h"
#include "tests/io_test_util.h"
#include "tests/test_util.h"

namespace {

namespace fs = std::filesystem;
using namespace sublift;
using sublift::testing::TempDir;

const fs::path kShared = SUBLIFT_SHARED_DATA;
const fs::path kGltf = kShared / "gltf";
const fs::path kAssets = SUBLIFT_ASSETS_DIR;

#define REQUIRE_DIR(dir) \
  if (!fs::is_directory(dir)) GTEST_SKIP() << (dir) << " not found (../shared/data absent): skipping"

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void spit(const fs::path& p, const std::string& bytes) {
  std::ofstream out(p, std::ios::binary);
  out << bytes;
}

using sublift::testing::error_text;  // the message of the sublift::Error a call throws ("" when none)

double bbox_diagonal(const std::vector<double>& p) {
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (std::size_t i = 0; i < p.size(); ++i) {
    lo[i % 3] = std::min(lo[i % 3], p[i]);
    hi[i % 3] = std::max(hi[i % 3], p[i]);
  }
  return std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

// The known non-trivial edit: p -> p + (0.1 y, 0, 0.05 x z / L), L the bounding-box diagonal.
std::vector<double> deform(const std::vector<double>& p) {
  const double L = bbox_diagonal(p);
  std::vector<double> q = p;
  for (std::size_t v = 0; v < p.size() / 3; ++v) {
    const double x = p[3 * v], y = p[3 * v + 1], z = p[3 * v + 2];
    q[3 * v] = x + 0.1 * y;
    q[3 * v + 2] = z + 0.05 * x * z / L;
  }
  return q;
}

// ---- The test's own glTF reading: plain tinygltf on trusted files, images not decoded.
bool no_decode(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) { return true; }

tinygltf::Model load_plain(const fs::path& p) {
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(&no_decode, nullptr);
  tinygltf::Model m;
  std::string err, warn;
  const bool ok = p.extension() == ".glb" ? loader.LoadBinaryFromFile(&m, &err, &warn, p.string())
                                          : loader.LoadASCIIFromFile(&m, &err, &warn, p.string());
  EXPECT_TRUE(ok) << p << ": " << err;
  return m;
}

struct Span {
  const tinygltf::Buffer* buffer;
  std::size_t base, stride, elem, count;
};

Span span_of(const tinygltf::Model& m, int acc) {
  const tinygltf::Accessor& a = m.accessors.at(std::size_t(acc));
  const tinygltf::BufferView& v = m.bufferViews.at(std::size_t(a.bufferView));
  const std::size_t elem = std::size_t(tinygltf::GetComponentSizeInBytes(std::uint32_t(a.componentType))) *
                           std::size_t(tinygltf::GetNumComponentsInType(std::uint32_t(a.type)));
  Span s{&m.buffers.at(std::size_t(v.buffer)), v.byteOffset + a.byteOffset, v.byteStride ? v.byteStride : elem, elem, a.count};
  EXPECT_LE(s.base + (s.count - 1) * s.stride + elem, s.buffer->data.size());
  return s;
}

std::vector<unsigned char> element_bytes(const tinygltf::Model& m, int acc) {
  const Span s = span_of(m, acc);
  std::vector<unsigned char> out;
  for (std::size_t i = 0; i < s.count; ++i) {
    const unsigned char* p = s.buffer->data.data() + s.base + i * s.stride;
    out.insert(out.end(), p, p + s.elem);
  }
  return out;
}

std::vector<float> floats(const tinygltf::Model& m, int acc) {
  const std::vector<unsigned char> b = element_bytes(m, acc);
  std::vector<float> f(b.size() / 4);
  std::memcpy(f.data(), b.data(), f.size() * 4);
  return f;
}

std::vector<std::uint32_t> indices(const tinygltf::Model& m, const tinygltf::Primitive& p, std::size_t nv) {
  std::vector<std::uint32_t> out;
  if (p.indices < 0) {
    for (std::uint32_t i = 0; i < nv; ++i) out.push_back(i);
    return out;
  }
  const std::vector<unsigned char> b = element_bytes(m, p.indices);
  const int cs = tinygltf::GetComponentSizeInBytes(std::uint32_t(m.accessors[std::size_t(p.indices)].componentType));
  for (std::size_t i = 0; i < b.size(); i += std::size_t(cs)) {
    std::uint32_t v = 0;
    std::memcpy(&v, &b[i], std::size_t(cs));
    out.push_back(v);
  }
  return out;
}

// Accessors that are some primitive's POSITION or NORMAL (the only data export may change).
std::set<int> rewritable(const tinygltf::Model& m) {
  std::set<int> out;
  for (const auto& mesh : m.meshes)
    for (const auto& p : mesh.primitives)
      for (const char* name : {"POSITION", "NORMAL"})
        if (p.attributes.count(name)) out.insert(p.attributes.at(name));
  return out;
}

// ---- glTF round trips on the shared sample models.
struct GltfCase {
  std::string name, source, output;
  std::size_t vertices, triangles;  // independently known (MANIFEST.md: raw verts, triangles)
};

void PrintTo(const GltfCase& c, std::ostream* os) { *os << c.name; }

class GltfRoundTrip : public ::testing::TestWithParam<GltfCase> {};

TEST_P(GltfRoundTrip, DeformExportReimportKeepsEverythingButPositionsAndNormals) {
  REQUIRE_DIR(kGltf);
  const GltfCase& c = GetParam();
  const fs::path src = kGltf / c.source;
  const Model m = import_model(src.string());
  EXPECT_EQ(m.num_vertices(), c.vertices);
  EXPECT_EQ(m.faces.rows(), c.triangles);
  ASSERT_EQ(m.normals.size(), m.positions.size());

  TempDir dir("sublift_model_io_" + c.name);
  const std::string out = dir.file(c.output);
  fs::create_directories(fs::path(out).parent_path());
  const std::vector<double> moved = deform(m.positions);
  export_model(m, moved, out);

  // Re-import: the deformed positions (to float precision), the same triangles.
  const Model back = import_model(out);
  ASSERT_EQ(back.positions.size(), moved.size());
  const double tol = 1e-6 * bbox_diagonal(m.positions);
  for (std::size_t i = 0; i < moved.size(); ++i) ASSERT_NEAR(back.positions[i], moved[i], tol) << "coordinate " << i;
  EXPECT_EQ(back.faces.offsets, m.faces.offsets);
  EXPECT_EQ(back.faces.items, m.faces.items);

  // Everything but POSITION and NORMAL data is as it was.
  const tinygltf::Model a = load_plain(src), b = load_plain(out);
  EXPECT_TRUE(a.nodes == b.nodes);
  EXPECT_TRUE(a.scenes == b.scenes);
  EXPECT_TRUE(a.meshes == b.meshes);
  EXPECT_TRUE(a.materials == b.materials);
  EXPECT_TRUE(a.textures == b.textures);
  EXPECT_TRUE(a.samplers == b.samplers);
  EXPECT_TRUE(a.skins == b.skins);
  EXPECT_TRUE(a.animations == b.animations);
  EXPECT_TRUE(a.bufferViews == b.bufferViews);
  const std::set<int> written = rewritable(a);
  ASSERT_EQ(a.accessors.size(), b.accessors.size());
  for (std::size_t i = 0; i < a.accessors.size(); ++i) {
    tinygltf::Accessor x = a.accessors[i], y = b.accessors[i];
    if (written.count(int(i))) x.minValues = y.minValues, x.maxValues = y.maxValues;
    EXPECT_TRUE(x == y) << "accessor " << i;
  }
  // Buffer bytes: identical outside the POSITION/NORMAL elements.
  ASSERT_EQ(a.buffers.size(), b.buffers.size());
  std::vector<std::vector<char>> mask(a.buffers.size());
  for (std::size_t i = 0; i < a.buffers.size(); ++i) {
    ASSERT_EQ(a.buffers[i].data.size(), b.buffers[i].data.size()) << "buffer " << i;
    mask[i].assign(a.buffers[i].data.size(), 0);
  }
  for (int acc : written) {
    const Span s = span_of(a, acc);
    const std::size_t buf = std::size_t(s.buffer - a.buffers.data());
    for (std::size_t e = 0; e < s.count; ++e) std::fill_n(mask[buf].begin() + std::ptrdiff_t(s.base + e * s.stride), s.elem, 1);
  }
  std::size_t changed_inside = 0;
  for (std::size_t i = 0; i < a.buffers.size(); ++i)
    for (std::size_t k = 0; k < a.buffers[i].data.size(); ++k) {
      if (!mask[i][k]) {
        ASSERT_EQ(a.buffers[i].data[k], b.buffers[i].data[k]) << "buffer " << i << " byte " << k;
      } else {
        changed_inside += a.buffers[i].data[k] != b.buffers[i].data[k];
      }
    }
  EXPECT_GT(changed_inside, 0u) << "the deformation must change POSITION bytes";
  // Explicitly: UVs and index buffers, byte for byte.
  for (const auto& mesh : a.meshes)
    for (const auto& p : mesh.primitives) {
      if (p.attributes.count("TEXCOORD_0")) {
        EXPECT_EQ(element_bytes(a, p.attributes.at("TEXCOORD_0")), element_bytes(b, p.attributes.at("TEXCOORD_0")));
      }
      if (p.indices >= 0) {
        EXPECT_EQ(element_bytes(a, p.indices), element_bytes(b, p.indices));
      }
    }
  // Images: the same ones, external files present beside the output with the same bytes.
  ASSERT_EQ(a.images.size(), b.images.size());
  for (std::size_t i = 0; i < a.images.size(); ++i) {
    EXPECT_EQ(a.images[i].uri, b.images[i].uri);
    EXPECT_EQ(a.images[i].bufferView, b.images[i].bufferView);
    if (!a.images[i].uri.empty()) {
      const fs::path copy = fs::path(out).parent_path() / b.images[i].uri;
      ASSERT_TRUE(fs::exists(copy)) << copy;
      EXPECT_EQ(slurp(copy), slurp(src.parent_path() / a.images[i].uri));
    }
  }
}

TEST_P(GltfRoundTrip, IdentityExportKeepsPositionBytes) {
  REQUIRE_DIR(kGltf);
  const GltfCase& c = GetParam();
  const fs::path src = kGltf / c.source;
  const Model m = import_model(src.string());
  TempDir dir("sublift_model_id_" + c.name);
  const std::string out = dir.file(c.output);
  fs::create_directories(fs::path(out).parent_path());
  export_model(m, m.positions, out);
  const tinygltf::Model a = load_plain(src), b = load_plain(out);
  for (const auto& mesh : a.meshes)
    for (const auto& p : mesh.primitives) {
      const int pos = p.attributes.at("POSITION");
      EXPECT_EQ(element_bytes(a, pos), element_bytes(b, pos));
      EXPECT_EQ(a.accessors[std::size_t(pos)].minValues, b.accessors[std::size_t(pos)].minValues);
      EXPECT_EQ(a.accessors[std::size_t(pos)].maxValues, b.accessors[std::size_t(pos)].maxValues);
    }
  const Model back = import_model(out);
  EXPECT_EQ(back.positions, m.positions);
}

INSTANTIATE_TEST_SUITE_P(
    SharedModels, GltfRoundTrip,
    ::testing::Values(GltfCase{"BoxGlb", "Box/Box.glb", "out.glb", 24, 12},
                      GltfCase{"BoxEmbedded", "Box/Box_embedded.gltf", "out.gltf", 24, 12},
                      GltfCase{"BoxTexturedGltf", "BoxTextured/BoxTextured.gltf", "out.gltf", 24, 12},
                      GltfCase{"BoxTexturedGltfToGlb", "BoxTextured/BoxTextured.gltf", "out.glb", 24, 12},
                      GltfCase{"BoxTexturedGlb", "BoxTextured/BoxTextured.glb", "out.glb", 24, 12},
                      GltfCase{"BoxTexturedGlbToGltf", "BoxTextured/BoxTextured.glb", "sub/out.gltf", 24, 12},
                      GltfCase{"FoxGlb", "Fox/Fox.glb", "out.glb", 1728, 576},
                      GltfCase{"SimpleSkin", "SimpleSkin/SimpleSkin.gltf", "out.gltf", 10, 8}),
    [](const ::testing::TestParamInfo<GltfCase>& i) { return i.param.name; });

TEST(GltfModel, BoxWorldPositionsAreTheNodeMatrixAppliedToTheMeshData) {
  REQUIRE_DIR(kGltf);
  const fs::path src = kGltf / "Box" / "Box.glb";
  const Model m = import_model(src.string());
  const tinygltf::Model a = load_plain(src);
  const std::vector<float> p = floats(a, a.meshes[0].primitives[0].attributes.at("POSITION"));
  const std::vector<float> n = floats(a, a.meshes[0].primitives[0].attributes.at("NORMAL"));
  ASSERT_EQ(p.size(), m.positions.size());
  // Node 0's column-major matrix [1,0,0,0, 0,0,-1,0, 0,1,0,0, 0,0,0,1] maps (x, y, z) to (x, z, -y).
  for (std::size_t v = 0; v < p.size() / 3; ++v) {
    EXPECT_EQ(m.positions[3 * v], p[3 * v]);
    EXPECT_EQ(m.positions[3 * v + 1], p[3 * v + 2]);
    EXPECT_EQ(m.positions[3 * v + 2], -p[3 * v + 1]);
    EXPECT_NEAR(m.normals[3 * v], n[3 * v], 1e-7);
    EXPECT_NEAR(m.normals[3 * v + 1], n[3 * v + 2], 1e-7);
    EXPECT_NEAR(m.normals[3 * v + 2], -n[3 * v + 1], 1e-7);
  }
  ASSERT_EQ(m.ranges.size(), 1u);
  EXPECT_EQ(m.ranges[0].node, 1);
  // Display normals recomputed from the (flat) faces agree with the file's.
  const std::vector<double> again = model_normals(m, m.positions);
  for (std::size_t i = 0; i < again.size(); ++i) EXPECT_NEAR(again[i], m.normals[i], 1e-12);
}

TEST(GltfModel, BoxIdentityExportWritesTheSameBuffer) {
  REQUIRE_DIR(kGltf);
  const fs::path src = kGltf / "Box" / "Box.glb";
  const Model m = import_model(src.string());
  TempDir dir("sublift_model_box_identity");
  export_model(m, m.positions, dir.file("same.glb"));
  EXPECT_TRUE(load_plain(src).buffers == load_plain(dir.file("same.glb")).buffers);
}

TEST(GltfModel, ExportedNormalsAreTheUnitAreaWeightedNormalsOfTheDeformedBox) {
  REQUIRE_DIR(kGltf);
  const fs::path src = kGltf / "Box" / "Box.glb";
  const Model m = import_model(src.string());
  TempDir dir("sublift_model_box_normals");
  export_model(m, deform(m.positions), dir.file("d.glb"));
  const tinygltf::Model a = load_plain(src), b = load_plain(dir.file("d.glb"));
  const auto& prim = b.meshes[0].primitives[0];
  const std::vector<float> p = floats(b, prim.attributes.at("POSITION"));
  const std::vector<float> n = floats(b, prim.attributes.at("NORMAL"));
  const std::vector<float> n0 = floats(a, prim.attributes.at("NORMAL"));
  const std::vector<std::uint32_t> idx = indices(b, prim, p.size() / 3);
  // The box's 24 vertices are 8 corners split by face, so each vertex's normal is the normalised
  // sum of the cross products of its own face's triangles (hard edges stay hard).
  std::vector<double> sum(p.size(), 0.0);
  for (std::size_t t = 0; t + 2 < idx.size(); t += 3) {
    const float* a0 = &p[3 * idx[t]];
    const float* a1 = &p[3 * idx[t + 1]];
    const float* a2 = &p[3 * idx[t + 2]];
    const double e1[3] = {double(a1[0]) - a0[0], double(a1[1]) - a0[1], double(a1[2]) - a0[2]};
    const double e2[3] = {double(a2[0]) - a0[0], double(a2[1]) - a0[1], double(a2[2]) - a0[2]};
    const double c[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    for (int k = 0; k < 3; ++k)
      for (std::size_t j = 0; j < 3; ++j) sum[3 * idx[t + j] + std::size_t(k)] += c[k];
  }
  std::size_t changed = 0;
  for (std::size_t v = 0; v < p.size() / 3; ++v) {
    const double len = std::sqrt(sum[3 * v] * sum[3 * v] + sum[3 * v + 1] * sum[3 * v + 1] + sum[3 * v + 2] * sum[3 * v + 2]);
    const double nl = std::sqrt(double(n[3 * v]) * n[3 * v] + double(n[3 * v + 1]) * n[3 * v + 1] + double(n[3 * v + 2]) * n[3 * v + 2]);
    EXPECT_NEAR(nl, 1.0, 1e-6);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(n[3 * v + std::size_t(k)], sum[3 * v + std::size_t(k)] / len, 1e-6) << "vertex " << v;
    changed += std::abs(n[3 * v] - n0[3 * v]) + std::abs(n[3 * v + 1] - n0[3 * v + 1]) + std::abs(n[3 * v + 2] - n0[3 * v + 2]) > 1e-3;
  }
  EXPECT_GT(changed, 0u);
}

TEST(GltfModel, SkinnedModelsUseTheBindPoseAsStoredAndSayWhy) {
  REQUIRE_DIR(kGltf);
  const fs::path src = kGltf / "Fox" / "Fox.glb";
  const Model m = import_model(src.string());
  const tinygltf::Model a = load_plain(src);
  EXPECT_EQ(floats(a, 0), std::vector<float>(m.positions.begin(), m.positions.end()));
  ASSERT_EQ(m.ranges.size(), 1u);
  EXPECT_TRUE(m.ranges[0].skinned);
  EXPECT_TRUE(std::any_of(m.notes.begin(), m.notes.end(), [](const std::string& n) { return n.find("skinned") != std::string::npos; }));
}

TEST(GltfModel, InvalidModelsFailWithMessagesNamingFileAndElement) {
  const fs::path dir = kGltf / "invalid";
  REQUIRE_DIR(dir);
  const std::string one = error_text([&] { import_model((dir / "IndexOutOfRange.gltf").string()); });
  EXPECT_NE(one.find("IndexOutOfRange.gltf"), std::string::npos) << one;
  EXPECT_NE(one.find("accessor 0 (indices of mesh 0 primitive 0): index 255 >= 24 vertices"), std::string::npos) << one;
  const std::string all = error_text([&] { import_model((dir / "AllIndicesOutOfRange.gltf").string()); });
  EXPECT_NE(all.find("AllIndicesOutOfRange.gltf"), std::string::npos) << all;
  EXPECT_NE(all.find(">= 24 vertices"), std::string::npos) << all;
  const std::string inf = error_text([&] { import_model((dir / "BoxWithInfinites.glb").string()); });
  EXPECT_NE(inf.find("BoxWithInfinites.glb"), std::string::npos) << inf;
  EXPECT_NE(inf.find("accessor 2 (POSITION of mesh 0 primitive 0): element 0 component 0 is not finite"), std::string::npos) << inf;
}

// The shared hostile corpus: controls and files whose fault is harmless to FFD load (with notes
// where something was skipped); everything else is refused with the file's name; nothing else
// happens (no crash, no file read outside, no command run).
TEST(GltfModel, BadInputCorpus) {
  const fs::path dir = kShared / "bad_inputs";
  REQUIRE_DIR(dir);
  const std::set<std::string> loads = {"ok_triangle.gltf", "ok_triangle.glb", "gltf_mode_lines.gltf",
                                       "gltf_image_uri_traversal_etc_passwd.gltf", "gltf_wordexp_injection.gltf",
                                       "gltf_png_decompression_bomb.gltf"};
  std::size_t seen = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    const std::string ext = e.path().extension().string();
    if (ext != ".gltf" && ext != ".glb") continue;
    ++seen;
    SCOPED_TRACE(name);
    if (loads.count(name)) {
      Model m;
      ASSERT_NO_THROW(m = import_model(e.path().string()));
      EXPECT_EQ(m.num_vertices(), 3u);
      EXPECT_EQ(m.faces.rows(), name == "gltf_mode_lines.gltf" ? 0u : 1u);
      if (name.starts_with("gltf_") && name != "gltf_png_decompression_bomb.gltf") {
        EXPECT_FALSE(m.notes.empty());
      }
    } else {
      const std::string msg = error_text([&] { import_model(e.path().string()); });
      EXPECT_NE(msg.find(name), std::string::npos) << "must name the file: '" << msg << "'";
    }
  }
  EXPECT_GE(seen, 30u);
  const Model traversal = import_model((dir / "gltf_image_uri_traversal_etc_passwd.gltf").string());
  EXPECT_NE(traversal.notes.front().find("outside the model's folder"), std::string::npos) << traversal.notes.front();
  EXPECT_FALSE(fs::exists("/tmp/sublift-probe/PWNED_backtick"));
  EXPECT_FALSE(fs::exists("/tmp/sublift-probe/PWNED_dollar"));
  const std::string parent = error_text([&] { import_model((dir / "gltf_buffer_uri_parent_dir.gltf").string()); });
  EXPECT_NE(parent.find("outside the model's folder"), std::string::npos) << parent;
}

// ---- Small models written by the tests: one interleaved vertex buffer (POSITION, NORMAL,
// TEXCOORD_0 with byteStride 32) and uint16 indices, in an external .bin beside the .gltf.
struct MiniGltf {
  std::vector<float> pos, nrm, uv;  // 3, 3, 2 per vertex
  std::vector<std::uint16_t> idx;
  std::string nodes = R"([{"mesh":0}])";
  std::string scenes = R"([{"nodes":[0]}])";
  std::string primitives_extra;   // more primitives after the first (JSON, leading comma)
  std::string accessors_extra;    // more accessors after the 4 (JSON, leading comma)
  std::string attributes_extra;   // more attributes of primitive 0 (JSON, leading comma)
  std::string position_extra;     // more members of the POSITION accessor (leading comma)
  std::string top_extra;          // more top-level members (leading comma)
  std::string buffer_uri = "mini.bin";
  int position_component = 5126;

  std::size_t nv() const { return pos.size() / 3; }
  std::string bin() const {
    std::string b(32 * nv() + 2 * idx.size(), '\0');
    for (std::size_t v = 0; v < nv(); ++v) {
      std::memcpy(&b[32 * v], &pos[3 * v], 12);
      std::memcpy(&b[32 * v + 12], &nrm[3 * v], 12);
      std::memcpy(&b[32 * v + 24], &uv[2 * v], 8);
    }
    std::memcpy(&b[32 * nv()], idx.data(), 2 * idx.size());
    while (b.size() % 4) b.push_back('\0');
    return b;
  }
  std::string json(std::size_t bin_size) const {
    float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
    for (std::size_t i = 0; i < pos.size(); ++i) lo[i % 3] = std::min(lo[i % 3], pos[i]), hi[i % 3] = std::max(hi[i % 3], pos[i]);
    std::ostringstream s;
    s.precision(9);
    s << R"({"asset":{"version":"2.0"},"scene":0,"scenes":)" << scenes << R"(,"nodes":)" << nodes
      << R"(,"meshes":[{"primitives":[{"attributes":{"POSITION":0,"NORMAL":1,"TEXCOORD_0":2)" << attributes_extra
      << R"(},"indices":3})" << primitives_extra << R"(]}],"accessors":[)"
      << R"({"bufferView":0,"componentType":)" << position_component << R"(,"count":)" << nv() << R"(,"type":"VEC3","min":[)"
      << lo[0] << ',' << lo[1] << ',' << lo[2] << R"(],"max":[)" << hi[0] << ',' << hi[1] << ',' << hi[2] << "]" << position_extra << "},"
      << R"({"bufferView":0,"byteOffset":12,"componentType":5126,"count":)" << nv() << R"(,"type":"VEC3"},)"
      << R"({"bufferView":0,"byteOffset":24,"componentType":5126,"count":)" << nv() << R"(,"type":"VEC2"},)"
      << R"({"bufferView":1,"componentType":5123,"count":)" << idx.size() << R"(,"type":"SCALAR"})" << accessors_extra
      << R"(],"bufferViews":[{"buffer":0,"byteLength":)" << 32 * nv() << R"(,"byteStride":32,"target":34962},)"
      << R"({"buffer":0,"byteOffset":)" << 32 * nv() << R"(,"byteLength":)" << 2 * idx.size() << R"(,"target":34963}],)"
      << R"("buffers":[{"byteLength":)" << bin_size << R"(,"uri":")" << buffer_uri << R"("}])" << top_extra << "}";
    return s.str();
  }
  // Writes NAME.gltf (and mini.bin) into dir; returns the .gltf path.
  std::string write(const fs::path& dir, const std::string& name) const {
    const std::string b = bin();
    spit(dir / "mini.bin", b);
    spit(dir / (name + ".gltf"), json(b.size()));
    return (dir / (name + ".gltf")).string();
  }
};

// Two triangles folded along a shared edge, the edge's vertices duplicated (a UV seam). With
// `hard`, the duplicates carry different normals (a hard edge) instead of the same one.
MiniGltf roof(bool hard) {
  MiniGltf g;
  g.pos = {0, 0, 0, 1, 0, 0, 0, 1, 0,   1, 0, 0, 0, 1, 0, 1, 1, 0.5f};
  const float a[3] = {0, 0, 1}, b[3] = {0.f, -0.4472136f, 0.8944272f}, s[3] = {0.f, -0.2297529f, 0.9732490f};
  for (int v = 0; v < 6; ++v) {
    const float* n = v == 0 ? a : v == 5 ? b : hard ? (v < 3 ? a : b) : s;
    g.nrm.insert(g.nrm.end(), n, n + 3);
    g.uv.insert(g.uv.end(), {float(v) / 8, float(v) / 4});
  }
  g.idx = {0, 1, 2, 3, 5, 4};
  return g;
}

TEST(GltfModel, InterleavedDataStaysInPlaceAndSeamsStaySmooth) {
  TempDir dir("sublift_model_interleaved");
  for (const bool hard : {false, true}) {
    SCOPED_TRACE(hard ? "hard edge" : "smooth seam");
    const MiniGltf g = roof(hard);
    const std::string path = g.write(dir.path(), "roof");
    const Model m = import_model(path);
    ASSERT_EQ(m.num_vertices(), 6u);
    ASSERT_EQ(m.faces.rows(), 2u);
    std::vector<double> q = m.positions;
    q[3 * 5 + 2] = 2.0;  // lift the far corner: the second triangle tilts
    q[3 * 0 + 2] = -0.5;
    export_model(m, q, dir.file("out.gltf"));
    const tinygltf::Model a = load_plain(path), b = load_plain(dir.file("out.gltf"));
    EXPECT_EQ(element_bytes(a, 2), element_bytes(b, 2));  // TEXCOORD_0, interleaved between the rewritten ones
    EXPECT_EQ(element_bytes(a, 3), element_bytes(b, 3));
    const std::vector<float> p = floats(b, 0), n = floats(b, 1);
    for (std::size_t i = 0; i < q.size(); ++i) EXPECT_EQ(p[i], float(q[i]));
    // Triangle normals of the deformed roof, by cross products (independent of Newell's formula).
    auto tri_normal = [&](int i0, int i1, int i2) {
      const double e1[3] = {q[3 * i1] - q[3 * i0], q[3 * i1 + 1] - q[3 * i0 + 1], q[3 * i1 + 2] - q[3 * i0 + 2]};
      const double e2[3] = {q[3 * i2] - q[3 * i0], q[3 * i2 + 1] - q[3 * i0 + 1], q[3 * i2 + 2] - q[3 * i0 + 2]};
      return std::array<double, 3>{e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    };
    const auto ta = tri_normal(0, 1, 2), tb = tri_normal(3, 5, 4);
    auto expect_normal = [&](int v, std::array<double, 3> s) {
      const double len = std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(n[3 * std::size_t(v) + std::size_t(k)], s[std::size_t(k)] / len, 1e-6) << "vertex " << v;
    };
    expect_normal(0, ta);
    expect_normal(5, tb);
    const std::array<double, 3> both{ta[0] + tb[0], ta[1] + tb[1], ta[2] + tb[2]};
    for (int v : {1, 2}) expect_normal(v, hard ? ta : both);
    for (int v : {3, 4}) expect_normal(v, hard ? tb : both);
  }
}

TEST(GltfModel, InstancedMeshIsDeformedInTheFrameOfItsFirstNode) {
  TempDir dir("sublift_model_instanced");
  MiniGltf g = roof(false);
  g.nodes = R"([{"mesh":0,"translation":[5,0,0]},{"mesh":0,"translation":[-5,0,0]}])";
  g.scenes = R"([{"nodes":[1,0]}])";
  const Model m = import_model(g.write(dir.path(), "two"));
  ASSERT_EQ(m.ranges.size(), 1u);
  EXPECT_EQ(m.ranges[0].node, 1);
  EXPECT_EQ(m.positions[0], -5.0);
  EXPECT_TRUE(std::any_of(m.notes.begin(), m.notes.end(), [](const std::string& n) { return n.find("instanced by 2 nodes") != std::string::npos; })) << m.notes.size();
  std::vector<double> q = deform(m.positions);
  export_model(m, q, dir.file("out.glb"));
  const tinygltf::Model b = load_plain(dir.file("out.glb"));
  const std::vector<float> p = floats(b, 0);
  for (std::size_t v = 0; v < 6; ++v) EXPECT_EQ(p[3 * v], float(q[3 * v] + 5.0));  // back through node 1's inverse
  const Model back = import_model(dir.file("out.glb"));
  for (std::size_t i = 0; i < q.size(); ++i) EXPECT_NEAR(back.positions[i], q[i], 1e-6);
}

TEST(GltfModel, PrimitivesSharingPositionsShareOneRange) {
  TempDir dir("sublift_model_shared");
  MiniGltf g = roof(false);
  g.primitives_extra = R"(,{"attributes":{"POSITION":0},"indices":4,"mode":5})";
  g.accessors_extra = R"(,{"bufferView":1,"componentType":5123,"count":4,"type":"SCALAR"})";  // 0 1 2 3 as a strip
  g.idx = {0, 1, 2, 3, 5, 4};
  const Model m = import_model(g.write(dir.path(), "shared"));
  ASSERT_EQ(m.ranges.size(), 1u);
  EXPECT_EQ(m.ranges[0].primitives.size(), 2u);
  // 2 TRIANGLES + the strip 0 1 2 3: (0 1 2) and, flipped, (1 3 2); (1 3 2) shares no index twice.
  ASSERT_EQ(m.faces.rows(), 4u);
  EXPECT_EQ(std::vector<std::uint32_t>(m.faces.items.begin() + 6, m.faces.items.end()), (std::vector<std::uint32_t>{0, 1, 2, 1, 3, 2}));
}

TEST(GltfModel, ObjectsWithOnlyDefaultValuesSurviveExport) {
  // tinygltf 2.7 serialises an all-default object as null and cannot read that back.
  TempDir dir("sublift_model_defaults");
  MiniGltf g = roof(false);
  g.nodes = R"([{"mesh":0},{}])";
  g.scenes = R"([{"nodes":[0,1]},{}])";
  g.top_extra = R"(,"materials":[{}],"samplers":[{}])";
  const Model m = import_model(g.write(dir.path(), "defaults"));
  for (const char* out : {"out.gltf", "out.glb"}) {
    SCOPED_TRACE(out);
    export_model(m, deform(m.positions), dir.file(out));
    const tinygltf::Model b = load_plain(dir.file(out));
    EXPECT_EQ(b.nodes.size(), 2u);
    EXPECT_EQ(b.scenes.size(), 2u);
    EXPECT_EQ(b.materials.size(), 1u);
    EXPECT_EQ(import_model(dir.file(out)).num_vertices(), 6u);
  }
}

TEST(GltfModel, RefusesWhatItCannotWriteBack) {
  TempDir dir("sublift_model_refuse");
  struct Case { std::string what, expect; std::function<void(MiniGltf&)> make; };
  const std::vector<Case> cases = {
      {"quantized", "is not float", [](MiniGltf& g) { g.position_component = 5122; g.position_extra = R"(,"normalized":true)"; }},
      {"sparse", "sparse", [](MiniGltf& g) { g.position_extra = R"(,"sparse":{"count":1,"indices":{"bufferView":1,"componentType":5123},"values":{"bufferView":0}})"; }},
      {"draco", "KHR_draco_mesh_compression", [](MiniGltf& g) { g.top_extra = R"(,"extensionsUsed":["KHR_draco_mesh_compression"],"extensionsRequired":["KHR_draco_mesh_compression"])"; }},
      {"aliased", "shares bytes", [](MiniGltf& g) {
         g.accessors_extra = R"(,{"bufferView":0,"byteOffset":4,"componentType":5126,"count":6,"type":"VEC2"})";
         g.attributes_extra = R"(,"TEXCOORD_1":4)"; }},
      {"position also uv", "cannot be rewritten", [](MiniGltf& g) { g.attributes_extra = R"(,"COLOR_0":0)"; }},
      {"cycle", "cycle", [](MiniGltf& g) { g.nodes = R"([{"mesh":0},{"children":[2]},{"children":[1]}])"; }},
      {"singular", "singular", [](MiniGltf& g) { g.nodes = R"([{"mesh":0,"scale":[1,0,1]}])"; }},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    MiniGltf g = roof(false);
    c.make(g);
    const std::string path = g.write(dir.path(), "bad");
    const std::string msg = error_text([&] { import_model(path); });
    EXPECT_NE(msg.find("bad.gltf"), std::string::npos) << msg;
    EXPECT_NE(msg.find(c.expect), std::string::npos) << msg;
  }
}

TEST(GltfModel, ExternalFilesAreReadOnlyFromTheModelsFolder) {
  TempDir dir("sublift_model_sandbox");
  const fs::path inner = dir.path() / "model";
  fs::create_directories(inner);
  const MiniGltf base = roof(false);
  const std::string bin = base.bin();
  spit(dir.path() / "secret.bin", bin);  // exists, with the right size: only the lock-down stops it
  spit(dir.path() / "secret.png", "not an image");
  fs::create_symlink(dir.path() / "secret.bin", inner / "link.bin");
  for (const std::string& uri : {std::string("../secret.bin"), (dir.path() / "secret.bin").string(), std::string("link.bin"),
                                std::string("%2e%2e/secret.bin"), std::string("file:///") + (dir.path() / "secret.bin").string(),
                                std::string("sub/../../secret.bin")}) {
    SCOPED_TRACE(uri);
    MiniGltf g = base;
    g.buffer_uri = uri;
    spit(inner / "m.gltf", g.json(bin.size()));
    const std::string msg = error_text([&] { import_model((inner / "m.gltf").string()); });
    EXPECT_NE(msg.find("m.gltf"), std::string::npos) << msg;
    EXPECT_NE(msg.find("outside the model's folder"), std::string::npos) << msg;
  }
  // Inside the folder it loads; an image outside is not read and says so.
  MiniGltf g = base;
  g.top_extra = R"(,"images":[{"uri":"../secret.png"}])";
  spit(inner / "mini.bin", bin);
  spit(inner / "ok.gltf", g.json(bin.size()));
  const Model m = import_model((inner / "ok.gltf").string());
  EXPECT_EQ(m.num_vertices(), 6u);
  ASSERT_FALSE(m.notes.empty());
  EXPECT_NE(m.notes.front().find("'../secret.png' points outside the model's folder"), std::string::npos) << m.notes.front();
}

TEST(GltfModel, ExternalImagesAreCopiedBesideAnOutputInAnotherFolder) {
  TempDir dir("sublift_model_images");
  MiniGltf g = roof(false);
  g.top_extra = R"(,"images":[{"uri":"tex/a%20b.png"}])";
  fs::create_directories(dir.path() / "src" / "tex");
  const std::string png = std::string("\x89PNG\r\n\x1a\n", 8) + "not decoded, kept byte for byte";
  spit(dir.path() / "src" / "tex" / "a b.png", png);
  const Model m = import_model(g.write(dir.path() / "src", "img"));
  fs::create_directories(dir.path() / "out");
  export_model(m, m.positions, (dir.path() / "out" / "img.gltf").string());
  EXPECT_EQ(slurp(dir.path() / "out" / "tex" / "a b.png"), png);
  EXPECT_EQ(load_plain(dir.path() / "out" / "img.gltf").images.at(0).uri, "tex/a%20b.png");
  // An image that came as a data: URI goes back as the same bytes.
  export_model(m, m.positions, (dir.path() / "out" / "img.glb").string());
  EXPECT_TRUE(fs::exists(dir.path() / "out" / "img.glb"));
}

// ---- Formats and files.
TEST(Model, ExportKeepsTheSourceFormatFamily) {
  TempDir dir("sublift_model_family");
  const Model obj = import_model((kAssets / "cube.obj").string());
  const std::string msg = error_text([&] { export_model(obj, obj.positions, dir.file("cube.ply")); });
  EXPECT_NE(msg.find("cube.ply"), std::string::npos) << msg;
  EXPECT_NE(msg.find(".obj"), std::string::npos) << msg;
  EXPECT_NE(error_text([&] { export_model(obj, obj.positions, dir.file("cube.glb")); }), "");
  EXPECT_NE(error_text([&] { export_model(obj, obj.positions, dir.file("cube.stl")); }), "");
  EXPECT_NE(error_text([&] { export_model(obj, std::vector<double>(3), dir.file("cube.obj")); }), "");
  EXPECT_THROW(export_model(obj, obj.positions, dir.file("missing/cube.obj")), IoError);
  EXPECT_FALSE(fs::exists(dir.file("cube.ply")));
  EXPECT_NE(error_text([&] { import_model(dir.file("nothing.glb")); }), "");
  EXPECT_NE(error_text([&] { import_model(dir.file("x.fbx")); }), "");
}

TEST(Model, ExtensionsAreCaseInsensitive) {
  REQUIRE_DIR(kGltf);
  TempDir dir("sublift_model_case");
  fs::copy_file(kGltf / "Box" / "Box.glb", dir.path() / "BOX.GLB");
  fs::copy_file(kAssets / "cube.obj", dir.path() / "Cube.Obj");
  EXPECT_EQ(import_model(dir.file("BOX.GLB")).num_vertices(), 24u);
  const Model obj = import_model(dir.file("Cube.Obj"));
  EXPECT_EQ(obj.format, ModelFormat::Obj);
  export_model(obj, obj.positions, dir.file("OUT.OBJ"));
  EXPECT_EQ(slurp(dir.file("OUT.OBJ")), slurp(kAssets / "cube.obj"));
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

std::vector<std::string> tokens_of(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> t;
  for (std::string s; in >> s;) t.push_back(s);
  return t;
}

// Deform, export, re-import: positions exact (17 digits); every line but `v`, `vn` (OBJ) or the
// vertex lines (OFF) byte-identical; an identity export is the file itself.
void check_text_round_trip(const fs::path& src, const std::string& tmp) {
  SCOPED_TRACE(src.string());
  const Model m = import_model(src.string());
  const std::string out = tmp + src.extension().string();
  export_model(m, m.positions, out);
  EXPECT_EQ(slurp(out), slurp(src)) << "identity export must give the file back";
  const std::vector<double> q = deform(m.positions);
  export_model(m, q, out);
  EXPECT_EQ(import_model(out).positions, q);
  const std::vector<std::string> a = lines_of(slurp(src)), b = lines_of(slurp(out));
  ASSERT_EQ(a.size(), b.size());
  const bool obj = src.extension() == ".obj";
  const bool off_normals = !obj && !a.empty() && a[0].find("NOFF") != std::string::npos;
  std::size_t vertex_lines = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i] == b[i]) continue;
    ++vertex_lines;
    const auto ta = tokens_of(a[i]), tb = tokens_of(b[i]);
    ASSERT_EQ(ta.size(), tb.size()) << "line " << i + 1 << ": " << b[i];
    if (obj) {
      ASSERT_TRUE(ta[0] == "v" || ta[0] == "vn") << "only v and vn lines may change, line " << i + 1 << ": " << a[i];
      if (ta[0] == "v") {
        for (std::size_t k = 4; k < ta.size(); ++k) EXPECT_EQ(ta[k], tb[k]) << "line " << i + 1;
      } else {
        const double x = std::stod(tb[1]), y = std::stod(tb[2]), z = std::stod(tb[3]);
        EXPECT_NEAR(x * x + y * y + z * z, 1.0, 1e-12) << "line " << i + 1;
      }
    } else {
      for (std::size_t k = off_normals ? 6 : 3; k < ta.size(); ++k) EXPECT_EQ(ta[k], tb[k]) << "line " << i + 1;
    }
  }
  EXPECT_GT(vertex_lines, 0u);
}

TEST(MeshModel, ObjAndOffRoundTripsRewriteOnlyVertexLines) {
  TempDir dir("sublift_model_text");
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(kAssets))
    if (e.path().extension() == ".obj") files.push_back(e.path());
  const fs::path shapes = kShared / "control_meshes";
  if (fs::is_directory(shapes)) {
    for (const auto& e : fs::recursive_directory_iterator(shapes))
      if ((e.path().extension() == ".obj" || e.path().extension() == ".off") && fs::file_size(e.path()) < 400000)
        files.push_back(e.path());
  } else {
    std::cout << "[ note ] " << shapes << " absent: only the project's assets are checked\n";
  }
  std::sort(files.begin(), files.end());
  ASSERT_GE(files.size(), 5u);
  for (const fs::path& f : files) check_text_round_trip(f, dir.file("out"));
}

TEST(MeshModel, ObjKeepsVertexColoursAndRecomputesFaceNormals) {
  TempDir dir("sublift_model_obj");
  // A unit cube with vertex colours, UVs, one normal per face and one unused normal.
  const std::string text =
      "# cube\nmtllib cube.mtl\no cube\n"
      "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 1 1 0 0 0 1\nv 0 1 0 1 1 0\nv 0 0 1 0 1 1\nv 1 0 1 1 0 1\nv 1 1 1 0.5 0.5 0.5\nv 0 1 1 0 0 0\n"
      "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
      "vn 0 0 -1\nvn 0 0 1\nvn 0 -1 0\nvn 0 1 0\nvn -1 0 0\nvn 1 0 0\nvn 0.6 0.8 0\n"
      "usemtl red\ns off\n"
      "f 1/1/1 4/4/1 3/3/1 2/2/1\nf 5/1/2 6/2/2 7/3/2 8/4/2\nf 1/1/3 2/2/3 6/3/3 5/4/3\n"
      "f 4/1/4 8/2/4 7/3/4 3/4/4\nf 1/1/5 5/2/5 8/3/5 4/4/5\nf 2/1/6 3/2/6 7/3/6 6/4/6\n";
  spit(dir.path() / "cube.obj", text);
  const Model m = import_model(dir.file("cube.obj"));
  ASSERT_EQ(m.num_vertices(), 8u);
  const std::vector<double> q = deform(m.positions);
  export_model(m, q, dir.file("out.obj"));
  const std::vector<std::string> lines = lines_of(slurp(dir.file("out.obj")));
  // Colours stay as written after the new coordinates.
  std::vector<std::vector<std::string>> v, vn;
  for (const std::string& l : lines) {
    const auto t = tokens_of(l);
    if (!t.empty() && t[0] == "v") v.push_back(t);
    if (!t.empty() && t[0] == "vn") vn.push_back(t);
  }
  ASSERT_EQ(v.size(), 8u);
  EXPECT_EQ((std::vector<std::string>(v[6].begin() + 4, v[6].end())), (std::vector<std::string>{"0.5", "0.5", "0.5"}));
  EXPECT_EQ(std::stod(v[6][1]), q[18]);
  // Each face's normal is its deformed quad's: (p2 - p0) x (p3 - p1), normalised.
  const int faces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {3, 7, 6, 2}, {0, 4, 7, 3}, {1, 2, 6, 5}};
  ASSERT_EQ(vn.size(), 7u);
  for (int f = 0; f < 6; ++f) {
    const double* p0 = &q[3 * faces[f][0]];
    const double* p1 = &q[3 * faces[f][1]];
    const double* p2 = &q[3 * faces[f][2]];
    const double* p3 = &q[3 * faces[f][3]];
    const double d1[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]}, d2[3] = {p3[0] - p1[0], p3[1] - p1[1], p3[2] - p1[2]};
    const double c[3] = {d1[1] * d2[2] - d1[2] * d2[1], d1[2] * d2[0] - d1[0] * d2[2], d1[0] * d2[1] - d1[1] * d2[0]};
    const double len = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(std::stod(vn[std::size_t(f)][std::size_t(k) + 1]), c[k] / len, 1e-12) << "face " << f;
  }
  EXPECT_EQ(vn[6], (std::vector<std::string>{"vn", "0.6", "0.8", "0"}));  // referenced by no face
}

// PLY with an element before the vertices, extra properties, double and float coordinates and
// float normals, in ASCII, little- and big-endian binary.
std::string ply_file(const std::string& format, const std::vector<double>& xyz) {
  const double n[3] = {0, 0, 1};
  std::string h = "ply\nformat " + format + " 1.0\ncomment made by model_io_test\nelement material 1\n"
                  "property list uchar int ids\nproperty uchar shine\nelement vertex 4\nproperty double x\n"
                  "property float y\nproperty float z\nproperty float nx\nproperty float ny\nproperty float nz\n"
                  "property uchar red\nproperty ushort quality\nelement face 2\nproperty list uchar int vertex_indices\n"
                  "end_header\n";
  if (format == "ascii") {
    std::ostringstream s;
    s << h << "3 7 8 9 200\n";
    for (int v = 0; v < 4; ++v)
      s << xyz[3 * std::size_t(v)] << ' ' << xyz[3 * std::size_t(v) + 1] << ' ' << xyz[3 * std::size_t(v) + 2] << " 0 0 1 " << 10 * v << ' ' << 1000 + v << '\n';
    s << "3 0 1 2\n3 0 2 3\n";
    return s.str();
  }
  const bool big = format == "binary_big_endian";
  auto put = [&](auto value) {
    char b[sizeof(value)];
    std::memcpy(b, &value, sizeof(value));
    if (big) std::reverse(b, b + sizeof(value));
    h.append(b, sizeof(value));
  };
  put(std::uint8_t(3)), put(std::int32_t(7)), put(std::int32_t(8)), put(std::int32_t(9)), put(std::uint8_t(200));
  for (int v = 0; v < 4; ++v) {
    put(xyz[3 * std::size_t(v)]), put(float(xyz[3 * std::size_t(v) + 1])), put(float(xyz[3 * std::size_t(v) + 2]));
    put(float(n[0])), put(float(n[1])), put(float(n[2])), put(std::uint8_t(10 * v)), put(std::uint16_t(1000 + v));
  }
  for (std::int32_t t : {0, 1, 2, 0, 2, 3}) {
    if (t == 0) put(std::uint8_t(3));
    put(t);
  }
  return h;
}

TEST(MeshModel, PlyOverwritesCoordinatesAndNormalsInTheirOwnTypes) {
  TempDir dir("sublift_model_ply");
  const std::vector<double> square = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  for (const std::string format : {"ascii", "binary_little_endian", "binary_big_endian"}) {
    SCOPED_TRACE(format);
    const std::string src = ply_file(format, square);
    spit(dir.path() / "in.ply", src);
    const Model m = import_model(dir.file("in.ply"));
    ASSERT_EQ(m.num_vertices(), 4u);
    // An affine map: the square stays planar, its normal is the tilted plane's.
    std::vector<double> q = m.positions;
    for (std::size_t v = 0; v < 4; ++v) q[3 * v + 2] = 0.25 * q[3 * v] + 0.1, q[3 * v] += 1.0 / 3.0;
    export_model(m, q, dir.file("out.ply"));
    const std::string out = slurp(dir.file("out.ply"));
    std::vector<double> expect = q;  // y and z are float in the file, x double
    for (std::size_t v = 0; v < 4; ++v) expect[3 * v + 1] = float(q[3 * v + 1]), expect[3 * v + 2] = float(q[3 * v + 2]);
    const Model back = import_model(dir.file("out.ply"));
    // Binary: the float32 values exactly; ASCII: the shortest text of the float, which reads back
    // as a double that rounds to the same float.
    for (std::size_t i = 0; i < expect.size(); ++i) {
      if (format == "ascii" && i % 3 != 0) EXPECT_EQ(float(back.positions[i]), float(expect[i])) << i;
      else EXPECT_EQ(back.positions[i], expect[i]) << i;
    }
    const double len = std::sqrt(0.25 * 0.25 + 1.0);
    const std::string want_ply = ply_file(format, expect);
    if (format == "ascii") {
      const auto a = lines_of(want_ply), b = lines_of(out);
      ASSERT_EQ(a.size(), b.size());
      for (std::size_t i = 0; i < a.size(); ++i) {
        const auto ta = tokens_of(a[i]), tb = tokens_of(b[i]);
        ASSERT_EQ(ta.size(), tb.size()) << b[i];
        if (ta.size() != 8) {
          EXPECT_EQ(a[i], b[i]);
          continue;
        }
        ASSERT_GE(i, 19u);
        EXPECT_EQ(std::stod(tb[0]), expect[3 * (i - 19)]) << b[i];
        for (std::size_t k = 1; k < 3; ++k) EXPECT_EQ(std::stof(tb[k]), float(expect[3 * (i - 19) + k])) << b[i];
        EXPECT_NEAR(std::stod(tb[3]), -0.25 / len, 1e-7);
        EXPECT_EQ(std::stod(tb[4]), 0.0);
        EXPECT_NEAR(std::stod(tb[5]), 1.0 / len, 1e-7);
        EXPECT_EQ(tb[6], ta[6]);
        EXPECT_EQ(tb[7], ta[7]);
      }
    } else {
      // Byte for byte the file written with the new positions, except the normals' 12 bytes.
      ASSERT_EQ(out.size(), want_ply.size());
      const std::size_t body = want_ply.find("end_header\n") + 11 + 14;
      for (std::size_t i = 0; i < out.size(); ++i) {
        const std::size_t in_row = (i - body) % 31;  // x double, y z nx ny nz float, uchar, ushort
        const bool normal = i >= body && i < body + 4 * 31 && in_row >= 16 && in_row < 28;
        if (!normal) {
          ASSERT_EQ(out[i], want_ply[i]) << "byte " << i;
        }
      }
      for (std::size_t v = 0; v < 4; ++v) {
        float nn[3];
        for (int k = 0; k < 3; ++k) {
          char b[4];
          std::memcpy(b, &out[body + 31 * v + 16 + 4 * std::size_t(k)], 4);
          if (format == "binary_big_endian") std::reverse(b, b + 4);
          std::memcpy(&nn[k], b, 4);
        }
        EXPECT_NEAR(nn[0], -0.25 / len, 1e-7);
        EXPECT_EQ(nn[1], 0.0f);
        EXPECT_NEAR(nn[2], 1.0 / len, 1e-7);
      }
    }
  }
}

TEST(MeshModel, OffKeepsColoursAndRewritesNormalsAndBinaryCoordinates) {
  TempDir dir("sublift_model_off");
  spit(dir.path() / "c.off", "CNOFF\n# square\n4 2 0\n0 0 0  0 0 1  255 0 0 255\n1 0 0  0 0 1  0 255 0 255\n"
                              "1 1 0  0 0 1  0 0 255 255\n0 1 0  0 0 1  9 9 9 255\n3 0 1 2\n3 0 2 3 1 2 3\n");
  const Model m = import_model(dir.file("c.off"));
  std::vector<double> q = m.positions;
  for (std::size_t v = 0; v < 4; ++v) q[3 * v + 2] = q[3 * v + 1];  // tilt about x: normal (0, -1, 1)/sqrt 2
  export_model(m, q, dir.file("o.off"));
  const auto lines = lines_of(slurp(dir.file("o.off")));
  ASSERT_EQ(lines.size(), 9u);
  for (std::size_t v = 0; v < 4; ++v) {
    const auto t = tokens_of(lines[3 + v]);
    ASSERT_EQ(t.size(), 10u);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(std::stod(t[std::size_t(k)]), q[3 * v + std::size_t(k)]);
    EXPECT_EQ(std::stod(t[3]), 0.0);
    EXPECT_NEAR(std::stod(t[4]), -std::sqrt(0.5), 1e-15);
    EXPECT_NEAR(std::stod(t[5]), std::sqrt(0.5), 1e-15);
    EXPECT_EQ(tokens_of(lines_of(slurp(dir.file("c.off")))[3 + v])[6], t[6]);
  }
  EXPECT_EQ(lines[8], "3 0 2 3 1 2 3");
  // OFF BINARY: big-endian float32 coordinates overwritten in place.
  std::string bin = "OFF BINARY\n";
  auto put = [&](auto value) {
    char b[sizeof(value)];
    std::memcpy(b, &value, sizeof(value));
    std::reverse(b, b + sizeof(value));
    bin.append(b, sizeof(value));
  };
  put(std::int32_t(3)), put(std::int32_t(1)), put(std::int32_t(0));
  for (float x : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) put(x);
  put(std::int32_t(3)), put(std::int32_t(0)), put(std::int32_t(1)), put(std::int32_t(2)), put(std::int32_t(0));
  spit(dir.path() / "b.off", bin);
  const Model mb = import_model(dir.file("b.off"));
  const std::vector<double> qb = {0.5, 0.25, 2, 1, 0, 0, 0, 1, -3};
  export_model(mb, qb, dir.file("bo.off"));
  EXPECT_EQ(import_model(dir.file("bo.off")).positions, qb);
  EXPECT_EQ(slurp(dir.file("bo.off")).size(), bin.size());
}

// Issue 18: messages that name the fault, not what tinygltf stumbled on afterwards.
TEST(GltfModel, ShortDataUriAndBadStrideNameTheirFault) {
  TempDir dir("sublift_gltf_messages");
  const MiniGltf g = roof(false);
  // 20 bytes of base64 (27 characters and one '=') where byteLength says 44.
  MiniGltf short_uri = g;
  short_uri.buffer_uri = "data:application/octet-stream;base64," + std::string(27, 'A') + "=";
  const fs::path a = dir.path() / "short.gltf";
  spit(a, short_uri.json(44));
  EXPECT_EQ(error_text([&] { import_model(a.string()); }), a.string() + ": buffer 0: data URI holds 20 bytes, byteLength says 44");
  MiniGltf bad = g;
  bad.buffer_uri = "data:application/octet-stream;base64,AAA@";
  spit(a, bad.json(3));
  EXPECT_EQ(error_text([&] { import_model(a.string()); }), a.string() + ": buffer 0: data URI is not base64: '@' at character 40 of the uri");
  // byteStride 256 is a multiple of 4: the fault is the range; 3 is neither.
  const std::string b = g.write(dir.path(), "stride");
  const std::string good = sublift::read_file_bytes(b);
  for (const char* stride : {"256", "3", "0"}) {
    std::string text = good;
    text.replace(text.find("\"byteStride\":32"), 15, std::string("\"byteStride\":") + stride);
    spit(b, text);
    EXPECT_EQ(error_text([&] { import_model(b); }),
              b + ": bufferView 0: byteStride " + stride + " is not allowed (glTF allows 4..252, a multiple of 4)");
  }
  spit(b, good);
  EXPECT_NO_THROW(import_model(b));
}

TEST(GltfModel, UrisWithNulAndControlBytesAreQuotedWhole) {
  TempDir dir("sublift_gltf_uri_bytes");
  MiniGltf g = roof(false);
  g.buffer_uri = "../se%00cret.bin";
  const std::string a = g.write(dir.path(), "nul");
  EXPECT_EQ(error_text([&] { import_model(a); }),
            a + ": uri '../se\\x00cret.bin' points outside the model's folder (an absolute path, '..', a URL or a symlink out): refused");
  g.buffer_uri = "mi%00ni.bin";  // a missing file: tinygltf's own message, quoted whole
  const std::string b = g.write(dir.path(), "missing");
  EXPECT_EQ(error_text([&] { import_model(b); }), b + ": glTF: File not found : mi\\x00ni.bin");
  g.buffer_uri = "caf\xc3\xa9\\u0007.bin";  // UTF-8 kept; BEL (JSON \u0007) escaped
  const std::string c = g.write(dir.path(), "ctrl");
  const std::string e = error_text([&] { import_model(c); });
  EXPECT_EQ(e.find('\0'), std::string::npos);
  EXPECT_NE(e.find("caf\xc3\xa9\\x07"), std::string::npos) << e;
}

}  // namespace
