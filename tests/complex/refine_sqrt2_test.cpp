// sqrt(2) refinement (core/complex/refine_sqrt2.h): closed-form counts, Euler characteristic, validate()
// and orientation on every level, 45-degree rotated odd levels, curves kept at odd and refined
// at even levels, and the two-step property checked against the engine's 1-to-4 refine() as an
// independent peer (vertex correspondence found from adjacency, not from the child arrays).
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "core/complex/complex_build.h"
#include "core/base/errors.h"
#include "core/complex/refine.h"
#include "core/complex/refine_sqrt2.h"
#include "core/io/lattice/shape_io.h"
#include "core/complex/shapes.h"
#include "tests/mesh_fixtures.h"

using namespace sublift;

namespace {

constexpr std::uint32_t kNone = Sqrt2Children::kNone;
using Pair = std::pair<std::uint32_t, std::uint32_t>;

Complex asset(const std::string& name) { return read_shape(std::string(SUBLIFT_ASSETS_DIR) + "/" + name).base; }

Complex torus(std::uint32_t nu, std::uint32_t nv) {
  const fixtures::Polygons m = fixtures::torus(nu, nv);
  return complex_from_polygons(m.num_vertices, m.faces);
}

// Open n x m quad grid; vertex (i, j) is j * (n + 1) + i.
Complex grid(std::uint32_t n, std::uint32_t m, const FeatureTags& tags = {}) {
  Csr faces;
  for (std::uint32_t j = 0; j < m; ++j)
    for (std::uint32_t i = 0; i < n; ++i) {
      const std::uint32_t v = j * (n + 1) + i;
      fixtures::push_row(faces, {v, v + 1, v + n + 2, v + n + 1});
    }
  return complex_from_polygons((n + 1) * (m + 1), faces, tags);
}

long long euler(const Complex& c) { return static_cast<long long>(c.num_vertices) - c.num_edges() + c.num_faces(); }

Pair key(std::uint32_t a, std::uint32_t b) { return a < b ? Pair{a, b} : Pair{b, a}; }

bool is_curve(const Complex& c, std::uint32_t e) { return c.edge_dim[e] == 1 || c.edge_faces.size(e) != 2; }

// validate(), symmetric derived rows, and consistent orientation: an edge shared by two faces
// is run a->b by one and b->a by the other.
void expect_valid(const Complex& c) {
  Complex copy = c;
  build_adjacency(copy);
  ASSERT_NO_THROW(validate(copy));
  EXPECT_EQ(copy.edge_faces.items, c.edge_faces.items);
  EXPECT_EQ(copy.vertex_edges.items, c.vertex_edges.items);
  for (std::uint32_t e = 0; e < c.num_edges(); ++e) {
    if (c.edge_faces.size(e) != 2) continue;
    int forward = 0;
    for (std::uint32_t f : c.edge_faces.row(e)) {
      const auto vs = c.faces.row(f);
      for (std::size_t i = 0; i < vs.size(); ++i)
        if (vs[i] == c.edge_verts[2 * e] && vs[(i + 1) % vs.size()] == c.edge_verts[2 * e + 1]) ++forward;
    }
    EXPECT_EQ(forward, 1) << "edge " << e;
  }
}

// Faces as vertex cycles rotated to start at their smallest vertex (orientation kept), sorted.
std::vector<std::vector<std::uint32_t>> face_set(const Complex& c, const std::vector<std::uint32_t>& map) {
  std::vector<std::vector<std::uint32_t>> out;
  for (std::uint32_t f = 0; f < c.num_faces(); ++f) {
    std::vector<std::uint32_t> vs;
    for (std::uint32_t v : c.faces.row(f)) vs.push_back(map.empty() ? v : map[v]);
    std::rotate(vs.begin(), std::min_element(vs.begin(), vs.end()), vs.end());
    out.push_back(vs);
  }
  std::sort(out.begin(), out.end());
  return out;
}

// Edge pair -> feature dim.
std::map<Pair, int> edge_set(const Complex& c, const std::vector<std::uint32_t>& map) {
  std::map<Pair, int> out;
  for (std::uint32_t e = 0; e < c.num_edges(); ++e) {
    std::uint32_t a = c.edge_verts[2 * e], b = c.edge_verts[2 * e + 1];
    if (!map.empty()) a = map[a], b = map[b];
    out[key(a, b)] = c.edge_dim[e];
  }
  return out;
}

// Two sqrt(2) steps from even level `level` of `base` against refine(base). The correspondence
// comes from the documented numbering (old vertices, then level-(j+1) face points of faces
// 0..nf-1) and from adjacency: every level-(j+2) point born at the curve step has exactly two
// old neighbours, the ends of the coarse edge whose 1-to-4 edge point it is.
void expect_catmull_clark(const Complex& base, int level, const char* name) {
  SCOPED_TRACE(name);
  const Sqrt2Step s1 = refine_sqrt2(base, level);
  const Sqrt2Step s2 = refine_sqrt2(s1.fine, level + 1);
  const Complex cc = refine(base);
  const Complex& l2 = s2.fine;
  const std::uint32_t nv = base.num_vertices, ne = base.num_edges(), nf = base.num_faces();
  ASSERT_EQ(s1.fine.num_vertices, nv + nf);
  ASSERT_EQ(l2.num_vertices, cc.num_vertices);
  std::map<Pair, std::uint32_t> base_edge;
  for (std::uint32_t e = 0; e < ne; ++e) base_edge[key(base.edge_verts[2 * e], base.edge_verts[2 * e + 1])] = e;
  std::vector<std::uint32_t> map(l2.num_vertices, kNone);
  for (std::uint32_t v = 0; v < nv; ++v) map[v] = v;
  for (std::uint32_t f = 0; f < nf; ++f) map[nv + f] = nv + ne + f;
  for (std::uint32_t v = nv + nf; v < l2.num_vertices; ++v) {
    std::vector<std::uint32_t> old;
    for (std::uint32_t e : l2.vertex_edges.row(v)) {
      const std::uint32_t w = l2.edge_verts[2 * e] == v ? l2.edge_verts[2 * e + 1] : l2.edge_verts[2 * e];
      if (w < nv) old.push_back(w);
    }
    ASSERT_EQ(old.size(), 2u) << "vertex " << v;
    const auto it = base_edge.find(key(old[0], old[1]));
    ASSERT_NE(it, base_edge.end()) << "vertex " << v;
    map[v] = nv + it->second;
  }
  std::vector<std::uint32_t> sorted = map;
  std::sort(sorted.begin(), sorted.end());
  for (std::uint32_t v = 0; v < l2.num_vertices; ++v) ASSERT_EQ(sorted[v], v) << "not a bijection";

  EXPECT_EQ(face_set(l2, map), face_set(cc, {}));
  EXPECT_EQ(edge_set(l2, map), edge_set(cc, {}));
  for (std::uint32_t v = 0; v < l2.num_vertices; ++v) EXPECT_EQ(l2.vertex_dim[v], cc.vertex_dim[map[v]]) << v;

  // The child arrays say the same: curve points and face points name their 1-to-4 edge.
  const Sqrt2Children& c1 = s1.children;
  const Sqrt2Children& c2 = s2.children;
  EXPECT_EQ(c2.first_face_point, nv + nf + c2.curve_edges.size());
  for (std::size_t k = 0; k < c2.curve_edges.size(); ++k) {
    const std::uint32_t e1 = c2.curve_edges[k];
    ASSERT_LT(e1, c1.curve_edges.size());  // kept curve edges come first at odd levels
    EXPECT_EQ(map[nv + nf + k], nv + c1.curve_edges[e1]);
  }
  for (std::size_t k = 0; k < c2.point_faces.size(); ++k)
    EXPECT_EQ(map[c2.first_face_point + k], nv + c1.fine_face_edge[c2.point_faces[k]]);
}

// Vertex pairs of the curve edges (feature dim 1 or not between two faces).
std::set<Pair> curve_pairs(const Complex& c) {
  std::set<Pair> out;
  for (std::uint32_t e = 0; e < c.num_edges(); ++e)
    if (is_curve(c, e)) out.insert(key(c.edge_verts[2 * e], c.edge_verts[2 * e + 1]));
  return out;
}

int count_faces(const Complex& c, std::uint32_t corners) {
  int n = 0;
  for (std::uint32_t f = 0; f < c.num_faces(); ++f) n += c.faces.size(f) == corners;
  return n;
}

}  // namespace

