// glTF animations: samplers and channels read through the checked accessors (gltf_access.h) and
// evaluated as glTF 2.0 sec. 3.11 and Appendix C say.
#include "core/io/model/gltf_channels.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>

#include "core/base/errors.h"
#include "core/io/model/gltf_access.h"

namespace sublift {
namespace {

const char* path_name(ChannelPath p) {
  static constexpr const char* kNames[] = {"translation", "rotation", "scale", "weights"};
  return kNames[static_cast<int>(p)];
}

// Key times of sampler `s`: float SCALAR, finite, strictly increasing.
KeySampler read_sampler(const tinygltf::Model& m, const tinygltf::AnimationSampler& in, const std::string& who,
                        const std::string& file) {
  KeySampler s;
  if (in.interpolation == "LINEAR") s.interpolation = Interpolation::Linear;
  else if (in.interpolation == "STEP") s.interpolation = Interpolation::Step;
  else if (in.interpolation == "CUBICSPLINE") s.interpolation = Interpolation::CubicSpline;
  else throw InputError(file, 0, who + ": interpolation '" + in.interpolation.substr(0, 64) + "' is not LINEAR, STEP or CUBICSPLINE");
  s.times = read_numbers(m, in.input, TINYGLTF_TYPE_SCALAR, {}, "input of " + who, file);
  for (std::size_t k = 1; k < s.times.size(); ++k)
    if (!(s.times[k] > s.times[k - 1]))
      throw InputError(file, 0, who + ": input (accessor " + std::to_string(in.input) + ") is not strictly increasing: key " + str(k) +
                                    " at " + std::to_string(s.times[k]) + " s follows key " + str(k - 1) + " at " + std::to_string(s.times[k - 1]) + " s");
  return s;
}

// The glTF spec's slerp (Appendix C): along the shorter arc, linear where the arc vanishes.
void slerp(const double* a, const double* b, double u, double* out) {
  double d = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
  const double sign = d < 0 ? -1.0 : 1.0;
  d = std::min(std::abs(d), 1.0);
  double wa = 1 - u, wb = u;
  const double angle = std::acos(d);
  if (angle > 1e-9) {
    wa = std::sin(angle * (1 - u)) / std::sin(angle);
    wb = std::sin(angle * u) / std::sin(angle);
  }
  for (int i = 0; i < 4; ++i) out[i] = wa * a[i] + sign * wb * b[i];
}

void normalize4(double* q, const double* fallback) {
  const double len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  if (len > 0 && std::isfinite(len)) {
    for (int i = 0; i < 4; ++i) q[i] /= len;
  } else {
    std::copy_n(fallback, 4, q);
  }
}

}  // namespace

std::size_t morph_target_count(const tinygltf::Model& m, int mesh, const std::string& file) {
  const auto& prims = m.meshes[std::size_t(mesh)].primitives;
  if (prims.empty()) return 0;
  for (std::size_t p = 1; p < prims.size(); ++p)
    if (prims[p].targets.size() != prims[0].targets.size())
      throw InputError(file, 0, prim_name(mesh, int(p)) + " has " + str(prims[p].targets.size()) + " morph targets but primitive 0 has " +
                                    str(prims[0].targets.size()) + " (glTF requires the same number in every primitive)");
  return prims[0].targets.size();
}

GltfAnimationData read_animation(const tinygltf::Model& m, int index, const std::string& file) {
  const tinygltf::Animation& in = m.animations[std::size_t(index)];
  const std::string anim = "animation " + std::to_string(index);
  GltfAnimationData a;
  a.index = index;
  a.name = in.name;
  a.file_channels = int(in.channels.size());
  for (std::size_t s = 0; s < in.samplers.size(); ++s)
    a.samplers.push_back(read_sampler(m, in.samplers[s], anim + " sampler " + str(s), file));
  std::vector<char> used(in.samplers.size(), 0);
  std::vector<char> taken(4 * m.nodes.size(), 0);  // node * 4 + path: already animated
  for (std::size_t ci = 0; ci < in.channels.size(); ++ci) {
    const tinygltf::AnimationChannel& ch = in.channels[ci];
    const std::string who = anim + " channel " + str(ci);
    if (ch.sampler < 0 || std::size_t(ch.sampler) >= in.samplers.size())
      throw InputError(file, 0, who + ": sampler " + std::to_string(ch.sampler) + " does not exist (the animation has " + str(in.samplers.size()) + ")");
    AnimChannel c;
    c.sampler = ch.sampler;
    c.node = ch.target_node;
    if (ch.target_path == "translation") c.path = ChannelPath::Translation;
    else if (ch.target_path == "rotation") c.path = ChannelPath::Rotation;
    else if (ch.target_path == "scale") c.path = ChannelPath::Scale;
    else if (ch.target_path == "weights") c.path = ChannelPath::Weights;
    else {
      a.notes.push_back(who + ": path '" + ch.target_path.substr(0, 64) + "' is not read (only translation, rotation, scale and weights)");
      continue;
    }
    if (c.node < 0 || std::size_t(c.node) >= m.nodes.size())
      throw InputError(file, 0, who + ": target node " + std::to_string(c.node) + " does not exist (the file has " + str(m.nodes.size()) + " nodes)");
    const tinygltf::Node& node = m.nodes[std::size_t(c.node)];
    char& twice = taken[4 * std::size_t(c.node) + static_cast<std::size_t>(c.path)];
    if (twice) throw InputError(file, 0, who + ": node " + std::to_string(c.node) + "'s " + path_name(c.path) + " is animated by an earlier channel too");
    twice = 1;
    if (c.path != ChannelPath::Weights && !node.matrix.empty())
      throw InputError(file, 0, who + ": node " + std::to_string(c.node) + " has a matrix, which glTF does not allow to be animated (only translation, rotation, scale)");
    const KeySampler& s = a.samplers[std::size_t(c.sampler)];
    const std::string sampler = anim + " sampler " + std::to_string(c.sampler);
    const std::string role = "output of " + sampler;
    const tinygltf::AnimationSampler& sin = in.samplers[std::size_t(c.sampler)];
    const std::size_t per_key = s.interpolation == Interpolation::CubicSpline ? 3 : 1;
    const std::size_t keys = s.times.size();
    // glTF 2.0 sec. 3.11, the accessor types of animation outputs.
    const std::initializer_list<int> kNormalized = {TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_SHORT,
                                  TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT};
    if (c.path == ChannelPath::Weights) {
      const std::size_t targets = node.mesh < 0 ? 0 : morph_target_count(m, node.mesh, file);
      if (targets == 0)
        throw InputError(file, 0, who + ": animates the weights of node " + std::to_string(c.node) + ", which has no mesh with morph targets");
      c.width = targets;
      c.values = read_numbers(m, sin.output, TINYGLTF_TYPE_SCALAR, kNormalized, role, file);
      if (c.values.size() != keys * per_key * targets) {
        const std::size_t per = c.values.size() % (keys * per_key) == 0 ? c.values.size() / (keys * per_key) : 0;
        throw InputError(file, 0, who + ": " + sampler + "'s output (accessor " + std::to_string(sin.output) + ") holds " + str(c.values.size()) +
                                      " weights for " + str(keys) + " keys" + (per_key == 3 ? " (CUBICSPLINE: 3 groups per key)" : "") +
                                      (per ? ", " + str(per) + " per key," : ",") + " but mesh " + std::to_string(node.mesh) + " of node " +
                                      std::to_string(c.node) + " has " + str(targets) + " morph targets");
      }
    } else {
      const bool rotation = c.path == ChannelPath::Rotation;
      c.width = rotation ? 4 : 3;
      c.values = rotation ? read_numbers(m, sin.output, TINYGLTF_TYPE_VEC4, kNormalized, role, file)
                          : read_numbers(m, sin.output, TINYGLTF_TYPE_VEC3, {}, role, file);
      if (c.values.size() != keys * per_key * c.width)
        throw InputError(file, 0, sampler + ": output (accessor " + std::to_string(sin.output) + ") has " + str(c.values.size() / c.width) +
                                      " elements for " + str(keys) + " keys" + (per_key == 3 ? " (CUBICSPLINE needs 3 per key)" : "") +
                                      " (" + who + ", " + path_name(c.path) + ")");
      if (rotation)
        for (std::size_t k = 0; k < keys; ++k) {
          double* q = &c.values[(per_key * k + (per_key == 3 ? 1 : 0)) * 4];
          const double len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
          if (!(len > 0)) throw InputError(file, 0, sampler + ": output key " + str(k) + " is a zero quaternion (" + who + ")");
          for (int i = 0; i < 4; ++i) q[i] /= len;
        }
    }
    used[std::size_t(c.sampler)] = 1;
    a.channels.push_back(std::move(c));
  }
  bool any = false;
  for (std::size_t s = 0; s < a.samplers.size(); ++s) {
    if (!used[s]) {
      a.notes.push_back(anim + " sampler " + str(s) + " is used by no channel that is read");
      continue;
    }
    const auto& t = a.samplers[s].times;
    a.start = any ? std::min(a.start, t.front()) : t.front();
    a.end = any ? std::max(a.end, t.back()) : t.back();
    any = true;
  }
  return a;
}

void evaluate_channel(const GltfAnimationData& a, const AnimChannel& c, double t, double* out) {
  const KeySampler& s = a.samplers[std::size_t(c.sampler)];
  const std::vector<double>& k = s.times;
  const std::size_t w = c.width, n = k.size();
  const bool cubic = s.interpolation == Interpolation::CubicSpline;
  auto value = [&](std::size_t i) { return &c.values[(cubic ? 3 * i + 1 : i) * w]; };
  if (n == 1 || t <= k.front()) {
    std::copy_n(value(0), w, out);
  } else if (t >= k.back()) {
    std::copy_n(value(n - 1), w, out);
  } else {
    const std::size_t i = std::size_t(std::upper_bound(k.begin(), k.end(), t) - k.begin()) - 1;  // k[i] <= t < k[i + 1]
    const double td = k[i + 1] - k[i], u = (t - k[i]) / td;
    const double* v0 = value(i);
    const double* v1 = value(i + 1);
    if (s.interpolation == Interpolation::Step) {
      std::copy_n(v0, w, out);
    } else if (!cubic) {
      if (c.path == ChannelPath::Rotation) slerp(v0, v1, u, out);
      else
        for (std::size_t j = 0; j < w; ++j) out[j] = (1 - u) * v0[j] + u * v1[j];
    } else {
      // Appendix C: p(u) = (2u^3 - 3u^2 + 1) v_i + td (u^3 - 2u^2 + u) b_i + (-2u^3 + 3u^2) v_i+1 + td (u^3 - u^2) a_i+1
      const double* b0 = &c.values[(3 * i + 2) * w];
      const double* a1 = &c.values[(3 * (i + 1)) * w];
      const double u2 = u * u, u3 = u2 * u;
      const double h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u, h01 = -2 * u3 + 3 * u2, h11 = u3 - u2;
      for (std::size_t j = 0; j < w; ++j) out[j] = h00 * v0[j] + td * h10 * b0[j] + h01 * v1[j] + td * h11 * a1[j];
    }
    if (c.path == ChannelPath::Rotation) normalize4(out, v0);
  }
}

}  // namespace sublift
