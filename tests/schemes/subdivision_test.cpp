// With zero details the programs are subdivision schemes with known answers: uniform cubic
// B-splines in 1-D, bicubic on regular quad grids, tricubic inside regular hex blocks, the
// extraordinary-vertex rule of DESIGN.md, and features that subdivide as curves of their own.
// Every expected value here comes from an independent formula, not from the engine.
#include <gtest/gtest.h>

#include <cmath>

#include "core/complex/complex_build.h"
#include "core/multires/hierarchy.h"
#include "core/io/mesh/mesh_import.h"
#include "core/complex/shapes.h"
#include "tests/test_shapes.h"

using namespace sublift;
using sublift::testing::edge_map;
using sublift::testing::edge_of;
using sublift::testing::random_values;

namespace {

std::vector<double> subdivide(const Complex& base, const std::vector<double>& pos, int levels, Scheme s,
                              int channels = 3) {
  Hierarchy h = make_hierarchy(base, levels, s, channels);
  set_base(h, pos);
  return synthesize(h, levels);
}

// One step of uniform cubic B-spline subdivision of a closed polygon (interleaved even/odd).
std::vector<double> bspline_closed(const std::vector<double>& p, int ch) {
  const std::size_t n = p.size() / ch;
  std::vector<double> out(2 * n * ch);
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < ch; ++c) {
      const double prev = p[((i + n - 1) % n) * ch + c], cur = p[i * ch + c], next = p[((i + 1) % n) * ch + c];
      out[(2 * i) * ch + c] = (prev + 6 * cur + next) / 8;
      out[(2 * i + 1) * ch + c] = (cur + next) / 2;
    }
  return out;
}

std::string assets(const char* f) { return std::string(SUBLIFT_ASSETS_DIR) + "/" + f; }

}  // namespace

TEST(CubicSubdivision, CurveIsUniformCubicBspline) {
  std::vector<double> pos;
  const Complex c = make_curve_loop(11, pos);
  pos = random_values(pos.size(), 1);
  std::vector<double> want = pos;
  for (int level = 1; level <= 3; ++level) {
    want = bspline_closed(want, 3);
    // Level-L engine order [v | e]: coarse vertex i at 2i, edge (i, i+1) at 2i+1 of `want`,
    // recursively; compare after mapping the engine's order to the interleaved one.
    const std::vector<double> got = subdivide(c, pos, level, Scheme::Cubic);
    // Build the interleaved index of every engine vertex by walking the levels' numbering.
    Hierarchy h = make_hierarchy(c, level, Scheme::Cubic, 3);
    std::vector<std::size_t> pos_of(h.num_vertices(0));
    for (std::size_t i = 0; i < pos_of.size(); ++i) pos_of[i] = i;
    for (int j = 0; j < level; ++j) {
      const Complex& p = h.levels[j];
      std::vector<std::size_t> next(p.num_child_vertices());
      for (std::uint32_t v = 0; v < p.num_vertices; ++v) next[v] = 2 * pos_of[v];
      for (std::uint32_t e = 0; e < p.num_edges(); ++e) {
        const std::size_t a = pos_of[p.edge_verts[2 * e]], b = pos_of[p.edge_verts[2 * e + 1]];
        const std::size_t n = pos_of.size();
        next[p.num_vertices + e] = ((b == (a + 1) % n) ? 2 * a + 1 : 2 * b + 1);
      }
      pos_of = next;
    }
    for (std::size_t v = 0; v < pos_of.size(); ++v)
      for (int c2 = 0; c2 < 3; ++c2) EXPECT_NEAR(got[v * 3 + c2], want[pos_of[v] * 3 + c2], 1e-14) << "level " << level;
  }
}

