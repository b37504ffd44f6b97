#pragma once
// Session: the live state of the modeler — a hierarchy, the control net of every level, per-level
// detail gains, the detail frame mode and an undo history (issue 4, DESIGN.md "Architecture").
// The GUI, `sublift --script` and `sublift-cli edit` all edit through this class.
//
// Representation. `hierarchy().coeffs` holds the level-0 scaling coefficients and the raw
// wavelet coefficients in world coordinates (the transform's native form, what projects store).
// Level j's control net is the synthesis of level 0 with every wavelet of level l < j multiplied
// by gain(l); it is kept in `positions(j)` for every level 0..J.
//
// Edits. move() adds delta * weight to control points of level j. Finer levels are resynthesised
// locally: by linearity, only the synthesis of the change (zero elsewhere) is computed, over the
// vertices the lifting stencils reach from the moved points (the executor's sparse mode, core/engine/executor.h). Coarser levels
// are updated by analysing the change down to level 0 (fold-back), so the hierarchy stays
// consistent and a later coarse edit keeps the fine edit as detail.
//
// Local frames. With DetailFrames::Local the session also keeps every wavelet as components in
// a frame of the coarser level (detail_frames.h): a coarse edit that turns the surface turns its
// detail too. World coefficients are then derived from the local ones wherever a frame moved.
//
// Undo. An operation records the old and new values of every vertex entry it changed (control
// points of each level, coefficients, local components); undo and redo write them back, so they
// restore coefficients bit for bit. Several move() calls between begin_edit() and end_edit()
// (a mouse drag) are one history entry.
#include <chrono>
#include <memory>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/multires/hierarchy.h"
#include "core/engine/executor.h"

namespace sublift {

enum class DetailFrames : std::uint8_t { World, Local };

/// What the last operation changed and what it cost.
struct OpReport {
  double resynthesis_ms = 0.0;          // local resynthesis and fold-back (no file I/O)
  double setup_ms = 0.0;                // one-time buffers the first edit after opening sizes
  std::size_t vertices_updated = 0;     // control points changed, summed over levels
  bool full = false;                    // every level from `from_level` up was recomputed
  int from_level = 0;
};

/// One undoable operation: sparse before/after values of every vertex entry it changed.
struct HistoryEntry {
  std::string label;
  struct Block {
    int array = 0;                       // 0..J: positions of that level; J+1: coeffs; J+2: local
    std::vector<std::uint32_t> vertices; // vertex indices in that array
    std::vector<double> before, after;   // 3 per vertex
  };
  std::vector<Block> blocks;
  int gain_level = -1;                   // a gain change: level and values
  double gain_before = 1.0, gain_after = 1.0;
  int levels_before = -1;  // a subdivide: the finest level before it
  std::size_t bytes() const;
};

/// Weights of a soft selection: every control point of `positions` (3 per vertex) within
/// `radius` of a selected one gets 1 - smoothstep(d / radius) (1 at the selected points).
/// radius <= 0 gives the selection itself with weight 1. Indices ascend.
struct SoftWeights {
  std::vector<std::uint32_t> vertices;
  std::vector<double> weights;
};
SoftWeights soft_selection(std::span<const double> positions, std::span<const std::uint32_t> selected,
                           double radius);

class Session {
 public:
  Session() = default;
  /// Takes a hierarchy with 3 channels (x, y, z) that is not in integer mode, and optionally
  /// the detail gain of each level 0..J-1 (empty: all 1); throws Error.
  explicit Session(Hierarchy h, std::vector<double> gains = {});

  const Hierarchy& hierarchy() const { return h_; }
  int finest_level() const { return h_.finest_level(); }
  int dim() const { return h_.levels.front().dim; }
  std::uint32_t num_vertices(int level) const { return h_.num_vertices(level); }
  /// Control net of `level`, 3 doubles per vertex in the engine's order.
  std::span<const double> positions(int level) const { return pos_.at(static_cast<std::size_t>(level)); }

  // ---- edits -------------------------------------------------------------------------------
  /// Adds weights[k] * delta to control point vertices[k] of `level` (weights empty: all 1),
  /// resynthesises finer levels locally and folds the change back into coarser ones. Throws
  /// Error on a bad level or index, or when a band below `level` has gain 0 (the fold-back
  /// would have to put detail into a muted band).
  OpReport move(int level, std::span<const std::uint32_t> vertices, std::span<const double> weights,
                const double delta[3]);
  /// The same with a delta of its own for each vertex (3 values per entry of `vertices`): what
  /// rotate, scale and the brushes apply.
  OpReport move_each(int level, std::span<const std::uint32_t> vertices, std::span<const double> deltas);
  /// The same, with every level from `level` up recomputed in full: the reference the tests and
  /// benchmarks compare local resynthesis with.
  OpReport move_full(int level, std::span<const std::uint32_t> vertices, std::span<const double> weights,
                     const double delta[3]);

