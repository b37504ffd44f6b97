// Face-varying texture coordinates (issue 20): the linear rule's values by hand on one quad and
// one triangle, seams kept apart and shared edges shared, OBJ vt read, written and read back,
// BoxTextured's TEXCOORD_0 read onto the welded box, and a subdivided textured box whose every
// corner still maps the texture point its place on the base face maps (an affine oracle computed
// from the base triangles, independent of the refinement code), through OBJ and glTF.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

#include <glm/glm.hpp>

#include "core/base/file_io.h"
#include "core/complex/complex_build.h"
#include "core/complex/face_varying.h"
#include "core/complex/refine.h"
#include "core/complex/refine_tri.h"
#include "core/io/lattice/shape_io.h"
#include "tests/cli_run.h"
#include "tests/io_test_util.h"

namespace sublift {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

const fs::path kBoxTextured = fs::path(SUBLIFT_SHARED_DATA) / "gltf" / "BoxTextured" / "BoxTextured.gltf";

std::array<double, 2> uv_of(const FaceVaryingUV& uv, std::size_t corner) {
  return {uv.points[2 * uv.corners[corner]], uv.points[2 * uv.corners[corner] + 1]};
}

// The not-kept entry of `report` whose text contains `what` (nullptr if none).
const ImportWarning* not_kept(const ImportReport& report, const std::string& what) {
  for (const ImportWarning& w : report.not_kept)
    if (w.what.find(what) != std::string::npos) return &w;
  return nullptr;
}

Complex polygons(std::uint32_t nv, const std::vector<std::vector<std::uint32_t>>& faces) {
  Csr f;
  for (const auto& face : faces) {
    f.items.insert(f.items.end(), face.begin(), face.end());
    f.offsets.push_back(static_cast<std::uint32_t>(f.items.size()));
  }
  return complex_from_polygons(nv, f);
}

TEST(FaceVaryingUv, QuadSplitByHand) {
  // One quad 0-1-2-3 with UVs (0,0) (1,0) (1,1) (0,1) at its corners, in order.
  const Complex c = polygons(4, {{0, 1, 2, 3}});
  const FaceVaryingUV uv{{0, 0, 1, 0, 1, 1, 0, 1}, {0, 1, 2, 3}};
  ASSERT_EQ(uv_problem(c, uv), "");
  const FaceVaryingUV fine = refine_uv_split(c, uv);
  const Complex f = refine(c);
  ASSERT_EQ(uv_problem(f, fine), "");
  // Child i of the quad is (v_i, mid(i, i+1), centre, mid(i-1, i)) (refine.h).
  const std::array<double, 2> expect[4][4] = {{{0, 0}, {0.5, 0}, {0.5, 0.5}, {0, 0.5}},
                                              {{1, 0}, {1, 0.5}, {0.5, 0.5}, {0.5, 0}},
                                              {{1, 1}, {0.5, 1}, {0.5, 0.5}, {1, 0.5}},
                                              {{0, 1}, {0, 0.5}, {0.5, 0.5}, {0.5, 1}}};
  for (std::size_t k = 0; k < 4; ++k)
    for (std::size_t j = 0; j < 4; ++j) EXPECT_EQ(uv_of(fine, 4 * k + j), expect[k][j]) << "child " << k << " corner " << j;
  EXPECT_EQ(fine.num_points(), 9u);  // 4 corners, 4 edge midpoints, 1 centre: one per fine vertex
}

TEST(FaceVaryingUv, TriangleSplitByHand) {
  const Complex c = polygons(3, {{0, 1, 2}});
  const FaceVaryingUV uv{{0, 0, 4, 0, 0, 2}, {0, 1, 2}};
  const FaceVaryingUV fine = refine_uv_tri(c, uv);
  ASSERT_EQ(uv_problem(refine_tri(c), fine), "");
  // 4f + k = (a_k, m_k, m_{k-1}); 4f + 3 = (m0, m1, m2) (refine_tri.h).
  const std::array<double, 2> a[3] = {{0, 0}, {4, 0}, {0, 2}}, m[3] = {{2, 0}, {2, 1}, {0, 1}};
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(uv_of(fine, 3 * k), a[k]);
    EXPECT_EQ(uv_of(fine, 3 * k + 1), m[k]);
    EXPECT_EQ(uv_of(fine, 3 * k + 2), m[(k + 2) % 3]);
  }
  for (int k = 0; k < 3; ++k) EXPECT_EQ(uv_of(fine, 9 + k), m[k]);
}