TEST(CubicSubdivision, RegularQuadTorusIsBicubic) {
  const int n = 8, m = 6;
  const SurfaceMesh t = make_quad_torus(n, m);
  const Complex c = complex_from_surface_mesh(t);
  const std::vector<double> pos = random_values(t.positions.size() * 3, 2);
  const std::vector<double> got = subdivide(c, pos, 1, Scheme::Cubic);
  // Tensor product of the 1-D rules on the periodic (2n x 2m) grid.
  auto P = [&](int i, int j, int ch) { return pos[(((i % n + n) % n) * m + (j % m + m) % m) * 3 + ch]; };
  auto rule = [](int parity, int k) {  // 1-D weights for offset k in {-1, 0, 1, 2} from coarse index
    if (parity == 0) return k == 0 ? 0.75 : (k == -1 || k == 1) ? 0.125 : 0.0;
    return (k == 0 || k == 1) ? 0.5 : 0.0;
  };
  auto fine = [&](int I, int J, int ch) {
    const int i = I / 2, j = J / 2;
    double s = 0;
    for (int a = -1; a <= 2; ++a)
      for (int b = -1; b <= 2; ++b) s += rule(I % 2, a) * rule(J % 2, b) * P(i + a, j + b, ch);
    return s;
  };
  const auto em = edge_map(c);
  auto vid = [&](int i, int j) { return static_cast<std::uint32_t>(((i % n + n) % n) * m + (j % m + m) % m); };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j)
      for (int ch = 0; ch < 3; ++ch) {
        EXPECT_NEAR(got[vid(i, j) * 3 + ch], fine(2 * i, 2 * j, ch), 1e-14);
        const std::uint32_t eu = c.num_vertices + edge_of(em, vid(i, j), vid(i + 1, j));
        const std::uint32_t ev = c.num_vertices + edge_of(em, vid(i, j), vid(i, j + 1));
        EXPECT_NEAR(got[eu * 3 + ch], fine(2 * i + 1, 2 * j, ch), 1e-14);
        EXPECT_NEAR(got[ev * 3 + ch], fine(2 * i, 2 * j + 1, ch), 1e-14);
        const std::uint32_t f = c.num_vertices + c.num_edges() + static_cast<std::uint32_t>(i * m + j);
        EXPECT_NEAR(got[f * 3 + ch], fine(2 * i + 1, 2 * j + 1, ch), 1e-14);
      }
}

TEST(CubicSubdivision, RegularHexBlockInteriorIsTricubic) {
  const int n = 4, s = n + 1;
  std::vector<double> pos;
  const Complex c = make_hex_block(n, pos);
  pos = random_values(pos.size(), 3);
  const std::vector<double> got = subdivide(c, pos, 1, Scheme::Cubic);
  auto P = [&](int i, int j, int k, int ch) { return pos[((k * s + j) * s + i) * 3 + ch]; };
  auto rule = [](int parity, int o) {
    if (parity == 0) return o == 0 ? 0.75 : (o == -1 || o == 1) ? 0.125 : 0.0;
    return (o == 0 || o == 1) ? 0.5 : 0.0;
  };
  // Fine value at grid point (I, J, K) of the (2n)^3 grid, if its stencil is inside the block.
  auto fine = [&](int I, int J, int K, int ch, bool& inside) {
    double sum = 0;
    inside = true;
    for (int a = -1; a <= 2; ++a)
      for (int b = -1; b <= 2; ++b)
        for (int d = -1; d <= 2; ++d) {
          const double w = rule(I % 2, a) * rule(J % 2, b) * rule(K % 2, d);
          if (w == 0) continue;
          const int i = I / 2 + a, j = J / 2 + b, k = K / 2 + d;
          if (i < 0 || j < 0 || k < 0 || i > n || j > n || k > n) {
            inside = false;
            return 0.0;
          }
          sum += w * P(i, j, k, ch);
        }
    return sum;
  };
  // Locate each level-1 vertex on the fine grid from its parent primitive's vertices.
  int checked = 0;
  auto grid_of = [&](std::uint32_t v) { return std::array<int, 3>{int(v % s), int((v / s) % s), int(v / (s * s))}; };
  auto check = [&](std::uint32_t fine_vertex, std::uint8_t dim, std::span<const std::uint32_t> corners) {
    if (dim != 3) return;  // interior primitives only: the boundary surface is a feature
    std::array<int, 3> sum{0, 0, 0};
    for (std::uint32_t v : corners) {
      const auto g = grid_of(v);
      for (int a = 0; a < 3; ++a) sum[a] += 2 * g[a];
    }
    for (int a = 0; a < 3; ++a) sum[a] /= static_cast<int>(corners.size());
    for (int ch = 0; ch < 3; ++ch) {
      bool inside = false;
      const double want = fine(sum[0], sum[1], sum[2], ch, inside);
      if (!inside) return;
      EXPECT_NEAR(got[fine_vertex * 3 + ch], want, 1e-13);
    }
    ++checked;
  };
  for (std::uint32_t v = 0; v < c.num_vertices; ++v) {
    const std::uint32_t one[1] = {v};
    check(v, c.vertex_dim[v], one);
  }
  for (std::uint32_t e = 0; e < c.num_edges(); ++e)
    check(c.num_vertices + e, c.edge_dim[e], std::span<const std::uint32_t>(&c.edge_verts[2 * e], 2));
  for (std::uint32_t f = 0; f < c.num_faces(); ++f) check(c.num_vertices + c.num_edges() + f, c.face_dim[f], c.faces.row(f));
  for (std::uint32_t k = 0; k < c.num_cells(); ++k)
    check(c.num_vertices + c.num_edges() + c.num_faces() + k, 3, c.cell_verts.row(k));
  EXPECT_GT(checked, 200);
}

