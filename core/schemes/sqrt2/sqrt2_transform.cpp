#include "core/schemes/sqrt2/sqrt2_transform.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <future>
#include <string>

#include <Eigen/Dense>

#include "core/base/errors.h"
#include "core/base/parallel.h"
#include "core/schemes/sqrt2/sqrt2_coefficients.h"

namespace sublift {

namespace {

constexpr std::uint32_t kNone = Sqrt2Children::kNone;

// Edge neighbours of the corner at slot s of face f in eq. 1's order: the next corner, the
// previous corner, then on around the vertex away from f. False when the corner is not inner
// (curve edge, open or non-manifold fan, valence outside 3..1000). inner[v]: no curve edge at v
// (computed once per transition instead of scanning v's edges per corner).
bool corner_ring(const Complex& c, const std::vector<std::uint8_t>& inner, std::uint32_t f, std::uint32_t s,
                 std::vector<std::uint32_t>& ring) {
  const std::uint32_t v = c.faces.items[s];
  const std::uint32_t valence = c.vertex_edges.size(v);
  if (valence < 3 || valence > 1000 || !inner[v]) return false;
  ring.clear();
  ring.push_back(c.faces.items[face_next_slot(c, f, s)]);
  ring.push_back(c.faces.items[face_prev_slot(c, f, s)]);
  const std::uint32_t first = c.face_edges.items[s];  // v -> next corner
  std::uint32_t e = c.face_edges.items[face_prev_slot(c, f, s)], face = f;
  while (true) {
    const auto fs = c.edge_faces.row(e);
    const std::uint32_t g = fs[0] == face ? fs[1] : fs[0];
    if (g == face) return false;
    std::uint32_t e2 = kNone;
    for (std::uint32_t t = c.faces.offsets[g]; t < c.faces.offsets[g + 1]; ++t) {
      if (c.faces.items[t] != v) continue;
      const std::uint32_t out = c.face_edges.items[t], in = c.face_edges.items[face_prev_slot(c, g, t)];
      if (out == e) e2 = in;
      else if (in == e) e2 = out;
    }
    if (e2 == kNone) return false;
    if (e2 == first) break;
    if (ring.size() >= valence) return false;
    ring.push_back(edge_other_end(c, e2, v));
    e = e2;
    face = g;
  }
  return ring.size() == valence;
}

// One term of a sub-step: weight * x[source] added to x[target], with (target, source) packed
// into one key (target in the high half) so sorting compares one integer.
struct Entry {
  std::uint64_t key;
  double weight;
};

Entry entry(std::uint32_t target, std::uint32_t source, double weight) {
  return {std::uint64_t(target) << 32 | source, weight};
}

// Rows sorted by target, duplicate sources merged (small closed curves repeat vertices; a face
// rule repeats its corners). Comparing the packed keys gives the same results as comparing
// (target, source) pairs, so std::sort moves the entries exactly as it did when they were
// tuples: duplicates are summed in the same order and the weights stay bit-identical.
WeightedStep make_substep(std::vector<Entry> t) {
  std::sort(t.begin(), t.end(), [](const Entry& a, const Entry& b) { return a.key < b.key; });
  WeightedStep s;
  s.sources.items.reserve(t.size());
  s.weights.reserve(t.size());
  for (const Entry& x : t) {
    const std::uint32_t tg = std::uint32_t(x.key >> 32), src = std::uint32_t(x.key);
    if (s.target.empty() || s.target.back() != tg) {
      if (!s.target.empty()) s.sources.offsets.push_back(static_cast<std::uint32_t>(s.sources.items.size()));
      s.target.push_back(tg);
    } else if (s.sources.items.back() == src) {
      s.weights.back() += x.weight;
      continue;
    }
    s.sources.items.push_back(src);
    s.weights.push_back(x.weight);
  }
  if (!s.target.empty()) s.sources.offsets.push_back(static_cast<std::uint32_t>(s.sources.items.size()));
  return s;
}

// Below this many entries a second thread costs more than it saves.
constexpr std::size_t kConcurrentSortEntries = 1 << 16;

// Runs a() and b(), at the same time on a second thread when `big` and parallel_threads() allow
// (a std::async thread, not the pool: callers may run inside a parallel_for).
template <class A, class B>
void side_by_side(bool big, A a, B b) {
  if (!big || parallel_threads() < 2) {
    a();
    b();
    return;
  }
  auto done = std::async(std::launch::async, a);
  b();
  done.get();  // rethrows a's exception, if any
}

// The face rules (eq. 1 / sec. 4) of one transition. Keeps what every face would otherwise
// recompute or allocate: eq. 1's weights per valence (sqrt2_face_alpha's values, computed once
// instead of four cos/sin per term) and the corner rings of the current face in reused buffers.
class FaceRules {
 public:
  FaceRules(const Complex& c, const std::vector<std::uint8_t>& inner) : c_(c), inner_(inner) {}

