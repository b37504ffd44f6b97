// Level detection (core/complex/detect_levels.h): Sublift's own refinements with vertices and
// faces shuffled, OpenSubdiv's refinements in OpenSubdiv's order (oracle), and meshes that break
// subdivision connectivity.
#include "core/complex/detect_levels.h"

#include <gtest/gtest.h>

#include <opensubdiv/far/topologyRefiner.h>

#include <algorithm>
#include <filesystem>
#include <numeric>
#include <random>
#include <initializer_list>
#include <set>

#include "core/base/errors.h"
#include "core/complex/complex_build.h"
#include "core/complex/refine.h"
#include "core/complex/refine_sqrt2.h"
#include "core/complex/refine_tri.h"
#include "core/io/mesh/mesh_import.h"
#include "tests/mesh_fixtures.h"
#include "tests/osd_refiner.h"

namespace sublift {
namespace {

using fixtures::Polygons;
using fixtures::shuffled;

Polygons from_complex(const Complex& c) { return {c.num_vertices, c.faces, {}}; }

// Sublift's refinement of `m`, `levels` times (quad split or triangle split).
Polygons refined(const Polygons& m, int levels, SplitKind split) {
  Complex c = complex_from_polygons(m.num_vertices, m.faces);
  if (split == SplitKind::Sqrt2) return from_complex(build_sqrt2_levels(c, levels).back());
  for (int l = 0; l < levels; ++l) c = split == SplitKind::Quads ? refine(c) : refine_tri(c);
  return from_complex(c);
}

// The base found equals `base` up to the vertex map `to_base` (input vertex -> base vertex, or
// UINT32_MAX for vertices that are no base vertex): a bijection carrying faces onto faces.
void expect_same_base(const DetectedLevels& d, const Polygons& base, const std::vector<std::uint32_t>& to_base) {
  ASSERT_EQ(d.base_vertices, base.num_vertices);
  ASSERT_EQ(d.base_faces.rows(), base.faces.rows());
  std::vector<std::uint32_t> map(d.base_vertices);
  std::set<std::uint32_t> hit;
  for (std::uint32_t v = 0; v < d.base_vertices; ++v) {
    map[v] = to_base[d.steps.front().input_vertex[v]];
    ASSERT_LT(map[v], base.num_vertices) << "rebuilt base vertex " << v << " is no vertex of the original base";
    hit.insert(map[v]);
  }
  EXPECT_EQ(hit.size(), base.num_vertices);
  std::set<std::vector<std::uint32_t>> want, got;
  for (std::size_t f = 0; f < base.faces.rows(); ++f) {
    std::vector<std::uint32_t> s(base.faces.row(f).begin(), base.faces.row(f).end());
    std::sort(s.begin(), s.end());
    want.insert(s);
  }
  for (std::size_t f = 0; f < d.base_faces.rows(); ++f) {
    std::vector<std::uint32_t> s;
    for (std::uint32_t v : d.base_faces.row(f)) s.push_back(map[v]);
    std::sort(s.begin(), s.end());
    got.insert(s);
  }
  EXPECT_EQ(got, want);
}

// Checks detection of `levels` levels of `base` refined by Sublift and shuffled, the base
// found, and the engine order against Sublift's own level complexes. `symmetric`: the base's
// connectivity has symmetries that move vertices to edge points (a regular torus), so topology
// alone finds *a* base of the same shape, not necessarily the same vertices (positions decide
// then: rebuild_test).
void check_own_refinement(const Polygons& base, int levels, SplitKind split, unsigned seed, bool symmetric = false) {
  SCOPED_TRACE("levels " + std::to_string(levels) + " seed " + std::to_string(seed));
  std::vector<std::uint32_t> perm;
  const Polygons fine = shuffled(refined(base, levels, split), seed, &perm);
  const DetectedLevels d = detect_levels(fine.num_vertices, fine.faces, split, levels);
  ASSERT_EQ(d.levels, levels) << d.stop;
  EXPECT_EQ(d.first_level, 0);
  EXPECT_TRUE(d.stop.empty());
  // Base vertex b is fine vertex b before the shuffle ([v | e | f] keeps them first).
  std::vector<std::uint32_t> to_base(fine.num_vertices, UINT32_MAX);
  for (std::uint32_t b = 0; b < base.num_vertices; ++b) to_base[perm[b]] = b;
  if (symmetric) {
    EXPECT_EQ(d.base_vertices, base.num_vertices);
    EXPECT_EQ(d.base_faces.rows(), base.faces.rows());
  } else {
    expect_same_base(d, base, to_base);
  }
  // engine_order maps the input onto the engine's level complexes built on the base found.
  std::vector<Complex> cs{complex_from_polygons(d.base_vertices, d.base_faces)};
  if (split == SplitKind::Sqrt2) cs = build_sqrt2_levels(cs.front(), levels);
  for (int l = 0; split != SplitKind::Sqrt2 && l < levels; ++l) cs.push_back(split == SplitKind::Quads ? refine(cs.back()) : refine_tri(cs.back()));
  const std::vector<std::uint32_t> engine = engine_order(d, cs);
  std::set<std::vector<std::uint32_t>> want, got;
  for (std::size_t f = 0; f < cs.back().faces.rows(); ++f) {
    std::vector<std::uint32_t> s(cs.back().faces.row(f).begin(), cs.back().faces.row(f).end());
    std::sort(s.begin(), s.end());
    want.insert(s);
  }
  for (std::size_t f = 0; f < fine.faces.rows(); ++f) {
    std::vector<std::uint32_t> s;
    for (std::uint32_t v : fine.faces.row(f)) s.push_back(engine[v]);
    std::sort(s.begin(), s.end());
    got.insert(s);
  }
  EXPECT_EQ(got, want);
}

Polygons joined(const Polygons& a, const Polygons& b) {
  Polygons m = a;
  for (std::uint32_t x : b.faces.items) m.faces.items.push_back(x + a.num_vertices);
  for (std::size_t f = 0; f < b.faces.rows(); ++f) m.faces.offsets.push_back(m.faces.offsets.back() + b.faces.size(f));
  m.num_vertices += b.num_vertices;
  return m;
}

TEST(DetectLevels, OwnQuadSplitsInAnyOrder) {
  for (int levels : {1, 2, 3}) {
    check_own_refinement(fixtures::cube(), levels, SplitKind::Quads, 11u + static_cast<unsigned>(levels));
    check_own_refinement(fixtures::mixed_patch(), levels, SplitKind::Quads, 21u + static_cast<unsigned>(levels));
  }
  // A 3 x 5 torus cannot be coarsened (odd sides): all levels found are the applied ones.
  check_own_refinement(fixtures::torus(3, 5), 2, SplitKind::Quads, 5, true);
}

TEST(DetectLevels, OwnTriangleSplitsInAnyOrder) {
  for (int levels : {1, 2, 3}) check_own_refinement(fixtures::octahedron(), levels, SplitKind::Triangles, 31u + static_cast<unsigned>(levels));
  // A triangle fan with a boundary.
  Polygons fan;
  fan.num_vertices = 6;
  for (std::uint32_t k = 0; k < 5; ++k) fixtures::push_row(fan.faces, {0, 1 + k, 1 + (k + 1) % 5});
  check_own_refinement(fan, 2, SplitKind::Triangles, 41);
}

TEST(DetectLevels, OwnSqrt2StepsOfClosedMeshesInAnyOrder) {
  for (int levels : {1, 2, 3, 5}) check_own_refinement(fixtures::cube(), levels, SplitKind::Sqrt2, 51u + static_cast<unsigned>(levels));
  check_own_refinement(fixtures::torus(3, 5), 3, SplitKind::Sqrt2, 61, true);
  // Two sqrt(2) steps make the quad split's connectivity (refine_sqrt2.h): the cube split twice
  // is 4 sqrt(2) steps of the cube, and the cube itself one step of the tetrahedron (its
  // vertices 2-coloured: 4 corners stay, the other 4 are the tetrahedron's face points).
  const Polygons cc = shuffled(refined(fixtures::cube(), 2, SplitKind::Quads), 3);
  const DetectedLevels s = detect_levels(cc.num_vertices, cc.faces, SplitKind::Sqrt2, 24);
  EXPECT_EQ(s.levels, 5);
  EXPECT_EQ(s.base_vertices, 4u);
  EXPECT_EQ(s.base_faces.rows(), 4u);
  // Boundaries refine every other step (triangles on odd levels, curve points on even ones).
  for (int levels : {1, 2, 3, 4}) check_own_refinement(fixtures::mixed_patch(), levels, SplitKind::Sqrt2, 71u + static_cast<unsigned>(levels));
  // A mesh with a boundary fixes the level parity: an odd number of steps of the patch, asked
  // for as many as it holds, comes back with the patch as base, level 0.
  const Polygons open = shuffled(refined(fixtures::mixed_patch(), 3, SplitKind::Sqrt2), 5);
  const DetectedLevels d = detect_levels(open.num_vertices, open.faces, SplitKind::Sqrt2, 24);
  EXPECT_EQ(d.levels, 3) << d.stop;
  EXPECT_EQ(d.first_level, 0);
  EXPECT_EQ(d.base_vertices, 7u);
}

TEST(DetectLevels, MaxFindsEveryLevelAndPrefersTheCube) {
  const Polygons fine = shuffled(refined(fixtures::cube(), 3, SplitKind::Quads), 7);
  const DetectedLevels d = detect_levels(fine.num_vertices, fine.faces, SplitKind::Quads, 12);
  EXPECT_EQ(d.levels, 3);
  EXPECT_EQ(d.base_vertices, 8u);  // the cube, not the octahedron (same level-1 connectivity)
  EXPECT_EQ(d.base_faces.rows(), 6u);
  EXPECT_NE(d.stop.find("the mesh 3 levels down"), std::string::npos) << d.stop;
}

TEST(DetectLevels, ComponentsGetTheLevelsAllOfThemHold) {
  const Polygons a = refined(fixtures::cube(), 2, SplitKind::Quads), b = refined(fixtures::mixed_patch(), 1, SplitKind::Quads);
  const Polygons m = shuffled(joined(a, b), 3);
  const DetectedLevels d = detect_levels(m.num_vertices, m.faces, SplitKind::Quads, 12);
  EXPECT_EQ(d.levels, 1);
  ASSERT_EQ(d.components.size(), 2u);
  std::multiset<int> each{d.components[0].levels, d.components[1].levels};
  EXPECT_EQ(each, (std::multiset<int>{1, 2}));
  // Each piece coarsened once: the cube refined once and the patch itself.
  EXPECT_EQ(d.base_vertices, refined(fixtures::cube(), 1, SplitKind::Quads).num_vertices + fixtures::mixed_patch().num_vertices);
  EXPECT_NE(d.stop.find("the piece with vertex"), std::string::npos) << d.stop;
}

TEST(DetectLevels, TriangleAmongQuadsIsNamed) {
  Polygons fine = refined(fixtures::cube(), 2, SplitKind::Quads);
  // Split quad 0 into two triangles.
  Polygons broken{fine.num_vertices, {}, {}};
  for (std::size_t f = 0; f < fine.faces.rows(); ++f) {
    const auto q = fine.faces.row(f);
    if (f == 0) {
      fixtures::push_row(broken.faces, {q[0], q[1], q[2]});
      fixtures::push_row(broken.faces, {q[0], q[2], q[3]});
    } else {
      fixtures::push_row(broken.faces, {q[0], q[1], q[2], q[3]});
    }
  }
  const DetectedLevels d = detect_levels(broken.num_vertices, broken.faces, SplitKind::Quads, 12);
  EXPECT_EQ(d.levels, 0);
  EXPECT_NE(d.stop.find("2 triangles among 95 quads near vertex"), std::string::npos) << d.stop;
  EXPECT_NE(d.stop_vertex, UINT32_MAX);
}

TEST(DetectLevels, FlippedDiagonalStopsTheTriangleSplit) {
  const Polygons fine = refined(fixtures::octahedron(), 2, SplitKind::Triangles);
  // Flip the edge shared by faces 0 and its neighbour across corners 1-2.
  Polygons m = fine;
  const auto q = fine.faces.row(0);
  const std::uint32_t a = q[1], b = q[2];
  std::size_t g = 0;
  for (std::size_t f = 1; f < fine.faces.rows(); ++f) {
    const auto r = fine.faces.row(f);
    if (std::count(r.begin(), r.end(), a) && std::count(r.begin(), r.end(), b)) g = f;
  }
  ASSERT_NE(g, 0u);
  std::uint32_t c = 0;
  for (std::uint32_t x : fine.faces.row(g))
    if (x != a && x != b) c = x;
  m.faces.items[m.faces.offsets[0] + 0] = q[0];
  m.faces.items[m.faces.offsets[0] + 1] = q[1];
  m.faces.items[m.faces.offsets[0] + 2] = c;
  m.faces.items[m.faces.offsets[g] + 0] = q[0];
  m.faces.items[m.faces.offsets[g] + 1] = c;
  m.faces.items[m.faces.offsets[g] + 2] = q[2];
  const DetectedLevels d = detect_levels(m.num_vertices, m.faces, SplitKind::Triangles, 12);
  EXPECT_LT(d.levels, 2);
  EXPECT_FALSE(d.stop.empty());
  EXPECT_NE(d.stop.find("vertex"), std::string::npos) << d.stop;
}

TEST(DetectLevels, NoSubdivisionConnectivity) {
  const Polygons c = fixtures::cube();
  const DetectedLevels d = detect_levels(c.num_vertices, c.faces, SplitKind::Quads, 12);
  EXPECT_EQ(d.levels, 0);
  EXPECT_EQ(d.base_vertices, 8u);
  EXPECT_NE(d.stop.find("the mesh: "), std::string::npos) << d.stop;
  EXPECT_NE(d.stop.find("vertex "), std::string::npos) << d.stop;
  const Polygons o = fixtures::octahedron();
  const DetectedLevels t = detect_levels(o.num_vertices, o.faces, SplitKind::Triangles, 12);
  EXPECT_EQ(t.levels, 0);
  EXPECT_FALSE(t.stop.empty());
  // Triangles asked to be quads, and the other way round.
  EXPECT_NE(detect_levels(o.num_vertices, o.faces, SplitKind::Quads, 3).stop.find("its faces are not quads"), std::string::npos);
  Polygons loose = c;
  loose.num_vertices = 9;
  EXPECT_THROW(detect_levels(loose.num_vertices, loose.faces, SplitKind::Quads, 3), TopologyError);
}

// ---- Volume lattices: the 1-to-8 split of simple cells -----------------------------------------

// `c` (a lattice) with its vertices renumbered by a random permutation (perm[old] = new).
Complex shuffled_lattice(const Complex& c, unsigned seed, std::vector<std::uint32_t>* perm_out) {
  std::mt19937 rng(seed);
  std::vector<std::uint32_t> perm(c.num_vertices);
  std::iota(perm.begin(), perm.end(), 0u);
  std::shuffle(perm.begin(), perm.end(), rng);
  Csr loops = c.faces;
  for (std::uint32_t& v : loops.items) v = perm[v];
  *perm_out = perm;
  return complex_from_cells(c.num_vertices, loops, c.cell_faces);
}

Complex tetrahedron_cell() {
  Csr loops, cells;
  for (auto f : {std::initializer_list<std::uint32_t>{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}}) fixtures::push_row(loops, f);
  fixtures::push_row(cells, {0, 1, 2, 3});
  return complex_from_cells(4, loops, cells);
}

Complex block(std::uint32_t n) {
  const fixtures::Cells b = fixtures::hex_block(n);
  return complex_from_cells(b.num_vertices, b.face_loops, b.cell_faces);
}

TEST(DetectLevels, LatticeSplitsInAnyOrder) {
  struct Case {
    Complex base;
    const char* name;
  };
  const Case cases[] = {{block(3), "3^3 hex block"}, {tetrahedron_cell(), "tetrahedron"}};
  for (const Case& c : cases)
    for (int levels : {1, 2}) {
      SCOPED_TRACE(std::string(c.name) + " levels " + std::to_string(levels));
      Complex fine = c.base;
      for (int l = 0; l < levels; ++l) fine = refine(fine);
      std::vector<std::uint32_t> perm;
      const Complex input = shuffled_lattice(fine, 7u + unsigned(levels), &perm);
      const DetectedLevels d = detect_volume_levels(input, levels);
      ASSERT_EQ(d.levels, levels) << d.stop;
      EXPECT_EQ(d.base_vertices, c.base.num_vertices);
      EXPECT_EQ(d.base_cells.rows(), c.base.num_cells());
      // Base vertex b is fine vertex b before the shuffle.
      for (std::uint32_t v = 0; v < d.base_vertices; ++v) {
        const std::uint32_t i = d.steps.front().input_vertex[v];
        EXPECT_LT(std::find(perm.begin(), perm.end(), i) - perm.begin(), std::ptrdiff_t(c.base.num_vertices));
      }
      std::vector<Complex> cs{complex_from_cells(d.base_vertices, d.base_faces, d.base_cells)};
      for (int l = 0; l < levels; ++l) cs.push_back(refine(cs.back()));
      const std::vector<std::uint32_t> engine = engine_order(d, cs);
      // The input's cells land on the engine's cells.
      std::set<std::vector<std::uint32_t>> want, got;
      for (std::size_t k = 0; k < cs.back().num_cells(); ++k) {
        std::vector<std::uint32_t> s(cs.back().cell_verts.row(k).begin(), cs.back().cell_verts.row(k).end());
        std::sort(s.begin(), s.end());
        want.insert(s);
      }
      for (std::size_t k = 0; k < input.num_cells(); ++k) {
        std::vector<std::uint32_t> s;
        for (std::uint32_t v : input.cell_verts.row(k)) s.push_back(engine[v]);
        std::sort(s.begin(), s.end());
        got.insert(s);
      }
      EXPECT_EQ(got, want);
    }
  // A 2^3 block is one split of a single hexahedron: max finds it.
  Complex two = refine(block(2));
  EXPECT_EQ(detect_volume_levels(two, 12).levels, 2);
  // A 3^3 block is no split (odd sides).
  const DetectedLevels none = detect_volume_levels(block(3), 12);
  EXPECT_EQ(none.levels, 0);
  EXPECT_FALSE(none.stop.empty());
}

// ---- OpenSubdiv in its own vertex order -------------------------------------------------------

namespace Far = OpenSubdiv::Far;
namespace Sdc = OpenSubdiv::Sdc;

// OpenSubdiv's level-L faces, and each base vertex's child at level L.
struct OsdFine {
  Polygons fine;
  std::vector<std::uint32_t> to_base;  // fine vertex -> base vertex or UINT32_MAX
};

OsdFine osd_fine(const Polygons& base, Sdc::SchemeType scheme, int levels) {
  const auto r = fixtures::osd_refiner(base, scheme, levels);
  EXPECT_TRUE(r);
  OsdFine out;
  const Far::TopologyLevel& lv = r->GetLevel(levels);
  out.fine.num_vertices = static_cast<std::uint32_t>(lv.GetNumVertices());
  for (int f = 0; f < lv.GetNumFaces(); ++f) {
    for (Far::Index v : lv.GetFaceVertices(f)) out.fine.faces.items.push_back(static_cast<std::uint32_t>(v));
    out.fine.faces.offsets.push_back(static_cast<std::uint32_t>(out.fine.faces.items.size()));
  }
  out.to_base.assign(out.fine.num_vertices, UINT32_MAX);
  for (std::uint32_t b = 0; b < base.num_vertices; ++b) {
    Far::Index v = static_cast<Far::Index>(b);
    for (int l = 0; l < levels; ++l) v = r->GetLevel(l).GetVertexChildVertex(v);
    out.to_base[static_cast<std::uint32_t>(v)] = b;
  }
  return out;
}

Polygons load_polygons(const std::filesystem::path& p) {
  const LoadedMesh lm = import_surface_mesh(p.string());
  Polygons m;
  m.num_vertices = static_cast<std::uint32_t>(lm.mesh.num_vertices());
  m.faces.offsets = lm.mesh.face_offsets;
  m.faces.items = lm.mesh.face_indices;
  return m;
}

TEST(DetectLevels, OpenSubdivRefinementsInOpenSubdivOrder) {
  struct Case {
    Polygons base;
    Sdc::SchemeType scheme;
    const char* name;
  };
  std::vector<Case> cases{{fixtures::cube(), Sdc::SCHEME_CATMARK, "cube"},
                          {fixtures::mixed_patch(), Sdc::SCHEME_BILINEAR, "mixed patch"},
                          {fixtures::torus(3, 5), Sdc::SCHEME_CATMARK, "torus 3x5"},
                          {fixtures::octahedron(), Sdc::SCHEME_LOOP, "octahedron"}};
  const std::filesystem::path dir = std::filesystem::path(SUBLIFT_SHARED_DATA) / "control_meshes/opensubdiv_shapes";
  if (std::filesystem::exists(dir)) {
    // Non-quad faces and boundaries; several components; extraordinary vertices; triangles.
    cases.push_back({load_polygons(dir / "bilinear_nonquads1.obj"), Sdc::SCHEME_BILINEAR, "bilinear_nonquads1"});
    cases.push_back({load_polygons(dir / "catmark_edgecorner.obj"), Sdc::SCHEME_CATMARK, "catmark_edgecorner"});
    cases.push_back({load_polygons(dir / "catmark_gregory_test1.obj"), Sdc::SCHEME_CATMARK, "catmark_gregory_test1"});
    cases.push_back({load_polygons(dir / "loop_cube.obj"), Sdc::SCHEME_LOOP, "loop_cube"});
    // Creased shapes (the creases move positions, not connectivity).
    cases.push_back({load_polygons(dir / "catmark_cube_creases1.obj"), Sdc::SCHEME_CATMARK, "catmark_cube_creases1"});
    cases.push_back({load_polygons(dir / "loop_cube_creases0.obj"), Sdc::SCHEME_LOOP, "loop_cube_creases0"});
  } else {
    std::printf("no third-party data at %s (SUBLIFT_SHARED_DATA): built-in meshes only\n", dir.string().c_str());
  }
  for (const Case& c : cases)
    for (int levels : {1, 3}) {
      SCOPED_TRACE(std::string(c.name) + " levels " + std::to_string(levels));
      const OsdFine o = osd_fine(c.base, c.scheme, levels);
      const SplitKind split = c.scheme == Sdc::SCHEME_LOOP ? SplitKind::Triangles : SplitKind::Quads;
      const DetectedLevels d = detect_levels(o.fine.num_vertices, o.fine.faces, split, levels);
      ASSERT_EQ(d.levels, levels) << d.stop;
      expect_same_base(d, c.base, o.to_base);
    }
}

}  // namespace
}  // namespace sublift

