#include "core/schemes/sqrt2/sqrt2_coefficients.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "core/base/errors.h"

namespace sublift {

namespace {

// --- The local configuration around a face (docs/sqrt2.md) ------------------------------------
//
// The mesh around the centre face P = p0 p1 p2 p3 with corner valences n0..n3 and every other
// vertex regular is assembled from pieces glued along "rays" (edge paths leaving a corner):
//   - P itself;
//   - for each edge p_i p_{i+1} a strip E_i one face wide, running outwards; its side at p_i is
//     p_i's last ray, its side at p_{i+1} is p_{i+1}'s first ray;
//   - for each corner p_i, n_i - 3 quadrant grids between consecutive rays of p_i.
// Corner p_i has n_i - 2 rays, numbered counterclockwise from the one shared with E_{i-1} (ray 0)
// to the one shared with E_i (ray n_i - 3); for n_i = 3 these coincide and E_{i-1}, E_i meet
// directly. Every vertex off the corners then has valence 4: a ray vertex gets two faces from each
// of the two pieces on its sides, a quadrant vertex four. The pieces are cut at radius kRadius,
// which leaves every vertex the masks need (distance <= 2 from a phi vertex) with a full ring.
constexpr int kRadius = 4;

struct LocalMesh {
  std::vector<std::array<std::uint32_t, 4>> faces;  // faces[0] = P, counterclockwise
  std::uint32_t vertices = 0;
  std::array<std::uint32_t, 12> phi{};  // vertex of phi_0..phi_11
};

class LocalMeshBuilder {
 public:
  explicit LocalMeshBuilder(const std::array<int, 4>& n) : n_(n) {}

  LocalMesh build() {
    LocalMesh m;
    m.faces.push_back({corner(0), corner(1), corner(2), corner(3)});
    for (int i = 0; i < 4; ++i) {
      const int i1 = (i + 1) % 4;
      for (int t = 0; t < kRadius; ++t)  // strip E_i, oriented like P
        m.faces.push_back({ray(i1, 0, t), ray(i, n_[i] - 3, t), ray(i, n_[i] - 3, t + 1),
                           ray(i1, 0, t + 1)});
      for (int q = 0; q + 4 <= n_[i]; ++q)  // quadrant between rays q and q+1 of p_i
        for (int a = 0; a < kRadius; ++a)
          for (int b = 0; b < kRadius; ++b)
            m.faces.push_back({quad(i, q, a, b), quad(i, q, a + 1, b), quad(i, q, a + 1, b + 1),
                               quad(i, q, a, b + 1)});
    }
    for (int i = 0; i < 4; ++i) {
      m.phi[std::size_t(i)] = corner(i);
      m.phi[std::size_t(4 + 2 * i)] = ray(i, n_[i] - 3, 1);
      m.phi[std::size_t(5 + 2 * i)] = ray((i + 1) % 4, 0, 1);
    }
    m.vertices = std::uint32_t(ids_.size());
    return m;
  }

 private:
  std::uint32_t id(const std::array<int, 5>& key) {
    return ids_.try_emplace(key, std::uint32_t(ids_.size())).first->second;
  }
  std::uint32_t corner(int i) { return id({0, i, 0, 0, 0}); }
  std::uint32_t ray(int i, int k, int t) { return t == 0 ? corner(i) : id({1, i, k, t, 0}); }
  // Quadrant q of p_i: (a, 0) lies on ray q, (0, b) on ray q+1.
  std::uint32_t quad(int i, int q, int a, int b) {
    if (b == 0) return ray(i, q, a);
    if (a == 0) return ray(i, q + 1, b);
    return id({2, i, q, a, b});
  }