TEST(CubicSubdivision, ExtraordinaryVertexRule) {
  // v' = 1/2 v + 1/4 mean(edge neighbours) + 1/4 mean(centroids of incident faces) (DESIGN.md).
  const LoadedMesh m = import_surface_mesh(assets("mixed_polygons.obj"));
  const Complex c = complex_from_surface_mesh(m.mesh);
  const std::vector<double> pos = random_values(m.mesh.positions.size() * 3, 4);
  const std::vector<double> got = subdivide(c, pos, 1, Scheme::Cubic);
  for (std::uint32_t v = 0; v < c.num_vertices; ++v) {
    ASSERT_EQ(c.vertex_dim[v], 2);
    for (int ch = 0; ch < 3; ++ch) {
      double nb = 0, fc = 0;
      for (std::uint32_t e : c.vertex_edges.row(v)) {
        const std::uint32_t w = c.edge_verts[2 * e] == v ? c.edge_verts[2 * e + 1] : c.edge_verts[2 * e];
        nb += pos[w * 3 + ch];
      }
      nb /= c.vertex_edges.size(v);
      for (std::uint32_t f : c.vertex_faces.row(v)) {
        double cen = 0;
        for (std::uint32_t w : c.faces.row(f)) cen += pos[w * 3 + ch];
        fc += cen / c.faces.size(f);
      }
      fc /= c.vertex_faces.size(v);
      EXPECT_NEAR(got[v * 3 + ch], 0.5 * pos[v * 3 + ch] + 0.25 * nb + 0.25 * fc, 1e-14);
    }
  }
}

TEST(CubicSubdivision, CubeCornerGoesToTwoThirds) {
  const LoadedMesh m = import_surface_mesh(assets("cube.obj"));
  const Complex c = complex_from_surface_mesh(m.mesh);
  const std::vector<double> got = subdivide(c, flatten_positions(m.mesh), 1, Scheme::Cubic);
  for (std::uint32_t v = 0; v < 8; ++v)
    for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(got[v * 3 + ch], (2.0 / 3.0) * m.mesh.positions[v][ch], 1e-15);
}

TEST(LinearSubdivision, IsMidpointAndCentroidRefinement) {
  const LoadedMesh m = import_surface_mesh(assets("mixed_polygons.obj"));
  const Complex c = complex_from_surface_mesh(m.mesh);
  const std::vector<double> pos = flatten_positions(m.mesh);
  const std::vector<double> got = subdivide(c, pos, 1, Scheme::Linear);
  for (std::uint32_t v = 0; v < c.num_vertices; ++v)
    for (int ch = 0; ch < 3; ++ch) EXPECT_DOUBLE_EQ(got[v * 3 + ch], pos[v * 3 + ch]);
  for (std::uint32_t e = 0; e < c.num_edges(); ++e)
    for (int ch = 0; ch < 3; ++ch)
      EXPECT_NEAR(got[(c.num_vertices + e) * 3 + ch], 0.5 * (pos[c.edge_verts[2 * e] * 3 + ch] + pos[c.edge_verts[2 * e + 1] * 3 + ch]), 1e-15);
  for (std::uint32_t f = 0; f < c.num_faces(); ++f)
    for (int ch = 0; ch < 3; ++ch) {
      double cen = 0;
      for (std::uint32_t w : c.faces.row(f)) cen += pos[w * 3 + ch];
      EXPECT_NEAR(got[(c.num_vertices + c.num_edges() + f) * 3 + ch], cen / c.faces.size(f), 1e-15);
    }
}
