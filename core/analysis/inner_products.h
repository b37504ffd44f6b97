#pragma once
// Exact inner products of subdivision scaling functions (paper 004, Lounsbery, DeRose & Warren,
// sec. 5), GL-free. docs/inner_products.md has the derivations and the numbers.
//
// Inner product (004 sec. 5.1): <f, g> = integral over M0 of f g, every triangle of M0 with the
// same area A (a level-j triangle has A / 4^j). In 1-D every interval has the same length h.
//
// Three layers:
//   solve_homogeneous         the general solver: unknowns x with x = T x (004 eq. 11 after the
//                             self-similarity substitution) plus one normalisation row
//                             sum_i w_i x_i = total; reports whether eigenvalue 1 is simple.
//   lattice_inner_products    the regular (translation-invariant) case on Z (1-D, factor 1/2) or
//                             on the regular triangular lattice (2-D, factor 1/4):
//                             I(d) = <phi_0, phi_d> = s sum_{k,l} a_k a_l I(2d + l - k),
//                             normalised by sum_d I(d) = integral of phi = vertex cell area.
//   polyhedral_inner_products the closed form for hat functions (004 Figure 4).
// plus the masks of the three regular schemes and a per-configuration cache.
#include <array>
#include <compare>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/schemes/scheme.h"

namespace sublift::ip {

// ---------------------------------------------------------------------------------------------
// General solver

/// The homogeneous system x = T x with one normalisation row sum_i normal[i] x_i = total.
struct HomogeneousSystem {
  struct Entry {
    std::size_t row = 0, col = 0;
    double value = 0;
  };
  std::size_t unknowns = 0;
  std::vector<Entry> T;        ///< entries of T; repeated (row, col) pairs add up
  std::vector<double> normal;  ///< normalisation weights, size `unknowns`
  double total = 1.0;          ///< right-hand side of the normalisation row
};

struct HomogeneousSolution {
  std::vector<double> values;  ///< the eigenvector of T for eigenvalue 1, normalised
  std::size_t nullity = 0;     ///< singular values of (T - Id) below tol: 1 when simple
  bool simple = false;         ///< nullity == 1 (eigenvalue 1 geometrically simple)
  double sigma_min = 0;        ///< smallest singular value of (T - Id)
  double sigma_next = 0;       ///< second smallest (the gap that makes the solution unique)
  double residual = 0;         ///< max_i |(T x - x)_i| of the returned values
  double subdominant = 0;      ///< largest |lambda| of T over eigenvalues other than the one at 1
};

/// Solves x = T x, sum normal_i x_i = total (dense Eigen; sizes up to a few hundred).
/// Throws sublift::Error when there is no eigenvalue 1 (nullity 0) or the normalisation row is
/// orthogonal to the null space. When eigenvalue 1 is not simple one solution (column-pivoted QR
/// of the augmented system) is returned with simple == false: callers decide
/// (lattice_inner_products throws).
HomogeneousSolution solve_homogeneous(const HomogeneousSystem& sys, double tol = 1e-9);

// ---------------------------------------------------------------------------------------------
// Regular lattices

/// Integer lattice offset. 1-D: (i, 0). 2-D: i e1 + j e2 with |e1| = |e2| = 1 at 60 degrees,
/// e1 = (1, 0), e2 = (1/2, sqrt(3)/2); the six neighbours of 0 are (1,0) (0,1) (-1,1) (-1,0)
/// (0,-1) (1,-1); triangles {(i,j),(i+1,j),(i,j+1)} and {(i+1,j),(i,j+1),(i+1,j+1)}.
struct Offset {
  int i = 0, j = 0;
  auto operator<=>(const Offset&) const = default;
};

/// phi(x) = sum_k a_k phi(2x - k): `coefficients` are the a_k (k in lattice coordinates).
struct LatticeMask {
  int dim = 2;  ///< 1 (curves, area factor 1/2) or 2 (triangular lattice, area factor 1/4)
  std::vector<std::pair<Offset, double>> coefficients;
};


/// 1-D hat: a_0 = 1, a_{+-1} = 1/2 (004 eq. 12).
LatticeMask curve_hat_mask();
/// The refinement mask of the scheme on the regular (valence-6) triangular lattice, converted
/// from its subdivision stencils (docs/inner_products.md, "Masks").
LatticeMask regular_mask(Scheme s);

/// 60-degree rotation of the 2-D lattice: e1 -> e2, e2 -> e2 - e1, i.e. (i, j) -> (-j, i + j).
Offset rotate60(Offset d);
/// The 12 symmetries of the triangular lattice (2-D) or {d, -d} (1-D).
std::vector<std::array<int, 4>> lattice_symmetries(int dim);
Offset apply(const std::array<int, 4>& m, Offset d);

struct LatticeInnerProducts {
  int dim = 2;
  double element = 1.0;         ///< triangle area A (2-D) or interval length h (1-D)
  double cell = 2.0;            ///< integral of phi = area per vertex: 2A (2-D), h (1-D)
  std::vector<Offset> offsets;  ///< all d whose I(d) may be nonzero (sorted)
  std::vector<double> values;   ///< I(d), aligned with offsets
  std::size_t unknowns = 0;     ///< size of the solved system (orbits when symmetry is used)
  HomogeneousSolution diagnostics;

  /// I(d); 0 outside `offsets`.
  double at(Offset d) const;
};

struct LatticeOptions {
  double element = 1.0;       ///< A (2-D) or h (1-D)
  bool use_symmetry = true;   ///< one unknown per symmetry orbit (the mask must be symmetric)
};

/// Solves for I(d) = <phi_0, phi_d>. Throws sublift::Error when eigenvalue 1 is not simple.
LatticeInnerProducts lattice_inner_products(const LatticeMask& mask, const LatticeOptions& opt = {});

// ---------------------------------------------------------------------------------------------
// Polyhedral (hat functions) in closed form

struct PolyhedralInnerProducts {
  double self = 0;       ///< <phi_i, phi_i> = n A / 6
  double neighbour = 0;  ///< <phi_i, phi_k> = A / 6 for an edge shared by two triangles
};
/// Hat functions on equal-area triangles: mask n at the centre, 1 at each neighbour, times A/6.
/// (A boundary edge, in one triangle only, would give A/12; a boundary vertex with f faces f A/6.)
PolyhedralInnerProducts polyhedral_inner_products(int valence, double triangle_area);

/// The full matrix I0 (row-major, nv x nv) of the hat functions of a triangle mesh whose
/// triangles all have area `triangle_area` (each triangle adds A/12 (1 + delta_ik)).
std::vector<double> polyhedral_matrix(std::size_t nv, const std::vector<std::array<std::uint32_t, 3>>& tris,
                                      double triangle_area);

// ---------------------------------------------------------------------------------------------
// Cache

/// A local configuration: the scheme and the valence of the (one) vertex it is built around.
/// Only valence 6 (the regular lattice) exists so far; extraordinary valences come with issue 8.
struct ConfigKey {
  Scheme scheme = Scheme::LinearTri;
  int valence = 6;
  auto operator<=>(const ConfigKey&) const = default;
};

/// Inner products at unit triangle area A = 1 (scale linearly for other A), computed on first
/// use and kept for the process (thread-safe). Throws sublift::Error for valence != 6.
const LatticeInnerProducts& cached_inner_products(const ConfigKey& key);
/// Number of configurations solved so far (tests check that repeated queries do not re-solve).
std::size_t inner_product_cache_solves();

}  // namespace sublift::ip
