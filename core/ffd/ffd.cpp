#include "core/ffd/ffd.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "core/base/errors.h"
#include "core/base/parallel.h"
#include "core/base/stopwatch.h"

namespace sublift {
namespace {

using Vec = glm::dvec3;

Vec at(const double* xyz, std::uint32_t v) { return {xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]}; }

// Per-cell data of the lattice: distinct vertices (hexahedra in trilinear corner order),
// whether the cell is a topological cube, bounding box and its diagonal.
struct Cells {
  Csr verts;
  std::vector<std::uint8_t> hex;
  std::vector<double> box;   // 6 per cell: lo xyz, hi xyz
  std::vector<double> size;  // bounding box diagonal
};

// Labels a cell's 8 vertices with trilinear corner numbers from its faces alone: the first
// face's loop gives corners 0, 1, 3, 2 and each of those has one edge leaving that face (to
// corner +4). Then every face must be one side of the cube, walked around its boundary.
bool hex_corners(const Complex& c, std::uint32_t k, std::array<std::uint32_t, 8>& h) {
  const auto faces = c.cell_faces.row(k);
  if (faces.size() != 6) return false;
  for (std::uint32_t f : faces)
    if (c.faces.size(f) != 4) return false;
  const auto b = c.faces.row(faces[0]);
  static constexpr int kBottom[4] = {0, 1, 3, 2};
  for (int i = 0; i < 4; ++i) h[static_cast<std::size_t>(kBottom[i])] = b[static_cast<std::size_t>(i)];
  auto in_bottom = [&](std::uint32_t v) { return std::find(b.begin(), b.end(), v) != b.end(); };
  std::array<std::uint32_t, 4> up;
  up.fill(UINT32_MAX);
  for (std::size_t fi = 1; fi < 6; ++fi) {
    const auto l = c.faces.row(faces[fi]);
    for (std::size_t i = 0; i < 4; ++i) {
      const std::uint32_t v = l[i];
      for (std::uint32_t w : {l[(i + 1) % 4], l[(i + 3) % 4]}) {
        if (!in_bottom(v) || in_bottom(w)) continue;
        const auto pos = static_cast<std::size_t>(std::find(b.begin(), b.end(), v) - b.begin());
        if (up[pos] != UINT32_MAX && up[pos] != w) return false;
        up[pos] = w;
      }
    }
  }
  for (int i = 0; i < 4; ++i) {
    if (up[static_cast<std::size_t>(i)] == UINT32_MAX) return false;
    h[static_cast<std::size_t>(kBottom[i] + 4)] = up[static_cast<std::size_t>(i)];
  }
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < i; ++j)
      if (h[static_cast<std::size_t>(i)] == h[static_cast<std::size_t>(j)]) return false;
  // Each side of the cube is the set of corners with one bit fixed; its loop changes one bit per step.
  std::uint32_t seen = 0;
  for (std::uint32_t f : faces) {
    const auto l = c.faces.row(f);
    int lab[4];
    std::uint32_t mask = 0;
    for (int i = 0; i < 4; ++i) {
      const auto it = std::find(h.begin(), h.end(), l[static_cast<std::size_t>(i)]);
      if (it == h.end()) return false;
      lab[i] = static_cast<int>(it - h.begin());
      mask |= 1u << lab[i];
    }
    for (int i = 0; i < 4; ++i) {
      const int d = lab[i] ^ lab[(i + 1) % 4];
      if (d != 1 && d != 2 && d != 4) return false;
    }
    static constexpr std::uint32_t kSides[6] = {0x55, 0xAA, 0x33, 0xCC, 0x0F, 0xF0};
    const auto side = std::find(std::begin(kSides), std::end(kSides), mask) - std::begin(kSides);
    if (side == 6 || (seen >> side & 1u)) return false;
    seen |= 1u << side;
  }
  return true;
}

