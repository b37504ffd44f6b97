#include "core/edit/session.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <unordered_map>

#include "core/base/stopwatch.h"
#include "core/edit/detail_frames.h"
#include "core/base/errors.h"
#include "core/io/project/project_io.h"
#include "core/complex/refine.h"

namespace sublift {
namespace {

// History block ids: positions of level l use l; these two follow.
constexpr int kCoeffs = 100;
constexpr int kLocal = 101;

}  // namespace

std::size_t HistoryEntry::bytes() const {
  std::size_t b = sizeof(HistoryEntry) + label.size();
  for (const Block& k : blocks) b += k.vertices.size() * 4 + (k.before.size() + k.after.size()) * 8;
  return b;
}

Session::Session(Hierarchy h, std::vector<double> gains) : h_(std::move(h)) {
  if (h_.channels != 3) throw Error("the modeler edits x, y, z: this hierarchy has " + std::to_string(h_.channels) + " channels");
  if (h_.integer) throw Error("integer-mode hierarchies cannot be edited (their rounding is not linear); analyse the shape without --integer");
  Complex& finest = h_.levels.back();
  if (finest.vertex_edges.rows() != finest.num_vertices) build_adjacency(finest);
  const int J = h_.finest_level();
  if (gains.empty()) gains.assign(static_cast<std::size_t>(J), 1.0);
  if (gains.size() != static_cast<std::size_t>(J))
    throw Error("one gain per level 0.." + std::to_string(J - 1) + " is needed, got " + std::to_string(gains.size()));
  for (const double g : gains)
    if (!std::isfinite(g)) throw Error("a detail gain is not finite");
  gains_ = std::move(gains);
  for (const Transition& t : h_.transitions) sparse_index_.push_back(build_sparse_index(t));
  pos_.resize(static_cast<std::size_t>(J) + 1);
  pos_[0].assign(h_.coeffs.begin(), h_.coeffs.begin() + std::size_t(num_vertices(0)) * 3);
  resynthesize_from(0);
  deltas_.resize(pos_.size());
  changed_.resize(pos_.size());
  set_all_changed(0);
}

double* Session::array_ptr(int array) {
  if (array == kCoeffs) return h_.coeffs.data();
  if (array == kLocal) return local_.data();
  return pos_.at(static_cast<std::size_t>(array)).data();
}

void Session::resynthesize_from(int level) {
  for (int l = level; l < finest_level(); ++l) resynthesize_one(l);
}

void Session::resynthesize_one(int l) {
  const std::size_t nl = std::size_t(num_vertices(l)) * 3, nn = std::size_t(num_vertices(l + 1)) * 3;
  std::vector<double>& x = pos_[static_cast<std::size_t>(l) + 1];
  x.resize(nn);
  std::copy(pos_[static_cast<std::size_t>(l)].begin(), pos_[static_cast<std::size_t>(l)].end(), x.begin());
  const double g = gains_[static_cast<std::size_t>(l)];
  bool zero = true;
  for (std::size_t i = nl; i < nn; ++i) {
    x[i] = g * h_.coeffs[i];
    zero &= x[i] == 0.0;
  }
  synthesize_transition(h_, l, x.data(), 3, false, zero);
}

const ChildSites* Session::sites(int l) const {
  return h_.sites.empty() ? nullptr : &h_.sites[static_cast<std::size_t>(l)];
}

void Session::synthesize_sparse(int l, SparseDelta& d) {
  const auto L = static_cast<std::size_t>(l);
  run_synthesis_sparse(h_.transitions[L], h_.levels[L], sparse_index_[L], d);
}

void Session::analyze_sparse(int l, SparseDelta& d) {
  const auto L = static_cast<std::size_t>(l);
  run_analysis_sparse(h_.transitions[L], h_.levels[L], sparse_index_[L], d);
}

void Session::clear_changed() {
  for (auto& c : changed_) c.clear();
}

void Session::set_all_changed(int from_level) {
  for (int l = 0; l <= finest_level(); ++l) {
    auto& c = changed_[static_cast<std::size_t>(l)];
    c.clear();
    if (l >= from_level) {
      c.resize(num_vertices(l));
      for (std::uint32_t v = 0; v < num_vertices(l); ++v) c[v] = v;
    }
  }
}

void Session::check_gain_below(int level) const {
  for (int l = 0; l < level; ++l)
    if (gains_[static_cast<std::size_t>(l)] == 0.0)
      throw Error("the detail gain of level " + std::to_string(l) +
                  " is 0: an edit at level " + std::to_string(level) +
                  " would fold detail back into that muted band; set its gain first");
}

// ---- history ---------------------------------------------------------------------------------

void Session::begin_edit(const std::string& label) {
  if (open_) end_edit();
  open_ = std::make_unique<HistoryEntry>();
  open_->label = label;
  ++stamp_;
  if (stamp_ == 0) {  // wrapped: forget old stamps
    for (auto& t : touched_) std::fill(t.begin(), t.end(), 0u);
    stamp_ = 1;
  }
}

void Session::record(int array, std::uint32_t v) {
  if (!open_) return;
  const std::size_t slot = array == kCoeffs ? touched_.size() - 2 : array == kLocal ? touched_.size() - 1 : static_cast<std::size_t>(array);
  std::vector<std::uint32_t>& t = touched_[slot];
  if (t[v] == stamp_) return;
  t[v] = stamp_;
  HistoryEntry::Block* b = nullptr;
  for (auto& k : open_->blocks)
    if (k.array == array) b = &k;
  if (!b) {
    open_->blocks.push_back({array, {}, {}, {}});
    b = &open_->blocks.back();
  }
  b->vertices.push_back(v);
  const double* p = array_ptr(array) + std::size_t(v) * 3;
  b->before.insert(b->before.end(), p, p + 3);
}

void Session::end_edit() {
  if (!open_) return;
  std::unique_ptr<HistoryEntry> e = std::move(open_);
  bool changed = e->gain_level >= 0 || e->levels_before >= 0;
  for (auto& b : e->blocks) {
    const double* base = array_ptr(b.array);
    b.after.resize(b.before.size());
    for (std::size_t k = 0; k < b.vertices.size(); ++k)
      std::memcpy(&b.after[3 * k], base + std::size_t(b.vertices[k]) * 3, 3 * sizeof(double));
    changed |= std::memcmp(b.before.data(), b.after.data(), b.before.size() * sizeof(double)) != 0;
  }
  if (changed) push_entry(std::move(*e));
}

void Session::cancel_edit() {
  if (!open_) return;
  std::unique_ptr<HistoryEntry> e = std::move(open_);
  for (auto& b : e->blocks) b.after = b.before;  // apply_entry reads `before` when going back
  apply_entry(*e, false);
}

void Session::push_entry(HistoryEntry e) {
  history_.resize(undo_pos_);
  if (saved_pos_ > undo_pos_) saved_invalid_ = true;
  history_.push_back(std::move(e));
  undo_pos_ = history_.size();
  std::size_t total = 0;
  for (const auto& h : history_) total += h.bytes();
  std::size_t drop = 0;
  while (drop + 1 < history_.size() && total > history_limit_) total -= history_[drop++].bytes();
  if (drop) {
    history_.erase(history_.begin(), history_.begin() + static_cast<std::ptrdiff_t>(drop));
    undo_pos_ -= drop;
    if (saved_pos_ < drop) saved_invalid_ = true;
    saved_pos_ = saved_pos_ >= drop ? saved_pos_ - drop : 0;
  }
}

double Session::prepare_edit_buffers() {
  const auto t0 = std::chrono::steady_clock::now();
  bool sized = false;
  const auto size = [&](std::vector<std::uint32_t>& t, std::uint32_t n) {
    if (t.size() != n) t.resize(n, 0u), sized = true;
  };
  touched_.resize(static_cast<std::size_t>(finest_level()) + 3);
  for (int l = 0; l <= finest_level(); ++l) {
    size(touched_[static_cast<std::size_t>(l)], num_vertices(l));
    SparseDelta& d = deltas_[static_cast<std::size_t>(l)];
    if (d.x.size() != std::size_t(num_vertices(l)) * 3) d.reset(num_vertices(l)), sized = true;
  }
  size(touched_[touched_.size() - 2], num_vertices(finest_level()));
  size(touched_[touched_.size() - 1], num_vertices(finest_level()));
  return sized ? ms_since(t0) : 0.0;
}

// ---- edits -----------------------------------------------------------------------------------

OpReport Session::move(int level, std::span<const std::uint32_t> vertices, std::span<const double> weights,
                       const double delta[3]) {
  return move_impl(level, vertices, weights, {delta, 3}, false);
}

OpReport Session::move_each(int level, std::span<const std::uint32_t> vertices, std::span<const double> deltas) {
  if (deltas.size() != 3 * vertices.size()) throw Error("three delta values per vertex are needed");
  return move_impl(level, vertices, {}, deltas, false);
}

OpReport Session::move_full(int level, std::span<const std::uint32_t> vertices, std::span<const double> weights,
                            const double delta[3]) {
  return move_impl(level, vertices, weights, {delta, 3}, true);
}

void Session::update_local(int l, std::span<const std::uint32_t> changed_pos, std::span<const std::uint32_t> changed_coeffs,
                           SparseDelta* out) {
  // Wavelets of level l whose frame reads a changed control point of level l, and those whose
  // world value changed: their local components (out == nullptr: fold-back, world is given) or
  // their world value (out != nullptr: synthesis, local is given; the change goes to out).
  const Complex& parent = h_.levels[static_cast<std::size_t>(l)];
  frame_list_.clear();
  if (frame_stamp_.size() < num_vertices(l + 1)) frame_stamp_.resize(num_vertices(l + 1), 0u);
  ++frame_epoch_;
  frames_reading(parent, changed_pos, frame_list_, frame_stamp_, frame_epoch_, sites(l));
  for (const std::uint32_t u : changed_coeffs)
    if (u >= num_vertices(l) && frame_stamp_[u] != frame_epoch_) {
      frame_stamp_[u] = frame_epoch_;
      frame_list_.push_back(u);
    }
  const double* p = pos_[static_cast<std::size_t>(l)].data();
  const double g = gains_[static_cast<std::size_t>(l)];
  for (const std::uint32_t u : frame_list_) {
    double f[9];
    wavelet_frame(parent, p, u, f, sites(l));
    double* w = &h_.coeffs[std::size_t(u) * 3];
    double* loc = &local_[std::size_t(u) * 3];
    if (out) {
      double nw[3];
      frame_to_world(f, loc, nw);
      if (nw[0] == w[0] && nw[1] == w[1] && nw[2] == w[2]) continue;
      record(kCoeffs, u);
      double* d = out->at(u);
      for (int c = 0; c < 3; ++c) {
        d[c] += g * (nw[c] - w[c]);
        w[c] = nw[c];
      }
    } else {
      double nl[3];
      frame_to_local(f, w, nl);
      if (nl[0] == loc[0] && nl[1] == loc[1] && nl[2] == loc[2]) continue;
      record(kLocal, u);
      std::memcpy(loc, nl, sizeof nl);
    }
  }
}

OpReport Session::move_impl(int level, std::span<const std::uint32_t> vertices, std::span<const double> weights,
                            std::span<const double> deltas, bool full) {
  const int J = finest_level();
  if (level < 0 || level > J) throw Error("level " + std::to_string(level) + " is outside 0.." + std::to_string(J));
  if (!weights.empty() && weights.size() != vertices.size()) throw Error("one weight per vertex is needed");
  for (const std::uint32_t v : vertices)
    if (v >= num_vertices(level))
      throw Error("vertex " + std::to_string(v) + " is not on level " + std::to_string(level) + " (it has " +
                  std::to_string(num_vertices(level)) + ")");
  for (const double d : deltas)
    if (!std::isfinite(d)) throw Error("the move is not finite");
  // One delta for every vertex (3 values) or one per vertex (move_each).
  const bool per_vertex = deltas.size() != 3 || vertices.size() == 1;
  check_gain_below(level);
  const bool own_entry = !open_;
  if (own_entry) begin_edit("Move");
  const double setup_ms = prepare_edit_buffers();
  const auto t0 = std::chrono::steady_clock::now();
  clear_changed();
  const bool local = frames_ == DetailFrames::Local;

  // The change of level `level`.
  SparseDelta& D = deltas_[static_cast<std::size_t>(level)];
  D.reset(num_vertices(level));
  for (std::size_t k = 0; k < vertices.size(); ++k) {
    const double w = weights.empty() ? 1.0 : weights[k];
    const double* delta = &deltas[per_vertex ? 3 * k : 0];
    double* d = D.at(vertices[k]);
    for (int c = 0; c < 3; ++c) d[c] += w * delta[c];
  }
  std::vector<double>& P = pos_[static_cast<std::size_t>(level)];
  for (const std::uint32_t v : D.list) {
    record(level, v);
    for (int c = 0; c < 3; ++c) P[3 * std::size_t(v) + c] += D.x[3 * std::size_t(v) + c];
  }
  changed_[static_cast<std::size_t>(level)] = D.list;

  if (full) {
    fold_back_dense(level);
    // Levels above: record everything they hold, then synthesise densely.
    for (int l = level + 1; l <= J; ++l)
      for (std::uint32_t v = 0; v < num_vertices(l); ++v) record(l, v);
    for (int l = level; l < J; ++l) {
      if (local) update_local_world_dense(l);
      resynthesize_one(l);
    }
    set_all_changed(0);
  } else {
    // Upwards: synthesise the change, level by level.
    for (int l = level; l < J; ++l) {
      SparseDelta& src = deltas_[static_cast<std::size_t>(l)];
      SparseDelta& dst = deltas_[static_cast<std::size_t>(l) + 1];
      dst.reset(num_vertices(l + 1));
      for (const std::uint32_t v : src.list) std::memcpy(dst.at(v), &src.x[3 * std::size_t(v)], 3 * sizeof(double));
      if (local) update_local(l, src.list, {}, &dst);
      if (l != level) src.clear();
      synthesize_sparse(l, dst);
      std::vector<double>& Q = pos_[static_cast<std::size_t>(l) + 1];
      for (const std::uint32_t v : dst.list) {
        record(l + 1, v);
        for (int c = 0; c < 3; ++c) Q[3 * std::size_t(v) + c] += dst.x[3 * std::size_t(v) + c];
      }
      changed_[static_cast<std::size_t>(l) + 1] = dst.list;
    }
    if (level < J) deltas_[static_cast<std::size_t>(J)].clear();
    fold_back_sparse(level);
  }
  // Level 0's control points are the scaling coefficients the project stores.
  for (const std::uint32_t v : changed_[0]) {
      record(kCoeffs, v);
      std::memcpy(&h_.coeffs[3 * std::size_t(v)], &pos_[0][3 * std::size_t(v)], 3 * sizeof(double));
    }

  report_ = {};
  report_.resynthesis_ms = ms_since(t0);
  report_.setup_ms = setup_ms;
  report_.full = full;
  report_.from_level = full ? 0 : level;
  for (const auto& c : changed_) report_.vertices_updated += c.size();
  if (own_entry) end_edit();
  return report_;
}

// Analyses the change of level `level` (in deltas_[level]) down to level 0: coarser control
// points and the wavelets of the levels below take it up.
void Session::fold_back_sparse(int level) {
  const bool local = frames_ == DetailFrames::Local;
  for (int l = level - 1; l >= 0; --l) {
    SparseDelta& cur = deltas_[static_cast<std::size_t>(l) + 1];
    analyze_sparse(l, cur);
    SparseDelta& next = deltas_[static_cast<std::size_t>(l)];
    next.reset(num_vertices(l));
    const std::uint32_t nl = num_vertices(l);
    const double g = gains_[static_cast<std::size_t>(l)];
    std::vector<double>& Q = pos_[static_cast<std::size_t>(l)];
    coeff_list_.clear();
    for (const std::uint32_t v : cur.list) {
      const double* d = &cur.x[3 * std::size_t(v)];
      if (v < nl) {
        std::memcpy(next.at(v), d, 3 * sizeof(double));
        record(l, v);
        for (int c = 0; c < 3; ++c) Q[3 * std::size_t(v) + c] += d[c];
      } else {
        record(kCoeffs, v);
        for (int c = 0; c < 3; ++c) h_.coeffs[3 * std::size_t(v) + c] += d[c] / g;
        coeff_list_.push_back(v);
      }
    }
    cur.clear();
    changed_[static_cast<std::size_t>(l)] = next.list;
    if (local) update_local(l, next.list, coeff_list_, nullptr);
  }
  deltas_[0].clear();
}

// The reference path: the whole of level `level` analysed down to level 0.
void Session::fold_back_dense(int level) {
  if (level == 0) return;
  std::vector<double> x = pos_[static_cast<std::size_t>(level)];
  for (int l = level - 1; l >= 0; --l) analyze_transition(h_, l, x.data(), 3, false);
  for (std::uint32_t v = 0; v < num_vertices(level); ++v) record(kCoeffs, v);
  for (int l = 0; l < level; ++l) {
    const double g = gains_[static_cast<std::size_t>(l)];
    for (std::size_t i = std::size_t(num_vertices(l)) * 3; i < std::size_t(num_vertices(l + 1)) * 3; ++i)
      h_.coeffs[i] = x[i] / g;
  }
  for (int l = 0; l < level; ++l)
    for (std::uint32_t v = 0; v < num_vertices(l); ++v) record(l, v);
  std::copy(x.begin(), x.begin() + std::size_t(num_vertices(0)) * 3, h_.coeffs.begin());
  pos_[0].assign(x.begin(), x.begin() + std::size_t(num_vertices(0)) * 3);
  resynthesize_levels_below(level);
  if (frames_ == DetailFrames::Local)
    for (int l = 0; l < level; ++l) local_from_world_dense(l);
}

// Levels 1..level-1 from level 0 and the coefficients (level itself is kept as edited).
void Session::resynthesize_levels_below(int level) {
  for (int l = 0; l + 1 < level; ++l) resynthesize_one(l);
}

void Session::local_from_world_dense(int l) {
  const Complex& parent = h_.levels[static_cast<std::size_t>(l)];
  const double* p = pos_[static_cast<std::size_t>(l)].data();
  for (std::uint32_t u = num_vertices(l); u < num_vertices(l + 1); ++u) {
    double f[9];
    wavelet_frame(parent, p, u, f, sites(l));
    record(kLocal, u);
    frame_to_local(f, &h_.coeffs[3 * std::size_t(u)], &local_[3 * std::size_t(u)]);
  }
}

void Session::update_local_world_dense(int l) {
  const Complex& parent = h_.levels[static_cast<std::size_t>(l)];
  const double* p = pos_[static_cast<std::size_t>(l)].data();
  for (std::uint32_t u = num_vertices(l); u < num_vertices(l + 1); ++u) {
    double f[9];
    wavelet_frame(parent, p, u, f, sites(l));
    record(kCoeffs, u);
    frame_to_world(f, &local_[3 * std::size_t(u)], &h_.coeffs[3 * std::size_t(u)]);
  }
}

// ---- gains, levels, frames -------------------------------------------------------------------

OpReport Session::set_gain(int level, double factor) {
  if (level < 0 || level >= finest_level())
    throw Error("gain level " + std::to_string(level) + " is outside 0.." + std::to_string(finest_level() - 1));
  if (!std::isfinite(factor)) throw Error("the gain is not finite");
  const auto t0 = std::chrono::steady_clock::now();
  const bool own_entry = !open_;
  if (own_entry) begin_edit("Gain");
  if (open_->gain_level != level) {
    if (open_->gain_level >= 0) {  // a second gain in one group: close the first
      const std::string label = open_->label;
      end_edit();
      begin_edit(label);
    }
    open_->gain_level = level;
    open_->gain_before = gains_[static_cast<std::size_t>(level)];
  }
  open_->gain_after = factor;
  gains_[static_cast<std::size_t>(level)] = factor;
  resynthesize_from(level);
  set_all_changed(level + 1);
  report_ = {};
  report_.resynthesis_ms = ms_since(t0);
  report_.full = true;
  report_.from_level = level + 1;
  for (const auto& c : changed_) report_.vertices_updated += c.size();
  if (own_entry) {
    if (open_->gain_before == open_->gain_after) open_.reset();
    else end_edit();
  }
  return report_;
}

void Session::add_level() {
  append_level(h_, true);
  sparse_index_.push_back(build_sparse_index(h_.transitions.back()));
  const std::size_t n = std::size_t(h_.levels.back().num_vertices) * 3;
  h_.coeffs.resize(n, 0.0);
  if (!local_.empty()) local_.resize(n, 0.0);
  gains_.push_back(1.0);
  pos_.emplace_back();
  deltas_.emplace_back();
  changed_.emplace_back();
  resynthesize_from(finest_level() - 1);
  ++topology_version_;
}

void Session::remove_level() {
  pop_level(h_);
  sparse_index_.pop_back();
  const std::size_t n = std::size_t(h_.levels.back().num_vertices) * 3;
  h_.coeffs.resize(n);
  if (!local_.empty()) local_.resize(n);
  gains_.pop_back();
  pos_.pop_back();
  deltas_.pop_back();
  changed_.pop_back();
  ++topology_version_;
}

OpReport Session::subdivide(double max_vertices) {
  const int most = max_levels(h_.scheme);
  if (finest_level() >= most) throw Error("at most " + std::to_string(most) + " levels");
  const double next = predicted_level_counts(h_.levels.back(), 1, h_.scheme, h_.first_level + finest_level()).back();
  if (next > max_vertices)
    throw Error("level " + std::to_string(finest_level() + 1) + " would have " + std::to_string(static_cast<long long>(next)) +
                " vertices, more than the limit of " + std::to_string(static_cast<long long>(max_vertices)));
  if (open_) end_edit();
  const auto t0 = std::chrono::steady_clock::now();
  HistoryEntry e;
  e.label = "Subdivide";
  e.levels_before = finest_level();
  add_level();
  push_entry(std::move(e));
  set_all_changed(finest_level());
  report_ = {};
  report_.resynthesis_ms = ms_since(t0);
  report_.full = true;
  report_.from_level = finest_level();
  report_.vertices_updated = num_vertices(finest_level());
  return report_;
}

void Session::set_detail_frames(DetailFrames f) {
  if (f == frames_) return;
  if (f == DetailFrames::Local && dim() != 2)
    throw Error("local detail frames need a surface; " + std::string(dim() == 3 ? "a lattice" : "a curve") +
                " keeps its detail in world coordinates");
  if (open_) end_edit();
  frames_ = f;
  if (f == DetailFrames::World) {
    local_.clear();
    local_.shrink_to_fit();
    return;
  }
  local_.assign(h_.coeffs.size(), 0.0);
  for (int l = 0; l < finest_level(); ++l) {
    const Complex& parent = h_.levels[static_cast<std::size_t>(l)];
    const double* p = pos_[static_cast<std::size_t>(l)].data();
    for (std::uint32_t u = num_vertices(l); u < num_vertices(l + 1); ++u) {
      double fr[9];
      wavelet_frame(parent, p, u, fr, sites(l));
      frame_to_local(fr, &h_.coeffs[3 * std::size_t(u)], &local_[3 * std::size_t(u)]);
    }
  }
}

// ---- undo / redo -----------------------------------------------------------------------------

void Session::apply_entry(const HistoryEntry& e, bool forward) {
  clear_changed();
  report_ = {};
  const auto t0 = std::chrono::steady_clock::now();
  if (e.levels_before >= 0) {
    if (forward) add_level();
    else remove_level();
    set_all_changed(finest_level());
  }
  int lowest = finest_level() + 1;
  for (const auto& b : e.blocks) {
    if (b.array == kLocal && frames_ != DetailFrames::Local) continue;
    double* base = array_ptr(b.array);
    const std::vector<double>& vals = forward ? b.after : b.before;
    for (std::size_t k = 0; k < b.vertices.size(); ++k)
      std::memcpy(base + std::size_t(b.vertices[k]) * 3, &vals[3 * k], 3 * sizeof(double));
    if (b.array < kCoeffs) {
      changed_[static_cast<std::size_t>(b.array)] = b.vertices;
      lowest = std::min(lowest, b.array);
    }
  }
  if (e.gain_level >= 0) {
    gains_[static_cast<std::size_t>(e.gain_level)] = forward ? e.gain_after : e.gain_before;
    resynthesize_from(e.gain_level);
    set_all_changed(e.gain_level + 1);
  }
  if (frames_ == DetailFrames::Local) sync_local_after_restore(e);
  report_.resynthesis_ms = ms_since(t0);
  report_.from_level = std::min(lowest, finest_level());
  for (const auto& c : changed_) report_.vertices_updated += c.size();
}

void Session::sync_local_after_restore(const HistoryEntry& e) {
  bool has_local = false;
  for (const auto& b : e.blocks) has_local |= b.array == kLocal;
  if (has_local) return;  // recorded in local mode: restored exactly
  // Recorded in world mode: local components of the wavelets whose frame or value moved.
  for (int l = 0; l < finest_level(); ++l) {
    std::vector<std::uint32_t> coeffs;
    for (const auto& b : e.blocks)
      if (b.array == kCoeffs)
        for (const std::uint32_t u : b.vertices)
          if (u >= num_vertices(l) && u < num_vertices(l + 1)) coeffs.push_back(u);
    update_local(l, changed_[static_cast<std::size_t>(l)], coeffs, nullptr);
  }
}

bool Session::undo() {
  if (open_) end_edit();
  if (!can_undo()) return false;
  --undo_pos_;
  apply_entry(history_[undo_pos_], false);
  return true;
}

bool Session::redo() {
  if (open_) end_edit();
  if (!can_redo()) return false;
  apply_entry(history_[undo_pos_], true);
  ++undo_pos_;
  return true;
}

// ---- soft selection --------------------------------------------------------------------------

SoftWeights soft_selection(std::span<const double> pos, std::span<const std::uint32_t> selected, double radius) {
  SoftWeights out;
  const std::size_t n = pos.size() / 3;
  std::vector<std::uint32_t> sel(selected.begin(), selected.end());
  std::sort(sel.begin(), sel.end());
  sel.erase(std::unique(sel.begin(), sel.end()), sel.end());
  for (const std::uint32_t v : sel)
    if (v >= n) throw Error("selected vertex " + std::to_string(v) + " does not exist (" + std::to_string(n) + " vertices)");
  if (!(radius > 0.0) || sel.empty()) {
    out.vertices = sel;
    out.weights.assign(sel.size(), 1.0);
    return out;
  }
  // Nearest selected point per vertex through a uniform grid of cell size `radius` over the
  // selected points: each vertex looks at the 27 cells around it.
  struct Key {
    long long x, y, z;
    bool operator==(const Key&) const = default;
  };
  auto key_of = [&](const double* p) {
    return Key{static_cast<long long>(std::floor(p[0] / radius)), static_cast<long long>(std::floor(p[1] / radius)),
               static_cast<long long>(std::floor(p[2] / radius))};
  };
  struct Hash {
    std::size_t operator()(const Key& k) const {
      return std::size_t(k.x * 73856093LL) ^ std::size_t(k.y * 19349663LL) ^ std::size_t(k.z * 83492791LL);
    }
  };
  std::unordered_map<Key, std::vector<std::uint32_t>, Hash> grid;
  for (const std::uint32_t v : sel) grid[key_of(&pos[3 * std::size_t(v)])].push_back(v);
  const double r2 = radius * radius;
  for (std::uint32_t v = 0; v < n; ++v) {
    const double* p = &pos[3 * std::size_t(v)];
    const Key k = key_of(p);
    double best = r2 * 1.0000001 + 1.0;
    bool found = false;
    for (long long dx = -1; dx <= 1; ++dx)
      for (long long dy = -1; dy <= 1; ++dy)
        for (long long dz = -1; dz <= 1; ++dz) {
          const auto it = grid.find(Key{k.x + dx, k.y + dy, k.z + dz});
          if (it == grid.end()) continue;
          for (const std::uint32_t s : it->second) {
            const double* q = &pos[3 * std::size_t(s)];
            const double d2 = (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]);
            if (d2 < best) best = d2, found = true;
          }
        }
    if (!found || best >= r2) {
      if (std::binary_search(sel.begin(), sel.end(), v)) out.vertices.push_back(v), out.weights.push_back(1.0);
      continue;
    }
    const double t = std::sqrt(best) / radius;
    const double w = std::binary_search(sel.begin(), sel.end(), v) ? 1.0 : 1.0 - t * t * (3.0 - 2.0 * t);
    if (w > 0.0) out.vertices.push_back(v), out.weights.push_back(w);
  }
  return out;
}

}  // namespace sublift
