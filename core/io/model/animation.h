#pragma once
// FrameSet: an animation of one mesh with fixed connectivity, sampled into frames; the input of
// the space-time lattice (issue 22). Two sources: a glTF animation (morph targets, skins, node
// transforms) sampled at uniform times, and a numbered sequence of OBJ/PLY/OFF files.
//
// Layout. `positions` is frame-major and flat: frame f, vertex v, axis a at
// (f * num_vertices + v) * 3 + a, world space. `faces` is one Csr over the vertices, the same in
// every frame. `times` are seconds, strictly increasing, one per frame.
//
// glTF decisions (docs/file_formats.md, "Animation sampling"):
// - The vertices are the glTF's as read_shape opens it: import_model's vertices (its checks and
//   sandbox apply) welded by weld_by_position (weld.h), so vertex v of a frame is vertex v of
//   read_shape(path) and `rest_positions` are read_shape's positions. Welding uses the rest
//   positions; a welded vertex takes its first copy's motion, and copies that part in some frame
//   are named in `notes` (how many, the largest gap).
// - Every mesh import_model takes is posed (a mesh of another scene or of no node too, said in
//   `notes`, so that the vertex order stays read_shape's). A mesh instanced by several nodes is
//   posed by its first node, as import_model places it.
// - Pose at time t: morph targets first (POSITION offsets times the weights: the animation's
//   "weights" channel of the mesh's node, else the node's, else the mesh's default weights, else
//   0), then the skin for a skinned mesh (JOINTS_n/WEIGHTS_n, joint matrix = animated joint world
//   matrix times its inverseBindMatrix; the node's own transform is ignored, as glTF says), else
//   the node's animated world matrix. Channels of other animations do not apply.
// - Samplers clamp outside their keys. LINEAR rotations use the glTF spec's slerp (shortest arc,
//   normalised); CUBICSPLINE is the spec's Hermite form, tangents scaled by the key interval.
// - Refused (InputError naming the file and "animation a sampler s", "channel c" or "accessor k"):
//   see sample_gltf_animation. Morph targets other than POSITION, KHR_animation_pointer channels,
//   cameras and lights are not read (named in `notes` where the file has them).
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/base/csr.h"

namespace sublift {

/// An animation of one mesh with fixed connectivity, sampled into frames.
struct FrameSet {
  std::string source;              // the file (glTF) or the first file of a sequence
  std::uint32_t num_vertices = 0;  // welded vertices (glTF) / the files' vertices (sequence)
  Csr faces;                       // polygons over those vertices (glTF: triangles)
  std::vector<double> times;       // seconds, one per frame, strictly increasing
  std::vector<double> positions;   // frame-major: frame f, vertex v, axis a at (f * num_vertices + v) * 3 + a; world space
  std::vector<double> rest_positions;  // 3 per vertex: glTF: read_shape's (no animation, skins as stored); sequence: frame 0
  std::vector<std::string> notes;  // decisions, repairs and whatever was not kept, by name
  std::size_t num_frames() const { return times.size(); }
  std::span<const double> frame(std::size_t f) const;  // 3 * num_vertices values
};

/// One animation of a glTF: its index, name, key time range [start, end] over all its samplers,
/// its channel count and which kinds of target it animates.
struct GltfAnimationInfo {
  int index = 0;
  std::string name;
  double start = 0, end = 0;
  int channels = 0;
  bool morph_weights = false, node_transforms = false;
};

/// The animations of a glTF file (validated as sample_gltf_animation does). Empty when it has
/// none. Throws InputError or IoError.
std::vector<GltfAnimationInfo> gltf_animations(const std::string& path);

/// Samples animation `animation` (index; -1 = the first) of the glTF at `frames` (>= 2) uniform
/// times: t_i = start + i * (end - start) / (frames - 1), or, when `cyclic`,
/// t_i = start + i * (end - start) / frames (the end is the start of the loop, not repeated).
/// Throws InputError naming the file and the element for: no animation, a bad index, frames < 2,
/// keys that span no time; a sampler input not float SCALAR, not finite or not strictly
/// increasing; an output of the wrong type or count (CUBICSPLINE: 3 per key); a channel naming a
/// missing sampler or node, a node with a matrix, a target twice; a "weights" channel on a node
/// without morph targets or with another target count; JOINTS_n not unsigned byte/short or >= the
/// skin's joints; WEIGHTS_n not float or normalised unsigned byte/short, not finite or summing to
/// 0; inverseBindMatrices not float MAT4 or fewer than the joints. Throws Error when the frames
/// would not fit in memory (memory_budget.h).
FrameSet sample_gltf_animation(const std::string& path, int animation, int frames, bool cyclic);

/// A numbered sequence of OBJ/PLY/OFF files with the same connectivity, one frame each, at times
/// i / fps, read through the validating mesh importer (mesh_import.h; its repairs are in `notes`
/// with the file's name). Connectivity is frame 0's faces after import: every other file must
/// have as many vertices and the same faces, corner for corner (vertices numbered from 0), else
/// InputError naming the file ("face 12 is 3 4 7 here but 3 4 8 in frame0.obj", "9 vertices here
/// but 8 in frame0.obj"). Also refused: fewer than 2 files, fps not finite and > 0, a file without
/// faces. Attributes (colours...), polylines and tags are named in `notes` as not kept.
FrameSet read_frame_sequence(std::span<const std::string> paths, double fps);

}  // namespace sublift
