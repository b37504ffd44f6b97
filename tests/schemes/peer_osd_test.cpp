// Peer comparison: Sublift's hierarchies with zero details against independent subdividers.
//   cubic  == OpenSubdiv Catmull-Clark (and OpenMesh's CatmullClarkT) where every vertex is regular
//   linear == OpenSubdiv bilinear on any polygon mesh
// compared vertex for vertex at levels 1..3. The two numberings are matched by topology, level by
// level: our child of vertex/edge/face x (refine.h) is the peer's child of the peer's vertex/edge/
// face with the same (already matched) corners, never by sorting positions.
#include <gtest/gtest.h>

#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include "core/fit/openmesh_kernel.h"  // before any other OpenMesh header
#include <OpenMesh/Tools/Subdivider/Uniform/CatmullClarkT.hh>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "core/complex/complex_build.h"
#include "core/multires/hierarchy.h"
#include "core/io/mesh/mesh_import.h"
#include "tests/mesh_fixtures.h"
#include "tests/osd_refiner.h"

namespace sublift {
namespace {

namespace Far = OpenSubdiv::Far;
namespace Sdc = OpenSubdiv::Sdc;
using fixtures::Polygons;

constexpr int kLevels = 3;

// ---- OpenSubdiv in double precision -------------------------------------------------------

struct OsdVertex {
  double p[3];
  void Clear(void* = nullptr) { p[0] = p[1] = p[2] = 0; }
  void AddWithWeight(const OsdVertex& s, double w) {
    p[0] += w * s.p[0];
    p[1] += w * s.p[1];
    p[2] += w * s.p[2];
  }
};

using fixtures::osd_refiner;

/// Positions of every level of `r`, level by level, from the base positions.
std::vector<std::vector<OsdVertex>> osd_positions(const Far::TopologyRefiner& r, const std::vector<double>& base) {
  std::vector<std::vector<OsdVertex>> out(static_cast<std::size_t>(r.GetMaxLevel()) + 1);
  out[0].resize(base.size() / 3);
  for (std::size_t v = 0; v < out[0].size(); ++v) out[0][v] = {{base[3 * v], base[3 * v + 1], base[3 * v + 2]}};
  Far::PrimvarRefinerReal<double> pr(r);
  for (int l = 1; l <= r.GetMaxLevel(); ++l) {
    out[l].resize(static_cast<std::size_t>(r.GetLevel(l).GetNumVertices()));
    OsdVertex* dst = out[l].data();
    pr.Interpolate(l, out[l - 1].data(), dst);
  }
  return out;
}

bool same_vertex_set(std::vector<int> a, std::vector<int> b) {
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  return a == b;
}

/// OpenSubdiv's numbering of level j+1's vertices given `ours` (level j) and `map` (our level-j
/// vertex -> OpenSubdiv's level-j vertex). Entries are -1 where no peer element matches.
std::vector<int> osd_child_map(const Complex& ours, const std::vector<int>& map, const Far::TopologyLevel& lv) {
  std::vector<int> child(ours.num_child_vertices(), -1);
  const std::uint32_t nv = ours.num_vertices, ne = ours.num_edges();
  for (std::uint32_t v = 0; v < nv; ++v) child[v] = lv.GetVertexChildVertex(map[v]);
  for (std::uint32_t e = 0; e < ne; ++e) {
    const Far::Index oe = lv.FindEdge(map[ours.edge_verts[2 * e]], map[ours.edge_verts[2 * e + 1]]);
    if (oe != Far::INDEX_INVALID) child[nv + e] = lv.GetEdgeChildVertex(oe);
  }
  for (std::uint32_t f = 0; f < ours.num_faces(); ++f) {
    std::vector<int> corners;
    for (std::uint32_t v : ours.faces.row(f)) corners.push_back(map[v]);
    const Far::Index oe = lv.FindEdge(corners[0], corners[1]);
    if (oe == Far::INDEX_INVALID) continue;
    for (Far::Index of : lv.GetEdgeFaces(oe)) {
      const auto fv = lv.GetFaceVertices(of);
      if (same_vertex_set(corners, std::vector<int>(fv.begin(), fv.end()))) child[nv + ne + f] = lv.GetFaceChildVertex(of);
    }
  }
  return child;
}

/// True when `map` is a permutation of 0..n-1.
bool is_bijection(const std::vector<int>& map, std::size_t n) {
  if (map.size() != n) return false;
  std::vector<char> hit(n, 0);
  for (int i : map) {
    if (i < 0 || static_cast<std::size_t>(i) >= n || hit[static_cast<std::size_t>(i)]) return false;
    hit[static_cast<std::size_t>(i)] = 1;
  }
  return true;
}

/// max |ours - peer| over all coordinates of level l, relative to the largest |coordinate|.
double relative_max_diff(const std::vector<double>& ours, const std::vector<OsdVertex>& peer, const std::vector<int>& map) {
  double diff = 0, scale = 0;
  for (std::size_t v = 0; v < map.size(); ++v)
    for (int k = 0; k < 3; ++k) {
      const double p = peer[static_cast<std::size_t>(map[v])].p[k];
      diff = std::max(diff, std::abs(ours[3 * v + k] - p));
      scale = std::max(scale, std::abs(p));
    }
  return diff / std::max(scale, 1.0);
}

Complex complex_of(const Polygons& m) { return complex_from_polygons(m.num_vertices, m.faces); }

/// Subdivides `m` with `scheme` (zero details) and OpenSubdiv's `peer` to kLevels and compares
/// every level vertex for vertex.
void expect_equal_to_osd(const Polygons& m, Scheme scheme, Sdc::SchemeType peer, const std::string& what) {
  SCOPED_TRACE(what);
  Hierarchy h = make_hierarchy(complex_of(m), kLevels, scheme, 3);
  set_base(h, m.positions);
  const auto refiner = osd_refiner(m, peer, kLevels);
  ASSERT_TRUE(refiner) << "OpenSubdiv refused the mesh";
  const auto peer_pos = osd_positions(*refiner, m.positions);
  std::vector<int> map(m.num_vertices);
  for (std::uint32_t v = 0; v < m.num_vertices; ++v) map[v] = static_cast<int>(v);
  for (int l = 1; l <= kLevels; ++l) {
    SCOPED_TRACE("level " + std::to_string(l));
    map = osd_child_map(h.levels[static_cast<std::size_t>(l - 1)], map, refiner->GetLevel(l - 1));
    ASSERT_EQ(h.num_vertices(l), static_cast<std::uint32_t>(refiner->GetLevel(l).GetNumVertices()));
    ASSERT_TRUE(is_bijection(map, h.num_vertices(l))) << "vertex numberings do not match by topology";
    EXPECT_LT(relative_max_diff(synthesize(h, l), peer_pos[static_cast<std::size_t>(l)], map), 1e-12);
  }
}

Polygons polygons_of(const SurfaceMesh& mesh) {
  Polygons m;
  m.num_vertices = static_cast<std::uint32_t>(mesh.num_vertices());
  m.faces.offsets = mesh.face_offsets;
  m.faces.items = mesh.face_indices;
  for (const auto& p : mesh.positions) m.positions.insert(m.positions.end(), {p.x, p.y, p.z});
  return m;
}

// ---- Tests ---------------------------------------------------------------------------------

TEST(PeerOsd, ChildNumberingMatchesByTopologyOnCube) {
  // Level 1 of a cube. Ours is [v | e | f] (refine.h); OpenSubdiv's uniform refinement (with
  // orderVerticesFromFacesFirst off) is [v | f | e], faces in input order, edges in its own
  // order. The topological map must find exactly that.
  const Polygons m = fixtures::cube();
  const Complex c = complex_of(m);
  ASSERT_EQ(c.num_edges(), 12u);
  const auto r = osd_refiner(m, Sdc::SCHEME_BILINEAR, 1);
  std::vector<int> id(8);
  for (int v = 0; v < 8; ++v) id[static_cast<std::size_t>(v)] = v;
  const auto map = osd_child_map(c, id, r->GetLevel(0));
  ASSERT_EQ(map.size(), 26u);
  EXPECT_TRUE(is_bijection(map, 26));
  for (int v = 0; v < 8; ++v) EXPECT_EQ(map[static_cast<std::size_t>(v)], v);
  for (int f = 0; f < 6; ++f) EXPECT_EQ(map[static_cast<std::size_t>(8 + 12 + f)], 8 + f);
  for (int e = 0; e < 12; ++e) {
    EXPECT_GE(map[static_cast<std::size_t>(8 + e)], 14);
    EXPECT_LT(map[static_cast<std::size_t>(8 + e)], 26);
  }
}

TEST(PeerOsd, CubicEqualsCatmullClarkOnRegularTorus) {
  for (auto [nu, nv] : {std::pair<std::uint32_t, std::uint32_t>{12, 8}, {48, 24}})
    expect_equal_to_osd(fixtures::torus(nu, nv), Scheme::Cubic, Sdc::SCHEME_CATMARK,
                        "torus " + std::to_string(nu) + "x" + std::to_string(nv));
}

TEST(PeerOsd, CubicDiffersFromCatmullClarkOnlyAtExtraordinaryVerticesOfCube) {
  // One step on a cube: face and edge points are Catmull-Clark's; the valence-3 corners follow
  // 1/2 v + 1/4 mean(edge nbrs) + 1/4 mean(face centroids) (DESIGN.md): 2/3 of the way from the
  // centre, where Catmull-Clark puts them at 5/9.
  const Polygons m = fixtures::cube();
  Hierarchy h = make_hierarchy(complex_of(m), 1, Scheme::Cubic, 3);
  set_base(h, m.positions);
  const auto ours = synthesize(h, 1);
  const auto r = osd_refiner(m, Sdc::SCHEME_CATMARK, 1);
  const auto peer = osd_positions(*r, m.positions);
  std::vector<int> id(8);
  for (int v = 0; v < 8; ++v) id[static_cast<std::size_t>(v)] = v;
  const auto map = osd_child_map(h.levels[0], id, r->GetLevel(0));
  ASSERT_TRUE(is_bijection(map, 26));
  for (std::size_t v = 0; v < 26; ++v)
    for (int k = 0; k < 3; ++k) {
      const double peer_k = peer[1][static_cast<std::size_t>(map[v])].p[k];
      if (v >= 8) {
        EXPECT_NEAR(ours[3 * v + k], peer_k, 1e-15) << "child " << v;
        continue;
      }
      const double centre = 0.5, offset = m.positions[3 * v + k] - centre;
      EXPECT_NEAR(ours[3 * v + k], centre + offset * 2 / 3, 1e-15) << "corner " << v;
      EXPECT_NEAR(peer_k, centre + offset * 5 / 9, 1e-15) << "corner " << v;
    }
}

TEST(PeerOsd, LinearEqualsBilinearOnAssets) {
  int compared = 0;
  for (const auto& entry : std::filesystem::directory_iterator(SUBLIFT_ASSETS_DIR)) {
    if (entry.path().extension() != ".obj") continue;
    const LoadedMesh loaded = import_surface_mesh(entry.path().string());
    expect_equal_to_osd(polygons_of(loaded.mesh), Scheme::Linear, Sdc::SCHEME_BILINEAR, entry.path().filename().string());
    ++compared;
  }
  EXPECT_GE(compared, 5);
}

TEST(PeerOsd, LinearEqualsBilinearOnSharedControlMeshes) {
  // Every OBJ/OFF there: faces of 3 to many sides, valences 2 to 8+, boundaries, holes, darts,
  // non-manifold edges and vertices (OpenSubdiv's own regression shapes and others).
  const std::filesystem::path dir = std::filesystem::path(SUBLIFT_SHARED_DATA) / "control_meshes";
  if (!std::filesystem::exists(dir)) GTEST_SKIP() << "no third-party data at " << dir << " (SUBLIFT_SHARED_DATA)";
  std::vector<std::filesystem::path> paths;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir))
    if (entry.path().extension() == ".obj" || entry.path().extension() == ".off") paths.push_back(entry.path());
  std::sort(paths.begin(), paths.end());
  for (const auto& path : paths) {
    const LoadedMesh loaded = import_surface_mesh(path.string());
    expect_equal_to_osd(polygons_of(loaded.mesh), Scheme::Linear, Sdc::SCHEME_BILINEAR,
                        std::filesystem::relative(path, dir).string());
  }
  EXPECT_GE(paths.size(), 20u);
}