  std::array<int, 4> n_;
  std::map<std::array<int, 5>, std::uint32_t> ids_;
};

// Edge neighbours of c in cyclic order, walking from face f across edges; empty when c's ring is
// open (c on the cut of the local mesh).
std::vector<std::uint32_t> ring(const LocalMesh& m,
                                const std::map<std::pair<std::uint32_t, std::uint32_t>,
                                               std::vector<std::uint32_t>>& edge_faces,
                                std::uint32_t c, std::uint32_t f) {
  auto nbrs_in = [&](std::uint32_t g) {
    const auto& q = m.faces[g];
    int k = 0;
    while (q[std::size_t(k)] != c) ++k;
    return std::pair{q[std::size_t((k + 1) % 4)], q[std::size_t((k + 3) % 4)]};
  };
  const auto [next, prev] = nbrs_in(f);
  std::vector<std::uint32_t> out{next, prev};
  std::uint32_t cur = f, last = prev;
  for (;;) {
    const auto& fs = edge_faces.at(std::minmax(c, last));
    if (fs.size() != 2) return {};
    const std::uint32_t g = fs[0] == cur ? fs[1] : fs[0];
    const auto [a, b] = nbrs_in(g);
    const std::uint32_t w = a == last ? b : a;
    if (w == next) break;
    out.push_back(w);
    cur = g;
    last = w;
  }
  return out;
}

// The 13 discrete basis functions after one primitive synthesis step (eq. 2) on unit
// coefficients: phi_0..phi_11 and psi (index 12), each as values at all vertex points then all
// face points of the local mesh (the paper's DisBas[13] per point).
std::vector<std::array<double, 13>> local_masks(const LocalMesh& m) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::uint32_t>> edge_faces;
  std::vector<std::uint32_t> some_face(m.vertices);
  for (std::uint32_t f = 0; f < m.faces.size(); ++f)
    for (int k = 0; k < 4; ++k) {
      const std::uint32_t a = m.faces[f][std::size_t(k)], b = m.faces[f][std::size_t((k + 1) % 4)];
      edge_faces[std::minmax(a, b)].push_back(f);
      some_face[a] = f;
    }
  // Only rules at the phi vertices and their edge neighbours can give a phi a weight; their rings
  // are needed (and must be closed), nothing else.
  std::map<std::uint32_t, std::vector<int>> slots;  // vertex -> phi slots on it
  for (int s = 0; s < 12; ++s) slots[m.phi[std::size_t(s)]].push_back(s);
  std::map<std::uint32_t, std::vector<std::uint32_t>> rings;
  for (const auto& [v, ss] : slots) rings[v];
  for (const auto& [e, fs] : edge_faces) {
    if (slots.count(e.first)) rings[e.second];
    if (slots.count(e.second)) rings[e.first];
  }
  for (auto& [c, r] : rings) {
    r = ring(m, edge_faces, c, some_face[c]);
    if (r.empty()) throw std::logic_error("sqrt2 local mesh too small");
  }

  std::vector<std::array<double, 13>> mask(m.vertices + m.faces.size(), std::array<double, 13>{});
  for (const auto& [v, ss] : slots)
    for (int s : ss) mask[v][std::size_t(s)] = 1.0;  // p <- p
  mask[m.vertices + 0][12] = 1.0;                    // psi: f <- f + 1 at P only
  for (std::uint32_t f = 0; f < m.faces.size(); ++f) {
    auto& out = mask[m.vertices + f];
    const auto& q = m.faces[f];
    for (int k = 0; k < 4; ++k) {
      const auto it = rings.find(q[std::size_t(k)]);
      if (it == rings.end()) continue;
      const std::vector<std::uint32_t>& r = it->second;
      const int n = int(r.size());
      // p_{c,0} = next corner of f, p_{c,1} = previous one, then onwards in that direction.
      const std::uint32_t next = q[std::size_t((k + 1) % 4)], prev = q[std::size_t((k + 3) % 4)];
      int at = 0;
      while (r[std::size_t(at)] != next) ++at;
      const int dir = r[std::size_t((at + 1) % n)] == prev ? 1 : -1;
      if (r[std::size_t((at + dir + n) % n)] != prev) throw std::logic_error("sqrt2 ring order");
      auto add = [&](std::uint32_t v, double w) {  // eq. 2: f <- f + 1/4 (...)
        if (auto s = slots.find(v); s != slots.end())
          for (int slot : s->second) out[std::size_t(slot)] += 0.25 * w;
      };
      add(it->first, kSqrt2Alpha0);
      for (int j = 0; j < n; ++j)
        add(r[std::size_t(((at + dir * j) % n + n) % n)], sqrt2_face_alpha(n, j));
    }
  }
  return mask;
}

void check_valence(int n) {
  if (n < 3 || n > 1000)
    throw TopologyError("sqrt(2) coefficients: corner valence " + std::to_string(n) +
                        " is outside 3..1000");
}

// Solves G x = -H (eq. 7) with the slots in `dropped` pinned to 0 (rows/columns of G and H set
// to 0, diagonal 1, as the paper's "slight modification").
template <std::size_t N>
std::array<double, N> solve_orthogonalisation(const std::vector<std::array<double, N + 1>>& mask,
                                              const std::array<bool, N>& dropped) {
  Eigen::Matrix<double, int(N), int(N)> G = Eigen::Matrix<double, int(N), int(N)>::Zero();
  Eigen::Matrix<double, int(N), 1> H = Eigen::Matrix<double, int(N), 1>::Zero();
  for (const auto& p : mask)
    for (std::size_t i = 0; i < N; ++i) {
      if (p[i] == 0.0) continue;
      H(int(i)) += p[i] * p[N];
      for (std::size_t j = 0; j < N; ++j) G(int(i), int(j)) += p[i] * p[j];
    }
  for (std::size_t i = 0; i < N; ++i)
    if (dropped[i]) {
      G.row(int(i)).setZero();
      G.col(int(i)).setZero();
      G(int(i), int(i)) = 1.0;
      H(int(i)) = 0.0;
    }
  const auto lu = G.fullPivLu();
  // A Gram matrix of distinct masks is positive definite; singular means a coinciding pair of
  // functions was not dropped.
  if (!lu.isInvertible()) throw std::logic_error("sqrt2 orthogonalisation: singular G");
  const Eigen::Matrix<double, int(N), 1> x = lu.solve(-H);
  std::array<double, N> out{};
  for (std::size_t i = 0; i < N; ++i) out[i] = dropped[i] ? 0.0 : x(int(i));
  return out;
}

// Curve masks for eta: old vertices v_0..v_{m-1}, midpoints between v_k and v_{k+1} by eq. 11
// (the corner variant where the far stencil vertex would be missing at v_0 when `end_at_0`);
// midpoints without a full stencil are left out (they lie beyond every mask used).
template <std::size_t N>
std::vector<std::array<double, N + 1>> curve_masks(int m, bool end_at_0,
                                                   const std::array<int, N>& phi_vertex,
                                                   int psi_edge) {
  std::vector<std::array<double, N + 1>> mask(std::size_t(2 * m - 1), std::array<double, N + 1>{});
  auto point = [](int v) { return std::size_t(2 * v); };
  for (std::size_t s = 0; s < N; ++s) mask[point(phi_vertex[s])][s] = 1.0;
  mask[std::size_t(2 * psi_edge + 1)][N] = 1.0;
  auto add = [&](std::size_t at, int v, double w) {
    for (std::size_t s = 0; s < N; ++s)
      if (phi_vertex[s] == v) mask[at][s] += w;
  };
  const auto w4 = sqrt2_four_point_weights();
  const auto w3 = sqrt2_four_point_corner_weights();
  for (int k = 0; k + 1 < m; ++k) {
    const std::size_t at = std::size_t(2 * k + 1);
    if (k == 0 && end_at_0) {  // eq. 11 (b): p2 = v_0 is the end, p1 = v_1, p0 = v_2
      add(at, 2, w3[0]);
      add(at, 1, w3[1]);
      add(at, 0, w3[2]);
    } else if (k >= 1 && k + 2 < m) {  // eq. 11 (a): p0..p3 = v_{k-1}..v_{k+2}
      for (int d = 0; d < 4; ++d) add(at, k - 1 + d, w4[std::size_t(d)]);
    }
  }
  return mask;
}

struct OmegaCache {
  std::mutex mutex;
  std::array<std::unique_ptr<std::array<double, 12>>, 10000> table;  // key: valences 3..12
};

}  // namespace

