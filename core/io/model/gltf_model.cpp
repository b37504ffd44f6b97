// glTF 2.0 models for FFD: read through the locked-down tinygltf (gltf_sandbox.h) with every
// accessor that is used checked before it is read; written back by overwriting the POSITION (and
// NORMAL) bytes in place and serialising the rest of the document as tinygltf read it.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <map>
#include <sstream>
#include <system_error>
#include <unordered_map>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/mat4x4.hpp>

#include "core/base/binary_cursor.h"
#include "core/base/errors.h"
#include "core/base/text_lines.h"
#include "core/base/file_io.h"
#include "core/io/model/gltf_access.h"
#include "core/io/model/gltf_precheck.h"
#include "core/io/model/gltf_sandbox.h"
#include "core/io/model/model_source.h"

namespace sublift {
namespace fs = std::filesystem;
namespace {

constexpr std::size_t kMaxGltfBytes = std::size_t(1) << 31;  // tinygltf takes 32-bit lengths
constexpr std::size_t kMaxQuotedUri = 256;  // a uri (or tinygltf's message quoting one) in a message

// Every buffer view lies inside its buffer (tinygltf 2.7 does not check; images read from views).
void check_buffer_views(const tinygltf::Model& m, const std::string& file) {
  for (std::size_t i = 0; i < m.bufferViews.size(); ++i) {
    const tinygltf::BufferView& v = m.bufferViews[i];
    if (v.buffer < 0 || std::size_t(v.buffer) >= m.buffers.size())
      throw InputError(file, 0, "bufferView " + str(i) + " names buffer " + std::to_string(v.buffer) + ", but the file has " + str(m.buffers.size()));
    const std::size_t size = m.buffers[std::size_t(v.buffer)].data.size();
    if (v.byteOffset > size || v.byteLength > size - v.byteOffset)
      throw InputError(file, 0, "bufferView " + str(i) + " [" + str(v.byteOffset) + ", " + str(v.byteOffset) + " + " +
                                    str(v.byteLength) + ") lies beyond the " + str(size) + " bytes of buffer " + std::to_string(v.buffer));
  }
}

// The model's triangles of one primitive (local vertex numbers), from its mode and indices.
std::vector<std::uint32_t> primitive_indices(const tinygltf::Model& m, const tinygltf::Primitive& p, int mesh, int prim,
                                             std::size_t num_vertices, const std::string& file) {
  std::vector<std::uint32_t> idx;
  if (p.indices < 0) {
    idx.resize(num_vertices);
    for (std::size_t i = 0; i < num_vertices; ++i) idx[i] = std::uint32_t(i);
    return idx;
  }
  const std::string role = "indices of " + prim_name(mesh, prim);
  const AccessorSpan s = checked_accessor(m, p.indices, role, file);
  const tinygltf::Accessor& a = m.accessors[std::size_t(p.indices)];
  if (a.type != TINYGLTF_TYPE_SCALAR ||
      (s.component != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && s.component != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
       s.component != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
    throw InputError(file, 0, "accessor " + std::to_string(p.indices) + " (" + role + "): not SCALAR unsigned byte, short or int");
  const unsigned char* data = m.buffers[std::size_t(s.buffer)].data.data();
  idx.resize(s.count);
  for (std::size_t i = 0; i < s.count; ++i) {
    idx[i] = load_index(data + s.base + i * s.stride, s.component);
    if (idx[i] >= num_vertices)
      throw InputError(file, 0, "accessor " + std::to_string(p.indices) + " (" + role + "): index " + std::to_string(idx[i]) +
                                    " >= " + str(num_vertices) + " vertices (element " + str(i) + ")");
  }
  return idx;
}

// Appends the triangles of a TRIANGLES/STRIP/FAN index list (glTF 2.0 sec. 3.7.2.1), offset by
// `first`, to `faces`; degenerate ones are dropped.
void add_triangles(Csr& faces, const std::vector<std::uint32_t>& idx, int mode, std::size_t first, int mesh, int prim,
                   const std::string& file) {
  auto add = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    if (a == b || b == c || a == c) return;
    faces.items.insert(faces.items.end(), {std::uint32_t(first + a), std::uint32_t(first + b), std::uint32_t(first + c)});
    faces.offsets.push_back(std::uint32_t(faces.items.size()));
  };
  const std::size_t n = idx.size();
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    if (n % 3 != 0) throw InputError(file, 0, prim_name(mesh, prim) + ": " + str(n) + " TRIANGLES indices, not a multiple of 3");
    for (std::size_t i = 0; i + 2 < n; i += 3) add(idx[i], idx[i + 1], idx[i + 2]);
  } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
    for (std::size_t i = 0; i + 2 < n; ++i)
      if (i % 2 == 0) add(idx[i], idx[i + 1], idx[i + 2]);
      else add(idx[i], idx[i + 2], idx[i + 1]);
  } else if (mode == TINYGLTF_MODE_TRIANGLE_FAN) {
    for (std::size_t i = 0; i + 2 < n; ++i) add(idx[i + 1], idx[i + 2], idx[0]);
  }
}

const char* mode_name(int mode) {
  static constexpr const char* kNames[] = {"POINTS", "LINES", "LINE_LOOP", "LINE_STRIP", "TRIANGLES", "TRIANGLE_STRIP", "TRIANGLE_FAN"};
  return mode >= 0 && mode <= 6 ? kNames[mode] : "?";
}

// Refuses POSITION/NORMAL accessors whose bytes are also another accessor's, a sparse block's or
// an image's: overwriting them in place would change that data too.
void check_rewritable(const tinygltf::Model& m, const std::map<int, std::string>& targets, const std::string& file) {
  std::map<int, std::vector<int>> owner;  // buffer -> byte owner (-1 free)
  for (const auto& [acc, role] : targets) {
    const AccessorSpan s = checked_accessor(m, acc, role, file);
    auto& own = owner[s.buffer];
    if (own.empty()) own.assign(m.buffers[std::size_t(s.buffer)].data.size(), -1);
    for (std::size_t i = 0; i < s.count; ++i)
      for (std::size_t b = s.base + i * s.stride, e = b + s.elem; b < e; ++b) {
        if (own[b] >= 0 && own[b] != acc)
          throw InputError(file, 0, "accessor " + std::to_string(acc) + " (" + role + ") shares bytes with accessor " +
                                        std::to_string(own[b]) + ": it cannot be rewritten in place");
        own[b] = acc;
      }
  }
  auto clash = [&](int buffer, std::size_t begin, std::size_t end, const std::string& what) {
    const auto it = owner.find(buffer);
    if (it == owner.end()) return;
    end = std::min(end, it->second.size());
    for (std::size_t b = begin; b < end; ++b)
      if (it->second[b] >= 0)
        throw InputError(file, 0, "accessor " + std::to_string(it->second[b]) + " (" + targets.at(it->second[b]) + ") shares bytes with " +
                                      what + ": it cannot be rewritten in place");
  };
  auto view_range = [&](int view, std::size_t offset, const std::string& what) {
    if (view < 0 || std::size_t(view) >= m.bufferViews.size()) return;
    const auto& v = m.bufferViews[std::size_t(view)];
    clash(v.buffer, v.byteOffset + std::min(offset, v.byteLength), v.byteOffset + v.byteLength, what);
  };
  for (std::size_t i = 0; i < m.accessors.size(); ++i) {
    const tinygltf::Accessor& a = m.accessors[i];
    const std::string what = "accessor " + str(i);
    if (a.sparse.isSparse) {
      view_range(a.sparse.indices.bufferView, std::size_t(std::max(0, a.sparse.indices.byteOffset)), what + " (sparse indices)");
      view_range(a.sparse.values.bufferView, std::size_t(std::max(0, a.sparse.values.byteOffset)), what + " (sparse values)");
    }
    if (targets.count(int(i)) || a.bufferView < 0 || std::size_t(a.bufferView) >= m.bufferViews.size()) continue;
    const tinygltf::BufferView& v = m.bufferViews[std::size_t(a.bufferView)];
    if (!owner.count(v.buffer)) continue;
    const int cs = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(a.componentType));
    const int nc = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(a.type));
    if (cs <= 0 || nc <= 0) continue;
    const std::size_t elem = std::size_t(cs) * std::size_t(nc), stride = v.byteStride ? v.byteStride : elem;
    const std::size_t begin = v.byteOffset + std::min(a.byteOffset, v.byteLength), end = v.byteOffset + v.byteLength;
    for (std::size_t e = 0, at = begin; e < a.count && at < end; ++e, at += stride) clash(v.buffer, at, std::min(at + elem, end), what);
  }
  for (std::size_t i = 0; i < m.images.size(); ++i) view_range(m.images[i].bufferView, 0, "image " + str(i));
}

