#include "core/schemes/tri/tri_transform.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <string_view>
#include <tuple>
#include <unordered_map>

#include "core/base/default_init.h"
#include "core/base/epoch_table.h"
#include "core/base/parallel.h"
#include "core/schemes/tri/new_signatures.h"
#include "core/schemes/tri/tri_local.h"
#include "core/schemes/tri/tri_wavelets.h"

namespace sublift {

namespace {

std::mutex builders_mutex;
// Kept to the end of the process, never torn down: freeing a fitted million-vertex base's
// hundreds of thousands of cached neighbourhoods at exit took half a second (perf).
std::map<std::pair<int, int>, std::unique_ptr<TriWaveletBuilder>>& builders() {
  static auto* b = new std::map<std::pair<int, int>, std::unique_ptr<TriWaveletBuilder>>;
  return *b;
}

// One old vertex's update row where every wavelet reaching it is the regular one: its terms as
// edges between labels of the vertex's canonical (disc + 1)-ring order (tri_local.h), each with
// its weight. Every such vertex has this row, up to the labels (the lattice's rotations map the
// regular wavelets onto each other), so the rows share one weight pattern and only their
// sources are listed.
struct RowTemplate {
  std::uint32_t labels = 0;                                    // size of the order
  std::vector<std::pair<std::uint32_t, std::uint32_t>> slots;  // each term's edge, as two labels
  std::vector<double> weights;                                 // aligned with slots
  // The order as walks, so a row is found without a search: label l > 0 is step[l] places
  // round the fan of label parent[l] from where that fan's walk starts; slot k's edge is
  // slot_step[k] places round the fan of its first label.
  std::vector<std::uint32_t> parent;
  std::vector<std::uint8_t> step, slot_step;
};

// Edge e's disc in its canonical order (a, b, then breadth first; tri_wavelets.h).
void edge_disc(const Complex& c, const TriRings& r, std::uint32_t e, int disc, LocalOrder& o) {
  const std::uint32_t seeds[2] = {c.edge_verts[2 * e], c.edge_verts[2 * e + 1]}, starts[2] = {seeds[1], seeds[0]};
  local_order(r, seeds, starts, disc, o);
}

// The template read off vertex i0 (whose rows reach only regular edges): the edges whose disc
// holds i0 are those at the vertices within `disc` of it; i0's weight from each is -alpha at
// i0's place in that edge's disc.
RowTemplate make_row_template(const Complex& c, const TriRings& r, std::uint32_t i0, int disc,
                              const std::vector<double>& alpha) {
  const std::uint32_t seeds[1] = {i0}, starts[1] = {r.ring.row(i0)[0]};
  const LocalOrder around = local_order(r, seeds, starts, disc + 1);
  RowTemplate t;
  t.labels = static_cast<std::uint32_t>(around.vertex.size());
  // Only off a plain lattice patch (1 + 3 R (R + 1) vertices within R rings): else no slots.
  const auto R = static_cast<std::uint32_t>(disc) + 1;
  if (t.labels != 1 + 3 * R * (R + 1)) return t;
  std::unordered_map<std::uint32_t, std::uint32_t> label;
  for (std::uint32_t l = 0; l < around.vertex.size(); ++l) label.emplace(around.vertex[l], l);
  std::vector<std::uint32_t> edges;
  for (std::uint32_t l = 0; l < around.vertex.size(); ++l)
    if (around.dist[l] <= disc)
      for (std::uint32_t e : r.ring_edge.row(around.vertex[l])) edges.push_back(e);
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  std::vector<std::tuple<std::uint32_t, std::uint32_t, double>> terms;
  LocalOrder d;
  for (std::uint32_t e : edges) {
    edge_disc(c, r, e, disc, d);
    const auto at = std::find(d.vertex.begin(), d.vertex.end(), i0);
    if (at == d.vertex.end() || d.vertex.size() != alpha.size())
      throw std::logic_error("tri_transform: a regular edge's disc misses its own vertex");
    const std::uint32_t la = label.at(c.edge_verts[2 * e]), lb = label.at(c.edge_verts[2 * e + 1]);
    terms.emplace_back(std::min(la, lb), std::max(la, lb), -alpha[static_cast<std::size_t>(at - d.vertex.begin())]);
  }
  std::sort(terms.begin(), terms.end());
  // Places round label l's fan (walked: l is within disc of i0) from where its walk starts.
  const auto steps_round = [&](std::uint32_t l, std::uint32_t x) {
    return static_cast<std::uint8_t>((fan_index(r, around.vertex[l], x) + 6 - around.fan0[l]) % 6);
  };
  t.parent.assign(t.labels, 0);
  t.step.assign(t.labels, 0);
  for (std::uint32_t l = 1; l < t.labels; ++l) {
    t.parent[l] = label.at(around.start[l]);
    t.step[l] = steps_round(t.parent[l], around.vertex[l]);
  }
  for (const auto& [la, lb, w] : terms) {
    t.slots.emplace_back(la, lb);
    t.slot_step.push_back(steps_round(la, around.vertex[lb]));
    t.weights.push_back(w);
  }
  return t;
}

// Vertex i's sources by the template; false where its neighbourhood is not the template's (the
// surface closes on itself within the radius: a small regular torus).
bool fill_template_row(const TriRings& r, const RowTemplate& t, std::uint32_t i, std::uint32_t nv, LocalOrder& o,
                       std::uint32_t* out) {
  // o.vertex: label -> vertex; o.fan0: label -> where its fan walk starts (at its parent).
  o.vertex.resize(t.labels);
  o.fan0.resize(t.labels);
  o.vertex[0] = i;
  o.fan0[0] = 0;
  const std::uint32_t* items = r.ring.items.data();
  const std::uint32_t* offsets = r.ring.offsets.data();
  for (std::uint32_t l = 1; l < t.labels; ++l) {
    const std::uint32_t p = t.parent[l], pv = o.vertex[p];
    const std::uint32_t v = items[offsets[pv] + (o.fan0[p] + t.step[l]) % 6];
    o.vertex[l] = v;
    o.fan0[l] = fan_index(r, v, pv);  // pv is v's neighbour, so it is found
  }
  // A surface that closes on itself within the radius gives some vertex two labels.
  if (!all_distinct(o.vertex, static_cast<std::uint32_t>(r.closed.size()))) return false;
  const std::uint32_t* edges = r.ring_edge.items.data();
  for (std::size_t k = 0; k < t.slots.size(); ++k) {
    const std::uint32_t at = offsets[o.vertex[t.slots[k].first]] + (o.fan0[t.slots[k].first] + t.slot_step[k]) % 6;
    if (items[at] != o.vertex[t.slots[k].second]) return false;
    out[k] = nv + edges[at];
  }
  return true;
}

// Every edge's wavelet: the regular ones share `regular_alpha`; the others' discs and alphas
// are listed by `irregular_at`.
struct EdgeWavelets {
  std::vector<std::uint8_t> dist;  // per coarse vertex: distance to irregular, capped
  int radius = 0;                  // an edge is regular when both ends are farther than this
  std::vector<std::uint8_t> regular;
  std::vector<double> regular_alpha;
  std::vector<std::uint32_t> irregular_at;  // per edge: index into discs, UINT32_MAX if regular
  std::vector<std::vector<std::uint32_t>> discs;
  std::vector<const std::vector<double>*> alphas;  // into the builder's cache, which keeps them
};

// Update rows (old vertex i += sum -alpha_{i,m} d_m), rows by old vertex. Rows that read only
// regular wavelets follow the template (when `with_template`); the others list their terms in
// edge order, from the edges that can reach them. False when a template row did not fit.
bool update_rows(const Complex& coarse, const TriRings& rings, const EdgeWavelets& w, int disc, bool with_template,
                 WeightedStep& up) {
  const std::uint32_t nv = coarse.num_vertices, ne = coarse.num_edges();
  const int R = w.radius;
  std::vector<std::uint8_t> by_template(nv, 0);
  RowTemplate tmpl;
  std::uint32_t first = UINT32_MAX;
  if (with_template && !w.regular_alpha.empty()) {
    for (std::uint32_t i = 0; i < nv; ++i)
      if (w.dist[i] > R + disc + 1) {  // every edge whose disc holds i is regular
        by_template[i] = 1;
        if (first == UINT32_MAX) first = i;
      }
    if (first != UINT32_MAX) tmpl = make_row_template(coarse, rings, first, disc, w.regular_alpha);
    // The pattern is read off a plain lattice patch, so a row whose neighbourhood closes on
    // itself shows as a vertex labelled twice.
    if (first != UINT32_MAX && tmpl.slots.empty()) {
      first = UINT32_MAX;
      std::fill(by_template.begin(), by_template.end(), 0);
    }
  }
  const bool templated = first != UINT32_MAX;
  // The edges whose discs can hold a vertex listed term by term, and their discs.
  std::vector<std::uint32_t> edges;
  for (std::uint32_t e = 0; e < ne; ++e)
    if (!templated || std::min(w.dist[coarse.edge_verts[2 * e]], w.dist[coarse.edge_verts[2 * e + 1]]) <= R + 2 * disc + 1)
      edges.push_back(e);
  const auto m = static_cast<std::uint32_t>(edges.size());
  std::vector<std::uint32_t> offset(std::size_t(m) + 1, 0);
  const auto regular_size = static_cast<std::uint32_t>(w.regular_alpha.size());
  for (std::uint32_t k = 0; k < m; ++k) {
    const std::uint32_t e = edges[k];
    offset[k + 1] = offset[k] + (w.regular[e] ? regular_size : static_cast<std::uint32_t>(w.discs[w.irregular_at[e]].size()));
  }
  UninitVector<std::uint32_t> disc_of(offset[m]);  // every entry is written (in parallel, below)
  std::atomic<bool> mismatch{false};
  parallel_for(m, 1024, [&](std::uint32_t begin, std::uint32_t end) {
    thread_local LocalOrder o;
    for (std::uint32_t k = begin; k < end; ++k) {
      const std::uint32_t e = edges[k];
      if (!w.regular[e]) {
        const auto& d = w.discs[w.irregular_at[e]];
        std::copy(d.begin(), d.end(), disc_of.data() + offset[k]);
        continue;
      }
      edge_disc(coarse, rings, e, disc, o);
      if (o.vertex.size() != regular_size) {
        mismatch = true;
        continue;
      }
      std::copy(o.vertex.begin(), o.vertex.end(), disc_of.data() + offset[k]);
    }
  });
  if (mismatch) throw std::logic_error("tri_transform: a regular edge's disc has an unexpected size");
  const auto alpha_of = [&](std::uint32_t e) {
    return w.regular[e] ? w.regular_alpha.data() : w.alphas[w.irregular_at[e]]->data();
  };

  // Terms listed one by one: a counting sort of the edges' entries by old vertex, over kBlocks
  // blocks of edges, each block counted and placed by its own thread after the prefix sums (so
  // entries of a row stay in edge order).
  constexpr std::uint32_t kBlocks = 4;
  const std::uint32_t per_block = (m + kBlocks - 1) / kBlocks;
  std::vector<std::uint32_t> fill(std::size_t(kBlocks) * nv, 0);  // block-major: count, then place
  parallel_for(kBlocks, 1, [&](std::uint32_t b0, std::uint32_t b1) {
    for (std::uint32_t blk = b0; blk < b1; ++blk) {
      std::uint32_t* count = fill.data() + std::size_t(blk) * nv;
      const std::uint32_t k0 = std::min(m, blk * per_block), k1 = std::min(m, k0 + per_block);
      for (std::uint32_t q = offset[k0]; q < offset[k1]; ++q)
        if (!by_template[disc_of[q]]) ++count[disc_of[q]];
    }
  });
  const auto T = static_cast<std::uint32_t>(tmpl.slots.size());
  // Row i's entry p (a source) has its weight at p - shift[i]: the template rows' own weights
  // are the pattern, so the listed terms' weights follow it, packed.
  std::vector<std::uint32_t> row_of(nv, UINT32_MAX), shift(nv, 0);
  up.target.reserve(nv);
  up.sources.offsets.reserve(std::size_t(nv) + 1);
  if (templated) up.weight_at.reserve(nv);
  std::uint32_t listed = 0;  // terms listed one by one so far
  {
    std::uint32_t at = 0;
    for (std::uint32_t i = 0; i < nv; ++i) {
      const std::uint32_t row_start = at;
      if (by_template[i]) {
        at += T;
      } else {
        for (std::uint32_t blk = 0; blk < kBlocks; ++blk) {
          std::uint32_t& c = fill[std::size_t(blk) * nv + i];
          const std::uint32_t n = c;
          c = at;
          at += n;
        }
      }
      if (at == row_start) continue;
      row_of[i] = static_cast<std::uint32_t>(up.target.size());
      up.target.push_back(i);
      up.sources.offsets.push_back(at);
      if (!templated) continue;
      if (by_template[i]) {
        up.weight_at.push_back(0);
      } else {
        up.weight_at.push_back(T + listed);
        // Sources before this row minus weights before it; unsigned, so a row before every
        // template row wraps round 2^32 and p - shift still lands right.
        shift[i] = row_start - (T + listed);
        listed += at - row_start;
      }
    }
  }
  up.sources.items.resize(up.sources.offsets.back());
  if (templated) {
    up.weights.resize(std::size_t(T) + listed);
    std::copy(tmpl.weights.begin(), tmpl.weights.end(), up.weights.begin());
  } else {
    up.weights.resize(up.sources.items.size());
  }
  // The template rows, in parallel.
  std::atomic<bool> misfit{false};
  if (templated)
    parallel_for(nv, 2048, [&](std::uint32_t begin, std::uint32_t end) {
      thread_local LocalOrder o;
      for (std::uint32_t i = begin; i < end && !misfit; ++i)
        if (by_template[i] &&
            !fill_template_row(rings, tmpl, i, nv, o, up.sources.items.data() + up.sources.offsets[row_of[i]]))
          misfit = true;
    });
  if (misfit) return false;
  // The listed terms.
  parallel_for(kBlocks, 1, [&](std::uint32_t b0, std::uint32_t b1) {
    for (std::uint32_t blk = b0; blk < b1; ++blk) {
      std::uint32_t* place = fill.data() + std::size_t(blk) * nv;
      const std::uint32_t k0 = std::min(m, blk * per_block), k1 = std::min(m, k0 + per_block);
      for (std::uint32_t k = k0; k < k1; ++k) {
        const std::uint32_t e = edges[k];
        const double* alpha = alpha_of(e);
        for (std::uint32_t q = offset[k]; q < offset[k + 1]; ++q) {
          const std::uint32_t i = disc_of[q];
          if (by_template[i]) continue;
          const std::uint32_t p = place[i]++;
          up.sources.items[p] = nv + e;
          up.weights[p - shift[i]] = -alpha[q - offset[k]];
        }
      }
    }
  });
  return true;
}

// Per irregular edge its anchored key (TriWaveletBuilder::anchor_type), UINT64_MAX where there
// is none; empty where anchors do not pay, fewer than `per_anchor` edges each: an anchor's
// signature costs about (2R + 1)^2 / R^2, 4-5 edges' ones, so they serve where the irregular
// vertices are few and far apart (every deep level). An edge's anchor is the irregular vertex nearest to its nearer end
// (within R). An anchor type is kept when a second anchor here has it or when it is alone in its
// neighbourhood (the same vertex then has the same type a level finer): a fitted base's
// crowded irregular vertices are mostly unique and stay with their edges' own keys.
std::vector<std::uint64_t> anchored_keys(TriWaveletBuilder& b, const Complex& coarse, const TriRings& rings,
                                         const std::vector<std::uint8_t>& dist, const std::vector<std::uint32_t>& nearest,
                                         const std::vector<std::uint32_t>& irregular, std::uint32_t per_anchor) {
  if (per_anchor == 0) return {};
  const std::uint32_t n = static_cast<std::uint32_t>(irregular.size());
  std::vector<std::uint32_t> anchor_of(n), anchors, anchor_slot(coarse.num_vertices, UINT32_MAX);
  for (std::uint32_t k = 0; k < n; ++k) {
    const std::uint32_t a = coarse.edge_verts[2 * irregular[k]], bb = coarse.edge_verts[2 * irregular[k] + 1];
    const std::uint32_t v = dist[a] <= dist[bb] ? nearest[a] : nearest[bb];
    if (anchor_slot[v] == UINT32_MAX) {
      anchor_slot[v] = static_cast<std::uint32_t>(anchors.size());
      anchors.push_back(v);
    }
    anchor_of[k] = anchor_slot[v];
  }
  if (anchors.empty() || n < std::size_t(per_anchor) * anchors.size()) return {};
  // Edges grouped by anchor.
  Csr edges_of;
  edges_of.offsets.assign(anchors.size() + 1, 0);
  for (std::uint32_t k = 0; k < n; ++k) ++edges_of.offsets[anchor_of[k] + 1];
  for (std::size_t i = 0; i < anchors.size(); ++i) edges_of.offsets[i + 1] += edges_of.offsets[i];
  edges_of.items.resize(n);
  {
    std::vector<std::uint32_t> place(edges_of.offsets.begin(), edges_of.offsets.end() - 1);
    for (std::uint32_t k = 0; k < n; ++k) edges_of.items[place[anchor_of[k]]++] = k;
  }
  // Each anchor's signature, and its edges' ends as labels of its order (20 bits each).
  const int radius = 2 * b.signature_radius() + 1;
  std::vector<std::string> signature(anchors.size());
  std::vector<std::uint8_t> alone(anchors.size(), 1);
  std::vector<std::uint64_t> labels(n, UINT64_MAX);
  std::atomic<bool> failed{false};
  parallel_for(static_cast<std::uint32_t>(anchors.size()), 1, [&](std::uint32_t begin, std::uint32_t end) {
    thread_local LocalOrder order;
    thread_local EpochTable label;
    try {
      for (std::uint32_t i = begin; i < end; ++i) {
        const std::uint32_t seeds[1] = {anchors[i]}, starts[1] = {rings.ring.row(anchors[i])[0]};
        local_order_and_key(coarse, rings, seeds, starts, radius, order, signature[i]);
        label.begin(coarse.num_vertices);
        for (std::uint32_t l = 0; l < order.vertex.size(); ++l) {
          label.set(order.vertex[l], l);
          if (l > 0 && dist[order.vertex[l]] == 0) alone[i] = 0;
        }
        for (std::uint32_t k : edges_of.row(i)) {
          const std::uint32_t la = label.get(coarse.edge_verts[2 * irregular[k]]);
          const std::uint32_t lb = label.get(coarse.edge_verts[2 * irregular[k] + 1]);
          if (la < (1u << 20) && lb < (1u << 20)) labels[k] = std::uint64_t(la) << 20 | lb;
        }
      }
    } catch (...) {
      failed = true;
    }
  });
  if (failed) return {};  // the edges' own keys follow and name a fault
  // Types in anchor order.
  std::unordered_map<std::string_view, std::uint32_t, SignatureHash> count;
  for (const std::string& sig : signature) ++count[sig];
  std::vector<std::uint64_t> type(anchors.size(), UINT64_MAX);
  for (std::size_t i = 0; i < anchors.size(); ++i) {
    if (!alone[i] && count[signature[i]] < 2 && !b.knows_anchor_type(signature[i])) continue;
    const std::uint32_t t = b.anchor_type(signature[i]);
    if (t < (1u << 24)) type[i] = std::uint64_t(t) << 40;
  }
  std::vector<std::uint64_t> out(n, UINT64_MAX);
  for (std::uint32_t k = 0; k < n; ++k)
    if (type[anchor_of[k]] != UINT64_MAX && labels[k] != UINT64_MAX) out[k] = type[anchor_of[k]] | labels[k];
  return out;
}

}  // namespace

TriTransitionResult build_tri_transition(const Complex& coarse, const Complex& fine, Scheme s, int disc,
                                         bool shared_rows, std::uint32_t edges_per_anchor,
                                         const std::vector<std::int32_t>* coarse_face_types) {
  const TriRings rings = build_tri_rings(coarse);
  TriStencils st = build_tri_stencils(coarse, s);  // moved into the steps at the end
  TriLevel level;
  level.coarse = &coarse;
  level.coarse_rings = &rings;
  level.fine = &fine;  // its rings are built only if a wavelet has to be solved
  level.stencils = &st;
  level.coarse_types = coarse_face_types;
  const std::uint32_t nv = coarse.num_vertices, ne = coarse.num_edges();
  TriTransitionResult out;
  Transition& t = out.transition;
  t.num_coarse = nv;
  t.num_fine = nv + ne;
  out.norm2.resize(ne);

  // Per edge its disc D (coarse vertices) and alpha. The regular edges, nearly all of a fine
  // level, share one alpha; the others are found by their neighbourhood's signature (keys
  // taken in parallel) or, when new, solved together (TriWaveletBuilder::solve), all under the
  // builders' lock.
  EdgeWavelets w;
  {
    const std::lock_guard<std::mutex> lock(builders_mutex);
    auto& slot = builders()[{static_cast<int>(s), disc}];
    if (!slot) slot = std::make_unique<TriWaveletBuilder>(s, disc);
    TriWaveletBuilder& b = *slot;
    w.radius = b.signature_radius();
    // Exact up to R + 2 disc + 1, the farthest an update row looks (update_rows).
    std::vector<std::uint32_t> nearest;
    w.dist = distance_to_irregular(coarse, rings, std::min(255, w.radius + 2 * disc + 2), &nearest);
    w.regular.resize(ne);
    w.irregular_at.assign(ne, UINT32_MAX);
    std::vector<std::uint32_t> irregular;
    for (std::uint32_t e = 0; e < ne; ++e) {
      w.regular[e] = std::min(w.dist[coarse.edge_verts[2 * e]], w.dist[coarse.edge_verts[2 * e + 1]]) > w.radius;
      if (!w.regular[e]) irregular.push_back(e);
    }
    // The regular wavelet (computed on the first regular edge unless cached).
    const EdgeWavelet* reg = nullptr;
    for (std::uint32_t e = 0; e < ne && !reg; ++e)
      if (w.regular[e]) {
        reg = &b.edge_wavelet(level, e, nullptr, true);
        w.regular_alpha = reg->alpha;
      }
    const std::vector<std::uint64_t> anchored =
        anchored_keys(b, coarse, rings, w.dist, nearest, irregular, edges_per_anchor);
    // Keys in parallel, each looked up at once (the cache is only read here): a found one
    // keeps no signature, so a deep level's thousands of known neighbourhoods allocate nothing.
    // A new one is kept once, however many edges have it (NewSignatures).
    // Edges of one anchored key have one wavelet: where the key is new, only its first edge
    // computes its signature and the others take that edge's wavelet (a level where the anchors
    // are first seen: the octahedron's six alike vertices key a sixth of their edges).
    std::vector<std::uint32_t> same_as(anchored.size(), UINT32_MAX);  // -> the first edge of its key
    {
      std::unordered_map<std::uint64_t, std::uint32_t> first;
      for (std::uint32_t k = 0; k < anchored.size(); ++k)
        if (anchored[k] != UINT64_MAX)
          if (const auto [it, fresh_key] = first.try_emplace(anchored[k], k); !fresh_key) same_as[k] = it->second;
    }
    w.discs.resize(irregular.size());  // each edge's disc, as its key or its anchored look-up finds it
    std::vector<const EdgeWavelet*> found(irregular.size(), nullptr);
    NewSignatures fresh;
    std::vector<NewSignatures::Entry*> fresh_of(irregular.size(), nullptr);
    std::atomic<bool> failed{false};
    std::atomic<std::uint32_t> anchored_hits{0};
    parallel_for(static_cast<std::uint32_t>(irregular.size()), 64, [&](std::uint32_t begin, std::uint32_t end) {
      thread_local std::string signature;
      thread_local LocalOrder disc_order;
      std::uint32_t hits = 0;
      try {
        for (std::uint32_t k = begin; k < end; ++k) {
          if (!anchored.empty() && anchored[k] != UINT64_MAX) {
            const EdgeWavelet* hit = b.find_anchored(anchored[k]);
            if (hit || same_as[k] != UINT32_MAX) {
              found[k] = hit;  // else taken from same_as[k] below
              hits += hit != nullptr;
              edge_disc(coarse, rings, irregular[k], disc, disc_order);
              w.discs[k] = disc_order.vertex;
              continue;
            }
          }
          b.edge_key(level, irregular[k], w.discs[k], signature);
          found[k] = b.find(signature);
          if (!found[k]) fresh_of[k] = fresh.add(signature, k);
        }
        anchored_hits += hits;
      } catch (...) {
        failed = true;
      }
    });
    if (failed) {  // the rings were checked, so this is a defect; the serial call names it
      for (std::uint32_t e : irregular) (void)b.edge_key(level, e);
      throw std::logic_error("tri_transform: an edge's neighbourhood could not be ordered");
    }
    for (std::uint32_t e = 0; e < ne; ++e)
      if (w.regular[e]) out.norm2[e] = reg->norm2;
    // The new neighbourhoods, each once (at its first edge, in edge order), solved together.
    {
      std::vector<std::string> signatures;
      std::vector<std::uint32_t> todo;
      std::vector<NewSignatures::Map::node_type> nodes = fresh.in_order();  // keeps fresh_of's entries
      for (auto& node : nodes) {
        todo.push_back(irregular[node.mapped().first]);
        signatures.push_back(std::move(node.key()));
      }
      const std::vector<const EdgeWavelet*> solved = b.solve(level, todo, signatures);
      for (std::uint32_t k = 0; k < irregular.size(); ++k)
        if (!found[k] && fresh_of[k]) found[k] = solved[fresh_of[k]->place];
      for (std::uint32_t k = 0; k < same_as.size(); ++k)  // first edges come first
        if (!found[k]) found[k] = found[same_as[k]];
    }
    for (std::size_t k = 0; k < anchored.size(); ++k)
      if (anchored[k] != UINT64_MAX) b.add_anchored(anchored[k], found[k]);  // kept if known
    out.anchored_edges = anchored_hits;
    out.fine_face_types = b.fine_face_types(level);
    w.alphas.resize(irregular.size());
    for (std::size_t k = 0; k < irregular.size(); ++k) {
      const std::uint32_t e = irregular[k];
      const EdgeWavelet& wave = *found[k];
      if (wave.alpha.size() != w.discs[k].size()) throw std::logic_error("tri_transform: disc and alpha sizes differ");
      w.irregular_at[e] = static_cast<std::uint32_t>(k);
      w.alphas[k] = &wave.alpha;
      out.norm2[e] = wave.norm2;
    }
  }
  WeightedStep up;
  if (!update_rows(coarse, rings, w, disc, shared_rows, up)) {
    up = WeightedStep{};
    update_rows(coarse, rings, w, disc, false, up);
  }
  WeightedStep predict;
  predict.target.resize(ne);
  for (std::uint32_t e = 0; e < ne; ++e) predict.target[e] = nv + e;
  predict.sources = std::move(st.new_rows);
  predict.weights = std::move(st.new_weights);
  t.add(std::move(up));
  t.add(std::move(predict));

  if (st.old_rows.rows() != 0) t.add(make_matrix_step(nv, std::move(st.old_rows), std::move(st.old_weights)));
  return out;
}

void loop_limit_rows(const Complex& c, Csr& rows, std::vector<double>& weights) {
  const std::uint32_t nv = c.num_vertices, ne = c.num_edges();
  std::vector<std::uint8_t> faces_of_edge(ne, 0);
  for (std::uint32_t e : c.face_edges.items) faces_of_edge[e] = static_cast<std::uint8_t>(std::min(2, faces_of_edge[e] + 1));
  const Csr vertex_edges = transpose_pairs(c.edge_verts, nv);
  rows.clear();
  weights.clear();
  std::vector<std::uint32_t> feature;
  for (std::uint32_t v = 0; v < nv; ++v) {
    feature.clear();
    const auto edges = vertex_edges.row(v);
    for (std::uint32_t e : edges)
      if (faces_of_edge[e] < 2 || (!c.edge_dim.empty() && c.edge_dim[e] == 1)) feature.push_back(e);
    const bool corner = feature.size() > 2 || edges.empty() || (!c.vertex_dim.empty() && c.vertex_dim[v] == 0);
    rows.items.push_back(v);
    if (corner) {
      weights.push_back(1.0);
    } else if (feature.size() == 2) {
      weights.push_back(2.0 / 3.0);
      for (std::uint32_t e : feature) {
        rows.items.push_back(edge_other_end(c, e, v));
        weights.push_back(1.0 / 6.0);
      }
    } else {
      const double n = double(edges.size());
      const double t = 0.375 + 0.25 * std::cos(2 * M_PI / n);
      const double beta = (0.625 - t * t) / n;
      const double g = 1.0 / (3.0 / (8.0 * beta) + n);
      weights.push_back(1.0 - n * g);
      for (std::uint32_t e : edges) {
        rows.items.push_back(edge_other_end(c, e, v));
        weights.push_back(g);
      }
    }
    rows.offsets.push_back(static_cast<std::uint32_t>(rows.items.size()));
  }
}

}  // namespace sublift
