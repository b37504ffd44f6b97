// Resampling onto a subdivided octahedron (core/analysis/sphere_resample.h, `sublift-cli resample-sphere`):
// a cube against the analytic ray-plane intersection, an icosphere against its discretisation
// error, a torus (not star-shaped: farthest hit kept), an open cube (misses filled), the output's
// topology against refine_tri^J of the octahedron (what `analyze --base` rebuilds), the CLI's
// JSON and errors, and a real closed scan from the shared data.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "core/complex/connectivity_match.h"
#include "core/base/errors.h"
#include "core/complex/refine_tri.h"
#include "core/io/lattice/shape_io.h"
#include "core/complex/shapes.h"
#include "core/analysis/sphere_resample.h"
#include "tests/cli_run.h"
#include "tests/io_test_util.h"

using namespace sublift;
using sublift::testing::ProcessResult;
using sublift::testing::run_cli;
using sublift::testing::TempDir;

namespace {

// Cube [-h, h]^3 as 6 outward quads (vertex k has x, y, z from bits 0, 1, 2); `drop_top`
// leaves out the z = +h face.
SurfaceMesh cube(double h = 1.0, bool drop_top = false) {
  SurfaceMesh m;
  for (int k = 0; k < 8; ++k) m.positions.emplace_back(k & 1 ? h : -h, k & 2 ? h : -h, k & 4 ? h : -h);
  const std::uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (int f = 0; f < 6; ++f)
    if (!(drop_top && f == 1)) m.add_face(quads[f]);
  return m;
}

// Icosahedron split 1-to-4 `splits` times, every vertex projected onto the unit sphere (built
// here with its own midpoint table, independent of refine_tri and of the octahedron).
SurfaceMesh icosphere(int splits) {
  const double t = (1 + std::sqrt(5.0)) / 2;
  std::vector<glm::dvec3> p = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                               {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (auto& q : p) q = glm::normalize(q);
  std::vector<std::array<std::uint32_t, 3>> tris = {
      {0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
      {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},   {4, 9, 5}, {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int s = 0; s < splits; ++s) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mid;
    auto m = [&](std::uint32_t a, std::uint32_t b) {
      auto [it, added] = mid.try_emplace({std::min(a, b), std::max(a, b)}, static_cast<std::uint32_t>(p.size()));
      if (added) p.push_back(glm::normalize(p[a] + p[b]));
      return it->second;
    };
    std::vector<std::array<std::uint32_t, 3>> next;
    for (const auto& [a, b, c] : tris) {
      const std::uint32_t ab = m(a, b), bc = m(b, c), ca = m(c, a);
      next.insert(next.end(), {{a, ab, ca}, {b, bc, ab}, {c, ca, bc}, {ab, bc, ca}});
    }
    tris = std::move(next);
  }
  SurfaceMesh mesh;
  mesh.positions = p;
  for (const auto& tri : tris) mesh.add_face(tri);
  return mesh;
}

glm::dvec3 position(const SphereResample& r, std::size_t v) {
  return {r.positions[3 * v], r.positions[3 * v + 1], r.positions[3 * v + 2]};
}

// Unit directions of the fine vertices, computed here from the rule (axes; then per level
// normalize(d_a + d_b) for the midpoint nv + e of coarse edge e, refine_tri's numbering).
std::vector<glm::dvec3> expected_directions(int levels) {
  std::vector<glm::dvec3> d = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  Complex c = octahedron_complex();
  for (int j = 0; j < levels; ++j) {
    const std::uint32_t nv = c.num_vertices;
    for (std::uint32_t e = 0; e < c.num_edges(); ++e) d.push_back(glm::normalize(d[c.edge_verts[2 * e]] + d[c.edge_verts[2 * e + 1]]));
    EXPECT_EQ(d.size(), nv + c.num_edges());
    c = refine_tri(c, false);
  }
  return d;
}

// Where the ray c + t d leaves the box [-h, h]^3 (c inside): t and the axis of the exit face;
// `second` is the t of the next-nearest face plane (to tell exits near an edge).
struct BoxExit {
  double t = 0, second = 0;
  int axis = 0, sign = 0;
};
BoxExit box_exit(const glm::dvec3& c, const glm::dvec3& d, double h) {
  BoxExit b;
  b.t = b.second = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    if (d[k] == 0) continue;
    const double t = ((d[k] > 0 ? h : -h) - c[k]) / d[k];
    if (t < b.t) {
      b.second = b.t;
      b.t = t, b.axis = k, b.sign = d[k] > 0 ? 1 : -1;
    } else {
      b.second = std::min(b.second, t);
    }
  }
  return b;
}

Complex refined_octahedron(int levels) {
  Complex c = octahedron_complex();
  for (int j = 0; j < levels; ++j) c = refine_tri(c);
  return c;
}

std::string write_text(const TempDir& dir, const std::string& name, const std::string& text) {
  const std::string path = dir.file(name);
  std::ofstream(path) << text;
  return path;
}

// The OBJ text of a mesh (for CLI inputs).
std::string obj_text(const SurfaceMesh& m) {
  std::ostringstream s;
  s.precision(17);
  for (const auto& p : m.positions) s << "v " << p.x << ' ' << p.y << ' ' << p.z << '\n';
  for (std::size_t f = 0; f < m.num_faces(); ++f) {
    s << 'f';
    for (std::uint32_t v : m.face(f)) s << ' ' << v + 1;
    s << '\n';
  }
  return s.str();
}

}  // namespace

TEST(SphereResample, OctahedronIsOutwardWithAxisVertices) {
  const Complex c = octahedron_complex();
  ASSERT_EQ(c.num_vertices, 6u);
  ASSERT_EQ(c.num_faces(), 8u);
  ASSERT_EQ(c.num_edges(), 12u);
  validate(c);
  const GeodesicSphere s = geodesic_sphere(0);
  const glm::dvec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (int v = 0; v < 6; ++v) EXPECT_EQ(s.directions[v], axes[v]) << v;
  for (std::uint32_t f = 0; f < 8; ++f) {
    const auto r = c.faces.row(f);
    const glm::dvec3 a = axes[r[0]], b = axes[r[1]], d = axes[r[2]];
    EXPECT_GT(glm::dot(glm::cross(b - a, d - a), a + b + d), 0.0) << "face " << f << " is not counterclockwise from outside";
  }
}

TEST(SphereResample, CubeHitsTheAnalyticRayPlaneIntersection) {
  const int levels = 4;
  const SphereResample r = resample_sphere(cube(), levels);
  EXPECT_EQ(r.centroid.kind, CentroidKind::Volume);
  EXPECT_LT(glm::length(r.centroid.point), 1e-14);
  EXPECT_EQ(r.missed, 0u);
  EXPECT_EQ(r.multiple_hits, 0u);
  EXPECT_EQ(r.fill_rounds, 0);
  const std::vector<glm::dvec3> d = expected_directions(levels);
  ASSERT_EQ(r.rays, d.size());
  ASSERT_EQ(r.positions.size(), 3 * d.size());
  double worst = 0, worst_on_cube = 0;
  for (std::size_t v = 0; v < d.size(); ++v) {
    const glm::dvec3 p = position(r, v);
    const BoxExit b = box_exit(r.centroid.point, d[v], 1.0);
    const glm::dvec3 expected = r.centroid.point + b.t * d[v];
    worst = std::max(worst, glm::length(p - expected));
    worst_on_cube = std::max(worst_on_cube, std::abs(std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}) - 1.0));
  }
  EXPECT_LT(worst, 1e-12);
  EXPECT_LT(worst_on_cube, 1e-12);
}

