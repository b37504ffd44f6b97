// The triangle-mesh schemes of paper 004 (linear-tri, butterfly, loop) in the engine: level
// counts, perfect reconstruction (float and integer), zero details = pure subdivision,
// interpolation, orthogonality of the synthesised wavelets checked by numerical integration,
// exact L2 norms, projects.
#include <gtest/gtest.h>

#include "tests/test_shapes.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "core/complex/complex_build.h"
#include "core/base/errors.h"
#include "core/multires/hierarchy.h"
#include "core/io/project/project_io.h"
#include "core/complex/refine_tri.h"
#include "core/io/lattice/shape_io.h"
#include "core/schemes/tri/tri_rules.h"

using namespace sublift;

namespace {

using sublift::testing::max_abs_diff;
using sublift::testing::random_coefficients;

struct Base {
  std::string name;
  Complex c;
  std::vector<double> xyz;
};

Base from_lists(std::string name, std::vector<double> xyz, const std::vector<std::uint32_t>& tris,
                const FeatureTags& tags = {}) {
  Csr f;
  for (std::size_t i = 0; i < tris.size(); i += 3) {
    f.items.insert(f.items.end(), tris.begin() + static_cast<std::ptrdiff_t>(i), tris.begin() + static_cast<std::ptrdiff_t>(i) + 3);
    f.offsets.push_back(static_cast<std::uint32_t>(f.items.size()));
  }
  return {std::move(name), complex_from_polygons(static_cast<std::uint32_t>(xyz.size() / 3), f, tags), std::move(xyz)};
}

Base octahedron() {
  return from_lists("octahedron", {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1},
                    {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5});
}

// An open 4 x 3 grid of squares cut into triangles (boundary, valences 2..6), with a bump.
Base open_grid() {
  std::vector<double> xyz;
  std::vector<std::uint32_t> t;
  const int w = 4, h = 3;
  for (int j = 0; j <= h; ++j)
    for (int i = 0; i <= w; ++i) xyz.insert(xyz.end(), {double(i), double(j), 0.3 * std::sin(i + 2.0 * j)});
  const auto v = [&](int i, int j) { return static_cast<std::uint32_t>(i + (w + 1) * j); };
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) t.insert(t.end(), {v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j), v(i + 1, j + 1), v(i, j + 1)});
  return from_lists("open_grid", xyz, t);
}

// The octahedron with a crease loop around its equator.
Base creased_octahedron() {
  Base b = octahedron();
  FeatureTags tags;
  tags.crease_edges = {{0, 2}, {2, 1}, {1, 3}, {3, 0}};
  Csr f = b.c.faces;
  b.c = complex_from_polygons(6, f, tags);
  b.name = "creased_octahedron";
  return b;
}

std::vector<Base> bases() {
  std::vector<Base> out{octahedron(), open_grid(), creased_octahedron()};
  const std::filesystem::path ico = std::filesystem::path(SUBLIFT_SHARED_DATA) / "control_meshes/opensubdiv_shapes/loop_icosahedron.obj";
  if (std::filesystem::exists(ico)) {
    Shape s = read_shape(ico.string());
    out.push_back({"loop_icosahedron", std::move(s.base), std::move(s.positions)});
  }
  return out;
}

const Scheme kTri[] = {Scheme::LinearTri, Scheme::Butterfly, Scheme::Loop};

}  // namespace