  // Face point `fp` of coarse face f. Returns true when f is a quad with 4 inner corners (the
  // lifting then uses the table), with their valences in `valences`.
  bool add(std::uint32_t f, std::uint32_t fp, std::vector<Entry>& predict, std::array<std::uint32_t, 4>& valences) {
    const std::uint32_t b = c_.faces.offsets[f], m = c_.faces.size(f);
    if (rings_.size() < m) rings_.resize(m);
    std::uint32_t l = 0;
    for (std::uint32_t i = 0; i < m; ++i)
      if (corner_ring(c_, inner_, f, b + i, rings_[i])) ++l;
      else rings_[i].clear();
    if (l == 0) {  // no inner corner: no rule of the paper applies; the mean keeps it affine
      for (std::uint32_t i = 0; i < m; ++i) predict.push_back(entry(fp, c_.faces.items[b + i], 1.0 / m));
      return false;
    }
    for (std::uint32_t i = 0; i < m; ++i) {
      const std::vector<std::uint32_t>& ring = rings_[i];
      if (ring.empty()) continue;
      const std::uint32_t n = static_cast<std::uint32_t>(ring.size());
      const std::vector<double>& alpha = alphas(n);
      predict.push_back(entry(fp, c_.faces.items[b + i], kSqrt2Alpha0 / l));
      for (std::uint32_t j = 0; j < n; ++j) predict.push_back(entry(fp, ring[j], alpha[j] / l));
      if (i < 4) valences[i] = n;
    }
    return l == 4 && m == 4;
  }

 private:
  // sqrt2_face_alpha(n, j) for j = 0..n-1.
  const std::vector<double>& alphas(std::uint32_t n) {
    if (alphas_.size() <= n) alphas_.resize(n + 1);
    std::vector<double>& a = alphas_[n];
    if (a.empty())
      for (std::uint32_t j = 0; j < n; ++j) a.push_back(sqrt2_face_alpha(int(n), int(j)));
    return a;
  }

