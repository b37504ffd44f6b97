#include "core/schemes/sqrt2/sqrt2_transform.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <string>
#include <span>
#include <utility>

#include <Eigen/Dense>

#include "core/base/errors.h"
#include "core/base/parallel.h"
#include "core/engine/stencil_rows.h"
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

// One term of a sub-step: weight * x[source] added to x[target], (target, source) packed into
// one key, target in the high half (swapping the halves gives the step's columns).
struct Entry {
  std::uint64_t key;
  double weight;
};

Entry entry(std::uint32_t target, std::uint32_t source, double weight) {
  return {std::uint64_t(target) << 32 | source, weight};
}

// The rule's terms of a face point (FaceRules::add) go to a RowBuilder (stencil_rows.h).
// The step of terms made in any order: a counting sort by target (stable, so each row keeps
// the order its terms were made in), then append_stencil_row per target. Linear in the terms
// (one std::sort of them all was half of the whole build).
WeightedStep make_substep(std::vector<Entry> t, std::uint32_t num_targets) {  // by value: freed on return
  std::vector<std::uint32_t> start(std::size_t(num_targets) + 1, 0);
  for (const Entry& x : t) ++start[(x.key >> 32) + 1];
  for (std::uint32_t i = 0; i < num_targets; ++i) start[i + 1] += start[i];
  std::vector<StencilTerm> terms(t.size());
  {
    std::vector<std::uint32_t> at(start.begin(), start.end() - 1);
    for (const Entry& x : t) terms[at[x.key >> 32]++] = {std::uint32_t(x.key), x.weight};
  }
  t = {};
  WeightedStep s;
  s.sources.items.reserve(terms.size());
  s.weights.reserve(terms.size());
  for (std::uint32_t tg = 0; tg < num_targets; ++tg) {
    if (start[tg] == start[tg + 1]) continue;
    s.target.push_back(tg);
    append_stencil_row(std::span<StencilTerm>(terms.data() + start[tg], start[tg + 1] - start[tg]), s.sources, s.weights);
  }
  return s;
}

// The face rules (eq. 1 / sec. 4) of one transition. Keeps what every face would otherwise
// recompute or allocate: eq. 1's weights per valence (sqrt2_face_alpha's values, computed once
// instead of four cos/sin per term) and the corner rings of the current face in reused buffers.
class FaceRules {
 public:
  FaceRules(const Complex& c, const std::vector<std::uint8_t>& inner) : c_(c), inner_(inner) {}