// ---- OpenMesh's CatmullClarkT as a second oracle ------------------------------------------

struct DoubleTraits : OpenMesh::DefaultTraits {
  typedef OpenMesh::Vec3d Point;
  typedef OpenMesh::Vec3d Normal;
};
using OmMesh = OpenMesh::PolyMesh_ArrayKernelT<DoubleTraits>;

/// OpenMesh's numbering after one CatmullClarkT step on `om` (level j, before the step): old
/// vertices keep their handles, edge points follow in edge order, face points in face order
/// (CatmullClarkT_impl.hh splits all edges, then all faces).
std::vector<int> om_child_map(const Complex& ours, const std::vector<int>& map, const OmMesh& om) {
  std::vector<int> child(ours.num_child_vertices(), -1);
  const std::uint32_t nv = ours.num_vertices, ne = ours.num_edges();
  const int onv = static_cast<int>(om.n_vertices()), one = static_cast<int>(om.n_edges());
  for (std::uint32_t v = 0; v < nv; ++v) child[v] = map[v];
  for (std::uint32_t e = 0; e < ne; ++e) {
    const auto he = om.find_halfedge(OmMesh::VertexHandle(map[ours.edge_verts[2 * e]]),
                                     OmMesh::VertexHandle(map[ours.edge_verts[2 * e + 1]]));
    if (he.is_valid()) child[nv + e] = onv + om.edge_handle(he).idx();
  }
  for (std::uint32_t f = 0; f < ours.num_faces(); ++f) {
    std::vector<int> corners;
    for (std::uint32_t v : ours.faces.row(f)) corners.push_back(map[v]);
    const auto he = om.find_halfedge(OmMesh::VertexHandle(corners[0]), OmMesh::VertexHandle(corners[1]));
    if (!he.is_valid()) continue;
    for (auto h : {he, om.opposite_halfedge_handle(he)}) {
      const auto fh = om.face_handle(h);
      if (!fh.is_valid()) continue;
      std::vector<int> fv;
      for (auto vh : om.fv_range(fh)) fv.push_back(vh.idx());
      if (same_vertex_set(corners, fv)) child[nv + ne + f] = onv + one + fh.idx();
    }
  }
  return child;
}