Cells make_cells(const Complex& c, const double* xyz) {
  Cells t;
  const std::uint32_t nc = c.num_cells();
  t.hex.assign(nc, 0);
  t.box.resize(6 * std::size_t(nc));
  t.size.resize(nc);
  std::vector<std::uint32_t> vs;
  for (std::uint32_t k = 0; k < nc; ++k) {
    std::array<std::uint32_t, 8> h;
    if (hex_corners(c, k, h)) {
      t.hex[k] = 1;
      t.verts.items.insert(t.verts.items.end(), h.begin(), h.end());
    } else {
      vs.clear();
      for (std::uint32_t f : c.cell_faces.row(k))
        for (std::uint32_t v : c.faces.row(f))
          if (std::find(vs.begin(), vs.end(), v) == vs.end()) vs.push_back(v);
      t.verts.items.insert(t.verts.items.end(), vs.begin(), vs.end());
    }
    t.verts.offsets.push_back(static_cast<std::uint32_t>(t.verts.items.size()));
    double* bx = &t.box[6 * std::size_t(k)];
    for (int a = 0; a < 3; ++a) bx[a] = std::numeric_limits<double>::infinity(), bx[3 + a] = -bx[a];
    for (std::uint32_t v : t.verts.row(k))
      for (int a = 0; a < 3; ++a) {
        bx[a] = std::min(bx[a], xyz[3 * v + a]);
        bx[3 + a] = std::max(bx[3 + a], xyz[3 * v + a]);
      }
    const Vec d{bx[3] - bx[0], bx[4] - bx[1], bx[5] - bx[2]};
    t.size[k] = std::sqrt(glm::dot(d, d));
  }
  return t;
}

// Where a point sits in a cell: trilinear (u, v, w) or barycentric (centroid, face centroid,
// a, b) in the tet of face `face`, edge `edge`. `violation` is how far outside the unit range
// the coordinates are (0 inside).
struct Param {
  bool tet = false;
  std::uint32_t face = 0, edge = 0;
  double c[4] = {0, 0, 0, 0};
  double violation = std::numeric_limits<double>::infinity();
};

// Newton on the trilinear map of the 8 corners; false when it does not converge.
bool inverse_trilinear(const double* xyz, const std::uint32_t* h, double scale, const Vec& p, double uvw[3]) {
  // Relative to corner 0, so round-off scales with the cell, not with its distance from the origin.
  const Vec o = at(xyz, h[0]);
  Vec X[8];
  for (int i = 0; i < 8; ++i) X[i] = at(xyz, h[i]) - o;
  const Vec q = p - o;
  // x(u,v,w) = a0 + a1 u + a2 v + a3 w + a4 uv + a5 uw + a6 vw + a7 uvw
  Vec a[8];
  for (int d = 0; d < 3; ++d) {
    a[0][d] = X[0][d];
    a[1][d] = X[1][d] - X[0][d];
    a[2][d] = X[2][d] - X[0][d];
    a[3][d] = X[4][d] - X[0][d];
    a[4][d] = X[3][d] - X[2][d] - X[1][d] + X[0][d];
    a[5][d] = X[5][d] - X[4][d] - X[1][d] + X[0][d];
    a[6][d] = X[6][d] - X[4][d] - X[2][d] + X[0][d];
    a[7][d] = X[7][d] - X[6][d] - X[5][d] - X[3][d] + X[4][d] + X[2][d] + X[1][d] - X[0][d];
  }
  double u = 0.5, v = 0.5, w = 0.5;
  const double accept = 1e-11 * scale, done = 4e-16 * scale;
  double best = std::numeric_limits<double>::infinity();
  double bu = u, bv = v, bw = w;
  for (int it = 0; it < 40; ++it) {
    Vec r, ju, jv, jw;
    for (int d = 0; d < 3; ++d) {
      r[d] = q[d] - (a[0][d] + a[1][d] * u + a[2][d] * v + a[3][d] * w + a[4][d] * u * v + a[5][d] * u * w +
                     a[6][d] * v * w + a[7][d] * u * v * w);
      ju[d] = a[1][d] + a[4][d] * v + a[5][d] * w + a[7][d] * v * w;
      jv[d] = a[2][d] + a[4][d] * u + a[6][d] * w + a[7][d] * u * w;
      jw[d] = a[3][d] + a[5][d] * u + a[6][d] * v + a[7][d] * u * v;
    }
    const double res = std::sqrt(glm::dot(r, r));
    if (!(res < best)) {
      if (it > 3 && best <= accept) break;  // round-off floor reached
    } else {
      best = res, bu = u, bv = v, bw = w;
      if (res <= done) break;
    }
    // Cramer's rule on J du = r with J = [ju jv jw].
    const Vec c_vw = glm::cross(jv, jw), c_wu = glm::cross(jw, ju), c_uv = glm::cross(ju, jv);
    const double det = glm::dot(ju, c_vw);
    if (!(std::abs(det) > 1e-14 * scale * scale * scale)) break;
    const double du = glm::dot(r, c_vw) / det, dv = glm::dot(r, c_wu) / det, dw = glm::dot(r, c_uv) / det;
    if (!std::isfinite(du) || !std::isfinite(dv) || !std::isfinite(dw)) break;
    u += du, v += dv, w += dw;
    if (std::abs(u) > 1e6 || std::abs(v) > 1e6 || std::abs(w) > 1e6) break;
  }
  if (!(best <= accept)) return false;
  uvw[0] = bu, uvw[1] = bv, uvw[2] = bw;
  return true;
}