TEST(SphereResample, IcosphereRadiiWithinItsDiscretisation) {
  // The flat triangles lie inside the unit sphere, each no nearer to the centre than its plane.
  const SurfaceMesh ico = icosphere(4);
  double nearest_plane = 1;
  for (std::size_t f = 0; f < ico.num_faces(); ++f) {
    const auto c = ico.face(f);
    const glm::dvec3 a = ico.positions[c[0]], b = ico.positions[c[1]], d = ico.positions[c[2]];
    nearest_plane = std::min(nearest_plane, std::abs(glm::dot(a, glm::normalize(glm::cross(b - a, d - a)))));
  }
  ASSERT_GT(nearest_plane, 0.998);  // the discretisation error of 4 splits: about 1e-3
  const SphereResample r = resample_sphere(ico, 5);
  EXPECT_EQ(r.centroid.kind, CentroidKind::Volume);
  EXPECT_LT(glm::length(r.centroid.point), 1e-12);
  EXPECT_EQ(r.missed, 0u);
  EXPECT_EQ(r.multiple_hits, 0u);
  double lo = 2, hi = 0;
  for (std::size_t v = 0; v < r.rays; ++v) {
    const double radius = glm::length(position(r, v) - r.centroid.point);
    lo = std::min(lo, radius);
    hi = std::max(hi, radius);
  }
  EXPECT_GE(lo, nearest_plane - 1e-12);
  EXPECT_LE(hi, 1 + 1e-12);
  // The rays land inside faces too, not only on the icosphere's vertices.
  EXPECT_LT(lo, 1 - 1e-5);
}

