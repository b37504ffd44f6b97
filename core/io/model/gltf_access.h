#pragma once
// Internal to the glTF readers of io_model (gltf_model.cpp, gltf_animation.cpp, gltf_channels.cpp): accessors checked
// against their buffer before anything is read or allocated from their counts, node matrices and
// the node hierarchy. Every throw is an InputError naming the file and the element.
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <tiny_gltf.h>

namespace sublift {

/// A checked accessor: element i occupies [base + i * stride, base + i * stride + elem) of buffer.
struct AccessorSpan {
  int buffer = -1;
  std::size_t base = 0, stride = 0, elem = 0, count = 0;
  int component = 0;
};

/// A count or index in a message.
inline std::string str(std::size_t v) { return std::to_string(v); }

/// "mesh 2 primitive 0".
std::string prim_name(int mesh, int prim);

/// A little-endian float at `p`.
float load_f32(const unsigned char* p);

/// A little-endian unsigned byte, short or int at `p` (`component`: its glTF componentType).
std::uint32_t load_index(const unsigned char* p, int component);

/// Checks that accessor `index` (used as `role`) can be read: it exists, is not sparse, has a
/// bufferView, and count elements of its type fit in that view (bufferViews are checked against
/// their buffers by import). Its count is then bounded by real bytes.
AccessorSpan checked_accessor(const tinygltf::Model& m, int index, const std::string& role, const std::string& file);

/// checked_accessor, and the accessor is float VEC3 (POSITION, NORMAL, morph target offsets).
AccessorSpan checked_vec3(const tinygltf::Model& m, int index, const std::string& role, const std::string& file);

/// The 3 floats of every element of a checked_vec3 span; throws on a non-finite one.
std::vector<float> read_vec3(const tinygltf::Model& m, const AccessorSpan& s, int index, const std::string& role,
                             const std::string& file);

/// "SCALAR", "VEC3", "MAT4"... for a TINYGLTF_TYPE_* value.
const char* type_name(int type);

/// Every component of accessor `index` (checked_accessor) as doubles, element-major. The accessor
/// must be of `type` (TINYGLTF_TYPE_*) and float, or a normalised integer of a componentType in
/// `normalized` (decoded as glTF 2.0 sec. 3.11 says: c / 255, max(c / 127, -1), ...). Throws
/// naming the accessor and `role` for another type, componentType or a non-finite float.
std::vector<double> read_numbers(const tinygltf::Model& m, int index, int type, std::initializer_list<int> normalized,
                                 const std::string& role, const std::string& file);

/// Every component of accessor `index` as unsigned integers; it must be of `type` and unsigned
/// byte or short, not normalised (JOINTS_n).
std::vector<std::uint32_t> read_unsigned(const tinygltf::Model& m, int index, int type, const std::string& role,
                                         const std::string& file);

/// Node `index`'s local matrix: `matrix`, else T * R * S of its translation, rotation, scale.
/// Throws for a wrong number of numbers or a non-finite one.
glm::dmat4 local_matrix(const tinygltf::Node& n, std::size_t index, const std::string& file);

/// World matrices of all nodes, and the order in which instances are met: the default scene depth
/// first, then the other scenes, then nodes in no scene.
struct NodeWalk {
  std::vector<glm::dmat4> world;
  std::vector<int> order;   // instance order (above)
  std::vector<int> parent;  // node -> parent, -1 for a root
  std::vector<int> topo;    // every node once, each after its parent (world matrices in this order)
};

/// Walks the node hierarchy; throws on a child, mesh or skin out of range, a node with two
/// parents, a cycle, or a scene naming a missing node.
NodeWalk walk_nodes(const tinygltf::Model& m, const std::string& file);

}  // namespace sublift