bool has_extension(const std::vector<std::string>& list, const char* name) {
  return std::find(list.begin(), list.end(), name) != list.end();
}

// Key of a smoothing group: a vertex's original position and normal bits (-0 as +0).
struct GroupKey {
  std::array<std::uint32_t, 6> bits{};
  bool operator==(const GroupKey&) const = default;
};
struct GroupKeyHash {
  std::size_t operator()(const GroupKey& k) const {
    std::size_t h = 1469598103934665603ull;
    for (std::uint32_t b : k.bits) h = (h ^ b) * 1099511628211ull;
    return h;
  }
};

glm::dmat4 range_world(const ModelRange& r) { return glm::make_mat4(r.world.data()); }

}  // namespace

Model import_gltf_model(const std::string& path, ModelFormat format) {
  const std::string bytes = read_file_bytes(path, kMaxGltfBytes);
  auto source = std::make_shared<ModelSource>();
  std::error_code ec;
  const fs::path folder = fs::canonical(fs::absolute(fs::path(path)).parent_path(), ec);
  if (ec) throw IoError(path + ": cannot resolve its folder: " + ec.message());
  source->folder = folder.string();
  GltfSandbox box{source->folder, {}};
  tinygltf::TinyGLTF loader;
  lock_down(loader, box);
  tinygltf::Model& g = source->gltf;
  std::string err, warn;
  bool ok = false;
  try {
    if (format == ModelFormat::Glb) {
      const std::size_t length = check_glb_container(bytes, path);
      const auto json_len = load_endian<std::uint32_t>(bytes.data() + 12, false);
      check_json_depth(std::string_view(bytes).substr(20, json_len), path);
      precheck_gltf_json(std::string_view(bytes).substr(20, json_len), path);
      ok = loader.LoadBinaryFromMemory(&g, &err, &warn, reinterpret_cast<const unsigned char*>(bytes.data()),
                                       static_cast<unsigned int>(length), source->folder);
    } else {
      if (bytes.empty()) throw InputError(path, 0, "empty file");
      check_json_depth(bytes, path);
      precheck_gltf_json(bytes, path);
      ok = loader.LoadASCIIFromString(&g, &err, &warn, bytes.data(), static_cast<unsigned int>(bytes.size()), source->folder);
    }
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(path, 0, std::string("glTF could not be parsed: ") + e.what());
  }
  if (!ok) {
    if (!box.refused.empty())
      throw InputError(path, 0, "uri '" + printable(box.refused.front(), kMaxQuotedUri) + "' points outside the model's folder (an absolute path, '..', a URL or a symlink out): refused");
    const auto errs = nonempty_lines(err);
    throw InputError(path, 0, "glTF: " + (errs.empty() ? std::string("tinygltf could not read it") : printable(errs.front(), kMaxQuotedUri)));
  }
  Model model;
  model.path = path;
  model.format = format;
  for (const std::string& r : box.refused)
    model.notes.push_back("image uri '" + printable(r, kMaxQuotedUri) + "' points outside the model's folder: not read, the reference is kept as it is");
  for (const std::string& w : nonempty_lines(warn)) model.notes.push_back("tinygltf: " + printable(w, kMaxQuotedUri));

  for (const char* ext : {"KHR_draco_mesh_compression", "EXT_meshopt_compression", "KHR_mesh_quantization", "EXT_mesh_gpu_instancing"})
    if (has_extension(g.extensionsRequired, ext))
      throw InputError(path, 0, std::string("requires extension ") + ext + ", which model import does not support");
  check_buffer_views(g, path);
  const NodeWalk walk = walk_nodes(g, path);

  // Ranges: one per POSITION accessor, placed by the first node instancing it.
  std::map<int, std::size_t> range_of;    // POSITION accessor -> range
  std::map<int, int> normal_position;     // NORMAL accessor -> its POSITION accessor
  std::map<int, std::string> targets;     // accessors rewritten on export -> role
  std::vector<int> first_node(g.meshes.size(), -1), instances(g.meshes.size(), 0);
  std::vector<float> orig_normals;        // mesh space, 3 per vertex (0 where the file has none)
  // Adds mesh `mesh` as instanced by `node` (-1: by none, placed in its own mesh space).
  auto add_mesh = [&](int mesh, int node) {
    const bool skinned = node >= 0 && g.nodes[std::size_t(node)].skin >= 0;
    const auto& prims = g.meshes[std::size_t(mesh)].primitives;
    bool morph = false;
    for (std::size_t pi = 0; pi < prims.size(); ++pi) {
      const tinygltf::Primitive& p = prims[pi];
      const int prim = int(pi);
      const int mode = p.mode < 0 ? TINYGLTF_MODE_TRIANGLES : p.mode;
      if (mode > TINYGLTF_MODE_TRIANGLE_FAN)
        throw InputError(path, 0, prim_name(mesh, prim) + ": mode " + std::to_string(mode) + " is not a glTF primitive mode");
      if (p.extensions.count("KHR_draco_mesh_compression"))
        throw InputError(path, 0, prim_name(mesh, prim) + ": Draco-compressed primitives are not supported");
      morph = morph || !p.targets.empty();
      const auto pos = p.attributes.find("POSITION");
      if (pos == p.attributes.end()) {
        model.notes.push_back(prim_name(mesh, prim) + " has no POSITION: left as it is");
        continue;
      }
      const std::string role = "POSITION of " + prim_name(mesh, prim);
      const AccessorSpan ps = checked_vec3(g, pos->second, role, path);
      auto found = range_of.find(pos->second);
      if (found == range_of.end()) {
        ModelRange r;
        r.first_vertex = model.num_vertices();
        r.num_vertices = ps.count;
        r.accessor = pos->second;
        r.node = node;
        r.skinned = skinned;
        const glm::dmat4 world = node < 0 || skinned ? glm::dmat4(1.0) : walk.world[std::size_t(node)];
        const double det = glm::determinant(world);
        if (!std::isfinite(det) || std::abs(det) < 1e-300)
          throw InputError(path, 0, "node " + std::to_string(node) + ": its world matrix is singular (a zero scale?), so " + role + " cannot be written back");
        std::copy_n(glm::value_ptr(world), 16, r.world.begin());
        if (model.num_vertices() + ps.count >= std::numeric_limits<std::uint32_t>::max())
          throw InputError(path, 0, "more than 2^32 vertices");
        const std::vector<float> mp = read_vec3(g, ps, pos->second, role, path);
        for (std::size_t v = 0; v < ps.count; ++v) {
          const glm::dvec4 w = world * glm::dvec4(mp[3 * v], mp[3 * v + 1], mp[3 * v + 2], 1.0);
          model.positions.insert(model.positions.end(), {w.x, w.y, w.z});
        }
        source->mesh_positions.insert(source->mesh_positions.end(), mp.begin(), mp.end());
        orig_normals.resize(3 * model.num_vertices(), 0.0f);
        targets[pos->second] = role;
        found = range_of.emplace(pos->second, model.ranges.size()).first;
        model.ranges.push_back(std::move(r));
        if (skinned)
          model.notes.push_back("mesh " + std::to_string(mesh) + " (node " + std::to_string(node) + ") is skinned: its bind-pose positions are deformed as stored, without skinning or the node's transform");
      } else if (model.ranges[found->second].node != node) {
        model.notes.push_back(role + " is also used by another mesh: deformed in the frame that mesh's node " +
                              std::to_string(model.ranges[found->second].node) + " gives it");
      }
      ModelRange& r = model.ranges[found->second];
      r.primitives.emplace_back(mesh, prim);

      const auto nrm = p.attributes.find("NORMAL");
      if (nrm != p.attributes.end()) {
        const std::string nrole = "NORMAL of " + prim_name(mesh, prim);
        const AccessorSpan ns = checked_vec3(g, nrm->second, nrole, path);
        if (ns.count != ps.count)
          throw InputError(path, 0, "accessor " + std::to_string(nrm->second) + " (" + nrole + "): " + str(ns.count) + " normals for " + str(ps.count) + " positions");
        const auto owner = normal_position.find(nrm->second);
        if (owner != normal_position.end() && owner->second != pos->second)
          throw InputError(path, 0, "accessor " + std::to_string(nrm->second) + " is the NORMAL of two different POSITION accessors (" +
                                        std::to_string(owner->second) + " and " + std::to_string(pos->second) + ")");
        if (r.normal_accessor >= 0 && r.normal_accessor != nrm->second)
          throw InputError(path, 0, "POSITION accessor " + std::to_string(pos->second) + " has two NORMAL accessors (" +
                                        std::to_string(r.normal_accessor) + " and " + std::to_string(nrm->second) + ")");
        if (r.normal_accessor < 0) {
          r.normal_accessor = nrm->second;
          normal_position[nrm->second] = pos->second;
          targets[nrm->second] = nrole;
          const std::vector<float> n = read_vec3(g, ns, nrm->second, nrole, path);
          std::copy(n.begin(), n.end(), orig_normals.begin() + std::ptrdiff_t(3 * r.first_vertex));
        }
      }
      // COLOR_0 (glTF 2.0 sec. 3.7.2.1: float or normalised unsigned byte/short, VEC3 or VEC4), the
      // first one of each POSITION accessor; RGBA, alpha 1 for VEC3.
      const auto col = p.attributes.find("COLOR_0");
      if (col != p.attributes.end() && !r.has_colors) {
        const std::string crole = "COLOR_0 of " + prim_name(mesh, prim);
        const tinygltf::Accessor* ca = col->second >= 0 && std::size_t(col->second) < g.accessors.size() ? &g.accessors[std::size_t(col->second)] : nullptr;
        const int type = ca && ca->type == TINYGLTF_TYPE_VEC3 ? TINYGLTF_TYPE_VEC3 : TINYGLTF_TYPE_VEC4;
        const std::vector<double> c = read_numbers(g, col->second, type, {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT}, crole, path);
        const std::size_t width = type == TINYGLTF_TYPE_VEC3 ? 3 : 4;
        if (c.size() != width * ps.count)
          throw InputError(path, 0, "accessor " + std::to_string(col->second) + " (" + crole + "): " + str(c.size() / width) + " colours for " + str(ps.count) + " positions");
        model.colors.resize(4 * model.num_vertices(), 1.0f);
        for (std::size_t v = 0; v < ps.count; ++v)
          for (std::size_t k = 0; k < width; ++k) model.colors[4 * (r.first_vertex + v) + k] = float(c[width * v + k]);
        r.has_colors = true;
      }
      // TEXCOORD_0 (sec. 3.7.2.1: float or normalised unsigned byte/short VEC2), the first one of
      // each POSITION accessor.
      const auto tex = p.attributes.find("TEXCOORD_0");
      if (tex != p.attributes.end() && !r.has_texcoords) {
        const std::string trole = "TEXCOORD_0 of " + prim_name(mesh, prim);
        const std::vector<double> t = read_numbers(g, tex->second, TINYGLTF_TYPE_VEC2, {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT}, trole, path);
        if (t.size() != 2 * ps.count)
          throw InputError(path, 0, "accessor " + std::to_string(tex->second) + " (" + trole + "): " + str(t.size() / 2) + " texture coordinates for " + str(ps.count) + " positions");
        model.texcoords.resize(2 * model.num_vertices(), 0.0f);
        for (std::size_t k = 0; k < 2 * ps.count; ++k) {
          model.texcoords[2 * r.first_vertex + k] = float(t[k]);
          if (!std::isfinite(model.texcoords[2 * r.first_vertex + k]))
            throw InputError(path, 0, "accessor " + std::to_string(tex->second) + " (" + trole + "): a texture coordinate that is not finite");
        }
        r.has_texcoords = true;
      }
      // Application-specific attributes ("_NAME", glTF 2.0 sec. 3.7.2.1): float SCALARs are read,
      // the first of each name per POSITION accessor; others are named as not read.
      for (const auto& [semantic, index] : p.attributes) {
        if (semantic.empty() || semantic[0] != '_') continue;
        const tinygltf::Accessor* acc = index >= 0 && std::size_t(index) < g.accessors.size() ? &g.accessors[std::size_t(index)] : nullptr;
        if (!acc || acc->type != TINYGLTF_TYPE_SCALAR || acc->componentType != TINYGLTF_COMPONENT_TYPE_FLOAT || acc->normalized) {
          model.notes.push_back(prim_name(mesh, prim) + ": attribute " + printable(semantic, 64) + " is not a float SCALAR: not read");
          continue;
        }
        const std::string& name = semantic;  // a structured binding cannot be captured before C++20's P1091 (clang 14)
        auto it = std::find_if(model.custom.begin(), model.custom.end(), [&](const auto& c) { return c.first == name; });
        if (it == model.custom.end()) {
          model.custom.emplace_back(semantic, std::vector<float>());
          it = model.custom.end() - 1;
        }
        if (it->second.size() >= r.first_vertex + ps.count) continue;  // this range has it already
        const std::vector<double> x = read_numbers(g, index, TINYGLTF_TYPE_SCALAR, {}, semantic + " of " + prim_name(mesh, prim), path);
        if (x.size() != ps.count)
          throw InputError(path, 0, "accessor " + std::to_string(index) + " (" + semantic + "): " + str(x.size()) + " values for " + str(ps.count) + " positions");
        it->second.resize(r.first_vertex + ps.count, 0.0f);
        for (std::size_t v = 0; v < ps.count; ++v) it->second[r.first_vertex + v] = float(x[v]);
      }
      const std::vector<std::uint32_t> idx = primitive_indices(g, p, mesh, prim, ps.count, path);
      if (mode >= TINYGLTF_MODE_TRIANGLES)
        add_triangles(model.faces, idx, mode, r.first_vertex, mesh, prim, path);
      else
        model.notes.push_back(prim_name(mesh, prim) + " (" + mode_name(mode) + "): its vertices move but are not drawn");
    }
    if (morph)
      model.notes.push_back("mesh " + std::to_string(mesh) + " has morph targets: the base positions are deformed, the targets (offsets) are kept");
  };
  for (int node : walk.order) {
    const int mesh = g.nodes[std::size_t(node)].mesh;
    if (mesh < 0 || instances[std::size_t(mesh)]++ > 0) continue;
    first_node[std::size_t(mesh)] = node;
    add_mesh(mesh, node);
  }
  for (std::size_t mesh = 0; mesh < g.meshes.size(); ++mesh) {
    if (instances[mesh] == 0) {
      model.notes.push_back("mesh " + str(mesh) + " is used by no node: deformed in its own mesh space");
      add_mesh(int(mesh), -1);
    } else if (instances[mesh] > 1) {
      model.notes.push_back("mesh " + str(mesh) + " is instanced by " + std::to_string(instances[mesh]) + " nodes: deformed in the frame of node " +
                            std::to_string(first_node[mesh]) + " (the first); the other instances show the same mesh-space change");
    }
  }
  // An accessor rewritten on export must not serve in any other role.
  auto other_use = [&](int acc, const std::string& role) {
    const auto t = targets.find(acc);
    if (t != targets.end() && t->second.compare(0, role.size(), role) != 0)
      throw InputError(path, 0, "accessor " + std::to_string(acc) + " is both " + t->second + " and " + role + ": it cannot be rewritten in place");
  };
  for (std::size_t mesh = 0; mesh < g.meshes.size(); ++mesh)
    for (std::size_t pi = 0; pi < g.meshes[mesh].primitives.size(); ++pi) {
      const tinygltf::Primitive& p = g.meshes[mesh].primitives[pi];
      const std::string where = " of " + prim_name(int(mesh), int(pi));
      for (const auto& [name, acc] : p.attributes)
        if (name == "POSITION" || name == "NORMAL") other_use(acc, name);
        else other_use(acc, name + where);
      if (p.indices >= 0) other_use(p.indices, "indices" + where);
      for (const auto& target : p.targets)
        for (const auto& [name, acc] : target) other_use(acc, "morph target " + name + where);
    }
  for (std::size_t s = 0; s < g.skins.size(); ++s)
    if (g.skins[s].inverseBindMatrices >= 0) other_use(g.skins[s].inverseBindMatrices, "inverseBindMatrices of skin " + str(s));
  for (std::size_t a = 0; a < g.animations.size(); ++a)
    for (const auto& sampler : g.animations[a].samplers) {
      other_use(sampler.input, "input of animation " + str(a));
      other_use(sampler.output, "output of animation " + str(a));
    }
  check_rewritable(g, targets, path);

  // Smoothing groups: vertices of one range with the same original position and normal.
  const std::size_t nv = model.num_vertices();
  source->smooth_rep.resize(nv);
  for (const ModelRange& r : model.ranges) {
    std::unordered_map<GroupKey, std::uint32_t, GroupKeyHash> rep;
    for (std::size_t v = r.first_vertex; v < r.first_vertex + r.num_vertices; ++v) {
      GroupKey k;
      for (int c = 0; c < 3; ++c) {
        k.bits[std::size_t(c)] = std::bit_cast<std::uint32_t>(source->mesh_positions[3 * v + std::size_t(c)] + 0.0f);
        k.bits[std::size_t(c) + 3] = std::bit_cast<std::uint32_t>(orig_normals[3 * v + std::size_t(c)] + 0.0f);
      }
      source->smooth_rep[v] = rep.emplace(k, std::uint32_t(v)).first->second;
    }
  }
  // Display normals: the file's own (to world by the inverse transpose), else area-weighted.
  model.normals = grouped_normals(model.faces, model.positions, source->smooth_rep);
  for (const ModelRange& r : model.ranges) {
    if (r.normal_accessor < 0) continue;
    const glm::dmat3 nm = glm::transpose(glm::inverse(glm::dmat3(range_world(r))));
    for (std::size_t v = r.first_vertex; v < r.first_vertex + r.num_vertices; ++v) {
      glm::dvec3 n = nm * glm::dvec3(orig_normals[3 * v], orig_normals[3 * v + 1], orig_normals[3 * v + 2]);
      const double len = glm::length(n);
      n = len > 0 ? n / len : glm::dvec3(0.0);
      for (int c = 0; c < 3; ++c) model.normals[3 * v + std::size_t(c)] = n[c];
    }
  }
  model.source = std::move(source);
  if (!model.colors.empty()) model.colors.resize(4 * model.num_vertices(), 1.0f);  // ranges after the first colours: white
  if (!model.texcoords.empty()) model.texcoords.resize(2 * model.num_vertices(), 0.0f);
  for (auto& [name, values] : model.custom) values.resize(model.num_vertices(), 0.0f);
  return model;
}