#include <opensubdiv/far/primvarRefiner.h>

#include "core/multires/rebuild.h"

namespace sublift {
namespace {

struct OsdPoint {
  double p[3];
  void Clear(void* = nullptr) { p[0] = p[1] = p[2] = 0; }
  void AddWithWeight(const OsdPoint& s, double w) {
    for (int k = 0; k < 3; ++k) p[k] += w * s.p[k];
  }
};

// OpenSubdiv's bilinear refinement, in OpenSubdiv's order, rebuilt and analysed with the linear
// scheme: every wavelet is zero and the finest level is OpenSubdiv's to the last bits.
TEST(DetectLevels, OpenSubdivBilinearHasZeroLinearWavelets) {
  std::vector<Polygons> bases;
  Polygons cube = fixtures::cube();
  bases.push_back(cube);
  const std::filesystem::path file = std::filesystem::path(SUBLIFT_SHARED_DATA) / "control_meshes/opensubdiv_shapes/bilinear_nonquads1.obj";
  if (std::filesystem::exists(file)) {
    const LoadedMesh lm = import_surface_mesh(file.string());
    Polygons m = load_polygons(file);
    for (const auto& p : lm.mesh.positions) m.positions.insert(m.positions.end(), {p.x, p.y, p.z});
    bases.push_back(m);
  } else {
    std::printf("no third-party data at %s: the cube only\n", file.string().c_str());
  }
  for (const Polygons& base : bases) {
    const int levels = 3;
    const auto r = fixtures::osd_refiner(base, Sdc::SCHEME_BILINEAR, levels);
    ASSERT_TRUE(r);
    std::vector<std::vector<OsdPoint>> pts(levels + 1);
    for (std::uint32_t v = 0; v < base.num_vertices; ++v)
      pts[0].push_back({{base.positions[3 * v], base.positions[3 * v + 1], base.positions[3 * v + 2]}});
    Far::PrimvarRefinerReal<double> pr(*r);
    for (int l = 1; l <= levels; ++l) {
      pts[l].resize(static_cast<std::size_t>(r->GetLevel(l).GetNumVertices()));
      OsdPoint* dst = pts[l].data();
      pr.Interpolate(l, pts[l - 1].data(), dst);
    }
    const OsdFine o = osd_fine(base, Sdc::SCHEME_BILINEAR, levels);
    std::vector<double> xyz;
    for (const OsdPoint& p : pts[levels]) xyz.insert(xyz.end(), {p.p[0], p.p[1], p.p[2]});
    const Rebuilt rb = rebuild_hierarchy(o.fine.num_vertices, o.fine.faces, xyz, Scheme::Linear, levels);
    double scale = 0, worst = 0;
    for (double x : xyz) scale = std::max(scale, std::abs(x));
    for (std::size_t i = 3 * std::size_t(rb.hierarchy.num_vertices(0)); i < rb.hierarchy.coeffs.size(); ++i)
      worst = std::max(worst, std::abs(rb.hierarchy.coeffs[i]));
    EXPECT_LE(worst, 1e-14 * scale) << base.num_vertices << "-vertex base";
  }
}

}  // namespace
}  // namespace sublift