TEST(FaceVaryingUv, SeamsStayApartSharedEdgesStayShared) {
  // Two quads sharing edge 1-4. Left: UV points 0..3 on its corners; right: its own points
  // (a seam along 1-4) in `seam`, or the left's points at vertices 1 and 4 in `shared`.
  const Complex c = polygons(6, {{0, 1, 4, 3}, {1, 2, 5, 4}});
  const FaceVaryingUV seam{{0, 0, 1, 0, 1, 1, 0, 1, 5, 0, 6, 0, 6, 1, 5, 1}, {0, 1, 2, 3, 4, 5, 6, 7}},
      shared{{0, 0, 1, 0, 1, 1, 0, 1, 2, 0, 2, 1}, {0, 1, 2, 3, 1, 4, 5, 2}};
  for (const bool with_seam : {true, false}) {
    const FaceVaryingUV fine = refine_uv_split(c, with_seam ? seam : shared);
    const Complex f = refine(c);
    ASSERT_EQ(uv_problem(f, fine), "");
    // The midpoint of edge 1-4 is one fine vertex; its corners in the two faces use one UV
    // point when the edge is shared, two different ones (each face's own mean) across a seam.
    std::set<std::uint32_t> uv_at_mid;
    std::set<std::array<double, 2>> values;
    const std::uint32_t mid = [&] {
      for (std::uint32_t e = 0; e < c.num_edges(); ++e)
        if (std::set<std::uint32_t>{c.edge_verts[2 * e], c.edge_verts[2 * e + 1]} == std::set<std::uint32_t>{1, 4}) return c.num_vertices + e;
      return 0u;
    }();
    for (std::size_t k = 0; k < f.faces.items.size(); ++k)
      if (f.faces.items[k] == mid) uv_at_mid.insert(fine.corners[k]), values.insert(uv_of(fine, k));
    EXPECT_EQ(uv_at_mid.size(), with_seam ? 2u : 1u);
    if (with_seam)
      EXPECT_EQ(values, (std::set<std::array<double, 2>>{{1, 0.5}, {5, 0.5}}));
    else
      EXPECT_EQ(values, (std::set<std::array<double, 2>>{{1, 0.5}}));
    // Without seams there is one UV point per fine vertex, as in the base.
    if (!with_seam) {
      EXPECT_EQ(fine.num_points(), f.num_vertices);
    }
  }
}

// A cube whose six faces each map the whole texture (seams on every edge).
constexpr char kCubeObj[] =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
    "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
    "f 1/1 4/2 3/3 2/4\nf 5/1 6/2 7/3 8/4\nf 1/1 2/2 6/3 5/4\nf 2/1 3/2 7/3 6/4\nf 3/1 4/2 8/3 7/4\nf 4/1 1/2 5/3 8/4\n";

TEST(ObjUv, ReadWrittenAndReadBackExactly) {
  TempDir dir("sublift_uv_obj");
  { std::ofstream(dir.file("cube.obj")) << kCubeObj; }
  const Shape s = read_shape(dir.file("cube.obj"));
  ASSERT_EQ(s.uv.num_points(), 4u);
  ASSERT_EQ(s.uv.corners.size(), 24u);
  EXPECT_EQ(uv_problem(s.base, s.uv), "");
  EXPECT_EQ(uv_of(s.uv, 5), (std::array<double, 2>{1, 0}));  // face 1's second corner: vt 2
  EXPECT_FALSE(not_kept(s.report, "texture")) << s.report.not_kept_summary();
  const auto notes = write_shape(dir.file("out.obj"), s.base, s.positions, {}, &s.uv);
  EXPECT_TRUE(notes.empty());
  const Shape back = read_shape(dir.file("out.obj"));
  EXPECT_EQ(back.uv.points, s.uv.points);
  EXPECT_EQ(back.uv.corners, s.uv.corners);
  // A format without face-varying data names what it leaves out.
  const auto ply = write_shape(dir.file("out.ply"), s.base, s.positions, {}, &s.uv);
  ASSERT_EQ(ply.size(), 1u);
  EXPECT_NE(ply[0].find("cannot hold texture coordinates"), std::string::npos) << ply[0];
}