  /// Groups the operations until end_edit() into one history entry named `label`.
  void begin_edit(const std::string& label);
  /// Ends the group; an edit that changed nothing leaves no entry.
  void end_edit();
  bool in_edit() const { return open_ != nullptr; }
  /// Reverts everything since begin_edit() and forgets it (a cancelled grab): no history entry,
  /// nothing to redo. Values come back bit for bit.
  void cancel_edit();

  /// Per-level detail gain: wavelets of `level` (on level+1's e/f/c vertices) are multiplied by
  /// `factor` in synthesis. Undoable; recomputes the levels above `level`.
  OpReport set_gain(int level, double factor);
  double gain(int level) const { return gains_.at(static_cast<std::size_t>(level)); }
  std::span<const double> gains() const { return gains_; }

  /// Adds one level with zero detail (Ctrl+D). Undoable. Throws Error beyond kMaxLevels or when
  /// the new level would pass `max_vertices`.
  OpReport subdivide(double max_vertices = 50e6);

  /// Switches how detail is kept; the shape does not change. Local needs a surface (dim 2).
  void set_detail_frames(DetailFrames f);
  DetailFrames detail_frames() const { return frames_; }

  // ---- history ------------------------------------------------------------------------------
  bool can_undo() const { return undo_pos_ > 0; }
  bool can_redo() const { return undo_pos_ < history_.size(); }
  /// Reverts the last operation; false when there is none.
  bool undo();
  bool redo();
  const std::vector<HistoryEntry>& history() const { return history_; }
  /// Entries [0, undo_position()) are applied; the rest can be redone.
  std::size_t undo_position() const { return undo_pos_; }
  /// Counts edits since the last mark_saved(); the GUI's "unsaved changes".
  bool dirty() const { return undo_pos_ != saved_pos_ || saved_invalid_; }
  void mark_saved() { saved_pos_ = undo_pos_, saved_invalid_ = false; }
  /// Dirty until the next save: a session that replaces an edited one (scheme switch, level
  /// deletion) holds changes no saved file has.
  void mark_unsaved() { saved_invalid_ = true; }

  // ---- what changed, for the viewport ---------------------------------------------------------
  /// Vertices of `level` whose control points the last operation (edit, undo, redo) changed;
  /// all of them when last_report().full and level >= from_level.
  std::span<const std::uint32_t> changed(int level) const { return changed_.at(static_cast<std::size_t>(level)); }
  const OpReport& last_report() const { return report_; }
  /// Bumped by every operation that changes topology (subdivide, undo/redo of one).
  std::uint64_t topology_version() const { return topology_version_; }

 private:
  OpReport move_impl(int level, std::span<const std::uint32_t> vertices, std::span<const double> weights,
                     std::span<const double> deltas, bool full);
  void resynthesize_from(int level);        // dense synthesis of every level above `level`
  void resynthesize_one(int level);         // level + 1 from level and its wavelets
  void resynthesize_levels_below(int level);
  void fold_back_sparse(int level);
  void fold_back_dense(int level);
  void update_local(int level, std::span<const std::uint32_t> changed_pos,
                    std::span<const std::uint32_t> changed_coeffs, SparseDelta* out);
  void local_from_world_dense(int level);
  void update_local_world_dense(int level);
  void add_level();
  void remove_level();
  const ChildSites* sites(int level) const;           // sqrt2's new-vertex sites, else nullptr
  void synthesize_sparse(int level, SparseDelta& d);  // transition level -> level + 1
  void analyze_sparse(int level, SparseDelta& d);
  /// Sizes the history stamps and per-level change buffers (first edit after opening or after
  /// the levels change); the ms it took, 0 when they were ready.
  double prepare_edit_buffers();
  void record(int array, std::uint32_t v);  // remembers the old value before a change
  double* array_ptr(int array);
  void apply_entry(const HistoryEntry& e, bool forward);
  void push_entry(HistoryEntry e);
  void clear_changed();
  void set_all_changed(int from_level);
  void check_gain_below(int level) const;
  void sync_local_after_restore(const HistoryEntry& e);

  Hierarchy h_;
  std::vector<std::vector<double>> pos_;  // per level, 3 per vertex
  std::vector<double> gains_;             // per level 0..J-1
  DetailFrames frames_ = DetailFrames::World;
  std::vector<double> local_;             // like coeffs (wavelet entries only) in Local mode
  std::vector<SparseDelta> deltas_;       // per level: the change being propagated
  std::vector<SparseIndex> sparse_index_;  // per transition: the rows reading each vertex
  std::vector<std::uint32_t> frame_list_, frame_stamp_, coeff_list_;
  std::uint32_t frame_epoch_ = 0;

  std::vector<HistoryEntry> history_;
  std::size_t undo_pos_ = 0, saved_pos_ = 0;
  bool saved_invalid_ = false;
  std::size_t history_limit_ = std::size_t(1) << 30;
  std::unique_ptr<HistoryEntry> open_;
  std::vector<std::vector<std::uint32_t>> touched_;  // per array: stamp of the open entry
  std::uint32_t stamp_ = 0;
  std::vector<std::vector<std::uint32_t>> changed_;
  OpReport report_;
  std::uint64_t topology_version_ = 0;
};

}  // namespace sublift