TEST(SphereResample, TorusKeepsTheFarthestHit) {
  // From the centre of a torus (R 1, r 0.4) a ray in its plane crosses the tube twice, at
  // about 0.6 and 1.4; a ray along the axis meets nothing.
  const SurfaceMesh torus = make_quad_torus(64, 32, 1.0, 0.4);
  const SphereResample r = resample_sphere(torus, 4);
  EXPECT_EQ(r.centroid.kind, CentroidKind::Volume);
  EXPECT_LT(glm::length(r.centroid.point), 1e-12);
  EXPECT_GT(r.multiple_hits, 0u);
  EXPECT_GT(r.missed, 0u);
  // +x (vertex 0) passes through the torus vertex (1.4, 0, 0) of the outer equator.
  EXPECT_LT(glm::length(position(r, 0) - glm::dvec3(1.4, 0, 0)), 1e-9);
  EXPECT_LT(glm::length(position(r, 2) - glm::dvec3(0, 1.4, 0)), 1e-9);
  // Every ray in the torus's plane ends on the outer equator (chords of 64 segments: >= 1.399).
  const std::vector<glm::dvec3> d = expected_directions(4);
  int in_plane = 0;
  for (std::size_t v = 0; v < d.size(); ++v) {
    if (d[v].z != 0) continue;
    ++in_plane;
    const double radius = glm::length(position(r, v) - r.centroid.point);
    EXPECT_GT(radius, 1.39) << "vertex " << v;
    EXPECT_LT(radius, 1.4 + 1e-9) << "vertex " << v;
  }
  EXPECT_EQ(in_plane, 4 * 16);
}