Vec mean_of(const double* xyz, std::span<const std::uint32_t> vs) {
  Vec m{0, 0, 0};
  for (std::uint32_t v : vs)
    for (int d = 0; d < 3; ++d) m[d] += xyz[3 * v + d];
  for (int d = 0; d < 3; ++d) m[d] /= double(vs.size());
  return m;
}

// The tet of cell k's split whose barycentric coordinates are least outside; stops at the
// first tet that contains p within `tol`. False when every tet is degenerate.
bool tet_split_param(const Complex& c, const Cells& t, const double* xyz, std::uint32_t k, const Vec& p, double tol,
                     Param& out) {
  const Vec cc = mean_of(xyz, t.verts.row(k));
  const double s = t.size[k], min_det = 1e-13 * s * s * s;
  bool any = false;
  for (std::uint32_t f : c.cell_faces.row(k)) {
    const auto loop = c.faces.row(f);
    const Vec m = mean_of(xyz, loop);
    const Vec dm = m - cc, dp = p - cc;
    for (std::uint32_t i = 0; i < loop.size(); ++i) {
      const Vec da = at(xyz, loop[i]) - cc, db = at(xyz, loop[(i + 1) % loop.size()]) - cc;
      // p - cc = lm dm + la da + lb db, by Cramer's rule.
      const Vec c_ab = glm::cross(da, db);
      const double det = glm::dot(dm, c_ab);
      if (!(std::abs(det) > min_det)) continue;
      const double lm = glm::dot(dp, c_ab) / det, la = glm::dot(dm, glm::cross(dp, db)) / det,
                   lb = glm::dot(dm, glm::cross(da, dp)) / det;
      const double lc = 1.0 - lm - la - lb;
      const double viol = std::max({0.0, -lc, -lm, -la, -lb});
      if (!std::isfinite(viol)) continue;
      if (viol < out.violation) {
        out.tet = true, out.face = f, out.edge = i;
        out.c[0] = lc, out.c[1] = lm, out.c[2] = la, out.c[3] = lb;
        out.violation = viol;
        any = true;
        if (viol <= tol) return true;
      }
    }
  }
  return any;
}

// Coordinates of p in cell k (extrapolated when outside); false when none can be computed.
bool cell_param(const Complex& c, const Cells& t, const double* xyz, std::uint32_t k, const Vec& p, double tol,
                Param& out) {
  out = Param{};
  if (t.hex[k]) {
    double uvw[3];
    if (inverse_trilinear(xyz, &t.verts.items[t.verts.offsets[k]], t.size[k], p, uvw)) {
      out.tet = false;
      out.c[0] = uvw[0], out.c[1] = uvw[1], out.c[2] = uvw[2];
      out.violation = 0;
      for (double x : uvw) out.violation = std::max({out.violation, -x, x - 1.0});
      return true;
    }
  }
  return tet_split_param(c, t, xyz, k, p, tol, out);
}

double box_distance2(const double* bx, const Vec& p) {
  double d2 = 0;
  for (int a = 0; a < 3; ++a) {
    const double e = std::max({bx[a] - p[a], 0.0, p[a] - bx[3 + a]});
    d2 += e * e;
  }
  return d2;
}