  const Complex& c_;
  const std::vector<std::uint8_t>& inner_;
  std::vector<std::vector<double>> alphas_;           // by valence
  std::vector<std::vector<std::uint32_t>> rings_;     // per corner of the current face
};

// phi_0..phi_11 of quad f (docs/sqrt2.md, Figure 3): the corners, then across edge p_i p_{i+1}
// the face running p_{i+1} -> p_i -> phi_{4+2i} -> phi_{5+2i}. A slot is kNone where that face
// is missing or not a quad. Returns true when all 12 exist and are inner (the table case).
bool find_phis(const Complex& c, std::uint32_t f, const std::vector<std::uint8_t>& inner, std::array<std::uint32_t, 12>& phi) {
  const std::uint32_t b = c.faces.offsets[f];
  phi.fill(kNone);
  for (std::uint32_t i = 0; i < 4; ++i) {
    phi[i] = c.faces.items[b + i];
    const std::uint32_t e = c.face_edges.items[b + i];
    if (c.edge_faces.size(e) != 2 || sqrt2_is_curve_edge(c, e)) continue;
    const auto fs = c.edge_faces.row(e);
    const std::uint32_t g = fs[0] == f ? fs[1] : fs[0];
    if (c.faces.size(g) != 4) continue;
    std::uint32_t t = c.faces.offsets[g];
    while (c.faces.items[t] != phi[i]) ++t;
    const std::uint32_t t1 = face_next_slot(c, g, t), t2 = face_next_slot(c, g, t1);
    phi[4 + 2 * i] = c.faces.items[t1];
    phi[5 + 2 * i] = c.faces.items[t2];
  }
  for (std::uint32_t v : phi)
    if (v == kNone || !inner[v]) return false;
  return true;
}

// 001 sec. 4 for a face point next to a curve: S_k of a corner on a curve is dropped, and so is
// any phi that is missing or on a curve (inner wavelets lift inner scaling functions only). The
// omega of the kept distinct vertices solve G omega = -H with the discrete inner products of
// the actual masks (one primitive synthesis step: phi_a is 1 at a and P[n][a] at new point n),
// G = I + P^T P and H_a = P[fp][a]. Rows of P by target: `rows`; columns: `cols`.
void lift_near_curve(std::uint32_t fp, const std::array<std::uint32_t, 12>& phi, const std::vector<std::uint8_t>& inner,
                     const WeightedStep& rows, const std::vector<std::uint32_t>& row_of, const WeightedStep& cols,
                     const std::vector<std::uint32_t>& col_of, std::vector<Entry>& update) {
  static constexpr int kS[4][3] = {{0, 11, 4}, {1, 5, 6}, {2, 7, 8}, {3, 9, 10}};
  bool keep[12];
  for (int k = 0; k < 12; ++k) keep[k] = phi[k] != kNone && inner[phi[k]];
  for (int k = 0; k < 4; ++k)
    if (!inner[phi[k]])
      for (int s : kS[k]) keep[s] = false;
  std::vector<std::uint32_t> vs;
  for (int k = 0; k < 12; ++k)
    if (keep[k] && std::find(vs.begin(), vs.end(), phi[k]) == vs.end()) vs.push_back(phi[k]);
  if (vs.empty()) return;
  auto weight = [](const WeightedStep& s, std::uint32_t r, std::uint32_t item) {
    for (std::uint32_t k = s.sources.offsets[r]; k < s.sources.offsets[r + 1]; ++k)
      if (s.sources.items[k] == item) return s.weights[k];
    return 0.0;
  };
  const int n = static_cast<int>(vs.size());
  Eigen::MatrixXd G = Eigen::MatrixXd::Identity(n, n);
  Eigen::VectorXd H(n);
  for (int a = 0; a < n; ++a) {
    const std::uint32_t ca = col_of[vs[a]];
    H[a] = ca == kNone ? 0.0 : weight(cols, ca, fp);
    if (ca == kNone) continue;
    for (std::uint32_t k = cols.sources.offsets[ca]; k < cols.sources.offsets[ca + 1]; ++k) {
      const std::uint32_t point = cols.sources.items[k];
      for (int b = 0; b < n; ++b) G(a, b) += cols.weights[k] * weight(rows, row_of[point], vs[b]);
    }
  }
  const Eigen::VectorXd omega = G.ldlt().solve(-H);
  for (int a = 0; a < n; ++a) update.push_back(entry(vs[a], fp, omega[a]));
}

}  // namespace

Sqrt2Transition build_sqrt2_transition(const Complex& c, const Complex& fine, const Sqrt2Children& ch) {
  const std::uint32_t nv = c.num_vertices;
  const std::uint32_t nc = static_cast<std::uint32_t>(ch.curve_edges.size());
  const std::uint32_t np = static_cast<std::uint32_t>(ch.point_faces.size());
  if (ch.first_face_point != nv + (ch.curve_step ? nc : 0) || fine.num_vertices != ch.first_face_point + np ||
      ch.curve_stencils.size() != (ch.curve_step ? 4 * std::size_t(nc) : 0))
    throw TopologyError("sqrt(2) transform: the fine level does not match its child description");
  Sqrt2Transition t;
  t.transition.num_coarse = nv;
  t.transition.num_fine = fine.num_vertices;

  // inner[v]: no curve edge at v (the fan check is done per corner in corner_ring).
  std::vector<std::uint8_t> inner(nv, 1);
  for (std::uint32_t e = 0; e < c.num_edges(); ++e)
    if (sqrt2_is_curve_edge(c, e)) inner[c.edge_verts[2 * e]] = inner[c.edge_verts[2 * e + 1]] = 0;

  // Reserved for a quad mesh of valence 4 (5 terms per corner, 12 lifting terms per face point)
  // plus the curve points, so the big arrays grow without copies in the common case.
  std::vector<Entry> update, predict;
  predict.reserve(20 * std::size_t(np) + 4 * std::size_t(nc));
  update.reserve(12 * std::size_t(np) + 4 * std::size_t(nc));
  FaceRules face_rules(c, inner);
  std::vector<std::uint32_t> near_curve;  // face points lifted by lift_near_curve below
  std::vector<std::array<std::uint32_t, 12>> near_phi;
  for (std::uint32_t k = 0; k < np; ++k) {
    const std::uint32_t f = ch.point_faces[k], fp = ch.first_face_point + k;
    std::array<std::uint32_t, 4> n{};
    std::array<std::uint32_t, 12> phi{};
    const bool all_inner = face_rules.add(f, fp, predict, n);
    if (c.faces.size(f) != 4) continue;  // level-0 polygons: no lifting (the paper starts from quads)
    if (!find_phis(c, f, inner, phi) || !all_inner) {
      near_curve.push_back(fp);
      near_phi.push_back(phi);
      continue;
    }
    const auto omega = sqrt2_omega(int(n[0]), int(n[1]), int(n[2]), int(n[3]));
    for (int s = 0; s < 12; ++s)
      if (omega[s] != 0.0) update.push_back(entry(phi[s], fp, omega[s]));  // dropped valence-3 slots are exact 0
    ++t.lifted_face_points;
  }

  const auto w4 = sqrt2_four_point_weights();
  const auto w3 = sqrt2_four_point_corner_weights();
  const auto eta = sqrt2_eta_inner();
  const auto etc = sqrt2_eta_corner();
  for (std::uint32_t k = 0; ch.curve_step && k < nc; ++k) {  // keep steps make no curve points
    const std::uint32_t* s = ch.curve_stencils.data() + 4 * std::size_t(k);
    const std::uint32_t a = s[0], p = s[1], q = s[2], b = s[3], x = nv + k;
    if (a != kNone && b != kNone) {
      const std::uint32_t v[4] = {a, p, q, b};
      for (int i = 0; i < 4; ++i) predict.push_back(entry(x, v[i], w4[i])), update.push_back(entry(v[i], x, eta[i]));
    } else if (a != kNone || b != kNone) {  // eq. 11 (b): (p0, p1, p2 = the curve end)
      const std::uint32_t v[3] = {a != kNone ? a : b, a != kNone ? p : q, a != kNone ? q : p};
      for (int i = 0; i < 3; ++i) predict.push_back(entry(x, v[i], w3[i]));
      for (int i = 0; i < 2; ++i) update.push_back(entry(v[i], x, etc[i]));
    } else {  // a curve of one edge between two ends: no rule in the paper; the midpoint
      predict.push_back(entry(x, p, 0.5));
      predict.push_back(entry(x, q, 0.5));
    }
  }
  // The sorts in make_substep take about half of the build; the two that do not wait for each
  // other run side by side (each is still one std::sort, so the result does not change).
  const bool big = predict.size() + update.size() >= kConcurrentSortEntries;
  WeightedStep pred, upd;
  if (near_curve.empty()) {
    side_by_side(big, [&] { pred = make_substep(std::move(predict)); }, [&] { upd = make_substep(std::move(update)); });
  } else {
    std::vector<Entry> swapped;  // the predict step by source: P's columns
    swapped.reserve(predict.size());
    for (const Entry& x : predict) swapped.push_back({x.key << 32 | x.key >> 32, x.weight});
    WeightedStep cols;
    side_by_side(big, [&] { pred = make_substep(std::move(predict)); }, [&] { cols = make_substep(std::move(swapped)); });
    std::vector<std::uint32_t> row_of(t.transition.num_fine, kNone), col_of(t.transition.num_fine, kNone);
    for (std::uint32_t r = 0; r < pred.target.size(); ++r) row_of[pred.target[r]] = r;
    for (std::uint32_t r = 0; r < cols.target.size(); ++r) col_of[cols.target[r]] = r;
    for (std::size_t i = 0; i < near_curve.size(); ++i)
      lift_near_curve(near_curve[i], near_phi[i], inner, pred, row_of, cols, col_of, update);
    t.near_curve_face_points = static_cast<std::uint32_t>(near_curve.size());
    upd = make_substep(std::move(update));  // after the near-curve terms were added
  }
  t.transition.add(std::move(upd));
  t.transition.add(std::move(pred));
  return t;
}

}  // namespace sublift
