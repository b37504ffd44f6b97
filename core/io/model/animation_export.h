#pragma once
// Writing a sampled animation of one polygon mesh (fixed connectivity) as glTF with morph
// targets, or as a numbered sequence of OBJ/PLY/glTF files (docs/animation.md).
//
// glTF layout: one mesh, one TRIANGLES primitive (polygons as fans from their first corner),
// frame 0 as the base POSITION and NORMAL, one morph target per later frame holding its
// POSITION and NORMAL offsets from frame 0 (with the min/max the validator checks), and one
// animation whose LINEAR sampler keys the node's weights one-hot at each frame's time: frame i
// shows target i alone, and between two keys the blend is the linear interpolation of the two
// frames. A cyclic animation gets one more key at the end of the loop, back to frame 0.
// Normals are area-weighted per frame. .gltf embeds the buffer as a base64 data URI.
#include <span>
#include <string>
#include <vector>

#include "core/base/csr.h"

namespace sublift {

/// Writes frames (frame-major, 3 doubles per vertex per frame) at `times` (seconds, strictly
/// increasing; cyclic: `loop_end` > the last time closes the loop) to a .gltf or .glb,
/// atomically. Throws InputError (sizes, fewer than 2 frames, times not increasing, values not
/// finite or beyond float32, no face) or IoError.
void write_animation_gltf(const std::string& path, const Csr& faces, std::span<const double> frames,
                          std::span<const double> times, bool cyclic, double loop_end);

/// The file name of frame `frame` of a sequence written to `pattern`: a run of '#' replaced by
/// the zero-padded frame number (at least as many digits as '#'), otherwise "_NNNN" inserted
/// before the extension.
std::string sequence_file_name(const std::string& pattern, int frame);

/// Writes each frame as its own surface file (sequence_file_name; .obj, .ply, .gltf or .glb)
/// with area-weighted normals; returns the names written.
std::vector<std::string> write_frame_sequence(const std::string& pattern, const Csr& faces, std::span<const double> frames,
                                              std::size_t num_frames);

}  // namespace sublift
