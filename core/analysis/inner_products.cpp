#include "core/analysis/inner_products.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <sstream>

#include "core/base/errors.h"
#include "core/schemes/registry.h"

namespace sublift::ip {
namespace {

using Stencil = std::vector<std::pair<Offset, double>>;

Offset add(Offset a, Offset b) { return {a.i + b.i, a.j + b.j}; }
Offset sub(Offset a, Offset b) { return {a.i - b.i, a.j - b.j}; }
Offset scale(int s, Offset a) { return {s * a.i, s * a.j}; }

// Stencils of the schemes on the regular lattice (docs/inner_products.md, "Masks").
// Edge stencil for the coarse edge a = (0,0), b = (1,0) (direction e1). Its wing vertices are
// c = (0,1) (triangle a b c above the edge) and d = (1,-1) (below); the butterfly's outer
// vertices sit across the four other edges of those two triangles: across a-c (-1,1), across
// b-c (1,1), across a-d (0,-1), across b-d (2,-1).
Stencil edge_stencil(Scheme s) {
  switch (s) {
    case Scheme::LinearTri:
      return {{{0, 0}, 0.5}, {{1, 0}, 0.5}};
    case Scheme::Loop:
      return {{{0, 0}, 3.0 / 8}, {{1, 0}, 3.0 / 8}, {{0, 1}, 1.0 / 8}, {{1, -1}, 1.0 / 8}};
    case Scheme::Butterfly:
      return {{{0, 0}, 0.5},        {{1, 0}, 0.5},        {{0, 1}, 1.0 / 8},   {{1, -1}, 1.0 / 8},
              {{-1, 1}, -1.0 / 16}, {{1, 1}, -1.0 / 16},  {{0, -1}, -1.0 / 16}, {{2, -1}, -1.0 / 16}};
    default: throw Error(scheme_name(s) + " has no triangle-lattice mask");
  }
}

// Vertex stencil for the old vertex (0,0): weights of (0,0) and its neighbours.
Stencil vertex_stencil(Scheme s) {
  if (s != Scheme::Loop) return {{{0, 0}, 1.0}};  // interpolating: the vertex is kept
  Stencil st{{{0, 0}, 5.0 / 8}};  // Loop, n = 6: beta = 3/(8n) = 1/16, 1 - n beta = 5/8
  Offset e{1, 0};
  for (int r = 0; r < 6; ++r, e = rotate60(e)) st.push_back({e, 1.0 / 16});
  return st;
}

std::string offset_str(Offset d) { return "(" + std::to_string(d.i) + "," + std::to_string(d.j) + ")"; }

long long cross(Offset o, Offset a, Offset b) {
  return (long long)(a.i - o.i) * (b.j - o.j) - (long long)(a.j - o.j) * (b.i - o.i);
}

// All lattice points in the closed convex hull of `pts` (2-D; sheared coordinates are fine,
// convexity is affine-invariant).
std::vector<Offset> hull_points(std::vector<Offset> pts) {
  std::sort(pts.begin(), pts.end());
  pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
  if (pts.size() < 3) return pts;
  std::vector<Offset> h(2 * pts.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {  // Andrew's monotone chain, counter-clockwise
    while (k >= 2 && cross(h[k - 2], h[k - 1], pts[i]) <= 0) --k;
    h[k++] = pts[i];
  }
  for (std::size_t i = pts.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross(h[k - 2], h[k - 1], pts[i]) <= 0) --k;
    h[k++] = pts[i];
  }
  h.resize(k - 1);
  int i0 = pts.front().i, i1 = pts.front().i, j0 = pts.front().j, j1 = pts.front().j;
  for (Offset p : pts) {
    i0 = std::min(i0, p.i), i1 = std::max(i1, p.i), j0 = std::min(j0, p.j), j1 = std::max(j1, p.j);
  }
  std::vector<Offset> out;
  for (int i = i0; i <= i1; ++i)
    for (int j = j0; j <= j1; ++j) {
      bool in = true;
      for (std::size_t e = 0; e < h.size() && in; ++e) in = cross(h[e], h[(e + 1) % h.size()], {i, j}) >= 0;
      if (in) out.push_back({i, j});
    }
  return out;
}

}  // namespace

// ---------------------------------------------------------------------------------------------

HomogeneousSolution solve_homogeneous(const HomogeneousSystem& sys, double tol) {
  const auto n = Eigen::Index(sys.unknowns);
  if (n == 0 || sys.normal.size() != sys.unknowns) throw Error("solve_homogeneous: empty system or normal size mismatch");
  Eigen::MatrixXd T = Eigen::MatrixXd::Zero(n, n);
  for (const auto& e : sys.T) {
    if (e.row >= sys.unknowns || e.col >= sys.unknowns) throw Error("solve_homogeneous: entry out of range");
    T(Eigen::Index(e.row), Eigen::Index(e.col)) += e.value;
  }
  const Eigen::MatrixXd M = T - Eigen::MatrixXd::Identity(n, n);
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(M, Eigen::ComputeFullV);
  const Eigen::VectorXd& sv = svd.singularValues();  // descending
  const double thr = tol * std::max(1.0, sv(0));
  HomogeneousSolution out;
  for (Eigen::Index i = 0; i < n; ++i) out.nullity += sv(i) < thr ? 1 : 0;
  out.sigma_min = sv(n - 1);
  out.sigma_next = n >= 2 ? sv(n - 2) : std::numeric_limits<double>::infinity();
  out.simple = out.nullity == 1;
  if (out.nullity == 0) {
    std::ostringstream s;
    s << "solve_homogeneous: 1 is not an eigenvalue of T (smallest singular value of T - I is " << out.sigma_min << ")";
    throw Error(s.str());
  }
  Eigen::VectorXd w(n);
  for (Eigen::Index i = 0; i < n; ++i) w(i) = sys.normal[std::size_t(i)];
  const Eigen::VectorXd v = svd.matrixV().col(n - 1);
  if (std::abs(w.dot(v)) <= tol * w.norm()) throw Error("solve_homogeneous: the normalisation row does not fix the scale");

  // The augmented system [T - I; w^T] x = [0; total] is consistent; QR solves it to rounding.
  Eigen::MatrixXd A(n + 1, n);
  A.topRows(n) = M;
  A.row(n) = w.transpose();
  Eigen::VectorXd b = Eigen::VectorXd::Zero(n + 1);
  b(n) = sys.total;
  const Eigen::VectorXd x = A.colPivHouseholderQr().solve(b);
  out.values.assign(x.data(), x.data() + n);
  out.residual = (M * x).cwiseAbs().maxCoeff();

  if (n >= 2) {
    Eigen::EigenSolver<Eigen::MatrixXd> es(T, /*computeEigenvectors=*/false);
    const auto& ev = es.eigenvalues();
    Eigen::Index one = 0;
    for (Eigen::Index i = 1; i < n; ++i)
      if (std::abs(ev(i) - 1.0) < std::abs(ev(one) - 1.0)) one = i;
    for (Eigen::Index i = 0; i < n; ++i)
      if (i != one) out.subdominant = std::max(out.subdominant, std::abs(ev(i)));
  }
  return out;
}

// ---------------------------------------------------------------------------------------------

Offset rotate60(Offset d) { return {-d.j, d.i + d.j}; }

Offset apply(const std::array<int, 4>& m, Offset d) { return {m[0] * d.i + m[1] * d.j, m[2] * d.i + m[3] * d.j}; }

std::vector<std::array<int, 4>> lattice_symmetries(int dim) {
  if (dim == 1) return {{1, 0, 0, 1}, {-1, 0, 0, -1}};
  // Generated by the rotation R (i,j) -> (-j, i+j) and the reflection S (i,j) -> (j,i).
  std::vector<std::array<int, 4>> g{{1, 0, 0, 1}};
  const std::array<int, 4> gens[2] = {{0, -1, 1, 1}, {0, 1, 1, 0}};
  for (std::size_t k = 0; k < g.size(); ++k)
    for (const auto& s : gens) {
      const auto& m = g[k];
      std::array<int, 4> p{s[0] * m[0] + s[1] * m[2], s[0] * m[1] + s[1] * m[3], s[2] * m[0] + s[3] * m[2],
                           s[2] * m[1] + s[3] * m[3]};
      if (std::find(g.begin(), g.end(), p) == g.end()) g.push_back(p);
    }
  return g;  // 12 elements
}

LatticeMask curve_hat_mask() { return {1, {{{-1, 0}, 0.5}, {{0, 0}, 1.0}, {{1, 0}, 0.5}}}; }

LatticeMask regular_mask(Scheme s) {
  // a_k = weight of coarse vertex 0 in the rule of fine vertex k (fine lattice coordinates:
  // old vertex p is 2p, the midpoint of edge (p, p + u) is 2p + u).
  std::map<Offset, double> a;
  for (const auto& [q, w] : vertex_stencil(s)) a[scale(-2, q)] += w;  // vertex p = -q has 0 at p + q
  const Offset e1{1, 0};
  for (int r = 0; r < 3; ++r) {  // the three edge directions e1, e2, e2 - e1: R^r e1
    for (const auto& [q, w] : edge_stencil(s)) {
      // Edge (p, p + R^r e1) uses vertex p + R^r q; it equals 0 for p = -R^r q, whose fine
      // midpoint is 2p + R^r e1 = R^r (e1 - 2q).
      Offset k = sub(e1, scale(2, q));
      for (int t = 0; t < r; ++t) k = rotate60(k);
      a[k] += w;
    }
  }
  LatticeMask m{2, {}};
  for (const auto& [k, w] : a)
    if (w != 0) m.coefficients.push_back({k, w});
  return m;
}

double LatticeInnerProducts::at(Offset d) const {
  auto it = std::lower_bound(offsets.begin(), offsets.end(), d);
  return it != offsets.end() && *it == d ? values[std::size_t(it - offsets.begin())] : 0.0;
}

LatticeInnerProducts lattice_inner_products(const LatticeMask& mask, const LatticeOptions& opt) {
  if (mask.dim != 1 && mask.dim != 2) throw Error("lattice_inner_products: dim must be 1 or 2");
  if (mask.coefficients.empty()) throw Error("lattice_inner_products: empty mask");
  std::map<Offset, double> a;
  for (const auto& [k, w] : mask.coefficients) {
    if (mask.dim == 1 && k.j != 0) throw Error("lattice_inner_products: 1-D mask with j != 0");
    a[k] += w;
  }
  const double s = mask.dim == 1 ? 0.5 : 0.25;  // Jacobian of x -> 2x

  // Autocorrelation c_m = sum_k a_k a_{k+m}: I(d) = s sum_m c_m I(2d + m).
  std::map<Offset, double> c;
  for (const auto& [k, ak] : a)
    for (const auto& [l, al] : a) c[sub(l, k)] += ak * al;

  // Unknowns: supp phi lies in the convex hull H of supp a, so I(d) = 0 unless d is in
  // H - H = hull(supp a - supp a) (= the support of c's hull). Everything outside is 0.
  std::vector<Offset> diff;
  for (const auto& [m, v] : c) diff.push_back(m);
  std::vector<Offset> D;
  if (mask.dim == 1) {
    for (int i = diff.front().i; i <= diff.back().i; ++i) D.push_back({i, 0});
  } else {
    D = hull_points(diff);
  }
  std::map<Offset, std::size_t> index;
  for (std::size_t u = 0; u < D.size(); ++u) index[D[u]] = u;

  // Orbits under the lattice symmetries (or singletons).
  std::vector<std::size_t> orbit(D.size(), SIZE_MAX);
  std::vector<Offset> reps;
  std::vector<double> orbit_size;
  const auto group = lattice_symmetries(mask.dim);
  if (opt.use_symmetry) {
    for (const auto& g : group)
      for (const auto& [k, w] : a) {
        auto it = a.find(apply(g, k));
        if (it == a.end() || std::abs(it->second - w) > 1e-14 * std::max(1.0, std::abs(w)))
          throw Error("lattice_inner_products: mask is not symmetric at " + offset_str(k) + "; use use_symmetry = false");
      }
  }
  for (std::size_t u = 0; u < D.size(); ++u) {
    if (orbit[u] != SIZE_MAX) continue;
    const std::size_t o = reps.size();
    reps.push_back(D[u]);
    orbit_size.push_back(0);
    if (!opt.use_symmetry) {
      orbit[u] = o, orbit_size[o] = 1;
      continue;
    }
    for (const auto& g : group) {
      auto it = index.find(apply(g, D[u]));
      if (it == index.end()) throw Error("lattice_inner_products: offset set not symmetric");
      if (orbit[it->second] == SIZE_MAX) orbit[it->second] = o, orbit_size[o] += 1;
    }
  }

  HomogeneousSystem sys;
  sys.unknowns = reps.size();
  for (std::size_t o = 0; o < reps.size(); ++o)
    for (const auto& [m, cm] : c) {
      auto it = index.find(add(scale(2, reps[o]), m));
      if (it != index.end()) sys.T.push_back({o, orbit[it->second], s * cm});
    }
  LatticeInnerProducts out;
  out.dim = mask.dim;
  out.element = opt.element;
  // integral of phi = sum_d I(d) = area per vertex: h in 1-D; 2A in 2-D (6 triangles per
  // vertex, 3 vertices per triangle). Uses sum_k a_k = 2^dim (affine invariance).
  out.cell = mask.dim == 1 ? opt.element : 2.0 * opt.element;
  sys.normal = orbit_size;
  sys.total = out.cell;
  out.diagnostics = solve_homogeneous(sys);
  if (!out.diagnostics.simple) {
    throw Error("lattice_inner_products: eigenvalue 1 of the transition matrix is not simple (nullity " +
                std::to_string(out.diagnostics.nullity) + ")");
  }
  out.unknowns = sys.unknowns;
  out.offsets = D;
  out.values.resize(D.size());
  for (std::size_t u = 0; u < D.size(); ++u) out.values[u] = out.diagnostics.values[orbit[u]];
  return out;
}

// ---------------------------------------------------------------------------------------------

PolyhedralInnerProducts polyhedral_inner_products(int valence, double triangle_area) {
  if (valence < 1) throw Error("polyhedral_inner_products: valence must be positive");
  // Over one triangle of area A: integral hat_i^2 = A/6, hat_i hat_k = A/12. The vertex lies in
  // n triangles; an interior edge in 2.
  return {valence * triangle_area / 6.0, triangle_area / 6.0};
}

std::vector<double> polyhedral_matrix(std::size_t nv, const std::vector<std::array<std::uint32_t, 3>>& tris,
                                      double triangle_area) {
  std::vector<double> m(nv * nv, 0.0);
  for (const auto& t : tris)
    for (std::uint32_t a : t) {
      if (a >= nv) throw Error("polyhedral_matrix: vertex index out of range");
      for (std::uint32_t b : t) m[std::size_t(a) * nv + b] += triangle_area / 12.0 * (a == b ? 2.0 : 1.0);
    }
  return m;
}

// ---------------------------------------------------------------------------------------------

namespace {
std::mutex g_cache_mutex;
std::map<ConfigKey, std::unique_ptr<LatticeInnerProducts>> g_cache;
std::size_t g_solves = 0;
}  // namespace

const LatticeInnerProducts& cached_inner_products(const ConfigKey& key) {
  if (key.valence != 6)
    throw Error("cached_inner_products: only the regular configuration (valence 6) is implemented");
  std::lock_guard<std::mutex> lock(g_cache_mutex);
  auto& slot = g_cache[key];
  if (!slot) {
    slot = std::make_unique<LatticeInnerProducts>(lattice_inner_products(regular_mask(key.scheme)));
    ++g_solves;
  }
  return *slot;
}

std::size_t inner_product_cache_solves() {
  std::lock_guard<std::mutex> lock(g_cache_mutex);
  return g_solves;
}

}  // namespace sublift::ip