TEST(PeerOpenMesh, CubicEqualsCatmullClarkTOnRegularTorus) {
  const Polygons m = fixtures::torus(12, 8);
  Hierarchy h = make_hierarchy(complex_of(m), kLevels, Scheme::Cubic, 3);
  set_base(h, m.positions);
  OmMesh om;
  for (std::uint32_t v = 0; v < m.num_vertices; ++v)
    om.add_vertex(OmMesh::Point(m.positions[3 * v], m.positions[3 * v + 1], m.positions[3 * v + 2]));
  for (std::size_t f = 0; f < m.faces.rows(); ++f) {
    std::vector<OmMesh::VertexHandle> corners;
    for (std::uint32_t v : m.faces.row(f)) corners.emplace_back(static_cast<int>(v));
    om.add_face(corners);
  }
  std::vector<int> map(m.num_vertices);
  for (std::uint32_t v = 0; v < m.num_vertices; ++v) map[v] = static_cast<int>(v);
  OpenMesh::Subdivider::Uniform::CatmullClarkT<OmMesh> cc;
  cc.attach(om);
  for (int l = 1; l <= kLevels; ++l) {
    SCOPED_TRACE("level " + std::to_string(l));
    map = om_child_map(h.levels[static_cast<std::size_t>(l - 1)], map, om);
    cc(1);
    ASSERT_EQ(h.num_vertices(l), om.n_vertices());
    ASSERT_TRUE(is_bijection(map, om.n_vertices()));
    const auto ours = synthesize(h, l);
    double diff = 0;
    for (std::size_t v = 0; v < map.size(); ++v)
      for (int k = 0; k < 3; ++k)
        diff = std::max(diff, std::abs(ours[3 * v + k] - om.point(OmMesh::VertexHandle(map[v]))[k]));
    EXPECT_LT(diff / 3.0, 1e-12);  // coordinates are at most ~2.8 in size
  }
  cc.detach();
}

}  // namespace
}  // namespace sublift