TEST(SphereResample, OpenCubeFillsTheMisses) {
  const int levels = 4;
  const SphereResample r = resample_sphere(cube(1.0, /*drop_top=*/true), levels);
  // Open: the area centroid of five faces of area 4 at z = 0 (four sides) and z = -1: z = -1/5.
  EXPECT_EQ(r.centroid.kind, CentroidKind::Area);
  EXPECT_LT(glm::length(r.centroid.point - glm::dvec3(0, 0, -0.2)), 1e-14);
  const std::vector<glm::dvec3> d = expected_directions(levels);
  std::size_t through_top = 0, near_edge = 0;
  double hit_lo = HUGE_VAL, hit_hi = 0;
  std::vector<std::size_t> filled;
  for (std::size_t v = 0; v < d.size(); ++v) {
    const BoxExit b = box_exit(r.centroid.point, d[v], 1.0);
    const bool top = b.axis == 2 && b.sign > 0;
    if (b.second - b.t < 1e-9) {
      ++near_edge;  // exits next to the top's rim or another edge: hit or missed are both right
    } else if (top) {
      ++through_top;
      filled.push_back(v);
      continue;
    } else {
      const glm::dvec3 expected = r.centroid.point + b.t * d[v];
      EXPECT_LT(glm::length(position(r, v) - expected), 1e-12) << "vertex " << v;
    }
    hit_lo = std::min(hit_lo, b.t);
    hit_hi = std::max(hit_hi, b.t);
  }
  EXPECT_GT(through_top, 0u);
  EXPECT_GE(r.missed, through_top);
  EXPECT_LE(r.missed, through_top + near_edge);
  EXPECT_GT(r.fill_rounds, 0);
  EXPECT_EQ(r.multiple_hits, 0u);
  for (std::size_t v : filled) {
    const glm::dvec3 p = position(r, v);
    ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) << "vertex " << v;
    // A mean of hit radii (of means of hit radii, ...) lies between the extremes.
    const double radius = glm::length(p - r.centroid.point);
    EXPECT_GE(radius, hit_lo - 1e-12) << "vertex " << v;
    EXPECT_LE(radius, hit_hi + 1e-12) << "vertex " << v;
  }
}

TEST(SphereResample, TopologyIsTheRefinedOctahedron) {
  for (int levels = 0; levels <= 5; ++levels) {
    const GeodesicSphere s = geodesic_sphere(levels);
    const Complex expected = refined_octahedron(levels);
    EXPECT_EQ(s.fine.num_vertices, sphere_vertex_count(levels));
    EXPECT_EQ(s.fine.num_faces(), 8u << (2 * levels));
    EXPECT_EQ(s.fine.num_edges(), 12u << (2 * levels));
    EXPECT_EQ(s.fine.faces.offsets, expected.faces.offsets);
    EXPECT_EQ(s.fine.faces.items, expected.faces.items);
    EXPECT_EQ(s.fine.edge_verts, expected.edge_verts);
    validate(s.fine);
    for (const glm::dvec3& d : s.directions) EXPECT_NEAR(glm::length(d), 1.0, 1e-15);
  }
  EXPECT_THROW(geodesic_sphere(kMaxSphereLevels + 1), Error);
  EXPECT_THROW(geodesic_sphere(-1), Error);
  EXPECT_EQ(sphere_vertex_count(9), 1048578u);
  EXPECT_EQ(sphere_vertex_count(10), 4194306u);
}

TEST(SphereResample, ErrorsOnMeshesWithoutFacesOrHits) {
  SurfaceMesh empty;
  empty.positions = {{0, 0, 0}, {1, 0, 0}};
  EXPECT_THROW(resample_sphere(empty, 2), TopologyError);
  EXPECT_THROW(mesh_centroid(empty), TopologyError);
  // Two small triangles on the diagonal through the origin (their area centroid): the six axis
  // rays of level 0 meet neither.
  SurfaceMesh off_axis;
  off_axis.positions = {{1.1, 1, 1}, {1, 1.1, 1}, {1, 1, 1.1}, {-1.1, -1, -1}, {-1, -1.1, -1}, {-1, -1, -1.1}};
  const std::uint32_t t0[3] = {0, 1, 2}, t1[3] = {3, 5, 4};
  off_axis.add_face(t0);
  off_axis.add_face(t1);
  EXPECT_LT(glm::length(mesh_centroid(off_axis).point), 1e-15);
  EXPECT_THROW(resample_sphere(off_axis, 0), TopologyError);
  EXPECT_THROW(resample_sphere(cube(), kMaxSphereLevels + 1), Error);
}

