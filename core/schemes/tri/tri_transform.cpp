#include "core/schemes/tri/tri_transform.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <map>
#include <mutex>

#include "core/base/parallel.h"
#include "core/schemes/tri/tri_local.h"
#include "core/schemes/tri/tri_wavelets.h"

namespace sublift {

namespace {

std::mutex builders_mutex;
std::map<std::pair<int, int>, std::unique_ptr<TriWaveletBuilder>>& builders() {
  static std::map<std::pair<int, int>, std::unique_ptr<TriWaveletBuilder>> b;
  return b;
}

}  // namespace

TriTransitionResult build_tri_transition(const Complex& coarse, const Complex& fine, Scheme s, int disc) {
  const TriRings rings = build_tri_rings(coarse);
  const TriStencils st = build_tri_stencils(coarse, s);
  std::unique_ptr<TriRings> fine_rings;  // built when an edge first needs its neighbourhood
  TriLevel level;
  level.coarse = &coarse;
  level.coarse_rings = &rings;
  level.fine = &fine;
  level.stencils = &st;
  const std::uint32_t nv = coarse.num_vertices, ne = coarse.num_edges();
  TriTransitionResult out;
  Transition& t = out.transition;
  t.num_coarse = nv;
  t.num_fine = nv + ne;
  out.norm2.resize(ne);

  // Update: old vertex i gets -alpha_{i,m} d_m. Per edge its disc D (coarse vertices) and
  // alpha; irregular edges are solved (or found cached) under the builders' lock, the regular
  // ones, nearly all of a fine level, share one alpha and only list their disc, in parallel.
  std::vector<std::uint8_t> regular(ne, 0);
  std::vector<std::uint32_t> offset(std::size_t(ne) + 1, 0);
  std::vector<std::uint32_t> disc_items;
  std::vector<double> alpha_items;
  std::vector<double> regular_alpha;
  {
    const std::lock_guard<std::mutex> lock(builders_mutex);
    auto& slot = builders()[{static_cast<int>(s), disc}];
    if (!slot) slot = std::make_unique<TriWaveletBuilder>(s, disc);
    TriWaveletBuilder& b = *slot;
    const int R = b.signature_radius();
    const std::vector<std::uint8_t> dist = distance_to_irregular(coarse, rings, R + 1);
    for (std::uint32_t e = 0; e < ne; ++e)
      regular[e] = std::min(dist[coarse.edge_verts[2 * e]], dist[coarse.edge_verts[2 * e + 1]]) > R ? 1 : 0;
    const auto need_fine_rings = [&] {
      if (fine_rings) return;
      fine_rings = std::make_unique<TriRings>(build_tri_rings(fine));
      level.fine_rings = fine_rings.get();
    };
    // The regular wavelet (computed on the first regular edge unless cached).
    const EdgeWavelet* reg = nullptr;
    for (std::uint32_t e = 0; e < ne && !reg; ++e)
      if (regular[e]) {
        if (!b.has_regular()) need_fine_rings();
        reg = &b.edge_wavelet(level, e, nullptr, true);
        regular_alpha = reg->alpha;
      }
    std::vector<std::uint32_t> d;
    for (std::uint32_t e = 0; e < ne; ++e) {
      if (regular[e]) {
        offset[e + 1] = static_cast<std::uint32_t>(regular_alpha.size());
        out.norm2[e] = reg->norm2;
        continue;
      }
      need_fine_rings();
      const EdgeWavelet& w = b.edge_wavelet(level, e, &d, false);
      if (w.alpha.size() != d.size()) throw std::logic_error("tri_transform: disc and alpha sizes differ");
      offset[e + 1] = static_cast<std::uint32_t>(d.size());
      disc_items.insert(disc_items.end(), d.begin(), d.end());
      alpha_items.insert(alpha_items.end(), w.alpha.begin(), w.alpha.end());
      out.norm2[e] = w.norm2;
    }
  }
  // Flat per-edge lists: irregular edges' entries move into place, regular ones are listed.
  for (std::uint32_t e = 0; e < ne; ++e) offset[e + 1] += offset[e];
  std::vector<std::uint32_t> disc_of(offset[ne]);
  std::vector<double> alpha_of(offset[ne]);
  {
    std::size_t k = 0;
    for (std::uint32_t e = 0; e < ne; ++e)
      if (!regular[e]) {
        std::copy_n(disc_items.begin() + static_cast<std::ptrdiff_t>(k), offset[e + 1] - offset[e], disc_of.begin() + offset[e]);
        std::copy_n(alpha_items.begin() + static_cast<std::ptrdiff_t>(k), offset[e + 1] - offset[e], alpha_of.begin() + offset[e]);
        k += offset[e + 1] - offset[e];
      }
  }
  const int k_disc = disc;
  std::atomic<bool> mismatch{false};
  parallel_for(ne, 4096, [&](std::uint32_t begin, std::uint32_t end) {
    for (std::uint32_t e = begin; e < end; ++e) {
      if (!regular[e]) continue;
      const std::uint32_t seeds[2] = {coarse.edge_verts[2 * e], coarse.edge_verts[2 * e + 1]};
      const std::uint32_t starts[2] = {seeds[1], seeds[0]};
      const LocalOrder o = local_order(rings, seeds, starts, k_disc);
      if (o.vertex.size() != offset[e + 1] - offset[e]) {
        mismatch = true;
        continue;
      }
      std::copy(o.vertex.begin(), o.vertex.end(), disc_of.begin() + offset[e]);
      std::copy(regular_alpha.begin(), regular_alpha.end(), alpha_of.begin() + offset[e]);
    }
  });
  if (mismatch) throw std::logic_error("tri_transform: a regular edge's disc has an unexpected size");
  // Rows by old vertex: a counting sort (entries of one row stay in edge order).
  std::vector<std::uint32_t> start(std::size_t(nv) + 1, 0);
  for (std::uint32_t i : disc_of) ++start[i + 1];
  for (std::uint32_t i = 0; i < nv; ++i) start[i + 1] += start[i];
  std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
  std::vector<std::uint32_t> items(disc_of.size());
  std::vector<double> weights(disc_of.size());
  for (std::uint32_t e = 0; e < ne; ++e)
    for (std::uint32_t q = offset[e]; q < offset[e + 1]; ++q) {
      const std::uint32_t i = disc_of[q];
      items[fill[i]] = nv + e;
      weights[fill[i]++] = -alpha_of[q];
    }
  WeightedStep up;
  up.target.reserve(nv);
  up.sources.items.reserve(items.size());
  up.weights.reserve(items.size());
  for (std::uint32_t i = 0; i < nv; ++i) {
    if (start[i] == start[i + 1]) continue;
    up.target.push_back(i);
    up.sources.items.insert(up.sources.items.end(), items.begin() + start[i], items.begin() + start[i + 1]);
    up.weights.insert(up.weights.end(), weights.begin() + start[i], weights.begin() + start[i + 1]);
    up.sources.offsets.push_back(static_cast<std::uint32_t>(up.sources.items.size()));
  }
  WeightedStep predict;
  predict.target.resize(ne);
  for (std::uint32_t e = 0; e < ne; ++e) predict.target[e] = nv + e;
  predict.sources = st.new_rows;
  predict.weights = st.new_weights;
  t.add(std::move(up));
  t.add(std::move(predict));

  if (st.old_rows.rows() != 0) t.add(make_matrix_step(nv, st.old_rows, st.old_weights));
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