TEST(RefineSqrt2, ClosedTorusCountsFollowClosedFormulas) {
  // A step on a closed mesh: V' = V + F, E' = number of corners (= 2E), F' = E. On a closed quad
  // mesh E = 2F, so every step doubles V, E and F; 12 x 8 torus: V = F = 96 * 2^j, E = 192 * 2^j.
  const std::vector<Complex> levels = build_sqrt2_levels(torus(12, 8), 4);
  ASSERT_EQ(levels.size(), 5u);
  for (std::uint32_t j = 0; j < 5; ++j) {
    SCOPED_TRACE(j);
    const Complex& c = levels[j];
    EXPECT_EQ(c.num_vertices, 96u << j);
    EXPECT_EQ(c.num_edges(), 192u << j);
    EXPECT_EQ(c.num_faces(), 96u << j);
    EXPECT_EQ(count_faces(c, 4), static_cast<int>(c.num_faces()));
    EXPECT_EQ(euler(c), 0);
    expect_valid(c);
  }
}

TEST(RefineSqrt2, OddLevelsAreRotated45Degrees) {
  // Every odd-level quad runs old vertex, face point, old vertex, face point: its old vertices
  // are the ends of the coarse edge it grows along, its face points those of the edge's faces.
  const Complex base = torus(6, 5);
  const Complex l2 = refine_sqrt2(refine_sqrt2(base, 0).fine, 1).fine;
  for (int level : {0, 2}) {
    const Complex& coarse = level == 0 ? base : l2;
    const Sqrt2Step s = refine_sqrt2(coarse, level);
    const std::uint32_t nv = coarse.num_vertices;
    ASSERT_EQ(s.children.fine_face_edge.size(), s.fine.num_faces());
    for (std::uint32_t f = 0; f < s.fine.num_faces(); ++f) {
      const auto vs = s.fine.faces.row(f);
      ASSERT_EQ(vs.size(), 4u);
      EXPECT_TRUE(vs[0] < nv && vs[1] >= nv && vs[2] < nv && vs[3] >= nv) << "face " << f;
      const std::uint32_t e = s.children.fine_face_edge[f];
      EXPECT_EQ(key(vs[0], vs[2]), key(coarse.edge_verts[2 * e], coarse.edge_verts[2 * e + 1]));
      const auto ef = coarse.edge_faces.row(e);
      EXPECT_EQ(key(vs[1], vs[3]), key(nv + ef[0], nv + ef[1]));
    }
  }
}