TEST(SphereResampleCli, OutputIsTheRefinedBaseInTheEnginesOrder) {
  TempDir dir("sublift_sphere_topology");
  const std::string in = write_text(dir, "cube.obj", obj_text(cube(1.5)));
  for (const auto& [levels, ext] : {std::pair{3, std::string("obj")}, std::pair{2, std::string("off")}}) {
    const std::string out = dir.file("fine." + ext), base = dir.file("base." + ext);
    const ProcessResult p = run_cli({"resample-sphere", in, "--levels", std::to_string(levels), "-o", out, "--base-out", base});
    ASSERT_EQ(p.exit_code, 0) << p.err;
    const Shape fine = read_shape(out), coarse = read_shape(base);
    // BASE is the octahedron, faces as octahedron_complex() lists them.
    const Complex octa = octahedron_complex();
    EXPECT_EQ(coarse.base.faces.offsets, octa.faces.offsets);
    EXPECT_EQ(coarse.base.faces.items, octa.faces.items);
    // What analyze does: refine BASE (as read) J times; FINE must have its faces corner by corner.
    Complex refined = coarse.base;
    for (int j = 0; j < levels; ++j) refined = refine_tri(refined);
    EXPECT_EQ(fine.base.num_vertices, refined.num_vertices);
    EXPECT_EQ(fine.base.faces.offsets, refined.faces.offsets);
    EXPECT_EQ(fine.base.faces.items, refined.faces.items);
    EXPECT_EQ(connectivity_mismatch(refined, fine.base), "");  // the check analyze runs
    const Complex direct = refined_octahedron(levels);
    EXPECT_EQ(fine.base.faces.items, direct.faces.items);
    EXPECT_EQ(fine.base.num_faces(), 8u << (2 * levels));
    EXPECT_EQ(fine.base.num_vertices, sphere_vertex_count(levels));
    // BASE's positions are FINE's first six.
    ASSERT_EQ(coarse.positions.size(), 18u);
    for (int i = 0; i < 18; ++i) EXPECT_EQ(fine.positions[i], coarse.positions[i]) << i;
    // ... and are the cube's face centres (the axes hit the faces at 1.5).
    EXPECT_NEAR(coarse.positions[0], 1.5, 1e-12);
    EXPECT_NEAR(coarse.positions[5 * 3 + 2], -1.5, 1e-12);
  }
}