// Uniform grid over the cells' bounding boxes, about one cell per bin.
struct Grid {
  Vec lo{0, 0, 0}, h{1, 1, 1};
  int n[3] = {1, 1, 1};
  Csr bins;  // bin -> cells (ascending)

  int coord(int a, double x) const {
    const double f = std::floor((x - lo[a]) / h[a]);
    return static_cast<int>(std::clamp(f, 0.0, double(n[a] - 1)));
  }
  std::size_t index(int i, int j, int k) const { return (std::size_t(k) * n[1] + j) * n[0] + i; }
};

Grid make_grid(const Cells& t, std::uint32_t nc, double tol) {
  Grid g;
  if (nc == 0) {
    g.bins.offsets = {0, 0};  // one empty bin
    return g;
  }
  Vec lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  double max_size = 0;
  for (std::uint32_t k = 0; k < nc; ++k) {
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], t.box[6 * k + a]), hi[a] = std::max(hi[a], t.box[6 * k + 3 + a]);
    max_size = std::max(max_size, t.size[k]);
  }
  for (int a = 0; a < 3; ++a) lo[a] -= tol * max_size, hi[a] += tol * max_size;
  const Vec ext = hi - lo;
  const double diag = std::sqrt(glm::dot(ext, ext));
  // Flat axes get a thickness so the bin size stays positive.
  const double floor_ext = diag > 0 ? 1e-6 * diag : 1.0;
  Vec e;
  for (int a = 0; a < 3; ++a) e[a] = std::max(ext[a], floor_ext);
  // About nc bins of equal sides; an axis thinner than one side gets one bin and the others share nc.
  bool thin[3] = {false, false, false};
  for (int round = 0; round < 3; ++round) {
    double vol = 1;
    int m = 0;
    for (int a = 0; a < 3; ++a)
      if (!thin[a]) vol *= e[a], ++m;
    const double side = std::pow(vol / double(nc), 1.0 / m);
    bool again = false;
    for (int a = 0; a < 3; ++a) {
      if (thin[a]) continue;
      if (e[a] < side && m > 1) thin[a] = again = true;
      g.n[a] = static_cast<int>(std::clamp(std::round(e[a] / side), 1.0, 1024.0));
    }
    if (!again) break;
    for (int a = 0; a < 3; ++a)
      if (thin[a]) g.n[a] = 1;
  }
  for (int a = 0; a < 3; ++a) {
    g.lo[a] = lo[a] - 0.5 * (e[a] - ext[a]);
    g.h[a] = e[a] / g.n[a];
  }
  // Cell -> the bins its box overlaps, grown by the inside tolerance so points accepted with
  // slack find their cell; transposed, bin -> cells.
  Csr cell_bins;
  for (std::uint32_t k = 0; k < nc; ++k) {
    const double pad = tol * t.size[k];
    int r[3][2];
    for (int a = 0; a < 3; ++a) {
      r[a][0] = g.coord(a, t.box[6 * k + a] - pad);
      r[a][1] = g.coord(a, t.box[6 * k + 3 + a] + pad);
    }
    for (int z = r[2][0]; z <= r[2][1]; ++z)
      for (int y = r[1][0]; y <= r[1][1]; ++y)
        for (int x = r[0][0]; x <= r[0][1]; ++x) cell_bins.items.push_back(static_cast<std::uint32_t>(g.index(x, y, z)));
    cell_bins.offsets.push_back(static_cast<std::uint32_t>(cell_bins.items.size()));
  }
  g.bins = transpose(cell_bins, std::size_t(g.n[0]) * g.n[1] * g.n[2]);
  return g;
}

struct Located {
  std::int32_t cell = -1;
  Placement placement = Placement::Stay;
  Param param;
};

struct Binder {
  const Complex& c;
  const double* xyz;
  const Cells& t;
  const Grid& g;
  double tol;

  bool inside_grid(const Vec& p) const {
    for (int a = 0; a < 3; ++a)
      if (p[a] < g.lo[a] || p[a] > g.lo[a] + g.h[a] * g.n[a]) return false;
    return true;
  }