TEST(TriHierarchy, NamesCountsAndRefusals) {
  EXPECT_EQ(parse_scheme("linear-tri"), Scheme::LinearTri);
  EXPECT_EQ(parse_scheme("butterfly"), Scheme::Butterfly);
  EXPECT_EQ(parse_scheme("loop"), Scheme::Loop);
  for (Scheme s : kTri) EXPECT_EQ(parse_scheme(scheme_name(s)), s);
  const Base o = octahedron();
  const Hierarchy h = make_hierarchy(o.c, 3, Scheme::Butterfly, 3);
  const std::vector<double> predicted = predicted_level_counts(o.c, 3, Scheme::Butterfly);
  for (int l = 0; l <= 3; ++l) {
    EXPECT_EQ(double(h.num_vertices(l)), predicted[static_cast<std::size_t>(l)]);
    EXPECT_EQ(h.num_vertices(l), 4u * (1u << (2 * l)) + 2u);  // a sphere: V = 2 + F / 2, F = 8 * 4^l
  }
  EXPECT_EQ(h.wavelet_norms.size(), h.num_vertices(3) - 6u);
  // A quad is refused with its face named; Loop has no integer mode.
  Csr quad;
  quad.items = {0, 1, 2, 3};
  quad.offsets = {0, 4};
  try {
    (void)make_hierarchy(complex_from_polygons(4, quad), 1, Scheme::Loop, 3);
    FAIL() << "a quad was accepted";
  } catch (const TopologyError& e) {
    EXPECT_NE(std::string(e.what()).find("face 0"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)make_hierarchy(o.c, 1, Scheme::Loop, 3, /*integer=*/true), Error);
}

// Zero details: synthesis is the scheme's subdivision (whose stencils tri_rules_test compares
// with OpenMesh and OpenSubdiv), and the interpolating schemes keep the old vertices bit for bit.
TEST(TriHierarchy, ZeroDetailsAreThePureSubdivision) {
  for (const Base& b : bases())
    for (Scheme s : kTri) {
      SCOPED_TRACE(b.name + " " + scheme_name(s));
      const int J = 3;
      Hierarchy h = make_hierarchy(b.c, J, s, 3);
      set_base(h, b.xyz);
      std::vector<double> x = b.xyz;
      Complex level = b.c;
      for (int l = 1; l <= J; ++l) {
        const TriStencils st = build_tri_stencils(level, s);
        std::vector<double> fine = subdivide_tri(st, x.data(), level.num_vertices, 3);
        const std::vector<double> ours = synthesize(h, l);
        EXPECT_LT(max_abs_diff(ours, fine), 1e-14) << "level " << l;
        if (scheme_interpolates(s)) {
          for (std::size_t i = 0; i < x.size(); ++i) ASSERT_EQ(ours[i], x[i]) << "level " << l << " value " << i;
        }
        x = std::move(fine);
        level = refine_tri(level);
      }
      // Analysing a pure subdivision gives back the base and zero wavelets.
      Hierarchy g = make_hierarchy(b.c, J, s, 3);
      analyze(g, x);
      const double tol = s == Scheme::Loop ? 1e-9 : 1e-13;
      for (std::size_t i = 0; i < b.xyz.size(); ++i) EXPECT_NEAR(g.coeffs[i], b.xyz[i], tol);
      for (std::size_t i = b.xyz.size(); i < g.coeffs.size(); ++i) ASSERT_NEAR(g.coeffs[i], 0.0, tol) << i;
    }
}

TEST(TriHierarchy, PerfectReconstruction) {
  for (const Base& b : bases())
    for (Scheme s : kTri)
      for (int J : {1, 3}) {
        SCOPED_TRACE(b.name + " " + scheme_name(s) + " J=" + std::to_string(J));
        Hierarchy h = make_hierarchy(b.c, J, s, 3);
        const std::vector<double> fine = random_coefficients(h.coeffs.size(), 7u + static_cast<unsigned>(J), false);
        analyze(h, fine);
        EXPECT_LT(max_abs_diff(synthesize(h, J), fine), s == Scheme::Loop ? 1e-9 : 1e-12);
        if (s == Scheme::Loop) continue;
        Hierarchy hi = make_hierarchy(b.c, J, s, 3, /*integer=*/true);
        const std::vector<double> ints = random_coefficients(hi.coeffs.size(), 11u, true);
        analyze(hi, ints);
        for (double v : hi.coeffs) ASSERT_EQ(v, std::round(v));
        const std::vector<double> back = synthesize(hi, J);
        for (std::size_t i = 0; i < ints.size(); ++i) ASSERT_EQ(back[i], ints[i]) << i;
      }
}

// The synthesised wavelet psi_m (a unit coefficient on m) is orthogonal to the level-j scaling
// functions of its 2-disc, checked independently of the inner-product code: both are
// subdivided K more levels and their product integrated as piecewise-linear functions (error
// O(4^-K)), against the size of <phi, phi>.
TEST(TriHierarchy, SynthesisedWaveletsAreOrthogonalToTheirDisc) {
  const Base o = octahedron();
  for (Scheme s : kTri) {
    SCOPED_TRACE(scheme_name(s));
    const int j = 1, K = 5;
    Hierarchy h = make_hierarchy(o.c, j + 1 + K, s, 1);
    const std::uint32_t nj = h.num_vertices(j), nf = h.num_vertices(j + 1 + K);
    // Fine values of a coefficient vector given on the first n vertices of the layout.
    const auto fine_of = [&](std::uint32_t index) {
      std::fill(h.coeffs.begin(), h.coeffs.end(), 0.0);
      h.coeffs[index] = 1.0;
      return synthesize(h, j + 1 + K);
    };
    // A level-j scaling function: synthesis from level j of a unit control point (coefficients
    // of level j's control net are not stored directly; analyse a unit net instead).
    const auto scaling = [&](std::uint32_t v) {
      Hierarchy g = make_hierarchy(o.c, j, s, 1);
      std::vector<double> net(nj, 0.0);
      net[v] = 1.0;
      analyze(g, net);
      std::fill(h.coeffs.begin(), h.coeffs.end(), 0.0);
      std::copy(g.coeffs.begin(), g.coeffs.end(), h.coeffs.begin());
      return synthesize(h, j + 1 + K);
    };
    const Complex& fine = h.levels.back();
    const double area = std::pow(0.25, j + 1 + K);
    const auto integrate = [&](const std::vector<double>& u, const std::vector<double>& w) {
      double sum = 0;
      for (std::uint32_t f = 0; f < fine.num_faces(); ++f) {
        double uu = 0, su = 0, sw = 0;
        for (std::uint32_t v : fine.faces.row(f)) {
          uu += u[v] * w[v];
          su += u[v];
          sw += w[v];
        }
        sum += area / 12.0 * (uu + su * sw);
      }
      return sum;
    };
    (void)nf;
    const std::uint32_t e = 5, m = nj + e;  // the wavelet of level-j edge 5
    const std::vector<double> psi = fine_of(m);
    // Its 2-disc: level-j vertices within 2 edges of the edge's ends.
    const Complex& lj = h.levels[j];
    std::vector<int> dist(nj, 99);
    dist[lj.edge_verts[2 * e]] = dist[lj.edge_verts[2 * e + 1]] = 0;
    for (int k = 0; k < 2; ++k)
      for (std::uint32_t x = 0; x < lj.num_edges(); ++x) {
        const std::uint32_t a = lj.edge_verts[2 * x], c = lj.edge_verts[2 * x + 1];
        if (dist[a] == k && dist[c] > k + 1) dist[c] = k + 1;
        if (dist[c] == k && dist[a] > k + 1) dist[a] = k + 1;
      }
    double worst = 0, scale = 0, outside = 0;
    for (std::uint32_t v = 0; v < nj; ++v) {
      const std::vector<double> phi = scaling(v);
      if (dist[v] > 2) {
        outside = std::max(outside, std::abs(integrate(psi, phi)));
        continue;
      }
      worst = std::max(worst, std::abs(integrate(psi, phi)));
      scale = std::max(scale, integrate(phi, phi));
    }
    // Hat functions are piecewise linear on level j+1, so their integration is exact; Loop and
    // butterfly carry the O(4^-K) error of the piecewise-linear quadrature.
    const double tol = s == Scheme::LinearTri ? 1e-13 : 5e-5;
    EXPECT_LT(worst, tol * scale) << "worst |<psi, phi>| " << worst << " vs <phi, phi> " << scale;
    // Outside the disc nothing forces it: the products there are far from zero, so the check
    // above can fail.
    EXPECT_GT(outside, 20 * tol * scale) << outside;
    const double norm2 = integrate(psi, psi);
    EXPECT_NEAR(std::sqrt(norm2), h.wavelet_norms[m - h.num_vertices(0)], 2e-2 * std::sqrt(norm2));
  }
}

TEST(TriHierarchy, ProjectRoundTrip) {
  const Base b = open_grid();
  Hierarchy h = make_hierarchy(b.c, 2, Scheme::Butterfly, 3, false, 0, 3);
  analyze(h, random_coefficients(h.coeffs.size(), 3, false));
  const std::string path = (std::filesystem::temp_directory_path() / "sublift_tri_project.sublift").string();
  write_project(path, h);
  const Hierarchy back = read_project(path);
  EXPECT_EQ(back.scheme, Scheme::Butterfly);
  EXPECT_EQ(back.disc, 3);
  EXPECT_EQ(back.coeffs, h.coeffs);
  EXPECT_EQ(synthesize(back, 2), synthesize(h, 2));
  std::filesystem::remove(path);
}