TEST(RefineSqrt2, TwoStepsGiveCatmullClarkTopology) {
  expect_catmull_clark(torus(5, 4), 0, "torus");
  expect_catmull_clark(asset("mixed_polygons.obj"), 0, "mixed polygons");
  expect_catmull_clark(asset("pyramid.obj"), 0, "pyramid");
  expect_catmull_clark(asset("quad_grid_boundary.obj"), 0, "open grid");
  expect_catmull_clark(asset("crease_loop.obj"), 0, "crease loop");
  FeatureTags corners;
  corners.corner_vertices = {0, 3, 8, 11};
  expect_catmull_clark(grid(3, 2, corners), 0, "grid with corner tags");
  // Again from level 2 (an even level that is itself a 1-to-4 split).
  const Complex grid2 = build_sqrt2_levels(asset("quad_grid_boundary.obj"), 2)[2];
  expect_catmull_clark(grid2, 2, "open grid, levels 2 -> 4");
  const Complex crease2 = build_sqrt2_levels(asset("crease_loop.obj"), 2)[2];
  expect_catmull_clark(crease2, 2, "crease loop, levels 2 -> 4");
}

TEST(RefineSqrt2, OpenGridHasBoundaryTrianglesAtOddLevels) {
  // 4 x 4 grid: V 25, E 40 (16 on the boundary), F 16. Keep step: V' = V + F, E' = boundary + 4F,
  // F' = inner edges + one triangle per boundary edge; the curve step then gives the 1-to-4
  // counts V + E + F, 2E + 4F, 4F of the base.
  const std::vector<Complex> levels = build_sqrt2_levels(asset("quad_grid_boundary.obj"), 4);
  const std::uint32_t V[] = {25, 41, 81, 145, 289}, E[] = {40, 80, 144, 288, 544}, F[] = {16, 40, 64, 144, 256};
  const int tris[] = {0, 16, 0, 32, 0}, boundary[] = {16, 16, 32, 32, 64};
  for (std::size_t j = 0; j < levels.size(); ++j) {
    SCOPED_TRACE(j);
    const Complex& c = levels[j];
    expect_valid(c);
    EXPECT_EQ(c.num_vertices, V[j]);
    EXPECT_EQ(c.num_edges(), E[j]);
    EXPECT_EQ(c.num_faces(), F[j]);
    EXPECT_EQ(euler(c), 1);
    EXPECT_EQ(count_faces(c, 3), tris[j]);
    EXPECT_EQ(count_faces(c, 4), static_cast<int>(F[j]) - tris[j]);
    EXPECT_EQ(static_cast<int>(curve_pairs(c).size()), boundary[j]);
    // Each triangle sits on exactly one boundary edge, its apex inside.
    for (std::uint32_t f = 0; f < c.num_faces(); ++f) {
      if (c.faces.size(f) != 3) continue;
      int on_boundary = 0;
      for (std::uint32_t e : c.face_edges.row(f)) on_boundary += c.edge_faces.size(e) == 1;
      EXPECT_EQ(on_boundary, 1) << "face " << f;
    }
  }
  // Odd levels keep the boundary polygon of the level before.
  EXPECT_EQ(curve_pairs(levels[1]), curve_pairs(levels[0]));
  EXPECT_EQ(curve_pairs(levels[3]), curve_pairs(levels[2]));
}