  Located locate(const Vec& p) const {
    Located r;
    if (!inside_grid(p)) return r;
    const std::size_t b = g.index(g.coord(0, p[0]), g.coord(1, p[1]), g.coord(2, p[2]));
    Param q;
    for (std::uint32_t k : g.bins.row(b)) {
      if (box_distance2(&t.box[6 * std::size_t(k)], p) > tol * tol * t.size[k] * t.size[k]) continue;
      if (cell_param(c, t, xyz, k, p, tol, q) && q.violation <= tol) {
        r.cell = static_cast<std::int32_t>(k);
        r.placement = Placement::Inside;
        r.param = q;
        return r;
      }
    }
    return r;
  }

  // Ring search over bins around p's (clamped) bin by bounding-box distance; among the cells
  // at (nearly) the smallest distance, the one whose coordinates are least outside.
  Located nearest(const Vec& p) const {
    const int b0[3] = {g.coord(0, p[0]), g.coord(1, p[1]), g.coord(2, p[2])};
    const double hmin = std::min({g.h[0], g.h[1], g.h[2]});
    const double eps = 1e-9 * hmin;
    const int rmax = std::max({g.n[0], g.n[1], g.n[2]});
    double best = std::numeric_limits<double>::infinity();
    std::vector<std::pair<double, std::uint32_t>> near;  // (distance, cell) within best + eps
    auto visit = [&](int x, int y, int z) {
      for (std::uint32_t k : g.bins.row(g.index(x, y, z))) {
        const double d = std::sqrt(box_distance2(&t.box[6 * std::size_t(k)], p));
        if (d > best + eps) continue;
        best = std::min(best, d);
        near.emplace_back(d, k);
      }
    };
    for (int r = 0; r <= rmax; ++r) {
      // The shell of bins at Chebyshev distance r from b0.
      const int x0 = b0[0] - r, x1 = b0[0] + r;
      for (int z = std::max(0, b0[2] - r); z <= std::min(g.n[2] - 1, b0[2] + r); ++z)
        for (int y = std::max(0, b0[1] - r); y <= std::min(g.n[1] - 1, b0[1] + r); ++y) {
          if (std::abs(z - b0[2]) == r || std::abs(y - b0[1]) == r) {
            for (int x = std::max(0, x0); x <= std::min(g.n[0] - 1, x1); ++x) visit(x, y, z);
          } else {
            if (x0 >= 0) visit(x0, y, z);
            if (r > 0 && x1 < g.n[0]) visit(x1, y, z);
          }
        }
      // Bins of ring r + 1 are at least r * hmin from p's projection onto the grid (and so from p).
      if (best + eps < double(r) * hmin) break;
    }
    std::sort(near.begin(), near.end(), [](const auto& a, const auto& b) { return a.second < b.second; });
    Located out;
    Param q;
    std::uint32_t last = UINT32_MAX;
    for (const auto& [d, k] : near) {
      if (d > best + eps || k == last) continue;
      last = k;
      if (cell_param(c, t, xyz, k, p, 0.0, q) && q.violation < out.param.violation) {
        out.cell = static_cast<std::int32_t>(k);
        out.placement = Placement::Nearest;
        out.param = q;
      }
    }
    return out;
  }
};

void check_finite(std::span<const double> xyz, const char* what) {
  for (std::size_t i = 0; i < xyz.size(); ++i)
    if (!std::isfinite(xyz[i]))
      throw Error(std::string("ffd: ") + what + " vertex " + std::to_string(i / 3) + " is not finite");
}

// The one formula both deform paths use, so they agree bit for bit.
// In displacement form, rest + sum w_k (x_k - rest_k): an unmoved lattice gives the rest
// position back bit for bit (not merely to round-off), so undoing every edit, or exporting an
// untouched model, returns the file's own coordinates. Weights sum to 1, so affine maps are
// reproduced as in the plain form.
inline void deform_one(const FfdBinding& b, const double* x, std::uint32_t i, double* out) {
  const std::uint32_t o0 = b.stencil.offsets[i], o1 = b.stencil.offsets[i + 1];
  double px = 0, py = 0, pz = 0;
  for (std::uint32_t o = o0; o < o1; ++o) {
    const double w = b.weight[o];
    const std::size_t k = 3 * std::size_t(b.stencil.items[o]);
    const double* q = x + k;
    const double* r = b.lattice_rest.data() + k;
    px += w * (q[0] - r[0]), py += w * (q[1] - r[1]), pz += w * (q[2] - r[2]);
  }
  out[3 * i] = b.rest[3 * i] + px, out[3 * i + 1] = b.rest[3 * i + 1] + py, out[3 * i + 2] = b.rest[3 * i + 2] + pz;
}

