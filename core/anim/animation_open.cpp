#include "core/anim/animation_open.h"

#include <chrono>
#include <cmath>

#include "core/base/bounds.h"
#include "core/base/errors.h"
#include "core/base/file_io.h"
#include "core/base/stopwatch.h"
#include "core/complex/complex_build.h"
#include "core/io/model/animation.h"

namespace sublift {
namespace {

bool is_gltf(const std::string& path) {
  const std::string ext = file_extension(path);
  return ext == "gltf" || ext == "glb";
}

}  // namespace

std::string valid_frame_counts(int frames, int levels, bool cyclic) {
  const int step = 1 << levels, extra = cyclic ? 0 : 1, least = cyclic ? 3 : 1;
  const int k = (frames - extra) / step;
  if (k < least) return std::to_string(least * step + extra);
  const int below = k * step + extra;
  if (below == frames) return std::to_string(below);
  return std::to_string(below) + " or " + std::to_string(below + step);
}

OpenedAnimation open_animation(std::span<const std::string> inputs, const AnimationOptions& options) {
  if (inputs.empty()) throw Error("no animation to open");
  const bool gltf = inputs.size() == 1 && is_gltf(inputs[0]);
  if (inputs.size() == 1 && !gltf)
    throw InputError(inputs[0], 0, "one file is an animation only as glTF; a sequence needs two or more OBJ/PLY/OFF files");
  const int levels = options.levels;
  const char* kind = options.cyclic ? "a cyclic" : "an open";
  const std::string rule = options.cyclic ? "2^J K frames with K >= 3" : "2^J K + 1 frames with K >= 1";
  auto t = std::chrono::steady_clock::now();
  OpenedAnimation a;
  a.source = inputs[0];
  FrameSet set;
  if (gltf) {
    int frames = options.frames > 0 ? options.frames : space_time_frames(4, levels, options.cyclic);
    if (options.frames == 0 && options.sample_fps > 0) {
      // At least sample_fps over the clip: its intervals rounded up to whole base steps.
      const std::vector<GltfAnimationInfo> clips = gltf_animations(inputs[0]);
      if (clips.empty()) throw InputError(inputs[0], 0, "the file has no animation");
      const int index = options.animation < 0 ? 0 : options.animation;
      if (index >= int(clips.size()))
        throw InputError(inputs[0], 0, "animation " + std::to_string(index) + " does not exist (the file has " + std::to_string(clips.size()) + ")");
      const double duration = clips[std::size_t(index)].end - clips[std::size_t(index)].start;
      const double intervals = std::ceil(duration * options.sample_fps - 1e-9);
      if (!(intervals < 1e6)) throw InputError(inputs[0], 0, "sampling at " + std::to_string(options.sample_fps) + " fps needs too many frames");
      const int step = 1 << levels, least = options.cyclic ? 3 : 1;
      const int k = std::max(least, int(std::ceil(std::max(intervals, 1.0) / step)));
      frames = space_time_frames(k, levels, options.cyclic);
      a.notes.push_back("sampled at " + std::to_string(frames) + " frames: at least " + std::to_string(options.sample_fps) +
                        " fps over " + std::to_string(duration) + " s, rounded up to what " + std::to_string(levels) + " levels take");
    }
    if (!space_time_base_steps(frames, levels, options.cyclic))
      throw InputError(inputs[0], 0, std::to_string(frames) + " frames do not fit " + std::to_string(levels) + " levels: " + kind +
                                         " animation takes " + rule + " (try " + valid_frame_counts(frames, levels, options.cyclic) + ")");
    set = sample_gltf_animation(inputs[0], options.animation, frames, options.cyclic);
  } else {
    const int frames = int(inputs.size());
    if (options.frames > 0 && options.frames != frames)
      throw InputError(inputs[0], 0, "--frames " + std::to_string(options.frames) + " but " + std::to_string(frames) + " files were given");
    if (!space_time_base_steps(frames, levels, options.cyclic))
      throw InputError(inputs[0], 0, std::to_string(frames) + " files do not fit " + std::to_string(levels) + " levels: " + kind +
                                         " animation takes " + rule + " (give " + valid_frame_counts(frames, levels, options.cyclic) +
                                         " files, or other --levels)");
    set = read_frame_sequence(inputs, options.fps);
  }
  a.load_ms = ms_since(t);
  a.notes.insert(a.notes.end(), set.notes.begin(), set.notes.end());
  a.times = set.times;
  const int n = int(set.num_frames());
  if (options.cyclic) a.loop_end = n > 1 ? set.times[std::size_t(n) - 1] + (set.times[1] - set.times[0]) : set.times[0] + 1;
  t = std::chrono::steady_clock::now();
  Complex surface;
  try {
    surface = complex_from_polygons(set.num_vertices, set.faces);
  } catch (const TopologyError& e) {
    throw InputError(a.source, 0, std::string("the animated mesh is not a surface Sublift can sweep: ") + e.what());
  }
  a.st = make_space_time(surface, *space_time_base_steps(n, levels, options.cyclic), options.cyclic, levels, options.scheme);
  a.build_ms = ms_since(t);
  t = std::chrono::steady_clock::now();
  a.frames = std::move(set.positions);
  a.fit = fit_frames(a.st, a.frames);
  a.fit_ms = ms_since(t);
  a.diagonal = bbox_diagonal(a.frames);
  return a;
}

AnimationExtras animation_extras(const OpenedAnimation& a) {
  AnimationExtras x;
  x.base_steps = a.st.base_steps;
  x.cyclic = a.st.cyclic;
  x.surface_vertices = a.st.surface.num_vertices;
  x.surface_faces = a.st.surface.num_faces();
  x.times = a.times;
  x.loop_end = a.loop_end;
  return x;
}

OpenedAnimation reopen_animation(const std::string& file, const Hierarchy& lattice, const AnimationExtras& x) {
  const Complex& base = lattice.levels.front();
  if (base.dim != 3 || x.surface_vertices > base.num_vertices || x.surface_faces > base.num_faces())
    throw InputError(file, 2, "header 'animation' does not describe this lattice (its surface is larger than the base)");
  Csr faces;  // the first layer's faces: sweep_lattice lists them first
  for (std::uint32_t f = 0; f < x.surface_faces; ++f) {
    for (std::uint32_t v : base.faces.row(f)) {
      if (v >= x.surface_vertices) throw InputError(file, 2, "header 'animation': face " + std::to_string(f) + " is not on the first layer");
      faces.items.push_back(v);
    }
    faces.offsets.push_back(std::uint32_t(faces.items.size()));
  }
  OpenedAnimation a;
  a.source = file;
  try {
    a.st = make_space_time(complex_from_polygons(x.surface_vertices, faces), x.base_steps, x.cyclic, lattice.finest_level(), lattice.scheme);
  } catch (const Error& e) {
    throw InputError(file, 2, std::string("header 'animation': ") + e.what());
  }
  const Complex& swept = a.st.lattice.levels.front();
  if (swept.num_vertices != base.num_vertices || swept.edge_verts != base.edge_verts || swept.faces.items != base.faces.items ||
      swept.cell_faces.items != base.cell_faces.items || lattice.channels != 3)
    throw InputError(file, 2, "header 'animation' does not describe this lattice: its sweep gives another complex");
  if (x.times.size() != std::size_t(a.st.layers(a.st.levels())))
    throw InputError(file, 2, "header 'animation' has " + std::to_string(x.times.size()) + " frame times for " +
                                  std::to_string(a.st.layers(a.st.levels())) + " frames");
  a.st.lattice.coeffs = lattice.coeffs;
  a.times = x.times;
  a.loop_end = x.loop_end;
  const std::vector<double> finest = synthesize(a.st.lattice, a.st.levels());
  a.diagonal = bbox_diagonal(finest);
  return a;
}

}  // namespace sublift