TEST(RefineSqrt2, CreaseIsACurveRefinedAtEvenLevels) {
  // crease_loop.obj: a box with a tagged loop of 4 crease edges around it.
  const std::vector<Complex> levels = build_sqrt2_levels(asset("crease_loop.obj"), 4);
  const std::size_t loop[] = {4, 4, 8, 8, 16};
  for (std::size_t j = 0; j < levels.size(); ++j) {
    SCOPED_TRACE(j);
    const Complex& c = levels[j];
    expect_valid(c);
    EXPECT_EQ(euler(c), 2);
    const std::set<Pair> crease = curve_pairs(c);
    EXPECT_EQ(crease.size(), loop[j]);
    // A closed loop: every crease vertex on two crease edges, of feature dim 1.
    std::map<std::uint32_t, int> valence;
    for (auto [a, b] : crease) ++valence[a], ++valence[b];
    EXPECT_EQ(valence.size(), loop[j]);
    for (auto [v, n] : valence) {
      EXPECT_EQ(n, 2) << "vertex " << v;
      EXPECT_EQ(c.vertex_dim[v], 1) << "vertex " << v;
    }
    // Inside the surface: two faces on every crease edge (triangles at odd levels).
    for (std::uint32_t e = 0; e < c.num_edges(); ++e)
      if (c.edge_dim[e] == 1) {
        EXPECT_EQ(c.edge_faces.size(e), 2u);
        for (std::uint32_t f : c.edge_faces.row(e)) EXPECT_EQ(c.faces.size(f), j % 2 ? 3u : 4u);
      }
  }
  EXPECT_EQ(curve_pairs(levels[1]), curve_pairs(levels[0]));
  EXPECT_EQ(curve_pairs(levels[3]), curve_pairs(levels[2]));

  // The 4-point stencils of the curve step from level 1 run along the loop.
  const Sqrt2Step s = refine_sqrt2(levels[1], 1);
  const std::set<Pair> crease = curve_pairs(levels[1]);
  ASSERT_EQ(s.children.curve_stencils.size(), 4 * s.children.curve_edges.size());
  for (std::size_t k = 0; k < s.children.curve_edges.size(); ++k) {
    const std::uint32_t* st = &s.children.curve_stencils[4 * k];
    const std::uint32_t e = s.children.curve_edges[k];
    EXPECT_EQ(st[1], levels[1].edge_verts[2 * e]);
    EXPECT_EQ(st[2], levels[1].edge_verts[2 * e + 1]);
    EXPECT_TRUE(crease.count(key(st[0], st[1])) && crease.count(key(st[2], st[3])));
    EXPECT_EQ(std::set<std::uint32_t>(st, st + 4).size(), 4u);  // a loop of 4 edges: all distinct
    EXPECT_EQ(s.fine.vertex_dim[levels[1].num_vertices + k], 1);
  }
}

TEST(RefineSqrt2, PolygonBaseBecomesQuads) {
  for (const char* name : {"mixed_polygons.obj", "pyramid.obj"}) {
    SCOPED_TRACE(name);
    const Complex base = asset(name);
    const std::vector<Complex> levels = build_sqrt2_levels(base, 3);
    EXPECT_EQ(levels[1].num_vertices, base.num_vertices + base.num_faces());
    EXPECT_EQ(levels[1].num_faces(), base.num_edges());
    EXPECT_EQ(levels[1].num_edges(), base.faces.items.size());
    for (const Complex& c : levels) {
      expect_valid(c);
      EXPECT_EQ(euler(c), 2);
    }
    for (std::size_t j = 1; j < levels.size(); ++j)
      EXPECT_EQ(count_faces(levels[j], 4), static_cast<int>(levels[j].num_faces()));
  }
}

