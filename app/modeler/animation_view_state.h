#pragma once
// The modeler's animation mode (issue 22; docs/animation.md): an animation opened as a
// space-time lattice (core/anim/animation_open.h) whose session is the lattice's. What is shown
// is one time: the finest layer at the current frame (between two layers, their blend) as the
// surface, and the edit level's layer nearest that frame as the control net; the points of the
// level's other layers are hidden and cannot be picked, so a drag moves a control point of that
// level at that time and the change spreads over the frames its time support covers. Ghosts
// are wireframes of the frames around the current one, at the edit level's layer spacing.
#include <cstdint>
#include <span>
#include <vector>

#include "core/anim/animation_open.h"

namespace sublift {

struct AnimationViewState {
  OpenedAnimation anim;
  double frame = 0;    // current finest frame; fractional between two layers
  int ghosts = 0;      // ghost frames either side of the current one
  bool playing = false;
  int layer = 0;       // the edit level's layer nearest the frame
  std::vector<std::uint8_t> on_layer;    // per vertex of the edit level: 1 on that layer
  std::vector<std::uint32_t> net_edges;  // that layer's net: lattice vertex pairs of the level
  std::vector<std::uint32_t> ghost_edges;  // into ghost_positions
  std::vector<double> ghost_positions;

  int frames() const { return anim.st.layers(anim.st.levels()); }
  /// Frames per second of the sampled frames (their spacing in time).
  double fps() const;
  /// The finest frame of layer `layer` of `level`.
  int layer_frame(int level, int layer) const { return layer << (anim.st.levels() - level); }
};

/// Recomputes the layer, its mask and its net edges for the edit level `level`.
void refresh_animation_layer(AnimationViewState& a, int level);
/// Recomputes the ghost wireframes from the finest level's control points (3 per vertex).
void refresh_ghosts(AnimationViewState& a, std::span<const double> finest, int level);

}  // namespace sublift
