// Exact inner products of subdivision scaling functions (paper 004 sec. 5; core/analysis/inner_products.h).
#include "core/analysis/inner_products.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "core/base/errors.h"
#include "core/schemes/registry.h"

namespace {

using namespace sublift::ip;
using sublift::Scheme;
using sublift::scheme_name;

// ---------------------------------------------------------------------------------------------
// An independent subdivision of a coefficient grid on the triangular lattice (the schemes'
// stencils written out again, not the library's masks), for numerical integration.

struct Grid {
  int n = 0;  // indices (i, j) in [-n, n]^2
  std::vector<double> v;
  double at(int i, int j) const {
    if (i < -n || i > n || j < -n || j > n) return 0.0;
    return v[std::size_t(i + n) * std::size_t(2 * n + 1) + std::size_t(j + n)];
  }
  double& ref(int i, int j) { return v[std::size_t(i + n) * std::size_t(2 * n + 1) + std::size_t(j + n)]; }
};

struct P2 {
  int i, j;
};
P2 rot(P2 p) { return {-p.j, p.i + p.j}; }     // +60 degrees
P2 rotinv(P2 p) { return {p.i + p.j, -p.i}; }  // -60 degrees
P2 plus(P2 a, P2 b) { return {a.i + b.i, a.j + b.j}; }

Grid subdivide(const Grid& g, Scheme s) {
  Grid f;
  f.n = 2 * g.n;
  f.v.assign(std::size_t(2 * f.n + 1) * std::size_t(2 * f.n + 1), 0.0);
  auto c = [&](P2 p) { return g.at(p.i, p.j); };
  for (int p = -f.n; p <= f.n; ++p)
    for (int q = -f.n; q <= f.n; ++q) {
      double val = 0;
      if ((p & 1) == 0 && (q & 1) == 0) {
        const P2 a{p / 2, q / 2};
        if (s == Scheme::Loop) {
          double nb = 0;
          P2 e{1, 0};
          for (int r = 0; r < 6; ++r, e = rot(e)) nb += c(plus(a, e));
          val = 5.0 / 8 * c(a) + nb / 16;
        } else {
          val = c(a);
        }
      } else {
        // The coarse edge (a, a + u) whose midpoint is fine (p, q).
        P2 a, u;
        if ((p & 1) && !(q & 1)) a = {(p - 1) / 2, q / 2}, u = {1, 0};
        else if (!(p & 1)) a = {p / 2, (q - 1) / 2}, u = {0, 1};
        else a = {(p + 1) / 2, (q - 1) / 2}, u = {-1, 1};
        const P2 b = plus(a, u);
        const P2 wc = plus(a, rot(u)), wd = plus(a, rotinv(u));  // the two wing tips
        switch (s) {
          case Scheme::LinearTri: val = 0.5 * (c(a) + c(b)); break;
          case Scheme::Loop: val = 3.0 / 8 * (c(a) + c(b)) + 1.0 / 8 * (c(wc) + c(wd)); break;
          case Scheme::Butterfly: {
            // Outer points: across the edges a-wc, b-wc, a-wd, b-wd.
            const double outer = c(plus(a, rot(rot(u)))) + c(plus(b, rot(u))) + c(plus(a, rotinv(rotinv(u)))) +
                                 c(plus(b, rotinv(u)));
            val = 0.5 * (c(a) + c(b)) + 1.0 / 8 * (c(wc) + c(wd)) - 1.0 / 16 * outer;
            break;
          }
          default: ADD_FAILURE() << "not a triangle scheme"; break;
        }
      }
      f.ref(p, q) = val;
    }
  return f;
}

// Integral of the product of the piecewise-linear interpolants of phi_0 and phi_d at level K
// (grid g holds phi_0's level-K coefficients; level-K triangles have area A / 4^K). Per
// triangle, integral of l_a l_b = A_t/12 (1 + delta_ab): summed, the mass matrix has A_t on the
// diagonal and A_t / 6 between neighbours.
double pl_inner_product(const Grid& g, const std::vector<double>& h, int K, Offset d, double A) {
  const int si = d.i * (1 << K), sj = d.j * (1 << K);
  const double At = A / std::pow(4.0, K);
  double sum = 0;
  for (int i = -g.n; i <= g.n; ++i) {
    const int i2 = i - si;
    if (i2 < -g.n || i2 > g.n) continue;
    for (int j = -g.n; j <= g.n; ++j) {
      const int j2 = j - sj;
      if (j2 < -g.n || j2 > g.n) continue;
      sum += g.at(i, j) * h[std::size_t(i2 + g.n) * std::size_t(2 * g.n + 1) + std::size_t(j2 + g.n)];
    }
  }
  return At * sum;
}

std::vector<double> mass_smoothed(const Grid& g) {
  std::vector<double> h(g.v.size());
  for (int i = -g.n; i <= g.n; ++i)
    for (int j = -g.n; j <= g.n; ++j) {
      double nb = 0;
      P2 e{1, 0};
      for (int r = 0; r < 6; ++r, e = rot(e)) nb += g.at(i + e.i, j + e.j);
      h[std::size_t(i + g.n) * std::size_t(2 * g.n + 1) + std::size_t(j + g.n)] = g.at(i, j) + nb / 6;
    }
  return h;
}

// I(d) by numerical integration at levels K = k0, k0+1, k0+2 and two Richardson steps (ratios
// 4 and 16: the error expands in even powers of 2^-K for these symmetric functions).
std::vector<double> integrate(Scheme s, const std::vector<Offset>& ds, int k0, bool verbose) {
  Grid g;
  g.n = 4;  // support of phi_0 lies in the hexagon of radius 3
  g.v.assign(81, 0.0);
  g.ref(0, 0) = 1.0;
  std::vector<std::vector<double>> J;
  for (int K = 1; K <= k0 + 2; ++K) {
    g = subdivide(g, s);
    if (K < k0) continue;
    const auto h = mass_smoothed(g);
    std::vector<double> row;
    for (Offset d : ds) row.push_back(pl_inner_product(g, h, K, d, 1.0));
    J.push_back(row);
  }
  std::vector<double> out;
  for (std::size_t m = 0; m < ds.size(); ++m) {
    const double r1a = (4 * J[1][m] - J[0][m]) / 3, r1b = (4 * J[2][m] - J[1][m]) / 3;
    const double r2 = (16 * r1b - r1a) / 15;
    if (verbose)
      std::printf("  %s d=(%d,%d): J %.12f %.12f %.12f  R1 %.12f %.12f  R2 %.12f\n", scheme_name(s).c_str(), ds[m].i,
                  ds[m].j, J[0][m], J[1][m], J[2][m], r1a, r1b, r2);
    out.push_back(r2);
  }
  return out;
}

bool verbose() { return std::getenv("SUBLIFT_IP_VERBOSE") != nullptr; }

// One representative per symmetry orbit.
std::vector<Offset> orbit_reps(const LatticeInnerProducts& ip) {
  std::vector<Offset> reps;
  const auto group = lattice_symmetries(ip.dim);
  for (Offset d : ip.offsets) {
    bool seen = false;
    for (const auto& g : group)
      for (Offset r : reps) seen = seen || apply(g, d) == r;
    if (!seen) reps.push_back(d);
  }
  return reps;
}

// ---------------------------------------------------------------------------------------------

TEST(InnerProducts, PaperOneDimensionalHatExampleAsHomogeneousSystem) {
  // 004 sec. 5.2: x1 = <phi_i, phi_i>, x2 = <phi_i, phi_i+1>; x1 = 3/4 x1 + x2,
  // x2 = 1/8 x1 + 1/2 x2; scale x1 := 1 gives x2 = 1/4.
  HomogeneousSystem sys;
  sys.unknowns = 2;
  sys.T = {{0, 0, 0.75}, {0, 1, 1.0}, {1, 0, 0.125}, {1, 1, 0.5}};
  sys.normal = {1.0, 0.0};
  sys.total = 1.0;
  const auto sol = solve_homogeneous(sys);
  EXPECT_TRUE(sol.simple);
  EXPECT_NEAR(sol.values[0], 1.0, 1e-15);
  EXPECT_NEAR(sol.values[1], 0.25, 1e-15);
  EXPECT_LT(sol.residual, 1e-15);
}

TEST(InnerProducts, PaperOneDimensionalHatExampleFromLatticeSolver) {
  // The same example built from the refinement mask 1/2, 1, 1/2 (004 eq. 12), with and without
  // the d -> -d symmetry: x2 = x1 / 4, and the exact values 2h/3, h/6.
  for (bool sym : {true, false}) {
    for (double h : {1.0, 0.3}) {
      const auto ip = lattice_inner_products(curve_hat_mask(), {h, sym});
      EXPECT_NEAR(ip.at({1, 0}), ip.at({0, 0}) / 4, 1e-15);
      EXPECT_NEAR(ip.at({0, 0}), 2.0 / 3 * h, 1e-15);
      EXPECT_NEAR(ip.at({1, 0}), h / 6, 1e-15);
      EXPECT_NEAR(ip.at({-1, 0}), h / 6, 1e-15);
      EXPECT_NEAR(ip.at({2, 0}), 0.0, 1e-15);
      EXPECT_EQ(ip.at({5, 0}), 0.0);
      EXPECT_TRUE(ip.diagnostics.simple);
      EXPECT_EQ(ip.unknowns, sym ? 3u : 5u);  // offsets -2..2: the touching pair I(2) = 0 too
    }
  }
}

TEST(InnerProducts, SolverRejectsMissingOrMultipleEigenvalueOne) {
  HomogeneousSystem none;
  none.unknowns = 2;
  none.T = {{0, 0, 0.5}, {1, 1, 0.25}};
  none.normal = {1, 1};
  EXPECT_THROW(solve_homogeneous(none), sublift::Error);
  HomogeneousSystem twice;
  twice.unknowns = 2;
  twice.T = {{0, 0, 1.0}, {1, 1, 1.0}};
  twice.normal = {1, 1};
  const auto sol = solve_homogeneous(twice);
  EXPECT_FALSE(sol.simple);
  EXPECT_EQ(sol.nullity, 2u);
}

TEST(InnerProducts, MasksSumRulesAndSymmetry) {
  for (auto s : {Scheme::LinearTri, Scheme::Butterfly, Scheme::Loop}) {
    const auto m = regular_mask(s);
    // Each coset of 2Z^2 sums to 1 (every fine rule is an affine combination), total 4.
    double coset[2][2] = {{0, 0}, {0, 0}};
    for (const auto& [k, w] : m.coefficients) coset[k.i & 1][k.j & 1] += w;
    for (auto& row : coset)
      for (double v : row) EXPECT_NEAR(v, 1.0, 1e-15) << scheme_name(s);
    for (const auto& g : lattice_symmetries(2))
      for (const auto& [k, w] : m.coefficients) {
        double found = 0;
        for (const auto& [k2, w2] : m.coefficients)
          if (k2 == apply(g, k)) found = w2;
        EXPECT_EQ(found, w) << scheme_name(s);
      }
  }
  EXPECT_EQ(regular_mask(Scheme::LinearTri).coefficients.size(), 7u);
  EXPECT_EQ(regular_mask(Scheme::Loop).coefficients.size(), 19u);
  EXPECT_EQ(regular_mask(Scheme::Butterfly).coefficients.size(), 25u);
  EXPECT_EQ(lattice_symmetries(2).size(), 12u);
}

TEST(InnerProducts, ButterflyMaskReproducesCubics) {
  // The butterfly scheme reproduces cubic polynomials (in Cartesian coordinates): refining the
  // samples of a cubic by the mask gives its samples at the fine points. Checks the stencil's
  // geometry (a wrong outer point breaks it).
  const auto m = regular_mask(Scheme::Butterfly);
  auto cubic = [](double u, double v) {
    const double x = u + 0.5 * v, y = std::sqrt(3.0) / 2 * v;
    return 1 + 2 * x - y + x * y - 3 * x * x * y + 0.5 * y * y * y + x * x * x - 2 * y * y;
  };
  for (int p = -3; p <= 3; ++p)
    for (int q = -3; q <= 3; ++q) {
      // fine value at (p, q) = sum_i a_{(p,q) - 2i} coarse_i
      double v = 0;
      for (const auto& [k, w] : m.coefficients) {
        const int di = p - k.i, dj = q - k.j;
        if ((di & 1) || (dj & 1)) continue;
        v += w * cubic(di / 2, dj / 2);
      }
      EXPECT_NEAR(v, cubic(p / 2.0, q / 2.0), 1e-11) << p << "," << q;
    }
}

TEST(InnerProducts, PolyhedralClosedForm) {
  for (int n : {3, 4, 5, 6, 7, 12}) {
    const auto p = polyhedral_inner_products(n, 0.7);
    EXPECT_DOUBLE_EQ(p.self, n * 0.7 / 6);
    EXPECT_DOUBLE_EQ(p.neighbour, 0.7 / 6);
    // Row sum = integral of the hat = n A / 3.
    EXPECT_NEAR(p.self + n * p.neighbour, n * 0.7 / 3, 1e-15);
  }
  // Tetrahedron (004 Figure 2) with unit total area: A = 1/4, I0 = (1/24) [3 1 1 1; ...]
  // = (1/8) [1 1/3 1/3 1/3; ...] - the Figure 4 mask (3 | 1 1 1) divided by 3, times 1/8.
  const std::vector<std::array<std::uint32_t, 3>> tet{{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
  const auto I0 = polyhedral_matrix(4, tet, 0.25);
  double total = 0;
  for (std::size_t a = 0; a < 4; ++a)
    for (std::size_t b = 0; b < 4; ++b) {
      EXPECT_NEAR(I0[a * 4 + b], a == b ? 1.0 / 8 : 1.0 / 24, 1e-16);
      total += I0[a * 4 + b];
    }
  EXPECT_NEAR(total, 1.0, 1e-15);
}

TEST(InnerProducts, LinearLatticeEqualsClosedForm) {
  for (bool sym : {true, false}) {
    const double A = 0.37;
    const auto ip = lattice_inner_products(regular_mask(Scheme::LinearTri), {A, sym});
    const auto cf = polyhedral_inner_products(6, A);
    EXPECT_NEAR(ip.at({0, 0}), cf.self, 1e-14);
    Offset e{1, 0};
    for (int r = 0; r < 6; ++r, e = rotate60(e)) EXPECT_NEAR(ip.at(e), cf.neighbour, 1e-14);
    for (std::size_t u = 0; u < ip.offsets.size(); ++u) {
      const Offset d = ip.offsets[u];
      const int hexdist = std::max({std::abs(d.i), std::abs(d.j), std::abs(d.i + d.j)});
      if (hexdist >= 2) {
        EXPECT_NEAR(ip.values[u], 0.0, 1e-14) << d.i << "," << d.j;
      }
    }
    EXPECT_TRUE(ip.diagnostics.simple);
  }
}

TEST(InnerProducts, PartitionOfUnityAndSymmetry) {
  for (auto s : {Scheme::LinearTri, Scheme::Butterfly, Scheme::Loop}) {
    // Solve without the symmetry reduction, then check the symmetries hold.
    const auto ip = lattice_inner_products(regular_mask(s), {1.0, false});
    EXPECT_TRUE(ip.diagnostics.simple) << scheme_name(s);
    EXPECT_GT(ip.diagnostics.sigma_next, 1e-3) << scheme_name(s);
    EXPECT_LT(ip.diagnostics.residual, 1e-14) << scheme_name(s);
    double sum = 0;
    for (double v : ip.values) sum += v;
    EXPECT_NEAR(sum, 2.0, 1e-13) << scheme_name(s);  // integral of phi = 2A
    for (Offset d : ip.offsets) {
      EXPECT_NEAR(ip.at(d), ip.at({-d.i, -d.j}), 1e-14) << scheme_name(s);
      EXPECT_NEAR(ip.at(d), ip.at(rotate60(d)), 1e-14) << scheme_name(s);
      EXPECT_NEAR(ip.at(d), ip.at({d.j, d.i}), 1e-14) << scheme_name(s);
    }
    // The symmetric (orbit) solve gives the same numbers.
    const auto ips = lattice_inner_products(regular_mask(s));
    EXPECT_LT(ips.unknowns, ip.unknowns);
    for (Offset d : ip.offsets) EXPECT_NEAR(ip.at(d), ips.at(d), 1e-14) << scheme_name(s);
  }
}

void check_against_integration(Scheme s, int k0) {
  const auto ip = lattice_inner_products(regular_mask(s));
  const auto reps = orbit_reps(ip);
  const auto num = integrate(s, reps, k0, verbose());
  for (std::size_t m = 0; m < reps.size(); ++m) {
    EXPECT_NEAR(ip.at(reps[m]), num[m], 1e-6) << scheme_name(s) << " d=(" << reps[m].i << "," << reps[m].j << ")";
    if (verbose())
      std::printf("%s I(%d,%d) = %.17g  numeric %.12f  diff %.2e\n", scheme_name(s).c_str(), reps[m].i, reps[m].j,
                  ip.at(reps[m]), num[m], ip.at(reps[m]) - num[m]);
  }
  if (verbose())
    std::printf("%s: %zu offsets, %zu orbit unknowns, sigma_next %.3e, subdominant |lambda| %.6f\n", scheme_name(s).c_str(),
                ip.offsets.size(), ip.unknowns, ip.diagnostics.sigma_next, ip.diagnostics.subdominant);
}

TEST(InnerProducts, LoopMatchesNumericalIntegration) { check_against_integration(Scheme::Loop, 4); }
TEST(InnerProducts, ButterflyMatchesNumericalIntegration) { check_against_integration(Scheme::Butterfly, 4); }
TEST(InnerProducts, LinearMatchesNumericalIntegration) { check_against_integration(Scheme::LinearTri, 1); }
// Heavier variant (levels 6, 7, 8; about 16x the work): run with --gtest_also_run_disabled_tests.
TEST(InnerProducts, DISABLED_DeepNumericalIntegration) {
  check_against_integration(Scheme::Loop, 6);
  check_against_integration(Scheme::Butterfly, 6);
}

TEST(InnerProducts, CacheSolvesOncePerConfiguration) {
  const std::size_t before = inner_product_cache_solves();
  const auto& a = cached_inner_products({Scheme::Loop, 6});
  const std::size_t after = inner_product_cache_solves();
  EXPECT_LE(after, before + 1);
  const auto& b = cached_inner_products({Scheme::Loop, 6});
  EXPECT_EQ(&a, &b);
  EXPECT_EQ(inner_product_cache_solves(), after);
  EXPECT_NEAR(a.at({0, 0}), lattice_inner_products(regular_mask(Scheme::Loop)).at({0, 0}), 0.0);
  EXPECT_THROW(cached_inner_products({Scheme::Loop, 5}), sublift::Error);
}

}  // namespace