TEST(RefineSqrt2, FacePointsKnowTheirCornersCounterclockwise) {
  for (const char* name : {"mixed_polygons.obj", "quad_grid_boundary.obj"}) {
    SCOPED_TRACE(name);
    const Complex base = asset(name);
    const Sqrt2Step s1 = refine_sqrt2(base, 0);
    const Sqrt2Step s2 = refine_sqrt2(s1.fine, 1);
    for (const auto* step : {&s1, &s2}) {
      const Complex& coarse = step == &s1 ? base : s1.fine;
      const Sqrt2Children& ch = step->children;
      ASSERT_EQ(ch.point_corners.rows(), ch.point_faces.size());
      EXPECT_EQ(ch.first_face_point + ch.point_faces.size(), step->fine.num_vertices);
      for (std::size_t k = 0; k < ch.point_faces.size(); ++k) {
        // The corners are the face's cycle (same orientation, any start) ...
        const auto face = coarse.faces.row(ch.point_faces[k]);
        const auto corners = ch.point_corners.row(k);
        ASSERT_EQ(corners.size(), face.size());
        const auto start = std::find(face.begin(), face.end(), corners[0]) - face.begin();
        for (std::size_t i = 0; i < face.size(); ++i) EXPECT_EQ(corners[i], face[(start + i) % face.size()]);
        // ... and exactly the face point's neighbours on the fine level.
        const std::uint32_t p = ch.first_face_point + static_cast<std::uint32_t>(k);
        std::set<std::uint32_t> nbrs;
        for (std::uint32_t e : step->fine.vertex_edges.row(p))
          nbrs.insert(step->fine.edge_verts[2 * e] == p ? step->fine.edge_verts[2 * e + 1] : step->fine.edge_verts[2 * e]);
        EXPECT_EQ(nbrs, std::set<std::uint32_t>(corners.begin(), corners.end()));
      }
    }
    // Keep steps give every face a point; curve steps only the quads (triangles take the
    // curve point of their curve edge).
    EXPECT_EQ(s1.children.point_faces.size(), base.num_faces());
    EXPECT_EQ(static_cast<int>(s2.children.point_faces.size()), count_faces(s1.fine, 4));
  }
}

TEST(RefineSqrt2, FourPointStencilsStopAtCorners) {
  // 3 x 2 grid, corners 0, 3, 8, 11 tagged: the boundary splits into four open curves; a curve
  // point next to a corner has no neighbour beyond it (001 eq. 11 case (b)).
  FeatureTags tags;
  tags.corner_vertices = {0, 3, 8, 11};
  const Complex l1 = refine_sqrt2(grid(3, 2, tags), 0).fine;
  const Sqrt2Step s = refine_sqrt2(l1, 1);
  const std::set<std::uint32_t> corner(tags.corner_vertices.begin(), tags.corner_vertices.end());
  ASSERT_EQ(s.children.curve_edges.size(), 10u);
  int open_ends = 0;
  for (std::size_t k = 0; k < 10; ++k) {
    const std::uint32_t* st = &s.children.curve_stencils[4 * k];
    EXPECT_EQ(st[0] == kNone, corner.count(st[1]) == 1) << k;
    EXPECT_EQ(st[3] == kNone, corner.count(st[2]) == 1) << k;
    open_ends += (st[0] == kNone) + (st[3] == kNone);
  }
  EXPECT_EQ(open_ends, 8);  // each of the 4 corners ends two curves
  // Untagged, the boundary is one closed curve and every stencil is complete.
  const Sqrt2Step u = refine_sqrt2(refine_sqrt2(grid(3, 2), 0).fine, 1);
  for (std::uint32_t x : u.children.curve_stencils) EXPECT_NE(x, kNone);
}

TEST(RefineSqrt2, RejectsWhatItCannotRefine) {
  std::vector<double> pos;
  EXPECT_THROW(refine_sqrt2(make_hex_block(1, pos), 0), TopologyError);
  // An odd level must hold quads and curve triangles only: a pentagon is no odd level.
  EXPECT_THROW(refine_sqrt2(asset("mixed_polygons.obj"), 1), TopologyError);
  // Two faces running the same way along their shared edge.
  Csr faces;
  fixtures::push_row(faces, {0, 1, 2, 3});
  fixtures::push_row(faces, {1, 2, 4, 5});
  EXPECT_THROW(refine_sqrt2(complex_from_polygons(6, faces), 0), TopologyError);
  EXPECT_THROW(build_sqrt2_levels(torus(3, 3), -1), std::invalid_argument);
}