TEST(SphereResampleCli, JsonAndErrors) {
  TempDir dir("sublift_sphere_cli");
  const std::string in = write_text(dir, "cube.obj", obj_text(cube()));
  const std::string out = dir.file("fine.obj");
  const ProcessResult ok = run_cli({"resample-sphere", in, "--levels", "2", "-o", out, "--json"});
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  const auto j = nlohmann::json::parse(ok.out);
  for (const char* key : {"levels", "vertices", "faces", "centroid", "centroid_kind", "missed", "multiple_hits", "rays", "seconds"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["levels"], 2);
  EXPECT_EQ(j["vertices"], 66);
  EXPECT_EQ(j["faces"], 128);
  EXPECT_EQ(j["rays"], 66);
  EXPECT_EQ(j["centroid_kind"], "volume");
  EXPECT_EQ(j["missed"], 0);
  EXPECT_EQ(j["multiple_hits"], 0);
  ASSERT_EQ(j["centroid"].size(), 3u);
  EXPECT_GE(j["seconds"].get<double>(), 0.0);

  // A missing file is named.
  const std::string missing = dir.file("no_such_mesh.obj");
  ProcessResult p = run_cli({"resample-sphere", missing, "--levels", "2", "-o", out});
  EXPECT_EQ(p.exit_code, 1);
  EXPECT_NE(p.err.find("no_such_mesh.obj"), std::string::npos) << p.err;
  // Too many levels: refused with the vertex count it would make.
  p = run_cli({"resample-sphere", in, "--levels", "11", "-o", out});
  EXPECT_EQ(p.exit_code, 2);
  EXPECT_NE(p.err.find("16777218"), std::string::npos) << p.err;
  p = run_cli({"resample-sphere", in, "--levels", "-1", "-o", out});
  EXPECT_EQ(p.exit_code, 2);
  p = run_cli({"resample-sphere", in, "--levels", "2"});
  EXPECT_EQ(p.exit_code, 2);
  EXPECT_NE(p.err.find("-o"), std::string::npos) << p.err;
  p = run_cli({"resample-sphere", in, "--levels", "2", "-o", dir.file("fine.stl")});
  EXPECT_EQ(p.exit_code, 2);
  // A mesh without faces (vertices only, or an empty file): exit 1 naming the file.
  for (const std::string text : {"v 0 0 0\nv 1 0 0\nv 0 1 0\n", ""}) {
    const std::string empty = write_text(dir, "empty_mesh.obj", text);
    p = run_cli({"resample-sphere", empty, "--levels", "1", "-o", out});
    EXPECT_EQ(p.exit_code, 1) << p.err;
    EXPECT_NE(p.err.find("empty_mesh.obj"), std::string::npos) << p.err;
    EXPECT_NE(p.err.find("no faces"), std::string::npos) << p.err;
  }
  // Usage text and the command list.
  p = run_cli({"resample-sphere", "--help"});
  EXPECT_EQ(p.exit_code, 0);
  EXPECT_NE(p.out.find("--base-out"), std::string::npos);
  p = run_cli({"--help"});
  EXPECT_NE(p.out.find("resample-sphere"), std::string::npos);
}

// Issue 17: a genus-1 part cannot be a sphere: refused, with the reason, nothing written.
TEST(SphereResampleCli, RockerArmIsRefused) {
  const std::string path = std::string(SUBLIFT_SHARED_DATA) + "/scans/rocker-arm.obj";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "shared data absent: " << path;
  TempDir dir("sublift_sphere_rocker");
  const std::string out = dir.file("rocker_sphere.obj");
  const ProcessResult p = run_cli({"resample-sphere", path, "--levels", "3", "-o", out}, 60);
  EXPECT_EQ(p.exit_code, 1);
  EXPECT_NE(p.err.find("genus 1, not 0"), std::string::npos) << p.err;
  EXPECT_NE(p.err.find("nothing written"), std::string::npos) << p.err;
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(SphereResampleCli, BunnyScanAtLevelFour) {
  const std::string path = std::string(SUBLIFT_SHARED_DATA) + "/scans/bunny_npm_lowres.obj";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "shared data absent: " << path;
  TempDir dir("sublift_sphere_bunny");
  const std::string out = dir.file("bunny_sphere.ply"), base = dir.file("bunny_base.obj");
  // A ray or two crosses the ears twice: refused without --force (nothing written), done with it.
  const ProcessResult refused = run_cli({"resample-sphere", path, "--levels", "4", "-o", out, "--json"}, 60);
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_NE(refused.err.find("more than once"), std::string::npos) << refused.err;
  EXPECT_FALSE(std::filesystem::exists(out));
  EXPECT_EQ(nlohmann::json::parse(refused.out)["written"], false);
  const ProcessResult p = run_cli({"resample-sphere", path, "--levels", "4", "-o", out, "--base-out", base, "--json", "--force"}, 60);
  ASSERT_EQ(p.exit_code, 0) << p.err;
  const auto j = nlohmann::json::parse(p.out);
  EXPECT_EQ(j["vertices"], 1026);
  EXPECT_EQ(j["faces"], 2048);
  EXPECT_EQ(j["rays"], 1026);
  EXPECT_EQ(j["centroid_kind"], "volume");  // a closed scan
  EXPECT_EQ(j["missed"], 0);                // its centroid is inside: every ray leaves it
  std::cout << "bunny_npm_lowres J=4: multiple_hits " << j["multiple_hits"] << ", missed " << j["missed"]
            << ", centroid " << j["centroid"] << ", resampling " << j["seconds"] << " s, process " << p.seconds << " s\n";
  const Shape fine = read_shape(out);
  for (double x : fine.positions) ASSERT_TRUE(std::isfinite(x));
  const Shape coarse = read_shape(base);
  for (int i = 0; i < 18; ++i) EXPECT_EQ(fine.positions[i], coarse.positions[i]) << i;
}
