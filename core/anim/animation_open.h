#pragma once
// Opening an animation as a space-time lattice: frames sampled from a glTF animation or read
// from a numbered OBJ/PLY/OFF sequence (core/io/model/animation.h), the base mesh swept over
// the base time steps that the frame count and level count imply, the finest level filled from
// the frames and analysed (spacetime.h). Shared by sublift-cli animation and the modeler.
#include <span>
#include <string>
#include <vector>

#include "core/anim/spacetime.h"
#include "core/io/project/project_io.h"

namespace sublift {

struct AnimationOptions {
  Scheme scheme = Scheme::Cubic;
  int levels = 2;
  int frames = 0;        // glTF samples; 0: from sample_fps, else base_steps 4 (4 2^J + 1, cyclic 4 2^J)
  double sample_fps = 0; // glTF, frames 0: sample at least this rate (the count rounded up to one
                         // the levels take); 0: unset
  bool cyclic = false;   // a periodic time axis (the last frame joins the first)
  int animation = -1;    // glTF animation index (-1: the first)
  double fps = 24;       // a sequence's frame rate
};

struct OpenedAnimation {
  SpaceTime st;
  std::string source;
  std::vector<std::string> notes;  // from sampling or reading, by name
  std::vector<double> frames;      // the frames as sampled: frame-major, 3 per base vertex
  std::vector<double> times;       // seconds of each frame
  double loop_end = 0;             // cyclic: the time the loop returns to frame 0
  FitReport fit;
  double diagonal = 0;             // bounding-box diagonal of every frame's base positions
  double load_ms = 0, build_ms = 0, fit_ms = 0;
  int frame_count() const { return int(times.size()); }
};

/// The frame counts an animation with `levels` levels accepts, nearest to `frames` (one below
/// and one above when they exist), for messages: "25 or 33".
std::string valid_frame_counts(int frames, int levels, bool cyclic);

/// Opens `inputs`: one .gltf/.glb (sampled at options.frames uniform times) or two or more
/// OBJ/PLY/OFF files (one frame each, options.frames ignored or equal to their count). Throws
/// InputError (files, a frame count that does not fit the levels, naming the counts that do) or
/// Error.
OpenedAnimation open_animation(std::span<const std::string> inputs, const AnimationOptions& options);

/// What a project keeps of an opened animation beside the lattice's hierarchy.
AnimationExtras animation_extras(const OpenedAnimation& a);

/// The animation of a project (read_project's hierarchy and its `animation` extras): the surface
/// taken from the lattice's first layer, swept again and checked to be the project's lattice,
/// the coefficients the project's. Throws InputError naming `file` when they do not fit.
OpenedAnimation reopen_animation(const std::string& file, const Hierarchy& lattice, const AnimationExtras& extras);

}  // namespace sublift
