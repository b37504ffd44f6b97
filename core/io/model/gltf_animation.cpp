// glTF animations sampled into frames (animation.h): import_model's vertices posed by morph
// targets, skins and node transforms at uniform times, then welded as read_shape welds them.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "core/base/bounds.h"
#include "core/base/errors.h"
#include "core/base/memory_budget.h"
#include "core/io/model/animation.h"
#include "core/io/model/gltf_access.h"
#include "core/io/model/gltf_channels.h"
#include "core/io/model/model_source.h"
#include "core/io/model/weld.h"

namespace sublift {
namespace {

// A measurement in a note, to 6 significant digits ("0.5", "4.2", "1e-07").
std::string num(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", x);
  return b;
}

// What poses one range of import_model's vertices (one POSITION accessor), read from the first
// primitive that uses it.
struct RangePose {
  std::size_t first = 0, count = 0;  // model vertices [first, first + count)
  int node = -1, mesh = -1, skin = -1;
  std::vector<std::vector<float>> targets;  // POSITION offsets per morph target, 3 per vertex (empty: none)
  std::vector<double> default_weights;      // the node's, else the mesh's, else zeros; one per target
  std::size_t influences = 0;               // joints per vertex: 4 per JOINTS_n/WEIGHTS_n set
  std::vector<std::uint32_t> joints;        // count * influences, slots of the skin's joints
  std::vector<double> weights;              // count * influences, summing to 1 per vertex
};

struct SkinData {
  std::vector<int> joints;          // nodes
  std::vector<glm::dmat4> inverse;  // inverseBindMatrices, one per joint
};

// Everything sampling needs besides the animation: the model as import_model reads it, the
// node hierarchy, the poses of its ranges and the skins they use.
struct Rig {
  Model model;
  NodeWalk walk;
  std::vector<RangePose> ranges;
  std::vector<SkinData> skins;  // by skin index; empty joints where unused
  std::vector<std::string> notes;
  const tinygltf::Model& gltf() const { return model.source->gltf; }
};

void read_skin(const tinygltf::Model& g, int s, SkinData& out, const std::string& file) {
  const tinygltf::Skin& skin = g.skins[std::size_t(s)];
  const std::string who = "skin " + std::to_string(s);
  if (skin.joints.empty()) throw InputError(file, 0, who + " has no joints");
  for (std::size_t j = 0; j < skin.joints.size(); ++j)
    if (skin.joints[j] < 0 || std::size_t(skin.joints[j]) >= g.nodes.size())
      throw InputError(file, 0, who + ": joint " + str(j) + " names node " + std::to_string(skin.joints[j]) + ", but the file has " + str(g.nodes.size()) + " nodes");
  out.joints = skin.joints;
  out.inverse.assign(skin.joints.size(), glm::dmat4(1.0));
  if (skin.inverseBindMatrices < 0) return;
  const std::vector<double> m = read_numbers(g, skin.inverseBindMatrices, TINYGLTF_TYPE_MAT4, {}, "inverseBindMatrices of " + who, file);
  if (m.size() / 16 < skin.joints.size())
    throw InputError(file, 0, "accessor " + std::to_string(skin.inverseBindMatrices) + " (inverseBindMatrices of " + who + "): " +
                                  str(m.size() / 16) + " matrices for " + str(skin.joints.size()) + " joints");
  for (std::size_t j = 0; j < skin.joints.size(); ++j) out.inverse[j] = glm::make_mat4(&m[16 * j]);
}

// JOINTS_n / WEIGHTS_n of `p` for a range of `count` vertices skinned by a skin of `num_joints`.
void read_influences(const tinygltf::Model& g, const tinygltf::Primitive& p, int mesh, int prim, std::size_t num_joints, RangePose& r,
                     std::vector<std::string>& notes, const std::string& file) {
  const std::string where = " of " + prim_name(mesh, prim);
  std::vector<std::vector<std::uint32_t>> joints;
  std::vector<std::vector<double>> weights;
  int weights0 = -1;
  for (int set = 0;; ++set) {
    const auto j = p.attributes.find("JOINTS_" + std::to_string(set));
    const auto w = p.attributes.find("WEIGHTS_" + std::to_string(set));
    if (j == p.attributes.end() && w == p.attributes.end()) break;
    if (j == p.attributes.end() || w == p.attributes.end())
      throw InputError(file, 0, prim_name(mesh, prim) + ": JOINTS_" + std::to_string(set) + " and WEIGHTS_" + std::to_string(set) + " must come together");
    const std::string jrole = "JOINTS_" + std::to_string(set) + where, wrole = "WEIGHTS_" + std::to_string(set) + where;
    joints.push_back(read_unsigned(g, j->second, TINYGLTF_TYPE_VEC4, jrole, file));
    weights.push_back(read_numbers(g, w->second, TINYGLTF_TYPE_VEC4,
                                   {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT}, wrole, file));
    if (set == 0) weights0 = w->second;
    auto check_count = [&](int acc, std::size_t n, const std::string& role) {
      if (n != r.count)
        throw InputError(file, 0, "accessor " + std::to_string(acc) + " (" + role + "): " + str(n) + " elements for " + str(r.count) + " vertices");
    };
    check_count(j->second, joints.back().size() / 4, jrole);
    check_count(w->second, weights.back().size() / 4, wrole);
    for (std::size_t i = 0; i < joints.back().size(); ++i)
      if (joints.back()[i] >= num_joints)
        throw InputError(file, 0, "accessor " + std::to_string(j->second) + " (" + jrole + "): element " + str(i / 4) + " names joint " +
                                      std::to_string(joints.back()[i]) + ", but skin " + std::to_string(r.skin) + " has " + str(num_joints) + " joints");
  }
  if (joints.empty())
    throw InputError(file, 0, prim_name(mesh, prim) + ": its node's skin " + std::to_string(r.skin) + " needs JOINTS_0 and WEIGHTS_0, which the primitive does not have");
  r.influences = 4 * joints.size();
  r.joints.resize(r.count * r.influences);
  r.weights.resize(r.count * r.influences);
  std::size_t renormalised = 0;
  double worst = 0;
  for (std::size_t v = 0; v < r.count; ++v) {
    double sum = 0;
    for (std::size_t s = 0; s < joints.size(); ++s)
      for (std::size_t k = 0; k < 4; ++k) {
        const double w = weights[s][4 * v + k];
        if (w < 0)
          throw InputError(file, 0, "WEIGHTS_" + str(s) + where + ": vertex " + str(v) + " has a negative weight (" + std::to_string(w) + ")");
        r.joints[v * r.influences + 4 * s + k] = joints[s][4 * v + k];
        r.weights[v * r.influences + 4 * s + k] = w;
        sum += w;
      }
    if (!(sum > 0))
      throw InputError(file, 0, "accessor " + std::to_string(weights0) + " (WEIGHTS_0" + where + "): the weights of element " + str(v) + " sum to 0");
    if (std::abs(sum - 1) > 1e-3) {
      ++renormalised;
      worst = std::max(worst, std::abs(sum - 1));
    }
    for (std::size_t k = 0; k < r.influences; ++k) r.weights[v * r.influences + k] /= sum;
  }
  if (renormalised)
    notes.push_back(prim_name(mesh, prim) + ": the skin weights of " + str(renormalised) + " vertices do not sum to 1 (off by up to " + num(worst) + "): divided by their sum");
}

// Morph targets' POSITION offsets and default weights of range `r`, from primitive `p`.
void read_morph(const tinygltf::Model& g, const tinygltf::Primitive& p, int mesh, int prim, RangePose& r, std::vector<std::string>& notes,
                const std::string& file) {
  const std::size_t nt = morph_target_count(g, mesh, file);
  bool other_attributes = false;
  for (std::size_t t = 0; t < nt; ++t) {
    other_attributes = other_attributes || p.targets[t].size() > p.targets[t].count("POSITION");
    const auto it = p.targets[t].find("POSITION");
    if (it == p.targets[t].end()) {
      r.targets.emplace_back();
      continue;
    }
    const std::string role = "morph target " + str(t) + " POSITION of " + prim_name(mesh, prim);
    const AccessorSpan s = checked_vec3(g, it->second, role, file);
    if (s.count != r.count)
      throw InputError(file, 0, "accessor " + std::to_string(it->second) + " (" + role + "): " + str(s.count) + " offsets for " + str(r.count) + " vertices");
    r.targets.push_back(read_vec3(g, s, it->second, role, file));
  }
  if (other_attributes) notes.push_back(prim_name(mesh, prim) + ": morph target offsets other than POSITION (normals, tangents) are not read");
  auto weights_of = [&](const std::vector<double>& w, const std::string& who) {
    if (w.size() != nt)
      throw InputError(file, 0, who + ": " + str(w.size()) + " default weights for the " + str(nt) + " morph targets of mesh " + std::to_string(mesh));
    for (double x : w)
      if (!std::isfinite(x)) throw InputError(file, 0, who + ": a default morph weight is not finite");
    return w;
  };
  const tinygltf::Mesh& m = g.meshes[std::size_t(mesh)];
  if (r.node >= 0 && !g.nodes[std::size_t(r.node)].weights.empty()) r.default_weights = weights_of(g.nodes[std::size_t(r.node)].weights, "node " + std::to_string(r.node));
  else if (!m.weights.empty()) r.default_weights = weights_of(m.weights, "mesh " + std::to_string(mesh));
  else r.default_weights.assign(nt, 0.0);
}

// Nodes drawn by the default scene (all nodes when the file has no scene).
std::vector<char> default_scene_nodes(const tinygltf::Model& g) {
  std::vector<char> in(g.nodes.size(), g.scenes.empty() ? 1 : 0);
  if (g.scenes.empty()) return in;
  const std::size_t s = g.defaultScene >= 0 && std::size_t(g.defaultScene) < g.scenes.size() ? std::size_t(g.defaultScene) : 0;
  std::vector<int> stack(g.scenes[s].nodes.begin(), g.scenes[s].nodes.end());  // checked by walk_nodes
  while (!stack.empty()) {
    const int n = stack.back();
    stack.pop_back();
    if (in[std::size_t(n)]) continue;
    in[std::size_t(n)] = 1;
    stack.insert(stack.end(), g.nodes[std::size_t(n)].children.begin(), g.nodes[std::size_t(n)].children.end());
  }
  return in;
}

Rig make_rig(const std::string& path) {
  Rig rig;
  rig.model = import_model(path);
  const tinygltf::Model& g = rig.gltf();
  rig.walk = walk_nodes(g, path);
  rig.skins.resize(g.skins.size());
  if (rig.model.faces.rows() == 0) throw InputError(path, 0, "no triangles to open as a surface (points and lines only)");
  const std::vector<char> drawn = default_scene_nodes(g);
  for (const ModelRange& range : rig.model.ranges) {
    RangePose r;
    r.first = range.first_vertex;
    r.count = range.num_vertices;
    r.node = range.node;
    const auto [mesh, prim] = range.primitives.front();
    r.mesh = mesh;
    const tinygltf::Primitive& p = g.meshes[std::size_t(mesh)].primitives[std::size_t(prim)];
    read_morph(g, p, mesh, prim, r, rig.notes, path);
    if (range.skinned) {
      r.skin = g.nodes[std::size_t(r.node)].skin;
      SkinData& skin = rig.skins[std::size_t(r.skin)];
      if (skin.joints.empty()) read_skin(g, r.skin, skin, path);
      read_influences(g, p, mesh, prim, skin.joints.size(), r, rig.notes, path);
    } else if (p.attributes.count("JOINTS_0")) {
      rig.notes.push_back(prim_name(mesh, prim) + " has JOINTS_0 but its node " + std::to_string(r.node) + " has no skin: placed by the node's transform");
    }
    // Another primitive sharing the POSITION accessor is posed with it, by the first one's data.
    for (std::size_t k = 1; k < range.primitives.size(); ++k) {
      const auto [m2, p2] = range.primitives[k];
      const tinygltf::Primitive& q = g.meshes[std::size_t(m2)].primitives[std::size_t(p2)];
      auto skin_attr = [](const tinygltf::Primitive& x, const char* name) {
        const auto it = x.attributes.find(name);
        return it == x.attributes.end() ? -1 : it->second;
      };
      if (q.targets != p.targets || skin_attr(q, "JOINTS_0") != skin_attr(p, "JOINTS_0") || skin_attr(q, "WEIGHTS_0") != skin_attr(p, "WEIGHTS_0"))
        rig.notes.push_back(prim_name(m2, p2) + " shares its POSITION with " + prim_name(mesh, prim) +
                            " but has other morph targets or skin attributes: posed with those of " + prim_name(mesh, prim));
    }
    if (r.node >= 0 && !drawn[std::size_t(r.node)])
      rig.notes.push_back("mesh " + std::to_string(mesh) + " (node " + std::to_string(r.node) +
                          ") is not in the default scene: posed all the same, so that the vertices stay read_shape's");
    rig.ranges.push_back(std::move(r));
  }
  return rig;
}

// Node local matrices as local_matrix builds them (T * R * S), for translation, rotation, scale.
glm::dmat4 trs_matrix(const double* t, const double* r, const double* s) {
  glm::dmat4 m = glm::translate(glm::dmat4(1.0), glm::dvec3(t[0], t[1], t[2]));
  m = m * glm::mat4_cast(glm::dquat(r[3], r[0], r[1], r[2]));
  return glm::scale(m, glm::dvec3(s[0], s[1], s[2]));
}

// Positions of every model vertex at time `t` of animation `a` (3 per vertex, world space).
void pose(const Rig& rig, const GltfAnimationData& a, double t, std::vector<double>& out) {
  const tinygltf::Model& g = rig.gltf();
  const std::size_t nn = g.nodes.size();
  // Animated nodes: their TRS (defaults from the node), overwritten by the channels.
  std::vector<std::array<double, 10>> trs(nn);
  std::vector<char> moved(nn, 0);
  std::vector<std::vector<double>> weights(nn);
  for (const AnimChannel& c : a.channels) {
    const std::size_t n = std::size_t(c.node);
    if (c.path == ChannelPath::Weights) {
      weights[n].resize(c.width);
      evaluate_channel(a, c, t, weights[n].data());
      continue;
    }
    if (!moved[n]) {
      const tinygltf::Node& node = g.nodes[n];
      trs[n] = {0, 0, 0, 0, 0, 0, 1, 1, 1, 1};  // translation, rotation x y z w, scale
      std::copy(node.translation.begin(), node.translation.end(), trs[n].begin());
      std::copy(node.rotation.begin(), node.rotation.end(), trs[n].begin() + 3);
      std::copy(node.scale.begin(), node.scale.end(), trs[n].begin() + 7);
      moved[n] = 1;
    }
    const std::size_t at = c.path == ChannelPath::Translation ? 0 : c.path == ChannelPath::Rotation ? 3 : 7;
    evaluate_channel(a, c, t, trs[n].data() + at);
  }
  std::vector<glm::dmat4> world(nn);
  for (int n : rig.walk.topo) {
    const std::size_t i = std::size_t(n);
    const glm::dmat4 local = moved[i] ? trs_matrix(&trs[i][0], &trs[i][3], &trs[i][7]) : local_matrix(g.nodes[i], i, rig.model.path);
    const int parent = rig.walk.parent[i];
    world[i] = parent < 0 ? local : world[std::size_t(parent)] * local;
  }
  std::vector<std::vector<glm::dmat4>> joint_matrices(rig.skins.size());
  for (std::size_t s = 0; s < rig.skins.size(); ++s)
    for (std::size_t j = 0; j < rig.skins[s].joints.size(); ++j)
      joint_matrices[s].push_back(world[std::size_t(rig.skins[s].joints[j])] * rig.skins[s].inverse[j]);

  const std::vector<float>& base = rig.model.source->mesh_positions;
  out.resize(base.size());
  for (const RangePose& r : rig.ranges) {
    const std::vector<double>& w = r.node >= 0 && !weights[std::size_t(r.node)].empty() ? weights[std::size_t(r.node)] : r.default_weights;
    const glm::dmat4 place = r.node >= 0 ? world[std::size_t(r.node)] : glm::dmat4(1.0);
    for (std::size_t i = 0; i < r.count; ++i) {
      const std::size_t v = r.first + i;
      glm::dvec4 p(base[3 * v], base[3 * v + 1], base[3 * v + 2], 1.0);
      for (std::size_t k = 0; k < r.targets.size(); ++k)  // morph: base + sum w_k offset_k (glTF 2.0 sec. 3.7.2.2)
        if (!r.targets[k].empty() && w[k] != 0)
          for (int c = 0; c < 3; ++c) p[c] += w[k] * r.targets[k][3 * i + std::size_t(c)];
      glm::dvec4 q(0.0);
      if (r.skin >= 0) {  // sec. 3.7.3: sum of weight * jointMatrix, jointMatrix = world(joint) * inverseBind
        for (std::size_t k = 0; k < r.influences; ++k) {
          const double wk = r.weights[i * r.influences + k];
          if (wk != 0) q += wk * (joint_matrices[std::size_t(r.skin)][r.joints[i * r.influences + k]] * p);
        }
      } else {
        q = place * p;
      }
      for (int c = 0; c < 3; ++c) out[3 * v + std::size_t(c)] = q[c];
    }
  }
}

// Notes of import_model that describe how FFD treats skins and morph targets (as stored), which
// sampling does not do.
bool ffd_note(const std::string& n) {
  return n.find("is skinned: its bind-pose positions are deformed as stored") != std::string::npos ||
         n.find("has morph targets: the base positions are deformed") != std::string::npos;
}

GltfAnimationInfo info_of(const GltfAnimationData& a) {
  GltfAnimationInfo i;
  i.index = a.index;
  i.name = a.name;
  i.start = a.start;
  i.end = a.end;
  i.channels = a.file_channels;
  for (const AnimChannel& c : a.channels) (c.path == ChannelPath::Weights ? i.morph_weights : i.node_transforms) = true;
  return i;
}

}  // namespace

std::vector<GltfAnimationInfo> gltf_animations(const std::string& path) {
  const Rig rig = make_rig(path);
  std::vector<GltfAnimationInfo> out;
  for (std::size_t a = 0; a < rig.gltf().animations.size(); ++a) out.push_back(info_of(read_animation(rig.gltf(), int(a), path)));
  return out;
}

FrameSet sample_gltf_animation(const std::string& path, int animation, int frames, bool cyclic) {
  if (frames < 2) throw InputError(path, 0, "an animation is sampled at 2 frames or more, not " + std::to_string(frames));
  const Rig rig = make_rig(path);
  const tinygltf::Model& g = rig.gltf();
  if (g.animations.empty()) throw InputError(path, 0, "the file has no animation");
  if (animation < -1 || animation >= int(g.animations.size()))
    throw InputError(path, 0, "animation " + std::to_string(animation) + " does not exist (the file has " + str(g.animations.size()) +
                                  ": 0.." + str(g.animations.size() - 1) + ", or -1 for the first)");
  const int index = animation < 0 ? 0 : animation;
  const GltfAnimationData a = read_animation(g, index, path);
  const std::string anim = "animation " + std::to_string(index);
  if (a.channels.empty()) throw InputError(path, 0, anim + " has no channel that is read (translation, rotation, scale or weights)");
  if (!(a.end > a.start)) throw InputError(path, 0, anim + "'s keys span no time (all at " + num(a.start) + " s): nothing to sample");

  FrameSet fs;
  fs.source = path;
  const PositionWeld weld = weld_by_position(rig.model.positions, rig.model.faces);
  const std::size_t nv = weld.first.size(), nm = rig.model.num_vertices();
  check_memory(double(frames) * double(nv) * 3 * sizeof(double), "sampling " + std::to_string(frames) + " frames of " + path);
  fs.num_vertices = static_cast<std::uint32_t>(nv);
  fs.faces = weld.faces;
  const double span = a.end - a.start;
  fs.times.resize(std::size_t(frames));
  for (int i = 0; i < frames; ++i) fs.times[std::size_t(i)] = a.start + double(i) * span / double(cyclic ? frames : frames - 1);
  for (std::size_t i = 1; i < fs.times.size(); ++i)
    if (!(fs.times[i] > fs.times[i - 1]))
      throw InputError(path, 0, anim + ": " + std::to_string(frames) + " frames over " + std::to_string(span) + " s are closer than double precision");
  fs.rest_positions.resize(3 * nv);
  for (std::size_t w = 0; w < nv; ++w) std::copy_n(&rig.model.positions[3 * std::size_t(weld.first[w])], 3, &fs.rest_positions[3 * w]);

  // Copies welded together that part: counted per model vertex, the largest gap kept.
  const double tolerance = 1e-9 * bbox_diagonal(rig.model.positions);
  std::vector<char> parted(nm, 0);
  double worst_gap = 0;
  std::size_t worst_frame = 0;
  fs.positions.resize(std::size_t(frames) * 3 * nv);
  std::vector<double> posed;
  for (std::size_t f = 0; f < fs.times.size(); ++f) {
    pose(rig, a, fs.times[f], posed);
    double* out = &fs.positions[f * 3 * nv];
    for (std::size_t w = 0; w < nv; ++w) std::copy_n(&posed[3 * std::size_t(weld.first[w])], 3, out + 3 * w);
    for (std::size_t v = 0; v < nm; ++v) {
      const double* p = &posed[3 * v];
      const double* q = out + 3 * std::size_t(weld.welded[v]);
      const double gap = std::hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]);
      if (!(gap <= tolerance)) {
        parted[v] = 1;
        if (gap > worst_gap) {
          worst_gap = gap;
          worst_frame = f;
        }
      }
    }
  }
  for (double x : fs.positions)
    if (!std::isfinite(x)) throw InputError(path, 0, anim + ": a posed position is not finite (a joint or node matrix overflows)");

  fs.notes.push_back(anim + (a.name.empty() ? "" : " '" + a.name + "'") + ": " + std::to_string(frames) + " frames from " +
                     num(a.start) + " s to " + num(a.end) + " s" + (cyclic ? " (cyclic: the end, which is the start, not repeated)" : ""));
  for (const std::string& n : rig.model.notes)
    if (!ffd_note(n)) fs.notes.push_back(n);
  fs.notes.insert(fs.notes.end(), rig.notes.begin(), rig.notes.end());
  fs.notes.insert(fs.notes.end(), a.notes.begin(), a.notes.end());
  if (g.animations.size() > 1) fs.notes.push_back("the file's other " + str(g.animations.size() - 1) + " animations are not applied");
  for (const AnimChannel& c : a.channels)
    if (c.path == ChannelPath::Weights &&
        std::none_of(rig.ranges.begin(), rig.ranges.end(), [&](const RangePose& r) { return r.node == c.node; }))
      fs.notes.push_back(anim + ": the weights of node " + std::to_string(c.node) + " animate an instance of a mesh that another node places: not shown");
  if (nv < nm)
    fs.notes.push_back("glTF vertices welded by position: " + str(nm) + " into " + str(nv) + " (the file splits them at seams of normals and UVs)");
  if (weld.dropped) fs.notes.push_back(str(weld.dropped) + " triangles whose corners welded together (dropped)");
  if (const auto n = std::size_t(std::count(parted.begin(), parted.end(), 1)))
    fs.notes.push_back(str(n) + " welded copies do not move with the vertex they were welded to (largest gap " + num(worst_gap) +
                       " at frame " + str(worst_frame) + "): each welded vertex takes its first copy's motion");
  fs.notes.push_back("glTF meshes sampled as one surface without their normals, UVs, colours, materials or node names");
  return fs;
}

}  // namespace sublift
