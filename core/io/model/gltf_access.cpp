// Checked glTF accessors and the node hierarchy (gltf_access.h), shared by the model import and
// the animation sampling.
#include "core/io/model/gltf_access.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "core/base/binary_cursor.h"
#include "core/base/errors.h"

namespace sublift {

std::string prim_name(int mesh, int prim) { return "mesh " + std::to_string(mesh) + " primitive " + std::to_string(prim); }

float load_f32(const unsigned char* p) { return load_endian<float>(p, false); }

std::uint32_t load_index(const unsigned char* p, int component) {
  if (component == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) return p[0];
  if (component == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8;
  return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 | std::uint32_t(p[3]) << 24;
}

// Checks that accessor `index` (used as `role`) can be read: not sparse, has a view, elements fit.
AccessorSpan checked_accessor(const tinygltf::Model& m, int index, const std::string& role, const std::string& file) {
  if (index < 0 || std::size_t(index) >= m.accessors.size())
    throw InputError(file, 0, role + " names accessor " + std::to_string(index) + ", but the file has " + str(m.accessors.size()));
  const std::string who = "accessor " + std::to_string(index) + " (" + role + ")";
  const tinygltf::Accessor& a = m.accessors[std::size_t(index)];
  if (a.sparse.isSparse) throw InputError(file, 0, who + ": sparse accessors are not supported");
  if (a.bufferView < 0) throw InputError(file, 0, who + ": has no bufferView (implicit zeros are not supported here)");
  if (std::size_t(a.bufferView) >= m.bufferViews.size())
    throw InputError(file, 0, who + ": bufferView " + std::to_string(a.bufferView) + " does not exist (the file has " + str(m.bufferViews.size()) + ")");
  const tinygltf::BufferView& v = m.bufferViews[std::size_t(a.bufferView)];
  const int cs = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(a.componentType));
  const int nc = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(a.type));
  if (cs <= 0 || nc <= 0) throw InputError(file, 0, who + ": invalid componentType or type");
  AccessorSpan s;
  s.buffer = v.buffer;
  s.elem = std::size_t(cs) * std::size_t(nc);
  s.stride = v.byteStride ? v.byteStride : s.elem;
  s.count = a.count;
  s.component = a.componentType;
  if (s.stride < s.elem) throw InputError(file, 0, who + ": byteStride " + str(s.stride) + " is smaller than one element (" + str(s.elem) + " bytes)");
  if (a.count == 0) throw InputError(file, 0, who + ": count is 0");
  if (a.byteOffset > v.byteLength || s.elem > v.byteLength - a.byteOffset ||
      a.count - 1 > (v.byteLength - a.byteOffset - s.elem) / s.stride)
    throw InputError(file, 0, who + ": " + str(a.count) + " elements of " + str(s.elem) + " bytes at byteOffset " + str(a.byteOffset) +
                                  " (stride " + str(s.stride) + ") do not fit in the " + str(v.byteLength) + " bytes of bufferView " +
                                  std::to_string(a.bufferView));
  s.base = v.byteOffset + a.byteOffset;
  return s;
}

// A checked float VEC3 accessor (POSITION, NORMAL).
AccessorSpan checked_vec3(const tinygltf::Model& m, int index, const std::string& role, const std::string& file) {
  const AccessorSpan s = checked_accessor(m, index, role, file);
  const tinygltf::Accessor& a = m.accessors[std::size_t(index)];
  const std::string who = "accessor " + std::to_string(index) + " (" + role + ")";
  if (a.type != TINYGLTF_TYPE_VEC3) throw InputError(file, 0, who + ": type is not VEC3");
  if (a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
    throw InputError(file, 0, who + ": componentType " + std::to_string(a.componentType) +
                                  " is not float; quantized or normalized integer data (KHR_mesh_quantization) is not supported");
  return s;
}

std::vector<float> read_vec3(const tinygltf::Model& m, const AccessorSpan& s, int index, const std::string& role, const std::string& file) {
  const unsigned char* data = m.buffers[std::size_t(s.buffer)].data.data();
  std::vector<float> out(3 * s.count);
  for (std::size_t i = 0; i < s.count; ++i)
    for (std::size_t k = 0; k < 3; ++k) {
      const float f = load_f32(data + s.base + i * s.stride + 4 * k);
      if (!std::isfinite(f))
        throw InputError(file, 0, "accessor " + std::to_string(index) + " (" + role + "): element " + str(i) + " component " + str(k) +
                                      " is not finite (" + std::to_string(f) + ")");
      out[3 * i + k] = f;
    }
  return out;
}

const char* type_name(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return "SCALAR";
    case TINYGLTF_TYPE_VEC2: return "VEC2";
    case TINYGLTF_TYPE_VEC3: return "VEC3";
    case TINYGLTF_TYPE_VEC4: return "VEC4";
    case TINYGLTF_TYPE_MAT2: return "MAT2";
    case TINYGLTF_TYPE_MAT3: return "MAT3";
    case TINYGLTF_TYPE_MAT4: return "MAT4";
    default: return "?";
  }
}