void check_deform_sizes(const FfdBinding& b, std::span<const double> lattice_xyz, std::span<double> out) {
  if (lattice_xyz.size() != 3 * std::size_t(b.num_lattice_vertices))
    throw Error("ffd: " + std::to_string(lattice_xyz.size() / 3) + " lattice positions for a binding of " +
                std::to_string(b.num_lattice_vertices) + " lattice vertices");
  if (out.size() != b.rest.size())
    throw Error("ffd: output holds " + std::to_string(out.size() / 3) + " positions for " +
                std::to_string(b.rest.size() / 3) + " model vertices");
}

}  // namespace

FfdBinding bind_model(const Complex& lattice, std::span<const double> lattice_xyz, std::span<const double> model_xyz,
                      const FfdOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  const Complex& c = lattice;
  if (c.dim != 3) throw Error("ffd: the lattice is not a volume complex (dim " + std::to_string(c.dim) + ")");
  if (lattice_xyz.size() != 3 * std::size_t(c.num_vertices))
    throw Error("ffd: " + std::to_string(lattice_xyz.size()) + " lattice coordinates for " +
                std::to_string(c.num_vertices) + " vertices");
  if (model_xyz.size() % 3 != 0) throw Error("ffd: model coordinates are not a multiple of 3");
  if (model_xyz.size() / 3 >= std::size_t(INT32_MAX)) throw Error("ffd: model too large");
  if (!(options.tolerance >= 0) || !std::isfinite(options.tolerance)) throw Error("ffd: bad tolerance");
  for (std::uint32_t v : c.faces.items)
    if (v >= c.num_vertices) throw Error("ffd: a lattice face names vertex " + std::to_string(v) + " out of range");
  for (std::uint32_t f : c.cell_faces.items)
    if (f >= c.num_faces()) throw Error("ffd: a lattice cell names face " + std::to_string(f) + " out of range");
  for (std::uint32_t f = 0; f < c.num_faces(); ++f)
    if (c.faces.size(f) < 3) throw Error("ffd: lattice face " + std::to_string(f) + " has fewer than 3 corners");
  check_finite(lattice_xyz, "lattice");
  check_finite(model_xyz, "model");

  const double* xyz = lattice_xyz.data();
  const Cells t = make_cells(c, xyz);
  const Grid g = make_grid(t, c.num_cells(), options.tolerance);
  const Binder binder{c, xyz, t, g, options.tolerance};

  const auto n = static_cast<std::uint32_t>(model_xyz.size() / 3);
  std::vector<Located> loc(n);
  parallel_for(n, 1024, [&](std::uint32_t i0, std::uint32_t i1) {
    for (std::uint32_t i = i0; i < i1; ++i) {
      const Vec p = at(model_xyz.data(), i);
      loc[i] = binder.locate(p);
      if (loc[i].cell < 0 && options.outside == Outside::Nearest && c.num_cells() > 0) loc[i] = binder.nearest(p);
    }
  });

  FfdBinding b;
  b.num_lattice_vertices = c.num_vertices;
  b.rest.assign(model_xyz.begin(), model_xyz.end());
  b.lattice_rest.assign(lattice_xyz.begin(), lattice_xyz.end());
  b.cell.resize(n);
  b.placement.resize(n);
  b.stencil.offsets.assign(std::size_t(n) + 1, 0);
  std::size_t total = 0;
  for (std::uint32_t i = 0; i < n; ++i) {
    b.cell[i] = loc[i].cell;
    b.placement[i] = loc[i].placement;
    if (loc[i].cell >= 0) total += t.verts.size(std::size_t(loc[i].cell));
    if (total > UINT32_MAX) throw Error("ffd: too many weights for 32-bit offsets");
    b.stencil.offsets[i + 1] = static_cast<std::uint32_t>(total);
    switch (loc[i].placement) {
      case Placement::Inside: ++b.report.bound; break;
      case Placement::Nearest: ++b.report.outside, ++b.report.nearest; break;
      case Placement::Stay: ++b.report.outside; break;
    }
    if (loc[i].cell >= 0 && loc[i].param.tet) ++b.report.tet_split;
  }
  b.stencil.items.resize(total);
  b.weight.resize(total);
  parallel_for(n, 2048, [&](std::uint32_t i0, std::uint32_t i1) {
    for (std::uint32_t i = i0; i < i1; ++i) {
      if (loc[i].cell < 0) continue;
      const auto k = static_cast<std::uint32_t>(loc[i].cell);
      const auto vs = t.verts.row(k);
      const Param& q = loc[i].param;
      std::uint32_t* sv = &b.stencil.items[b.stencil.offsets[i]];
      double* sw = &b.weight[b.stencil.offsets[i]];
      std::copy(vs.begin(), vs.end(), sv);
      if (!q.tet) {
        const double u = q.c[0], v = q.c[1], w = q.c[2];
        for (int j = 0; j < 8; ++j)
          sw[j] = (j & 1 ? u : 1 - u) * (j & 2 ? v : 1 - v) * (j & 4 ? w : 1 - w);
        continue;
      }
      // Barycentric (centroid, face centroid, a, b) spread to the cell's vertices.
      const auto loop = c.faces.row(q.face);
      const std::uint32_t va = loop[q.edge], vb = loop[(q.edge + 1) % loop.size()];
      const double wc = q.c[0] / double(vs.size()), wf = q.c[1] / double(loop.size());
      for (std::size_t j = 0; j < vs.size(); ++j) {
        double w = wc;
        if (std::find(loop.begin(), loop.end(), vs[j]) != loop.end()) w += wf;
        if (vs[j] == va) w += q.c[2];
        if (vs[j] == vb) w += q.c[3];
        sw[j] = w;
      }
    }
  });
  b.users = transpose(b.stencil, c.num_vertices);
  b.report.ms = ms_since(t0);
  return b;
}