namespace {

// Writes the external image files the model references next to `out_dir` when they are not
// there already (the output is in another folder, or the file is missing).
void copy_external_images(const ModelSource& src, const fs::path& out_dir, const std::string& path) {
  std::error_code ec;
  const fs::path out_real = fs::weakly_canonical(out_dir, ec);
  const bool same_folder = !ec && out_real.string() == src.folder;
  for (const tinygltf::Image& image : src.gltf.images) {
    if (image.uri.empty() || image.image.empty()) continue;  // embedded, or not read at import
    const std::string rel = percent_decode(image.uri);
    const fs::path r(rel);
    if (r.is_absolute() || std::any_of(r.begin(), r.end(), [](const fs::path& c) { return c == ".."; }))
      continue;  // never resolved at import either
    const fs::path dest = out_dir / r;
    const bool exists = fs::exists(dest, ec);
    if (exists && same_folder) continue;  // the model's own file
    if (exists) {
      try {
        const std::string have = read_file_bytes(dest.string());
        if (have.size() == image.image.size() && std::equal(have.begin(), have.end(), image.image.begin(),
                                                            [](char a, unsigned char b) { return static_cast<unsigned char>(a) == b; }))
          continue;
      } catch (const IoError&) {
        // unreadable: replaced below
      }
    }
    fs::create_directories(dest.parent_path(), ec);
    if (ec) throw IoError(path + ": cannot create folder " + dest.parent_path().string() + " for image '" + image.uri + "': " + ec.message());
    write_file_atomic(dest.string(), [&](std::ostream& out) {
      out.write(reinterpret_cast<const char*>(image.image.data()), static_cast<std::streamsize>(image.image.size()));
    }, true);
  }
}

}  // namespace