// ---- Semi-sharp creases against OpenSubdiv (issue 20) --------------------------------------

namespace sublift {
namespace {
namespace semi {

// OpenSubdiv's refiner of `m` with the crease edges (vertex pairs) at `sharpness`.
std::unique_ptr<Far::TopologyRefiner> creased_refiner(const Polygons& m, const std::vector<std::pair<int, int>>& creases,
                                                      float sharpness, int levels) {
  std::vector<int> sizes(m.faces.rows());
  for (std::size_t f = 0; f < sizes.size(); ++f) sizes[f] = static_cast<int>(m.faces.size(f));
  const std::vector<Far::Index> corners(m.faces.items.begin(), m.faces.items.end());
  std::vector<Far::Index> pairs;
  for (auto [a, b] : creases) pairs.insert(pairs.end(), {a, b});
  const std::vector<float> weights(creases.size(), sharpness);
  Far::TopologyDescriptor desc;
  desc.numVertices = static_cast<int>(m.num_vertices);
  desc.numFaces = static_cast<int>(sizes.size());
  desc.numVertsPerFace = sizes.data();
  desc.vertIndicesPerFace = corners.data();
  desc.numCreases = static_cast<int>(creases.size());
  desc.creaseVertexIndexPairs = pairs.data();
  desc.creaseWeights = weights.data();
  Sdc::Options opts;
  opts.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_ONLY);
  opts.SetCreasingMethod(Sdc::Options::CREASE_UNIFORM);
  using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
  std::unique_ptr<Far::TopologyRefiner> r(Factory::Create(desc, Factory::Options(Sdc::SCHEME_CATMARK, opts)));
  if (r) r->RefineUniform(Far::TopologyRefiner::UniformOptions(levels));
  return r;
}

// Per level 1..levels: max |ours - OpenSubdiv| relative to the largest coordinate.
// `ours`: the sharpness Sublift is given (default: the same as OpenSubdiv's).
std::vector<double> level_differences(const Polygons& m, const std::vector<std::pair<int, int>>& creases, float sharpness, int levels,
                                      float ours = -1) {
  if (ours < 0) ours = sharpness;
  FeatureTags tags;
  for (auto [a, b] : creases) {
    tags.crease_edges.emplace_back(std::uint32_t(a), std::uint32_t(b));
    tags.crease_sharpness.push_back(ours >= 10 ? INFINITY : ours);
  }
  Hierarchy h = make_hierarchy(complex_from_polygons(m.num_vertices, m.faces, tags), levels, Scheme::Cubic, 3);
  set_base(h, m.positions);
  const auto refiner = creased_refiner(m, creases, sharpness, levels);
  if (!refiner) return {};
  const auto peer = osd_positions(*refiner, m.positions);
  std::vector<int> map(m.num_vertices);
  for (std::uint32_t v = 0; v < m.num_vertices; ++v) map[v] = static_cast<int>(v);
  std::vector<double> out;
  for (int l = 1; l <= levels; ++l) {
    map = osd_child_map(h.levels[static_cast<std::size_t>(l - 1)], map, refiner->GetLevel(l - 1));
    if (!is_bijection(map, h.num_vertices(l))) return {};
    out.push_back(relative_max_diff(synthesize(h, l), peer[static_cast<std::size_t>(l)], map));
  }
  return out;
}

}  // namespace semi

// On a regular quad torus Bertram's cubic rules and Catmull-Clark coincide for smooth and for
// infinitely sharp edges, and so they do for semi-sharp ones level by level: a crease loop, an
// open chain (its ends are darts) and two crossing loops (a vertex on four creases: a corner
// while they are sharp), sharpness 1, 2, 3 and 10, equal to OpenSubdiv (uniform creasing) at
// every level 1..4 to rounding. A crease of sharpness 1 is not one of sharpness 10: level 1
// agrees, the levels after it do not (the test sees the softening).
TEST(PeerOsdSemiSharp, RegularTorusEqualsOpenSubdivAtIntegerSharpness) {
  const Polygons m = fixtures::torus(8, 8);
  std::vector<std::pair<int, int>> loop;  // the ring j = 0 around the torus
  for (int i = 0; i < 8; ++i) loop.emplace_back(i, (i + 1) % 8);
  const std::vector<std::pair<int, int>> chain(loop.begin(), loop.begin() + 4);
  std::vector<std::pair<int, int>> cross = loop;  // a second ring through vertex 0
  for (int j = 0; j < 8; ++j) cross.emplace_back(j * 8, ((j + 1) % 8) * 8);
  using Creases = std::vector<std::pair<int, int>>;
  for (const Creases* creases : std::initializer_list<const Creases*>{&loop, &chain, &cross})
    for (const float s : {1.0f, 2.0f, 3.0f, 10.0f}) {
      SCOPED_TRACE((creases == &loop ? "loop" : creases == &chain ? "chain" : "cross") + std::string(" sharpness ") + std::to_string(s));
      const std::vector<double> d = semi::level_differences(m, *creases, s, 4);
      ASSERT_EQ(d.size(), 4u) << "OpenSubdiv refused the mesh or the numberings do not match";
      for (std::size_t l = 0; l < d.size(); ++l) EXPECT_LT(d[l], 1e-12) << "level " << l + 1;
    }
  const std::vector<double> softer = semi::level_differences(m, loop, 10.0f, 4, 1.0f);
  ASSERT_EQ(softer.size(), 4u);
  EXPECT_LT(softer[0], 1e-12);
  for (std::size_t l = 1; l < softer.size(); ++l) EXPECT_GT(softer[l], 1e-3) << "level " << l + 1;
}

// Fractional sharpness: Sublift keeps a crease sharp for floor(s) levels and does not blend the
// fraction (docs/features.md); OpenSubdiv blends it in the level after. So s = 1.5 is OpenSubdiv's
// s = 1 exactly, and differs from OpenSubdiv's own 1.5 from level 2 on, by the blend (a few
// thousandths of the size here), not at level 1.
TEST(PeerOsdSemiSharp, FractionalSharpnessIsFlooredWhereOpenSubdivBlends) {
  const Polygons m = fixtures::torus(8, 8);
  std::vector<std::pair<int, int>> loop;
  for (int i = 0; i < 8; ++i) loop.emplace_back(i, (i + 1) % 8);
  const std::vector<double> floored = semi::level_differences(m, loop, 1.0f, 4, 1.5f);
  ASSERT_EQ(floored.size(), 4u);
  for (double d : floored) EXPECT_LT(d, 1e-12);
  const std::vector<double> blended = semi::level_differences(m, loop, 1.5f, 4);
  ASSERT_EQ(blended.size(), 4u);
  EXPECT_LT(blended[0], 1e-12);
  for (std::size_t l = 1; l < blended.size(); ++l) {
    EXPECT_GT(blended[l], 1e-4) << "level " << l + 1;
    EXPECT_LT(blended[l], 2e-2) << "level " << l + 1;
  }
  std::printf("sharpness 1.5 against OpenSubdiv's blend, levels 1-4: %.3g %.3g %.3g %.3g\n", blended[0], blended[1], blended[2], blended[3]);
}

}  // namespace
}  // namespace sublift