void deform(const FfdBinding& b, std::span<const double> lattice_xyz, std::span<double> out) {
  check_deform_sizes(b, lattice_xyz, out);
  const double* x = lattice_xyz.data();
  double* o = out.data();
  parallel_for(b.num_model_vertices(), 4096, [&](std::uint32_t i0, std::uint32_t i1) {
    for (std::uint32_t i = i0; i < i1; ++i) deform_one(b, x, i, o);
  });
}

void deform_changed(const FfdBinding& b, std::span<const double> lattice_xyz, std::span<const std::uint32_t> changed,
                    std::span<double> out, std::vector<std::uint32_t>* touched) {
  check_deform_sizes(b, lattice_xyz, out);
  const std::uint32_t n = b.num_model_vertices();
  std::vector<std::uint8_t> mark(n, 0);
  std::size_t count = 0;
  for (std::uint32_t v : changed) {
    if (v >= b.num_lattice_vertices)
      throw Error("ffd: changed lattice vertex " + std::to_string(v) + " out of range (" +
                  std::to_string(b.num_lattice_vertices) + " vertices)");
    for (std::uint32_t i : b.users.row(v))
      if (!mark[i]) mark[i] = 1, ++count;
  }
  // A scan of the marks gives ascending order for about the price of a memset.
  std::vector<std::uint32_t> local;
  std::vector<std::uint32_t>& list = touched ? *touched : local;
  list.clear();
  list.reserve(count);
  for (std::uint32_t i = 0; i < n && list.size() < count; ++i)
    if (mark[i]) list.push_back(i);
  const double* x = lattice_xyz.data();
  double* o = out.data();
  parallel_for(static_cast<std::uint32_t>(list.size()), 4096, [&](std::uint32_t i0, std::uint32_t i1) {
    for (std::uint32_t i = i0; i < i1; ++i) deform_one(b, x, list[i], o);
  });
}

}  // namespace sublift