void export_gltf_model(const Model& model, std::span<const double> world_positions, const std::string& path) {
  const ModelSource& src = *model.source;
  tinygltf::Model g = src.gltf;
  const bool glb = file_extension(path) == "glb";
  const std::size_t nv = model.num_vertices();

  // World -> mesh space through each range's inverse world matrix, rounded to float.
  std::vector<float> f32(3 * nv);
  std::vector<double> mesh_xyz(3 * nv);
  std::vector<char> moved(nv, 0);
  for (const ModelRange& r : model.ranges) {
    const glm::dmat4 inv = glm::inverse(range_world(r));
    for (std::size_t v = r.first_vertex; v < r.first_vertex + r.num_vertices; ++v) {
      const glm::dvec4 p = inv * glm::dvec4(world_positions[3 * v], world_positions[3 * v + 1], world_positions[3 * v + 2], 1.0);
      for (int c = 0; c < 3; ++c) {
        const float f = static_cast<float>(p[c]);
        if (!std::isfinite(f))
          throw InputError(path, 0, "vertex " + str(v) + ": its mesh-space position does not fit in float32");
        f32[3 * v + std::size_t(c)] = f;
        mesh_xyz[3 * v + std::size_t(c)] = f;
        if (std::bit_cast<std::uint32_t>(f) != std::bit_cast<std::uint32_t>(src.mesh_positions[3 * v + std::size_t(c)])) moved[v] = 1;
      }
    }
  }
  // Writes 3 floats per element into accessor `acc` and refreshes its min/max (the validator
  // checks them against the data; POSITION must have them).
  auto write_vec3 = [&](int acc, const std::vector<float>& values, std::size_t first, bool force_bounds) {
    const AccessorSpan s = checked_vec3(g, acc, "rewritten accessor", path);
    unsigned char* data = g.buffers[std::size_t(s.buffer)].data.data();
    tinygltf::Accessor& a = g.accessors[std::size_t(acc)];
    std::vector<double> lo(3, std::numeric_limits<double>::infinity()), hi(3, -std::numeric_limits<double>::infinity());
    for (std::size_t i = 0; i < s.count; ++i)
      for (std::size_t c = 0; c < 3; ++c) {
        const float f = values[3 * (first + i) + c];
        store_endian(data + s.base + i * s.stride + 4 * c, f, false);
        lo[c] = std::min(lo[c], double(f));
        hi[c] = std::max(hi[c], double(f));
      }
    if (force_bounds || !a.minValues.empty() || !a.maxValues.empty()) {
      a.minValues = lo;
      a.maxValues = hi;
    }
  };
  for (const ModelRange& r : model.ranges) write_vec3(r.accessor, f32, r.first_vertex, true);

  // Normals: area-weighted over the deformed triangles in mesh space, by smoothing group, only
  // where a triangle of the group moved; elsewhere the file's normal stays as it was.
  bool any_normals = false;
  for (const ModelRange& r : model.ranges) any_normals = any_normals || r.normal_accessor >= 0;
  if (any_normals) {
    const std::vector<double> n = grouped_normals(model.faces, mesh_xyz, src.smooth_rep);
    std::vector<char> touched(nv, 0);
    for (std::size_t f = 0; f < model.faces.rows(); ++f) {
      const auto c = model.faces.row(f);
      if (std::any_of(c.begin(), c.end(), [&](std::uint32_t v) { return moved[v]; }))
        for (std::uint32_t v : c) touched[src.smooth_rep[v]] = 1;
    }
    for (const ModelRange& r : model.ranges) {
      if (r.normal_accessor < 0) continue;
      const AccessorSpan s = checked_vec3(g, r.normal_accessor, "NORMAL", path);
      const unsigned char* data = g.buffers[std::size_t(s.buffer)].data.data();
      std::vector<float> out(3 * r.num_vertices);
      for (std::size_t i = 0; i < r.num_vertices; ++i) {
        const std::size_t v = r.first_vertex + i;
        const double* nv3 = &n[3 * v];
        if (touched[src.smooth_rep[v]] && (nv3[0] != 0 || nv3[1] != 0 || nv3[2] != 0)) {
          float f[3] = {float(nv3[0]), float(nv3[1]), float(nv3[2])};
          const float len = std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);  // unit again in float
          for (int c = 0; c < 3; ++c) out[3 * i + std::size_t(c)] = f[c] / len;
        } else {
          for (std::size_t c = 0; c < 3; ++c) out[3 * i + c] = load_f32(data + s.base + i * s.stride + 4 * c);
        }
      }
      write_vec3(r.normal_accessor, out, 0, false);
    }
  }

  if (glb && !g.buffers.empty()) g.buffers[0].uri.clear();  // buffer 0 becomes the BIN chunk
  tinygltf::TinyGLTF writer;
  write_images_as_read(writer);
  std::ostringstream out(std::ios::binary);
  if (!writer.WriteGltfSceneToStream(&g, out, /*prettyPrint=*/!glb, glb) || !out)
    throw IoError(path + ": cannot serialise glTF");
  const std::string bytes = fix_null_objects(std::move(out).str(), glb);
  fs::path out_dir = fs::path(path).parent_path();
  if (out_dir.empty()) out_dir = ".";
  std::error_code ec;
  if (!fs::is_directory(out_dir, ec)) throw IoError(path + ": folder " + out_dir.string() + " does not exist");
  copy_external_images(src, out_dir, path);
  write_file_atomic(path, [&](std::ostream& o) { o.write(bytes.data(), static_cast<std::streamsize>(bytes.size())); }, true);
}

}  // namespace sublift