  // The terms of coarse face f's face point. Returns true when f is a quad with 4 inner corners (the
  // lifting then uses the table), with their valences in `valences`.
  bool add(std::uint32_t f, RowBuilder& predict, std::array<std::uint32_t, 4>& valences) {
    const std::uint32_t b = c_.faces.offsets[f], m = c_.faces.size(f);
    if (rings_.size() < m) rings_.resize(m);
    std::uint32_t l = 0;
    for (std::uint32_t i = 0; i < m; ++i)
      if (corner_ring(c_, inner_, f, b + i, rings_[i])) ++l;
      else rings_[i].clear();
    if (l == 0) {  // no inner corner: no rule of the paper applies; the mean keeps it affine
      for (std::uint32_t i = 0; i < m; ++i) predict.add(c_.faces.items[b + i], 1.0 / m);
      return false;
    }
    for (std::uint32_t i = 0; i < m; ++i) {
      const std::vector<std::uint32_t>& ring = rings_[i];
      if (ring.empty()) continue;
      const std::uint32_t n = static_cast<std::uint32_t>(ring.size());
      const std::vector<double>& alpha = alphas(n);
      predict.add(c_.faces.items[b + i], kSqrt2Alpha0 / l);
      for (std::uint32_t j = 0; j < n; ++j) predict.add(ring[j], alpha[j] / l);
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

  // Reserved for a quad mesh of valence 4 (12 distinct sources per face point: its corners and
  // their 8 outer neighbours; 12 lifting terms) plus the curve points, so the big arrays grow
  // without copies in the common case. The predict rows are made in target order: the curve
  // points (nv ..), then the face points.
  WeightedStep pred;
  pred.target.reserve(std::size_t(np) + nc);
  pred.sources.offsets.reserve(std::size_t(np) + nc + 1);
  pred.sources.items.reserve(12 * std::size_t(np) + 4 * std::size_t(nc));
  pred.weights.reserve(12 * std::size_t(np) + 4 * std::size_t(nc));
  RowBuilder predict;
  std::vector<Entry> update;
  update.reserve(12 * std::size_t(np) + 4 * std::size_t(nc));
  const auto w4 = sqrt2_four_point_weights();
  const auto w3 = sqrt2_four_point_corner_weights();
  const auto eta = sqrt2_eta_inner();
  const auto etc = sqrt2_eta_corner();
  for (std::uint32_t k = 0; ch.curve_step && k < nc; ++k) {  // keep steps make no curve points
    const std::uint32_t* s = ch.curve_stencils.data() + 4 * std::size_t(k);
    const std::uint32_t a = s[0], p = s[1], q = s[2], b = s[3], x = nv + k;
    if (a != kNone && b != kNone) {
      const std::uint32_t v[4] = {a, p, q, b};
      for (int i = 0; i < 4; ++i) predict.add(v[i], w4[i]), update.push_back(entry(v[i], x, eta[i]));
    } else if (a != kNone || b != kNone) {  // eq. 11 (b): (p0, p1, p2 = the curve end)
      const std::uint32_t v[3] = {a != kNone ? a : b, a != kNone ? p : q, a != kNone ? q : p};
      for (int i = 0; i < 3; ++i) predict.add(v[i], w3[i]);
      for (int i = 0; i < 2; ++i) update.push_back(entry(v[i], x, etc[i]));
    } else {  // a curve of one edge between two ends: no rule in the paper; the midpoint
      predict.add(p, 0.5);
      predict.add(q, 0.5);
    }
    pred.target.push_back(x);
    predict.flush(pred.sources, pred.weights);
  }
  // The face points in chunks, each on its own thread with its own rows and lifting terms,
  // joined in chunk order: the same rows and terms in the same order whatever the threads.
  struct Chunk {
    Csr rows;  // the face points' prediction rows
    std::vector<double> weights;
    std::vector<Entry> update;
    std::vector<std::uint32_t> near_curve;  // face points lifted by lift_near_curve below
    std::vector<std::array<std::uint32_t, 12>> near_phi;
    std::uint32_t lifted = 0;
    std::exception_ptr error;
  };
  constexpr std::uint32_t kChunk = 8192;
  std::vector<Chunk> chunks((np + kChunk - 1) / kChunk);
  parallel_for(static_cast<std::uint32_t>(chunks.size()), 1, [&](std::uint32_t c0, std::uint32_t c1) {
    FaceRules face_rules(c, inner);
    RowBuilder predict;
    std::array<std::uint32_t, 4> last_n{};  // sqrt2_omega takes a lock: the last one is kept
    std::array<double, 12> omega{};
    for (std::uint32_t ci = c0; ci < c1; ++ci) {
      Chunk& out = chunks[ci];
      try {
        // As for the whole step above: a quad mesh of valence 4 fills these without regrowing.
        const std::uint32_t k0 = ci * kChunk, k1 = std::min(np, k0 + kChunk);
        out.rows.offsets.reserve(std::size_t(k1 - k0) + 1);
        out.rows.items.reserve(12 * std::size_t(k1 - k0));
        out.weights.reserve(12 * std::size_t(k1 - k0));
        out.update.reserve(12 * std::size_t(k1 - k0));
        for (std::uint32_t k = k0; k < k1; ++k) {
          const std::uint32_t f = ch.point_faces[k], fp = ch.first_face_point + k;
          std::array<std::uint32_t, 4> n{};
          std::array<std::uint32_t, 12> phi{};
          const bool all_inner = face_rules.add(f, predict, n);
          predict.flush(out.rows, out.weights);
          if (c.faces.size(f) != 4) continue;  // level-0 polygons: no lifting (the paper starts from quads)
          if (!find_phis(c, f, inner, phi) || !all_inner) {
            out.near_curve.push_back(fp);
            out.near_phi.push_back(phi);
            continue;
          }
          if (n != last_n) omega = sqrt2_omega(int(n[0]), int(n[1]), int(n[2]), int(n[3])), last_n = n;
          for (int s = 0; s < 12; ++s)
            if (omega[s] != 0.0) out.update.push_back(entry(phi[s], fp, omega[s]));  // dropped valence-3 slots are exact 0
          ++out.lifted;
        }
      } catch (...) {
        out.error = std::current_exception();
      }
    }
  });
  // Joined in chunk order: the rows copied to their places in parallel (join_rows), the face
  // points' targets in order after the curve points', the terms and short lists appended.
  std::vector<std::uint32_t> near_curve;
  std::vector<std::array<std::uint32_t, 12>> near_phi;
  std::vector<Csr> parts(chunks.size());
  std::vector<std::vector<double>> part_weights(chunks.size());
  for (std::size_t i = 0; i < chunks.size(); ++i) {
    Chunk& part = chunks[i];
    if (part.error) std::rethrow_exception(part.error);
    parts[i] = std::move(part.rows);
    part_weights[i] = std::move(part.weights);
    update.insert(update.end(), part.update.begin(), part.update.end());
    near_curve.insert(near_curve.end(), part.near_curve.begin(), part.near_curve.end());
    near_phi.insert(near_phi.end(), part.near_phi.begin(), part.near_phi.end());
    t.lifted_face_points += part.lifted;
    part = Chunk{};
  }
  join_rows(parts, part_weights, pred.sources, pred.weights);
  for (std::uint32_t k = 0; k < np; ++k) pred.target.push_back(ch.first_face_point + k);
  if (!near_curve.empty()) {
    std::vector<Entry> swapped;  // the predict step by source: P's columns
    swapped.reserve(pred.sources.items.size());
    for (std::uint32_t r = 0; r < pred.target.size(); ++r)
      for (std::uint32_t k = pred.sources.offsets[r]; k < pred.sources.offsets[r + 1]; ++k)
        swapped.push_back(entry(pred.sources.items[k], pred.target[r], pred.weights[k]));
    const WeightedStep cols = make_substep(std::move(swapped), t.transition.num_fine);
    std::vector<std::uint32_t> row_of(t.transition.num_fine, kNone), col_of(t.transition.num_fine, kNone);
    for (std::uint32_t r = 0; r < pred.target.size(); ++r) row_of[pred.target[r]] = r;
    for (std::uint32_t r = 0; r < cols.target.size(); ++r) col_of[cols.target[r]] = r;
    for (std::size_t i = 0; i < near_curve.size(); ++i)
      lift_near_curve(near_curve[i], near_phi[i], inner, pred, row_of, cols, col_of, update);
    t.near_curve_face_points = static_cast<std::uint32_t>(near_curve.size());
  }
  t.transition.add(make_substep(std::move(update), t.transition.num_fine));  // after any near-curve terms
  t.transition.add(std::move(pred));
  return t;
}

}  // namespace sublift