double sqrt2_face_alpha(int n, int j) {
  const double t = 2.0 * std::numbers::pi / double(n);
  const double tj = t * double(j), tm = t * double(j - 1);
  return (1.0 + std::cos(tj) + std::sin(tj) + std::cos(tm) - std::sin(tm)) / (2.0 * double(n));
}

std::array<double, 4> sqrt2_four_point_weights() {
  return {-1.0 / 16.0, 9.0 / 16.0, 9.0 / 16.0, -1.0 / 16.0};  // 001 eq. 11 (a)
}

std::array<double, 3> sqrt2_four_point_corner_weights() {
  return {-1.0 / 8.0, 6.0 / 8.0, 3.0 / 8.0};  // 001 eq. 11 (b)
}

std::array<double, 12> sqrt2_omega_solve(const std::array<int, 4>& valences) {
  for (int n : valences) check_valence(n);
  const LocalMesh m = LocalMeshBuilder(valences).build();
  std::array<bool, 12> dropped{};
  for (int k = 0; k < 4; ++k)
    if (valences[std::size_t(k)] == 3) {
      const std::size_t drop = std::size_t(4 + (2 * k + 7) % 8);
      if (m.phi[drop] != m.phi[std::size_t(4 + 2 * k)])
        throw std::logic_error("sqrt2 local mesh: valence-3 neighbours do not coincide");
      dropped[drop] = true;
    }
  return solve_orthogonalisation<12>(local_masks(m), dropped);
}

std::array<double, 12> sqrt2_omega(int n0, int n1, int n2, int n3) {
  const std::array<int, 4> n{n0, n1, n2, n3};
  for (int v : n) check_valence(v);
  if (n0 > 12 || n1 > 12 || n2 > 12 || n3 > 12) return sqrt2_omega_solve(n);
  static OmegaCache cache;
  const std::size_t key =
      std::size_t(((n0 - 3) * 10 + (n1 - 3)) * 10 + (n2 - 3)) * 10 + std::size_t(n3 - 3);
  {
    std::lock_guard lock(cache.mutex);
    if (cache.table[key]) return *cache.table[key];
  }
  auto w = std::make_unique<std::array<double, 12>>(sqrt2_omega_solve(n));
  std::lock_guard lock(cache.mutex);
  if (!cache.table[key]) cache.table[key] = std::move(w);
  return *cache.table[key];
}

std::array<double, 4> sqrt2_eta_inner() {
  // v_0..v_9; psi between v_4 and v_5, p0..p3 = v_3..v_6.
  const std::array<int, 4> phi{3, 4, 5, 6};
  return solve_orthogonalisation<4>(curve_masks<4>(10, false, phi, 4), {});
}

std::array<double, 2> sqrt2_eta_corner() {
  // v_0 the end; psi between v_0 and v_1, p1 = v_1, p0 = v_2.
  const std::array<int, 2> phi{2, 1};
  return solve_orthogonalisation<2>(curve_masks<2>(8, true, phi, 0), {});
}

}  // namespace sublift
