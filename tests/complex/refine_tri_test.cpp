// 1-to-4 triangle refinement (core/complex/refine_tri.h): closed-form counts, Euler characteristic,
// validate() and consistent orientation over several levels on closed and open meshes; the
// documented numbering (midpoints, halves, inner edges, child faces) checked against positions
// computed from it; feature dims inherited (boundary, OBJ `t crease` / `t corner` tags); errors
// for non-triangles and lattices; and the child topology compared with OpenSubdiv Far's uniform
// Loop refinement (the same 1-to-4 split), vertices matched through Far's parent-child tables.
#include <gtest/gtest.h>

#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "core/complex/complex_build.h"
#include "core/base/errors.h"
#include "core/complex/refine_tri.h"
#include "core/io/lattice/shape_io.h"
#include "core/complex/shapes.h"
#include "tests/mesh_fixtures.h"
#include "tests/osd_refiner.h"

using namespace sublift;

namespace {

namespace Far = OpenSubdiv::Far;
namespace Sdc = OpenSubdiv::Sdc;
using Pair = std::pair<std::uint32_t, std::uint32_t>;
using Tri = std::array<std::uint32_t, 3>;

struct Mesh {
  Complex c;
  std::vector<double> xyz;  // 3 per vertex
};

// Regular octahedron (closed, chi 2), outward counterclockwise faces.
Mesh octahedron() {
  Mesh m;
  m.xyz = {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1};
  Csr faces;
  const Tri tris[8] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (const Tri& t : tris)
    fixtures::push_row(faces, {t[0], t[1], t[2]});
  m.c = complex_from_polygons(6, faces);
  return m;
}

// The quad torus of mesh_fixtures.h with every quad split along a diagonal (closed, chi 0,
// valence 6 everywhere).
Mesh tri_torus(std::uint32_t nu, std::uint32_t nv) {
  const fixtures::Polygons q = fixtures::torus(nu, nv);
  Csr faces;
  for (std::size_t f = 0; f < q.faces.rows(); ++f) {
    const auto r = q.faces.row(f);
    fixtures::push_row(faces, {r[0], r[1], r[2]});
    fixtures::push_row(faces, {r[0], r[2], r[3]});
  }
  return {complex_from_polygons(q.num_vertices, faces), q.positions};
}

// Open n x m grid in the plane z = 0, each square split along alternating diagonals (one
// boundary loop, chi 1). Vertex (i, j) is j * (n + 1) + i.
Mesh tri_grid(std::uint32_t n, std::uint32_t m, const FeatureTags& tags = {}) {
  Mesh g;
  Csr faces;
  for (std::uint32_t j = 0; j <= m; ++j)
    for (std::uint32_t i = 0; i <= n; ++i) g.xyz.insert(g.xyz.end(), {double(i), double(j) + 0.1 * i * i, 0.0});
  for (std::uint32_t j = 0; j < m; ++j)
    for (std::uint32_t i = 0; i < n; ++i) {
      const std::uint32_t a = j * (n + 1) + i, b = a + 1, c = b + n + 1, d = a + n + 1;
      if ((i + j) % 2 == 0) {
        fixtures::push_row(faces, {a, b, c});
        fixtures::push_row(faces, {a, c, d});
      } else {
        fixtures::push_row(faces, {a, b, d});
        fixtures::push_row(faces, {b, c, d});
      }
    }
  g.c = complex_from_polygons((n + 1) * (m + 1), faces, tags);
  return g;
}

long long euler(const Complex& c) { return static_cast<long long>(c.num_vertices) - c.num_edges() + c.num_faces(); }

// Positions of the child level from the numbering alone: old vertices stay, nv + e is the
// midpoint of coarse edge e.
std::vector<double> child_positions(const Complex& coarse, const std::vector<double>& xyz) {
  std::vector<double> out(xyz);
  out.resize(3 * std::size_t(coarse.num_vertices + coarse.num_edges()));
  for (std::uint32_t e = 0; e < coarse.num_edges(); ++e)
    for (int k = 0; k < 3; ++k)
      out[3 * (coarse.num_vertices + e) + k] =
          0.5 * (xyz[3 * coarse.edge_verts[2 * e] + k] + xyz[3 * coarse.edge_verts[2 * e + 1] + k]);
  return out;
}

// Twice the vector area of triangle (a, b, c).
std::array<double, 3> area2(const std::vector<double>& x, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  const double u[3] = {x[3 * b] - x[3 * a], x[3 * b + 1] - x[3 * a + 1], x[3 * b + 2] - x[3 * a + 2]};
  const double v[3] = {x[3 * c] - x[3 * a], x[3 * c + 1] - x[3 * a + 1], x[3 * c + 2] - x[3 * a + 2]};
  return {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
}

// validate(), derived rows equal to a fresh build_adjacency, all faces triangles whose edges join
// their corners, and consistent orientation: an edge shared by two faces is run a->b by one and
// b->a by the other.
void expect_valid(const Complex& c) {
  Complex copy = c;
  build_adjacency(copy);
  ASSERT_NO_THROW(validate(copy));
  EXPECT_EQ(copy.edge_faces.items, c.edge_faces.items);
  EXPECT_EQ(copy.vertex_edges.items, c.vertex_edges.items);
  EXPECT_EQ(copy.vertex_faces.items, c.vertex_faces.items);
  for (std::uint32_t f = 0; f < c.num_faces(); ++f) {
    ASSERT_EQ(c.faces.size(f), 3u) << "face " << f;
    for (std::uint32_t k = 0; k < 3; ++k) {
      const std::uint32_t e = c.face_edges.row(f)[k], u = c.faces.row(f)[k], w = c.faces.row(f)[(k + 1) % 3];
      const Pair ends{c.edge_verts[2 * e], c.edge_verts[2 * e + 1]};
      EXPECT_TRUE(ends == Pair(u, w) || ends == Pair(w, u)) << "face " << f << " slot " << k;
    }
  }
  for (std::uint32_t e = 0; e < c.num_edges(); ++e) {
    if (c.edge_faces.size(e) != 2) continue;
    int forward = 0;
    for (std::uint32_t f : c.edge_faces.row(e)) {
      const auto vs = c.faces.row(f);
      for (std::size_t i = 0; i < 3; ++i)
        if (vs[i] == c.edge_verts[2 * e] && vs[(i + 1) % 3] == c.edge_verts[2 * e + 1]) ++forward;
    }
    EXPECT_EQ(forward, 1) << "edge " << e;
  }
}

// A triangle rotated to start at its smallest vertex (orientation kept).
Tri canonical(Tri t) {
  std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
  return t;
}

Pair key(std::uint32_t a, std::uint32_t b) { return a < b ? Pair{a, b} : Pair{b, a}; }

// ---- counts, Euler, validity -------------------------------------------------------------

void expect_counts_over_levels(const Complex& base, int levels, const char* name) {
  SCOPED_TRACE(name);
  const long long chi = euler(base);
  Complex c = base;
  for (int l = 1; l <= levels; ++l) {
    SCOPED_TRACE("level " + std::to_string(l));
    const Complex next = refine_tri(c);
    EXPECT_EQ(next.num_vertices, c.num_vertices + c.num_edges());
    EXPECT_EQ(next.num_edges(), 2 * c.num_edges() + 3 * c.num_faces());
    EXPECT_EQ(next.num_faces(), 4 * c.num_faces());
    EXPECT_EQ(euler(next), chi);
    expect_valid(next);
    // Boundary edges: each splits in two, no new ones appear inside.
    std::uint32_t bc = 0, bn = 0;
    for (std::uint32_t e = 0; e < c.num_edges(); ++e) bc += c.edge_faces.size(e) == 1;
    for (std::uint32_t e = 0; e < next.num_edges(); ++e) bn += next.edge_faces.size(e) == 1;
    EXPECT_EQ(bn, 2 * bc);
    c = next;
  }
}

TEST(RefineTri, CountsEulerAndOrientationOverLevels) {
  expect_counts_over_levels(octahedron().c, 4, "octahedron");
  expect_counts_over_levels(tri_torus(6, 4).c, 3, "triangulated torus");
  expect_counts_over_levels(tri_grid(3, 2).c, 4, "open grid");
  // A single triangle and a fan with a non-manifold edge (three faces on edge 0-1).
  Csr one;
  fixtures::push_row(one, {0, 1, 2});
  expect_counts_over_levels(complex_from_polygons(3, one), 4, "one triangle");
  Csr fan;
  fixtures::push_row(fan, {0, 1, 2});
  fixtures::push_row(fan, {1, 0, 3});
  fixtures::push_row(fan, {0, 1, 4});
  const Complex nm = complex_from_polygons(5, fan);
  const Complex nm1 = refine_tri(nm);
  EXPECT_EQ(nm1.num_vertices, 5u + 7u);
  EXPECT_EQ(nm1.num_faces(), 12u);
  EXPECT_EQ(euler(nm1), euler(nm));
}

TEST(RefineTri, WithoutAdjacencyAndWithoutCoarseAdjacency) {
  const Mesh m = tri_grid(2, 2);
  const Complex full = refine_tri(m.c);
  const Complex bare = refine_tri(m.c, false);
  EXPECT_EQ(bare.vertex_edges.rows(), 0u);
  EXPECT_EQ(bare.edge_faces.rows(), 0u);
  EXPECT_EQ(bare.faces.items, full.faces.items);
  EXPECT_EQ(bare.face_edges.items, full.face_edges.items);
  EXPECT_EQ(bare.edge_verts, full.edge_verts);
  // Only downward rows are read: a coarse level without derived rows refines the same.
  Complex down = m.c;
  down.vertex_edges.clear(), down.vertex_faces.clear(), down.edge_faces.clear();
  const Complex again = refine_tri(down);
  EXPECT_EQ(again.faces.items, full.faces.items);
  EXPECT_EQ(again.edge_faces.items, full.edge_faces.items);
}

// ---- the documented numbering ------------------------------------------------------------

void expect_numbering(const Mesh& m, const char* name) {
  SCOPED_TRACE(name);
  const Complex& p = m.c;
  const Complex c = refine_tri(p);
  const std::uint32_t nv = p.num_vertices, ne = p.num_edges(), nf = p.num_faces();
  const std::vector<double> x = child_positions(p, m.xyz);
  auto dist = [&](std::uint32_t a, std::uint32_t b) {
    return std::hypot(x[3 * a] - x[3 * b], x[3 * a + 1] - x[3 * b + 1], x[3 * a + 2] - x[3 * b + 2]);
  };
  // Halves: 2e = (edge_verts[2e], nv + e), 2e+1 = (nv + e, edge_verts[2e+1]), each half as long.
  for (std::uint32_t e = 0; e < ne; ++e) {
    const std::uint32_t a = p.edge_verts[2 * e], b = p.edge_verts[2 * e + 1];
    EXPECT_EQ(Pair(c.edge_verts[4 * e], c.edge_verts[4 * e + 1]), Pair(a, nv + e)) << "edge " << e;
    EXPECT_EQ(Pair(c.edge_verts[4 * e + 2], c.edge_verts[4 * e + 3]), Pair(nv + e, b)) << "edge " << e;
    EXPECT_NEAR(dist(a, nv + e), 0.5 * dist(a, b), 1e-14);
    EXPECT_NEAR(dist(nv + e, b), 0.5 * dist(a, b), 1e-14);
  }
  for (std::uint32_t f = 0; f < nf; ++f) {
    const auto a = p.faces.row(f);
    const auto e = p.face_edges.row(f);
    const std::uint32_t m0 = nv + e[0], m1 = nv + e[1], m2 = nv + e[2], i = 2 * ne + 3 * f;
    // Inner edges run m_k -> m_{k+1}, each parallel to and half as long as the opposite edge.
    const Pair inner[3] = {{m0, m1}, {m1, m2}, {m2, m0}};
    for (std::uint32_t k = 0; k < 3; ++k) {
      EXPECT_EQ(Pair(c.edge_verts[2 * (i + k)], c.edge_verts[2 * (i + k) + 1]), inner[k]) << "face " << f;
      EXPECT_NEAR(dist(inner[k].first, inner[k].second), 0.5 * dist(a[(k + 2) % 3], a[k]), 1e-14);
    }
    // Child faces: corners as documented, edges as documented.
    const Tri want[4] = {{a[0], m0, m2}, {a[1], m1, m0}, {a[2], m2, m1}, {m0, m1, m2}};
    auto half = [&](std::uint32_t pe, std::uint32_t v) { return p.edge_verts[2 * pe] == v ? 2 * pe : 2 * pe + 1; };
    const Tri want_edges[4] = {{half(e[0], a[0]), i + 2, half(e[2], a[0])},
                               {half(e[1], a[1]), i + 0, half(e[0], a[1])},
                               {half(e[2], a[2]), i + 1, half(e[1], a[2])},
                               {i, i + 1, i + 2}};
    const auto parent_area = area2(x, a[0], a[1], a[2]);
    for (std::uint32_t k = 0; k < 4; ++k) {
      const auto fv = c.faces.row(4 * f + k), fe = c.face_edges.row(4 * f + k);
      EXPECT_EQ((Tri{fv[0], fv[1], fv[2]}), want[k]) << "face " << f << " child " << k;
      EXPECT_EQ((Tri{fe[0], fe[1], fe[2]}), want_edges[k]) << "face " << f << " child " << k;
      // Orientation kept: the child's vector area is a quarter of the parent's, same direction.
      const auto ca = area2(x, fv[0], fv[1], fv[2]);
      for (int d = 0; d < 3; ++d) EXPECT_NEAR(ca[d], 0.25 * parent_area[d], 1e-13) << "face " << f << " child " << k;
    }
  }
}

TEST(RefineTri, NumberingMatchesTheDocumentedLayout) {
  expect_numbering(octahedron(), "octahedron");
  expect_numbering(tri_torus(5, 4), "triangulated torus");
  expect_numbering(tri_grid(3, 3), "open grid");
  // Two levels down: the numbering holds on a refined level too.
  Mesh g = tri_grid(2, 2);
  g.xyz = child_positions(g.c, g.xyz);
  g.c = refine_tri(g.c);
  expect_numbering(g, "open grid, level 1");
}

// ---- feature dims ------------------------------------------------------------------------

void expect_inherited_dims(const Complex& p, const Complex& c) {
  const std::uint32_t nv = p.num_vertices, ne = p.num_edges(), nf = p.num_faces();
  for (std::uint32_t v = 0; v < nv; ++v) EXPECT_EQ(c.vertex_dim[v], p.vertex_dim[v]) << "vertex " << v;
  for (std::uint32_t e = 0; e < ne; ++e) {
    EXPECT_EQ(c.vertex_dim[nv + e], p.edge_dim[e]) << "midpoint of " << e;
    EXPECT_EQ(c.edge_dim[2 * e], p.edge_dim[e]) << "half of " << e;
    EXPECT_EQ(c.edge_dim[2 * e + 1], p.edge_dim[e]) << "half of " << e;
  }
  for (std::uint32_t f = 0; f < nf; ++f) {
    for (std::uint32_t k = 0; k < 3; ++k) EXPECT_EQ(c.edge_dim[2 * ne + 3 * f + k], p.face_dim[f]);
    for (std::uint32_t k = 0; k < 4; ++k) EXPECT_EQ(c.face_dim[4 * f + k], p.face_dim[f]);
  }
}

TEST(RefineTri, FeatureDimsAreInherited) {
  // Through the OBJ reader: a 2 x 2 grid of squares split into 8 triangles, a crease chain
  // across the middle (3-4-5) and a corner tag on vertex 0.
  const std::string obj =
      "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nv 1 1 0\nv 2 1 0\nv 0 2 0\nv 1 2 0\nv 2 2 0\n"
      "f 1 2 5\nf 1 5 4\nf 2 3 6\nf 2 6 5\nf 4 5 8\nf 4 8 7\nf 5 6 9\nf 5 9 8\n"
      "t crease 3/1/0 3 4 5 10\n"
      "t corner 1/1/0 0 10\n";
  const Shape s = read_shape_from_memory("tagged.obj", obj);
  const Complex& p = s.base;
  ASSERT_EQ(p.num_faces(), 8u);
  int crease_edges = 0;
  for (std::uint32_t e = 0; e < p.num_edges(); ++e)
    crease_edges += p.edge_dim[e] == 1 && p.edge_faces.size(e) == 2;
  ASSERT_EQ(crease_edges, 2);
  ASSERT_EQ(p.vertex_dim[0], 0);
  Complex c = p;
  for (int l = 0; l < 3; ++l) {
    SCOPED_TRACE("level " + std::to_string(l + 1));
    const Complex next = refine_tri(c);
    expect_inherited_dims(c, next);
    expect_valid(next);
    // Counts of each dim: midpoints and halves follow their edge, inner edges the face.
    std::uint32_t dim1 = 0, dim1_next = 0;
    for (std::uint32_t e = 0; e < c.num_edges(); ++e) dim1 += c.edge_dim[e] == 1;
    for (std::uint32_t e = 0; e < next.num_edges(); ++e) dim1_next += next.edge_dim[e] == 1;
    EXPECT_EQ(dim1_next, 2 * dim1);
    c = next;
  }
  // The crease stays inside: at level 3 its 2 * 8 = 16 pieces still have two faces each.
  int inner_crease = 0;
  for (std::uint32_t e = 0; e < c.num_edges(); ++e) inner_crease += c.edge_dim[e] == 1 && c.edge_faces.size(e) == 2;
  EXPECT_EQ(inner_crease, 16);
  EXPECT_EQ(c.vertex_dim[0], 0);  // the corner stays a corner

  // Boundaries of a generated grid: boundary edges are dim 1 and stay so.
  const Mesh g = tri_grid(3, 2, FeatureTags{{{1, 5}}, {6}, {}});
  expect_inherited_dims(g.c, refine_tri(g.c));
}

// ---- errors ------------------------------------------------------------------------------

// Runs f, expecting a TopologyError whose message contains every string of `parts`.
template <class F>
void expect_topology_error(F f, std::initializer_list<const char*> parts) {
  try {
    f();
    ADD_FAILURE() << "no TopologyError";
  } catch (const TopologyError& e) {
    for (const char* part : parts) EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
}

TEST(RefineTri, RejectsNonTrianglesAndLattices) {
  Csr faces;
  fixtures::push_row(faces, {0, 1, 2});
  fixtures::push_row(faces, {0, 2, 3, 4});
  const Complex quad = complex_from_polygons(5, faces);
  expect_topology_error([&] { refine_tri(quad); }, {"face 1", "4 corners"});
  Csr poly;
  poly.items = {0, 1, 2, 3, 4, 5};  // (push_row here trips GCC 12's -Wstringop-overflow false positive)
  poly.offsets = {0, 6};
  const Complex hexagon = complex_from_polygons(6, poly);
  expect_topology_error([&] { refine_tri(hexagon); }, {"face 0", "6 corners"});
  std::vector<double> xyz;
  const Complex block = make_hex_block(1, xyz);
  expect_topology_error([&] { refine_tri(block); }, {"dim 3", "1 cells"});
  Complex curve = make_curve_loop(5, xyz);
  expect_topology_error([&] { refine_tri(curve); }, {"dim 1"});
  // face_edges that do not join the corners (a hand-edited complex).
  Complex broken = octahedron().c;
  std::swap(broken.face_edges.items[3], broken.face_edges.items[4]);
  expect_topology_error([&] { refine_tri(broken); }, {"face 1"});
  // The empty surface refines to itself.
  const Complex empty = refine_tri(Complex{});
  EXPECT_EQ(empty.num_vertices, 0u);
  EXPECT_EQ(empty.num_faces(), 0u);
}

// ---- OpenSubdiv Far as a peer ------------------------------------------------------------

// One level of uniform Loop refinement of c's faces (same vertex indices), or null; with the
// level-1 edges, which the comparison reads.
std::unique_ptr<Far::TopologyRefiner> osd_loop(const Complex& c) {
  return fixtures::osd_refiner(fixtures::Polygons{c.num_vertices, c.faces, {}}, Sdc::SCHEME_LOOP, 1, true);
}

// Our child topology against Far's. Vertices are matched through Far's level-0 parent-child
// tables: our old vertex v -> GetVertexChildVertex(v); our midpoint nv + e -> GetEdgeChildVertex
// of Far's edge between e's ends (FindEdge). Then every child face must match: per coarse face
// f, our 4f + k against GetFaceChildFaces(f)[k] (as vertex cycles up to rotation, so the
// orientation is compared too), and the edge sets must agree.
void expect_equal_to_osd(const Complex& p, const std::string& name) {
  SCOPED_TRACE(name);
  const auto r = osd_loop(p);
  ASSERT_TRUE(r) << "OpenSubdiv refused the mesh";
  const Complex c = refine_tri(p);
  const Far::TopologyLevel& l0 = r->GetLevel(0);
  const Far::TopologyLevel& l1 = r->GetLevel(1);
  ASSERT_EQ(l0.GetNumEdges(), static_cast<int>(p.num_edges()));
  ASSERT_EQ(l1.GetNumVertices(), static_cast<int>(c.num_vertices));
  ASSERT_EQ(l1.GetNumEdges(), static_cast<int>(c.num_edges()));
  ASSERT_EQ(l1.GetNumFaces(), static_cast<int>(c.num_faces()));
  const std::uint32_t nv = p.num_vertices;
  std::vector<std::uint32_t> map(c.num_vertices);
  for (std::uint32_t v = 0; v < nv; ++v)
    map[v] = static_cast<std::uint32_t>(l0.GetVertexChildVertex(static_cast<int>(v)));
  for (std::uint32_t e = 0; e < p.num_edges(); ++e) {
    const Far::Index oe = l0.FindEdge(static_cast<int>(p.edge_verts[2 * e]), static_cast<int>(p.edge_verts[2 * e + 1]));
    ASSERT_NE(oe, Far::INDEX_INVALID) << "edge " << e;
    map[nv + e] = static_cast<std::uint32_t>(l0.GetEdgeChildVertex(oe));
  }
  std::vector<std::uint32_t> sorted = map;
  std::sort(sorted.begin(), sorted.end());
  for (std::uint32_t v = 0; v < c.num_vertices; ++v) ASSERT_EQ(sorted[v], v) << "vertex map is not a bijection";

  auto mapped = [&](std::uint32_t f) {
    const auto vs = c.faces.row(f);
    return canonical({map[vs[0]], map[vs[1]], map[vs[2]]});
  };
  auto far_face = [&](Far::Index f) {
    const auto vs = l1.GetFaceVertices(f);
    EXPECT_EQ(vs.size(), 3);
    return canonical({std::uint32_t(vs[0]), std::uint32_t(vs[1]), std::uint32_t(vs[2])});
  };
  // Per parent face, child by child (Far splits a triangle in the same order).
  for (std::uint32_t f = 0; f < p.num_faces(); ++f) {
    const auto kids = l0.GetFaceChildFaces(static_cast<int>(f));
    ASSERT_EQ(kids.size(), 4) << "face " << f;
    for (int k = 0; k < 4; ++k) EXPECT_EQ(mapped(4 * f + k), far_face(kids[k])) << "face " << f << " child " << k;
  }
  // Whole sets (independent of Far's per-parent order).
  std::vector<Tri> ours, theirs;
  for (std::uint32_t f = 0; f < c.num_faces(); ++f) ours.push_back(mapped(f));
  for (int f = 0; f < l1.GetNumFaces(); ++f) theirs.push_back(far_face(f));
  std::sort(ours.begin(), ours.end());
  std::sort(theirs.begin(), theirs.end());
  EXPECT_EQ(ours, theirs);
  std::set<Pair> our_edges, their_edges;
  for (std::uint32_t e = 0; e < c.num_edges(); ++e)
    our_edges.insert(key(map[c.edge_verts[2 * e]], map[c.edge_verts[2 * e + 1]]));
  for (int e = 0; e < l1.GetNumEdges(); ++e) {
    const auto vs = l1.GetEdgeVertices(e);
    their_edges.insert(key(std::uint32_t(vs[0]), std::uint32_t(vs[1])));
  }
  EXPECT_EQ(our_edges, their_edges);
  // Halves: Far's two child edges of each coarse edge are our 2e and 2e+1.
  for (std::uint32_t e = 0; e < p.num_edges(); ++e) {
    const Far::Index oe = l0.FindEdge(static_cast<int>(p.edge_verts[2 * e]), static_cast<int>(p.edge_verts[2 * e + 1]));
    const auto kids = l0.GetEdgeChildEdges(oe);
    ASSERT_EQ(kids.size(), 2);
    std::set<Pair> far_halves, our_halves;
    for (int k = 0; k < 2; ++k) {
      const auto vs = l1.GetEdgeVertices(kids[k]);
      far_halves.insert(key(std::uint32_t(vs[0]), std::uint32_t(vs[1])));
      our_halves.insert(key(map[c.edge_verts[4 * e + 2 * k]], map[c.edge_verts[4 * e + 2 * k + 1]]));
    }
    EXPECT_EQ(our_halves, far_halves) << "edge " << e;
  }
}

TEST(RefineTri, EqualsOpenSubdivLoopSplit) {
  expect_equal_to_osd(octahedron().c, "octahedron");
  expect_equal_to_osd(tri_torus(6, 4).c, "triangulated torus");
  expect_equal_to_osd(tri_grid(4, 3).c, "open grid");
  Mesh g = tri_grid(2, 2);
  g.c = refine_tri(g.c);
  expect_equal_to_osd(g.c, "open grid, level 1");
}

TEST(RefineTri, EqualsOpenSubdivLoopSplitOnSharedLoopShapes) {
  // OpenSubdiv's own Loop regression shapes: closed, open, creased, several components.
  const std::filesystem::path dir = std::filesystem::path(SUBLIFT_SHARED_DATA) / "control_meshes/opensubdiv_shapes";
  if (!std::filesystem::exists(dir)) GTEST_SKIP() << "no third-party data at " << dir << " (SUBLIFT_SHARED_DATA)";
  std::vector<std::filesystem::path> paths;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    if (entry.path().filename().string().starts_with("loop_") && entry.path().extension() == ".obj")
      paths.push_back(entry.path());
  std::sort(paths.begin(), paths.end());
  int compared = 0;
  for (const auto& path : paths) {
    Shape s;
    try {
      s = read_shape(path.string());
    } catch (const Error& e) {  // degenerate faces in the non-manifold shapes
      std::printf("note: %s not read: %s\n", path.filename().c_str(), e.what());
      continue;
    }
    expect_equal_to_osd(s.base, path.filename().string());
    // Dims are inherited; semi-sharp tags soften instead (tests/complex/semisharp_test.cpp), so
    // they are checked here without their sharpness.
    Complex plain = s.base;
    plain.edge_sharpness.clear();
    plain.vertex_sharpness.clear();
    expect_inherited_dims(plain, refine_tri(plain));
    ++compared;
  }
  EXPECT_GE(compared, 10);
}

}  // namespace