std::vector<double> read_numbers(const tinygltf::Model& m, int index, int type, std::initializer_list<int> normalized,
                                 const std::string& role, const std::string& file) {
  const AccessorSpan s = checked_accessor(m, index, role, file);
  const tinygltf::Accessor& a = m.accessors[std::size_t(index)];
  const std::string who = "accessor " + std::to_string(index) + " (" + role + ")";
  if (a.type != type) throw InputError(file, 0, who + ": type is " + type_name(a.type) + ", not " + type_name(type));
  const bool is_float = a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT;
  const bool is_normalized = std::find(normalized.begin(), normalized.end(), a.componentType) != normalized.end();
  if (!is_float && !(is_normalized && a.normalized))
    throw InputError(file, 0, who + ": componentType " + std::to_string(a.componentType) + (is_normalized ? " without normalized: true" : "") +
                                  " is not allowed here (float" + (normalized.size() ? " or a normalised integer" : "") + ")");
  // Matrices of 1- and 2-byte components pad their columns to 4 bytes (glTF 2.0 sec. 3.6.2.4).
  if ((type == TINYGLTF_TYPE_MAT2 || type == TINYGLTF_TYPE_MAT3) && !is_float)
    throw InputError(file, 0, who + ": integer matrices are not supported");
  const std::size_t nc = std::size_t(tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(type)));
  const std::size_t cs = std::size_t(tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(a.componentType)));
  const unsigned char* data = m.buffers[std::size_t(s.buffer)].data.data();
  std::vector<double> out(nc * s.count);  // count checked against the view's bytes above
  for (std::size_t i = 0; i < s.count; ++i)
    for (std::size_t c = 0; c < nc; ++c) {
      const unsigned char* p = data + s.base + i * s.stride + c * cs;
      double x = 0;
      switch (a.componentType) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: x = load_f32(p); break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: x = p[0] / 255.0; break;
        case TINYGLTF_COMPONENT_TYPE_BYTE: x = std::max(static_cast<std::int8_t>(p[0]) / 127.0, -1.0); break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: x = load_endian<std::uint16_t>(p, false) / 65535.0; break;
        case TINYGLTF_COMPONENT_TYPE_SHORT: x = std::max(load_endian<std::int16_t>(p, false) / 32767.0, -1.0); break;
        default: break;
      }
      if (!std::isfinite(x))
        throw InputError(file, 0, who + ": element " + str(i) + " component " + str(c) + " is not finite (" + std::to_string(x) + ")");
      out[nc * i + c] = x;
    }
  return out;
}

std::vector<std::uint32_t> read_unsigned(const tinygltf::Model& m, int index, int type, const std::string& role,
                                         const std::string& file) {
  const AccessorSpan s = checked_accessor(m, index, role, file);
  const tinygltf::Accessor& a = m.accessors[std::size_t(index)];
  const std::string who = "accessor " + std::to_string(index) + " (" + role + ")";
  if (a.type != type) throw InputError(file, 0, who + ": type is " + type_name(a.type) + ", not " + type_name(type));
  if ((a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) || a.normalized)
    throw InputError(file, 0, who + ": componentType " + std::to_string(a.componentType) + (a.normalized ? " normalized" : "") +
                                  " is not unsigned byte or unsigned short");
  const std::size_t nc = std::size_t(tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(type)));
  const std::size_t cs = std::size_t(tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(a.componentType)));
  const unsigned char* data = m.buffers[std::size_t(s.buffer)].data.data();
  std::vector<std::uint32_t> out(nc * s.count);
  for (std::size_t i = 0; i < s.count; ++i)
    for (std::size_t c = 0; c < nc; ++c) out[nc * i + c] = load_index(data + s.base + i * s.stride + c * cs, a.componentType);
  return out;
}