TEST(ObjUv, IncompleteOrBrokenUvsAreNamedNotKept) {
  TempDir dir("sublift_uv_obj_bad");
  // Face 2 (line 7) has no vt: a UV set must cover every corner.
  { std::ofstream(dir.file("partial.obj")) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nf 1/1 2/1 3/1\nf 2 4 3\n"; }
  const Shape p = read_shape(dir.file("partial.obj"));
  EXPECT_TRUE(p.uv.empty());
  const ImportWarning* w = not_kept(p.report, "texture coordinates (vt): a face without them");
  ASSERT_TRUE(w) << p.report.not_kept_summary();
  EXPECT_EQ(w->first_lines, std::vector<std::size_t>{7});
  // An index beyond the vt lines (line 5).
  { std::ofstream(dir.file("range.obj")) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/9\n"; }
  const Shape r = read_shape(dir.file("range.obj"));
  EXPECT_TRUE(r.uv.empty());
  w = not_kept(r.report, "texture-coordinate index out of range");
  ASSERT_TRUE(w) << r.report.not_kept_summary();
  EXPECT_EQ(w->first_lines, std::vector<std::size_t>{5});
  // An unreadable vt line, named by its line (4).
  { std::ofstream(dir.file("junk.obj")) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 zero\nf 1/1 2/1 3/1\n"; }
  const Shape j = read_shape(dir.file("junk.obj"));
  EXPECT_TRUE(j.uv.empty());
  w = not_kept(j.report, "unreadable 'vt");
  ASSERT_TRUE(w) << j.report.not_kept_summary();
  EXPECT_EQ(w->first_lines, std::vector<std::size_t>{4});
  // Positions and faces come in all the same.
  EXPECT_EQ(p.base.num_faces(), 2u);
  EXPECT_EQ(r.base.num_faces(), 1u);
  EXPECT_EQ(j.base.num_faces(), 1u);
}

// BoxTextured: 24 glTF vertices (4 per face) welded into the 8 corners of the box; each
// triangle corner keeps its own vertex's TEXCOORD_0 (v = 1 - t).
TEST(GltfUv, BoxTexturedReadWithItsTexture) {
  if (!fs::exists(kBoxTextured)) GTEST_SKIP() << kBoxTextured << " not found (../shared/data absent)";
  const Shape s = read_shape(kBoxTextured.string());
  EXPECT_EQ(s.positions.size(), 3u * 8);
  ASSERT_EQ(s.base.num_faces(), 12u);
  ASSERT_EQ(s.uv.num_points(), 24u);
  EXPECT_EQ(uv_problem(s.base, s.uv), "");
  // The texture is the PNG beside the file, byte for byte, with the material's sampler.
  EXPECT_EQ(s.texture.bytes, read_file_bytes((kBoxTextured.parent_path() / "CesiumLogoFlat.png").string()));
  EXPECT_EQ(s.texture.mime_type, "image/png");
  EXPECT_EQ(s.texture.name, "CesiumLogoFlat.png");
  EXPECT_EQ(s.texture.wrap_s, 33648);  // MIRRORED_REPEAT, as the file's sampler says
  EXPECT_EQ(s.texture.wrap_t, 33071);  // CLAMP_TO_EDGE
  EXPECT_EQ(s.texture.metallic, 0.0);
  // One UV point per glTF vertex in file order, v = 1 - t; values read from BoxTextured0.bin with
  // python3: vertex 0 (6, 0), vertex 2 (6, 0.99999988079071045), u over 0..6 (a strip per face,
  // which the mirrored-repeat sampler folds back), t over 0..1.
  EXPECT_EQ(uv_of(FaceVaryingUV{s.uv.points, {0}}, 0), (std::array<double, 2>{6, 1}));
  EXPECT_EQ(s.uv.points[4], 6.0);
  EXPECT_EQ(s.uv.points[5], 1.0 - double(0.99999988079071045f));
  double lo[2] = {1e9, 1e9}, hi[2] = {-1e9, -1e9};
  for (std::size_t k = 0; k < s.uv.points.size(); ++k) lo[k % 2] = std::min(lo[k % 2], s.uv.points[k]), hi[k % 2] = std::max(hi[k % 2], s.uv.points[k]);
  EXPECT_EQ(lo[0], 0.0);
  EXPECT_EQ(hi[0], 6.0);
  EXPECT_EQ(lo[1], 0.0);
  EXPECT_EQ(hi[1], 1.0);
  // Seams: every box corner has three different UV points, one per face.
  std::map<std::uint32_t, std::set<std::uint32_t>> per_vertex;
  for (std::size_t k = 0; k < s.base.faces.items.size(); ++k) per_vertex[s.base.faces.items[k]].insert(s.uv.corners[k]);
  for (const auto& [v, uvs] : per_vertex) EXPECT_EQ(uvs.size(), 3u) << "box corner " << v << " is on three faces, each its own chart";
}

// The affine map of base triangle t from position to UV: barycentric coordinates in the
// triangle's plane. Finds for each fine face the base triangle containing its centroid and checks
// every corner's UV against that triangle's map.
void expect_maps_as_base(const Shape& base, const Shape& fine, double tolerance) {
  ASSERT_FALSE(fine.uv.empty());
  const auto p = [](const Shape& s, std::uint32_t v) { return glm::dvec3(s.positions[3 * v], s.positions[3 * v + 1], s.positions[3 * v + 2]); };
  std::size_t checked = 0;
  for (std::uint32_t f = 0; f < fine.base.num_faces(); ++f) {
    const auto corners = fine.base.faces.row(f);
    glm::dvec3 centroid(0.0);
    for (std::uint32_t v : corners) centroid += p(fine, v);
    centroid /= double(corners.size());
    int found = -1;
    glm::dvec3 bary_c(0.0);
    auto bary = [&](std::uint32_t t, const glm::dvec3& x) {
      const std::uint32_t* a = &base.base.faces.items[base.base.faces.offsets[t]];
      const glm::dvec3 p0 = p(base, a[0]), e1 = p(base, a[1]) - p0, e2 = p(base, a[2]) - p0, d = x - p0;
      const double d11 = glm::dot(e1, e1), d12 = glm::dot(e1, e2), d22 = glm::dot(e2, e2);
      const double b1 = glm::dot(d, e1), b2 = glm::dot(d, e2), det = d11 * d22 - d12 * d12;
      const double v = (d22 * b1 - d12 * b2) / det, w = (d11 * b2 - d12 * b1) / det;
      const double off_plane = glm::length(d - v * e1 - w * e2);
      return std::pair{glm::dvec3(1 - v - w, v, w), off_plane};
    };
    for (std::uint32_t t = 0; t < base.base.num_faces() && found < 0; ++t) {
      const auto [b, off] = bary(t, centroid);
      if (off < 1e-6 && b.x > 1e-6 && b.y > 1e-6 && b.z > 1e-6) found = int(t), bary_c = b;
    }
    ASSERT_GE(found, 0) << "fine face " << f << " lies in no base triangle";
    const std::uint32_t first = base.base.faces.offsets[std::uint32_t(found)];
    for (std::uint32_t k = fine.base.faces.offsets[f]; k < fine.base.faces.offsets[f + 1]; ++k) {
      const auto [b, off] = bary(std::uint32_t(found), p(fine, fine.base.faces.items[k]));
      double u = 0, v = 0;
      for (int i = 0; i < 3; ++i) {
        const auto t = uv_of(base.uv, first + std::uint32_t(i));
        u += b[i] * t[0], v += b[i] * t[1];
      }
      const auto got = uv_of(fine.uv, k);
      EXPECT_NEAR(got[0], u, tolerance) << "fine face " << f << " corner slot " << k;
      EXPECT_NEAR(got[1], v, tolerance) << "fine face " << f << " corner slot " << k;
      ++checked;
    }
  }
  EXPECT_GT(checked, 0u);
}

// Subdivided with the linear schemes (which keep the box flat, so each fine face lies in one
// base triangle), written as glTF (float32) and OBJ (17 digits), read back: the map is the base's.
TEST(GltfUv, SubdividedBoxTexturedStillMapsItsTexture) {
  if (!fs::exists(kBoxTextured)) GTEST_SKIP() << kBoxTextured << " not found (../shared/data absent)";
  TempDir dir("sublift_uv_box_textured");
  const Shape base = read_shape(kBoxTextured.string());
  for (const char* scheme : {"linear", "linear-tri"})
    for (const char* ext : {"glb", "obj"}) {
      SCOPED_TRACE(std::string(scheme) + " ." + ext);
      const std::string out = dir.file(std::string("fine_") + scheme + "." + ext);
      const auto r = testing::run_cli({"subdivide", kBoxTextured.string(), "--scheme", scheme, "--levels", "3", "-o", out, "--json"});
      ASSERT_EQ(r.exit_code, 0) << r.err;
      EXPECT_EQ(r.err.find("not written"), std::string::npos) << r.err;  // (the weld of the file's 24 vertices is a warning)
      EXPECT_NE(r.out.find("\"texture\": \"CesiumLogoFlat.png\""), std::string::npos) << r.out;
      const Shape fine = read_shape(out);
      expect_maps_as_base(base, fine, std::string(ext) == "glb" ? 1e-6 : 1e-12);
      // The texture goes with them: embedded in the glb, beside the obj through its .mtl.
      const std::string image = std::string(ext) == "glb" ? fine.texture.bytes
                                                          : read_file_bytes(dir.file(std::string("fine_") + scheme + "_CesiumLogoFlat.png"));
      EXPECT_EQ(image, base.texture.bytes);
      if (std::string(ext) == "obj") {
        const std::string mtl = read_file_bytes(dir.file(std::string("fine_") + scheme + ".mtl"));
        EXPECT_NE(mtl.find(std::string("map_Kd fine_") + scheme + "_CesiumLogoFlat.png"), std::string::npos) << mtl;
      }
    }
}

TEST(GltfUv, Sqrt2SaysWhyItLeavesTheUvsOut) {
  if (!fs::exists(kBoxTextured)) GTEST_SKIP() << kBoxTextured << " not found (../shared/data absent)";
  TempDir dir("sublift_uv_sqrt2");
  // BoxTextured is all triangles; sqrt2 takes quad-dominant surfaces, so use a textured quad cube.
  { std::ofstream(dir.file("cube.obj")) << kCubeObj; }
  const auto r = testing::run_cli({"subdivide", dir.file("cube.obj"), "--scheme", "sqrt2", "--levels", "2", "-o", dir.file("s.obj")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("texture coordinates not written: sqrt2 cannot carry texture coordinates"), std::string::npos) << r.err;
  EXPECT_TRUE(read_shape(dir.file("s.obj")).uv.empty());
}


// Projects keep the base's UVs (header 'uv'): analyze with a textured BASE, synthesize gives each
// level the UVs subdivide gives it; rebuild of a textured fine mesh in its own order coarsens
// them, and synthesize of the finest level gives the file's UVs back corner for corner.
TEST(ProjectUv, AnalyzeSynthesizeAndRebuildKeepThem) {
  TempDir dir("sublift_uv_project");
  { std::ofstream(dir.file("cube.obj")) << kCubeObj; }
  auto r = testing::run_cli({"subdivide", dir.file("cube.obj"), "--scheme", "cubic", "--levels", "2", "-o", dir.file("fine.obj")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = testing::run_cli({"analyze", dir.file("fine.obj"), "--base", dir.file("cube.obj"), "--scheme", "cubic", "--levels", "2",
                        "-o", dir.file("cube.sublift")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = testing::run_cli({"info", dir.file("cube.sublift"), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("\"uv_points\": 4"), std::string::npos) << r.out;
  for (int level = 0; level <= 2; ++level) {
    const std::string sub = dir.file("sub" + std::to_string(level) + ".obj"), syn = dir.file("syn" + std::to_string(level) + ".obj");
    ASSERT_EQ(testing::run_cli({"subdivide", dir.file("cube.obj"), "--scheme", "cubic", "--levels", std::to_string(level), "-o", sub}).exit_code, 0);
    r = testing::run_cli({"synthesize", dir.file("cube.sublift"), "--level", std::to_string(level), "-o", syn});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const Shape a = read_shape(sub), b = read_shape(syn);
    EXPECT_EQ(a.uv.points, b.uv.points) << "level " << level;
    EXPECT_EQ(a.uv.corners, b.uv.corners) << "level " << level;
  }
  // rebuild finds the levels of fine.obj (written in the engine's order) and its base's UVs.
  r = testing::run_cli({"rebuild", dir.file("fine.obj"), "--scheme", "cubic", "-o", dir.file("rebuilt.sublift")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("texture coordinates"), std::string::npos) << r.err;
  r = testing::run_cli({"synthesize", dir.file("rebuilt.sublift"), "-o", dir.file("back.obj")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Shape fine = read_shape(dir.file("fine.obj")), back = read_shape(dir.file("back.obj"));
  ASSERT_EQ(back.base.faces.items, fine.base.faces.items);  // the file's own order
  ASSERT_EQ(back.uv.corners.size(), fine.uv.corners.size());
  for (std::size_t k = 0; k < fine.uv.corners.size(); ++k) EXPECT_EQ(uv_of(back.uv, k), uv_of(fine.uv, k)) << "corner " << k;
}

TEST(ProjectUv, UvsThatAreNoLinearRefinementAreNamedNotKept) {
  TempDir dir("sublift_uv_project_bent");
  { std::ofstream(dir.file("cube.obj")) << kCubeObj; }
  ASSERT_EQ(testing::run_cli({"subdivide", dir.file("cube.obj"), "--scheme", "cubic", "--levels", "1", "-o", dir.file("fine.obj")}).exit_code, 0);
  // Move the last UV point (a face centre's) off the linear rule.
  std::string text = read_file_bytes(dir.file("fine.obj"));
  const std::size_t last_vt = text.rfind("\nvt ");
  ASSERT_NE(last_vt, std::string::npos);
  text.replace(last_vt + 1, text.find('\n', last_vt + 1) - last_vt - 1, "vt 0.25 0.75");
  { std::ofstream(dir.file("bent.obj")) << text; }
  const auto r = testing::run_cli({"rebuild", dir.file("bent.obj"), "--scheme", "cubic", "-o", dir.file("bent.sublift")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("not kept in the project (nor written back): texture coordinates (14 UV points): the UVs are not the linear refinement"),
            std::string::npos) << r.err;
}

TEST(ProjectUv, AHeaderWhoseUvsDoNotFitTheBaseIsRefused) {
  TempDir dir("sublift_uv_project_bad");
  { std::ofstream(dir.file("cube.obj")) << kCubeObj; }
  ASSERT_EQ(testing::run_cli({"subdivide", dir.file("cube.obj"), "--scheme", "linear", "--levels", "1", "-o", dir.file("fine.obj")}).exit_code, 0);
  ASSERT_EQ(testing::run_cli({"analyze", dir.file("fine.obj"), "--base", dir.file("cube.obj"), "--scheme", "linear", "--levels", "1",
                              "-o", dir.file("cube.sublift")}).exit_code, 0);
  std::string bytes = read_file_bytes(dir.file("cube.sublift"));
  const std::size_t at = bytes.find("\"uv\":{\"corners\":[");
  ASSERT_NE(at, std::string::npos);
  bytes.insert(at + std::string("\"uv\":{\"corners\":[").size(), "0,");  // one corner too many
  { std::ofstream(dir.file("bad.sublift"), std::ios::binary) << bytes; }
  const auto r = testing::run_cli({"info", dir.file("bad.sublift")});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("bad.sublift:2: header 'uv': 25 UV corners for 24 face corners"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace sublift
