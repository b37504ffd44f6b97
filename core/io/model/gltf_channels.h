#pragma once
// Internal to the glTF animation sampling (gltf_animation.cpp): one animation's samplers and
// channels read, checked and evaluated at a time.
//
// Layout. A channel keeps its sampler's output as `values`, `width` numbers per key (3 for
// translation and scale, 4 for a rotation quaternion x y z w, the mesh's morph target count for
// weights); CUBICSPLINE keys hold three groups each: in-tangent, value, out-tangent (glTF 2.0
// Appendix C). Rotation keys are unit quaternions (normalised when read).
#include <cstddef>
#include <string>
#include <vector>

#include <tiny_gltf.h>

namespace sublift {

enum class ChannelPath { Translation, Rotation, Scale, Weights };
enum class Interpolation { Linear, Step, CubicSpline };

struct KeySampler {
  Interpolation interpolation = Interpolation::Linear;
  std::vector<double> times;  // finite, strictly increasing, at least one
};

struct AnimChannel {
  int node = -1;
  ChannelPath path = ChannelPath::Translation;
  int sampler = -1;
  std::size_t width = 0;
  std::vector<double> values;  // keys * width, x3 for CUBICSPLINE
};

struct GltfAnimationData {
  int index = 0;
  std::string name;
  double start = 0, end = 0;  // key range of the samplers the kept channels use
  int file_channels = 0;      // channels in the file (kept or not)
  std::vector<KeySampler> samplers;
  std::vector<AnimChannel> channels;  // the ones applied: translation, rotation, scale, weights
  std::vector<std::string> notes;     // channels and samplers not used, by index
};

/// The morph target count of mesh `mesh`; throws when its primitives disagree (glTF requires
/// the same count in every primitive).
std::size_t morph_target_count(const tinygltf::Model& m, int mesh, const std::string& file);

/// Reads and checks animation `index` of `m` (a model import_model accepted: nodes and meshes in
/// range). Throws InputError naming "animation a sampler s" or "animation a channel c".
GltfAnimationData read_animation(const tinygltf::Model& m, int index, const std::string& file);

/// The value of channel `c` of `a` at time `t` into out[0 .. c.width): clamped to the first and
/// last keys outside them; STEP, LINEAR (slerp for rotations), CUBICSPLINE (Hermite); rotations
/// normalised.
void evaluate_channel(const GltfAnimationData& a, const AnimChannel& c, double t, double* out);

}  // namespace sublift