glm::dmat4 local_matrix(const tinygltf::Node& n, std::size_t index, const std::string& file) {
  const std::string who = "node " + str(index);
  auto finite = [&](const std::vector<double>& v, const char* what) {
    for (double x : v)
      if (!std::isfinite(x)) throw InputError(file, 0, who + ": " + what + " is not finite");
  };
  if (!n.matrix.empty()) {
    if (n.matrix.size() != 16) throw InputError(file, 0, who + ": matrix has " + str(n.matrix.size()) + " numbers, not 16");
    finite(n.matrix, "matrix");
    return glm::make_mat4(n.matrix.data());  // column-major, as glm
  }
  glm::dmat4 m(1.0);
  if (!n.translation.empty()) {
    if (n.translation.size() != 3) throw InputError(file, 0, who + ": translation does not have 3 numbers");
    finite(n.translation, "translation");
    m = glm::translate(m, glm::dvec3(n.translation[0], n.translation[1], n.translation[2]));
  }
  if (!n.rotation.empty()) {
    if (n.rotation.size() != 4) throw InputError(file, 0, who + ": rotation does not have 4 numbers");
    finite(n.rotation, "rotation");
    m = m * glm::mat4_cast(glm::dquat(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]));
  }
  if (!n.scale.empty()) {
    if (n.scale.size() != 3) throw InputError(file, 0, who + ": scale does not have 3 numbers");
    finite(n.scale, "scale");
    m = glm::scale(m, glm::dvec3(n.scale[0], n.scale[1], n.scale[2]));
  }
  return m;
}

NodeWalk walk_nodes(const tinygltf::Model& m, const std::string& file) {
  const std::size_t nn = m.nodes.size();
  std::vector<int> parent(nn, -1);
  for (std::size_t n = 0; n < nn; ++n) {
    const tinygltf::Node& node = m.nodes[n];
    for (int c : node.children) {
      if (c < 0 || std::size_t(c) >= nn)
        throw InputError(file, 0, "node " + str(n) + " names child " + std::to_string(c) + ", but the file has " + str(nn) + " nodes");
      if (parent[std::size_t(c)] != -1 || std::size_t(c) == n)
        throw InputError(file, 0, "node " + std::to_string(c) + " has more than one parent (the node hierarchy must be a forest)");
      parent[std::size_t(c)] = int(n);
    }
    if (node.mesh >= 0 && std::size_t(node.mesh) >= m.meshes.size())
      throw InputError(file, 0, "node " + str(n) + " names mesh " + std::to_string(node.mesh) + ", but the file has " + str(m.meshes.size()));
    if (node.skin >= 0 && std::size_t(node.skin) >= m.skins.size())
      throw InputError(file, 0, "node " + str(n) + " names skin " + std::to_string(node.skin) + ", but the file has " + str(m.skins.size()));
  }
  NodeWalk w;
  w.world.assign(nn, glm::dmat4(1.0));
  std::vector<char> placed(nn, 0);
  std::vector<int> stack;
  for (std::size_t r = 0; r < nn; ++r) {
    if (parent[r] != -1) continue;
    stack.assign(1, int(r));
    while (!stack.empty()) {
      const int n = stack.back();
      stack.pop_back();
      const glm::dmat4 local = local_matrix(m.nodes[std::size_t(n)], std::size_t(n), file);
      w.world[std::size_t(n)] = parent[std::size_t(n)] < 0 ? local : w.world[std::size_t(parent[std::size_t(n)])] * local;
      placed[std::size_t(n)] = 1;
      w.topo.push_back(n);
      for (int c : m.nodes[std::size_t(n)].children) stack.push_back(c);
    }
  }
  if (const auto it = std::find(placed.begin(), placed.end(), 0); it != placed.end())
    throw InputError(file, 0, "the node hierarchy has a cycle (through node " + str(std::size_t(it - placed.begin())) + ")");
  std::vector<char> seen(nn, 0);
  auto visit = [&](int root) {
    stack.assign(1, root);
    while (!stack.empty()) {
      const int n = stack.back();
      stack.pop_back();
      if (seen[std::size_t(n)]) continue;
      seen[std::size_t(n)] = 1;
      w.order.push_back(n);
      const auto& ch = m.nodes[std::size_t(n)].children;
      for (auto it = ch.rbegin(); it != ch.rend(); ++it) stack.push_back(*it);  // pre-order, children in order
    }
  };
  std::vector<std::size_t> scenes;
  const std::size_t first = m.defaultScene >= 0 && std::size_t(m.defaultScene) < m.scenes.size() ? std::size_t(m.defaultScene) : 0;
  if (!m.scenes.empty()) scenes.push_back(first);
  for (std::size_t s = 0; s < m.scenes.size(); ++s)
    if (s != first) scenes.push_back(s);
  for (std::size_t s : scenes)
    for (int root : m.scenes[s].nodes) {
      if (root < 0 || std::size_t(root) >= nn)
        throw InputError(file, 0, "scene " + str(s) + " names node " + std::to_string(root) + ", but the file has " + str(nn));
      visit(root);
    }
  for (std::size_t n = 0; n < nn; ++n)
    if (parent[n] == -1) visit(int(n));
  w.parent = std::move(parent);
  return w;
}

}  // namespace sublift
