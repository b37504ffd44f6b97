#include "core/io/model/surface_export.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cctype>
#include <cstring>
#include <limits>
#include <ostream>
#include <sstream>
#include <vector>

#include <tiny_gltf.h>

#include "core/base/binary_cursor.h"
#include "core/base/errors.h"
#include "core/base/file_io.h"
#include "core/base/magnitude.h"
#include "core/complex/face_varying.h"
#include "core/io/mesh/mesh_export.h"

namespace sublift {
namespace {

// The surface after checking: positions as given, normals of unit length.
struct Surface {
  const Csr& faces;
  std::span<const double> xyz;
  std::vector<double> normals;
  std::span<const VertexAttribute> attributes;  // glTF only
  std::span<const double> texcoords;             // glTF only: u, v per vertex (v up), or empty
  const SurfaceTexture* texture = nullptr;       // glTF only
  std::size_t num_vertices() const { return xyz.size() / 3; }
};

bool is_colour(const std::string& name) { return name == "red" || name == "green" || name == "blue" || name == "alpha"; }

// "_QUALITY" for "quality": glTF's application-specific attribute semantics start with '_'.
std::string custom_semantic(const std::string& name) {
  std::string s = "_";
  for (char c : name) s += std::isalnum(static_cast<unsigned char>(c)) ? char(std::toupper(static_cast<unsigned char>(c))) : '_';
  return s;
}

Surface checked_surface(const std::string& path, const Csr& faces, std::span<const double> xyz,
                        std::span<const double> normals) {
  if (xyz.size() % 3 != 0) throw InputError(path, 0, "positions are not 3 values per vertex");
  if (normals.size() != xyz.size())
    throw InputError(path, 0, std::to_string(normals.size() / 3) + " normals for " + std::to_string(xyz.size() / 3) + " vertices");
  if (xyz.size() / 3 > 0xffffffffu) throw InputError(path, 0, "more than 2^32 vertices");
  if (faces.offsets.empty() || faces.offsets.front() != 0 || faces.offsets.back() != faces.items.size())
    throw InputError(path, 0, "face offsets do not run from 0 to the corner count");
  // A lattice whose every face is shared has no boundary: an OBJ of bare vertices says nothing.
  if (faces.rows() == 0) throw InputError(path, 0, "the surface has no faces (a lattice without boundary faces?); nothing written");
  const std::size_t nv = xyz.size() / 3;
  for (std::size_t f = 0; f < faces.rows(); ++f) {
    if (faces.offsets[f + 1] < faces.offsets[f] + 3)
      throw InputError(path, 0, "face " + std::to_string(f) + " has fewer than 3 corners");
    for (std::uint32_t v : faces.row(f))
      if (v >= nv) throw InputError(path, 0, "face " + std::to_string(f) + " names vertex " + std::to_string(v) + ", beyond " + std::to_string(nv));
  }
  check_writable_positions(path, xyz);
  Surface s{faces, xyz, std::vector<double>(normals.begin(), normals.end()), {}, {}, nullptr};
  for (std::size_t v = 0; v < nv; ++v) {
    double* n = &s.normals[3 * v];
    if (!std::isfinite(n[0]) || !std::isfinite(n[1]) || !std::isfinite(n[2]))
      throw InputError(path, 0, "normal of vertex " + std::to_string(v) + " is not finite");
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (std::abs(len - 1.0) <= 1e-12) {
      // unit already: written bit for bit
    } else if (len > 0 && std::isfinite(len)) {
      for (int k = 0; k < 3; ++k) n[k] /= len;
    } else {
      n[0] = 0, n[1] = 0, n[2] = 1;
    }
  }
  return s;
}

void write_obj(std::ostream& out, const Surface& s, const FaceVaryingUV* uv) {
  out << "# written by Sublift\n";
  const std::size_t nv = s.num_vertices();
  for (std::size_t v = 0; v < nv; ++v) write_xyz_line(out, "v ", &s.xyz[3 * v]);
  if (uv)
    for (std::size_t k = 0; k < uv->num_points(); ++k)
      out << "vt " << format_double(uv->points[2 * k]) << ' ' << format_double(uv->points[2 * k + 1]) << '\n';
  for (std::size_t v = 0; v < nv; ++v) write_xyz_line(out, "vn ", &s.normals[3 * v]);
  for (std::size_t f = 0; f < s.faces.rows(); ++f) {
    out << 'f';
    for (std::uint32_t k = s.faces.offsets[f]; k < s.faces.offsets[f + 1]; ++k) {
      const std::uint32_t v = s.faces.items[k];
      out << ' ' << v + 1 << '/';
      if (uv) out << uv->corners[k] + 1;
      out << '/' << v + 1;
    }
    out << '\n';
  }
}

template <class T>
void put_le(std::ostream& out, T x) {
  unsigned char b[sizeof(T)];
  store_endian(b, x, false);
  out.write(reinterpret_cast<const char*>(b), sizeof(T));
}

void write_ply(std::ostream& out, const Surface& s) {
  std::uint32_t widest = 0;
  for (std::size_t f = 0; f < s.faces.rows(); ++f) widest = std::max(widest, s.faces.size(f));
  const bool wide = widest > 255;  // a uchar count cannot hold this face
  const std::size_t nv = s.num_vertices();
  out << "ply\nformat binary_little_endian 1.0\ncomment written by Sublift\nelement vertex " << nv
      << "\nproperty double x\nproperty double y\nproperty double z\nproperty double nx\nproperty double ny\n"
         "property double nz\nelement face "
      << s.faces.rows() << "\nproperty list " << (wide ? "uint" : "uchar") << " uint vertex_indices\nend_header\n";
  for (std::size_t v = 0; v < nv; ++v) {
    for (int k = 0; k < 3; ++k) put_le(out, s.xyz[3 * v + k]);
    for (int k = 0; k < 3; ++k) put_le(out, s.normals[3 * v + k]);
  }
  for (std::size_t f = 0; f < s.faces.rows(); ++f) {
    if (wide) put_le(out, s.faces.size(f));
    else put_le(out, static_cast<std::uint8_t>(s.faces.size(f)));
    for (std::uint32_t v : s.faces.row(f)) put_le(out, v);
  }
}

// Appends `values` to the buffer as little-endian bytes.
template <class T>
void append_le(std::vector<unsigned char>& buf, const std::vector<T>& values) {
  const std::size_t at = buf.size();
  buf.resize(at + values.size() * sizeof(T));
  std::memcpy(buf.data() + at, values.data(), values.size() * sizeof(T));
  if constexpr (std::endian::native == std::endian::big)
    for (std::size_t i = at; i < buf.size(); i += sizeof(T)) std::reverse(buf.begin() + i, buf.begin() + i + sizeof(T));
}

int add_view(tinygltf::Model& m, std::size_t offset, std::size_t length, int target) {
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = offset;
  view.byteLength = length;
  view.target = target;
  m.bufferViews.push_back(view);
  return static_cast<int>(m.bufferViews.size()) - 1;
}

// The glTF document of the surface (one scene, node, mesh, primitive), serialised in memory.
std::string gltf_bytes(const std::string& path, const Surface& s, bool binary) {
  const std::size_t nv = s.num_vertices();
  std::vector<float> pos(3 * nv), nrm(3 * nv);
  for (std::size_t i = 0; i < 3 * nv; ++i) {
    pos[i] = static_cast<float>(s.xyz[i]);
    if (!std::isfinite(pos[i])) throw InputError(path, 0, "position of vertex " + std::to_string(i / 3) + " overflows float32");
  }
  for (std::size_t v = 0; v < nv; ++v) {  // unit length again after rounding to float
    float n[3];
    for (int k = 0; k < 3; ++k) n[k] = static_cast<float>(s.normals[3 * v + k]);
    const float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; ++k) nrm[3 * v + k] = n[k] / len;
  }
  std::vector<std::uint32_t> tri;  // fans from each face's first corner
  for (std::size_t f = 0; f < s.faces.rows(); ++f) {
    const auto c = s.faces.row(f);
    for (std::size_t i = 1; i + 1 < c.size(); ++i) tri.insert(tri.end(), {c[0], c[i], c[i + 1]});
  }
  if (tri.empty()) throw InputError(path, 0, "glTF needs at least one face");
  const double bytes = 24.0 * double(nv) + 4.0 * double(tri.size());
  if (bytes > double(std::numeric_limits<std::uint32_t>::max()) - (1 << 20))
    throw InputError(path, 0, "the surface needs more than 4 GB of glTF buffer");

  tinygltf::Model m;
  m.asset.version = "2.0";
  m.asset.generator = "Sublift";
  tinygltf::Buffer buffer;
  append_le(buffer.data, pos);
  append_le(buffer.data, nrm);
  append_le(buffer.data, tri);
  m.buffers.push_back(std::move(buffer));
  const int pos_view = add_view(m, 0, 12 * nv, TINYGLTF_TARGET_ARRAY_BUFFER);
  const int nrm_view = add_view(m, 12 * nv, 12 * nv, TINYGLTF_TARGET_ARRAY_BUFFER);
  const int idx_view = add_view(m, 24 * nv, 4 * tri.size(), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);

  auto accessor = [](int view, int component, int type, std::size_t count) {  // over a whole view
    tinygltf::Accessor a;
    a.bufferView = view;
    a.componentType = component;
    a.type = type;
    a.count = count;
    return a;
  };
  tinygltf::Accessor position = accessor(pos_view, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, nv);
  position.minValues.assign(3, std::numeric_limits<double>::infinity());
  position.maxValues.assign(3, -std::numeric_limits<double>::infinity());
  for (std::size_t v = 0; v < nv; ++v)
    for (int k = 0; k < 3; ++k) {  // glTF 2.0 sec. 3.6.2.5: POSITION requires min and max
      position.minValues[k] = std::min(position.minValues[k], double(pos[3 * v + k]));
      position.maxValues[k] = std::max(position.maxValues[k], double(pos[3 * v + k]));
    }
  m.accessors = {position, accessor(nrm_view, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, nv),
                 accessor(idx_view, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, tri.size())};

  tinygltf::Primitive prim;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  prim.attributes["POSITION"] = 0;
  prim.attributes["NORMAL"] = 1;
  prim.indices = 2;
  // Attributes after the indices: COLOR_0 from red, green, blue (alpha), the rest as "_NAME".
  auto append = [&](const std::vector<float>& values, int type, std::size_t count) {
    tinygltf::Buffer& b = m.buffers[0];
    const std::size_t at = b.data.size();
    append_le(b.data, values);
    m.bufferViews.push_back({});
    tinygltf::BufferView& view = m.bufferViews.back();
    view.buffer = 0;
    view.byteOffset = at;
    view.byteLength = 4 * values.size();
    view.target = TINYGLTF_TARGET_ARRAY_BUFFER;
    m.accessors.push_back(accessor(int(m.bufferViews.size()) - 1, TINYGLTF_COMPONENT_TYPE_FLOAT, type, count));
    return int(m.accessors.size()) - 1;
  };
  const VertexAttribute* channel[4] = {nullptr, nullptr, nullptr, nullptr};
  for (const VertexAttribute& a : s.attributes) {
    const char* names[4] = {"red", "green", "blue", "alpha"};
    for (int k = 0; k < 4; ++k)
      if (a.name == names[k]) channel[k] = &a;
  }
  if (channel[0] && channel[1] && channel[2]) {
    std::vector<float> rgba(4 * nv, 1.0f);
    for (int k = 0; k < 4; ++k) {
      if (!channel[k]) continue;
      const double scale = channel[k]->type == "uchar" ? 1.0 / 255 : channel[k]->type == "ushort" ? 1.0 / 65535 : 1.0;
      for (std::size_t v = 0; v < nv; ++v) rgba[4 * v + std::size_t(k)] = float(std::clamp(channel[k]->values[v] * scale, 0.0, 1.0));
    }
    prim.attributes["COLOR_0"] = append(rgba, TINYGLTF_TYPE_VEC4, nv);
  }
  for (const VertexAttribute& a : s.attributes) {
    if (is_colour(a.name) && channel[0] && channel[1] && channel[2]) continue;
    std::vector<float> values(nv);
    for (std::size_t v = 0; v < nv; ++v) {
      values[v] = float(a.values[v]);
      if (!std::isfinite(values[v])) throw InputError(path, 0, "attribute " + a.name + " of vertex " + std::to_string(v) + " overflows float32");
    }
    prim.attributes[custom_semantic(a.name)] = append(values, TINYGLTF_TYPE_SCALAR, nv);
  }
  if (!s.texcoords.empty()) {  // glTF's t runs down the image
    std::vector<float> st(2 * nv);
    for (std::size_t v = 0; v < nv; ++v) {
      st[2 * v] = float(s.texcoords[2 * v]);
      st[2 * v + 1] = float(1.0 - s.texcoords[2 * v + 1]);
      if (!std::isfinite(st[2 * v]) || !std::isfinite(st[2 * v + 1])) throw InputError(path, 0, "texture coordinate of vertex " + std::to_string(v) + " overflows float32");
    }
    prim.attributes["TEXCOORD_0"] = append(st, TINYGLTF_TYPE_VEC2, nv);
  }
  if (s.texture && !s.texture->empty() && !s.texcoords.empty()) {  // the image in the buffer (4-byte aligned)
    const SurfaceTexture& t = *s.texture;
    tinygltf::Buffer& b = m.buffers[0];
    const std::size_t at = b.data.size();
    b.data.insert(b.data.end(), t.bytes.begin(), t.bytes.end());
    b.data.resize((b.data.size() + 3) / 4 * 4, 0);
    m.bufferViews.push_back({});
    m.bufferViews.back().buffer = 0;
    m.bufferViews.back().byteOffset = at;
    m.bufferViews.back().byteLength = t.bytes.size();
    tinygltf::Image image;
    image.name = t.name;
    image.mimeType = t.mime_type;
    image.bufferView = int(m.bufferViews.size()) - 1;
    m.images.push_back(image);
    tinygltf::Sampler sampler;
    sampler.magFilter = t.mag_filter, sampler.minFilter = t.min_filter, sampler.wrapS = t.wrap_s, sampler.wrapT = t.wrap_t;
    m.samplers.push_back(sampler);
    tinygltf::Texture texture;
    texture.sampler = 0;
    texture.source = 0;
    m.textures.push_back(texture);
    tinygltf::Material mat;
    mat.name = "texture";
    mat.pbrMetallicRoughness.baseColorTexture.index = 0;
    mat.pbrMetallicRoughness.baseColorFactor.assign(t.base_colour, t.base_colour + 4);
    mat.pbrMetallicRoughness.metallicFactor = t.metallic;
    mat.pbrMetallicRoughness.roughnessFactor = t.roughness;
    mat.doubleSided = t.double_sided;
    m.materials.push_back(mat);
    prim.material = 0;
  }
  tinygltf::Mesh mesh;
  mesh.name = "surface";
  mesh.primitives.push_back(prim);
  m.meshes.push_back(mesh);
  tinygltf::Node node;
  node.name = "surface";
  node.mesh = 0;
  m.nodes.push_back(node);
  tinygltf::Scene scene;  // named and non-empty: tinygltf 2.7 cannot read back a null scene
  scene.name = "Sublift";
  scene.nodes = {0};
  m.scenes.push_back(scene);
  m.defaultScene = 0;

  std::ostringstream out(std::ios::binary);
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToStream(&m, out, /*prettyPrint=*/!binary, binary) || !out)
    throw IoError(path + ": cannot serialise glTF");
  return std::move(out).str();
}

}  // namespace

bool surface_export_supported(const std::string& path) {
  const std::string ext = file_extension(path);
  return ext == "obj" || ext == "ply" || ext == "gltf" || ext == "glb";
}

namespace {

// The surface with one vertex per (vertex, UV point) pair its corners use, in the order first
// met, so glTF's per-vertex TEXCOORD_0 holds face-varying UVs: positions, normals and attributes
// copied to each part, faces renumbered.
struct SplitSurface {
  Csr faces;
  std::vector<double> xyz, normals, texcoords;
  std::vector<VertexAttribute> attributes;
};

SplitSurface split_surface(const Surface& s, const FaceVaryingUV& uv) {
  UvVertexSplit split = split_at_uv_seams(s.faces, uv, s.num_vertices());
  SplitSurface out;
  out.xyz = at_split_vertices(split, s.xyz, 3);
  out.normals = at_split_vertices(split, s.normals, 3);
  for (const VertexAttribute& a : s.attributes) out.attributes.push_back({a.name, a.type, at_split_vertices(split, a.values, 1)});
  out.faces = std::move(split.faces);
  out.texcoords = std::move(split.texcoords);
  return out;
}

}  // namespace

std::vector<std::string> write_surface_with_normals(const std::string& path, const Csr& faces, std::span<const double> xyz,
                                                    std::span<const double> normals, std::span<const VertexAttribute> attributes,
                                                    const FaceVaryingUV* uv, const SurfaceTexture* texture) {
  const std::string ext = file_extension(path);
  if (!surface_export_supported(path))
    throw InputError(path, 0, "cannot export a surface with normals to '." + ext + "' (expected .obj, .ply, .gltf or .glb)");
  Surface s = checked_surface(path, faces, xyz, normals);
  for (const VertexAttribute& a : attributes)
    if (a.values.size() != s.num_vertices())
      throw InputError(path, 0, "attribute " + a.name + " has " + std::to_string(a.values.size()) + " values for " + std::to_string(s.num_vertices()) + " vertices");
  s.attributes = attributes;
  if (uv && uv->empty()) uv = nullptr;
  if (uv)
    if (const std::string why = uv_problem(faces.items.size(), *uv); !why.empty()) throw InputError(path, 0, "texture coordinates: " + why);
  std::vector<std::string> notes;  // what OBJ and PLY with normals have no place for
  if (ext == "obj" || ext == "ply") {
    std::string names;
    for (const VertexAttribute& a : attributes) names += (names.empty() ? "" : ", ") + a.name;
    if (!names.empty()) notes.push_back("vertex attributes " + names + " not written: ." + ext + " with normals has no place for them (use .gltf or .glb)");
    if (uv && ext == "ply") notes.push_back("texture coordinates not written: .ply has none (use .obj, .gltf or .glb)");
    if (uv && texture && !texture->empty()) notes.push_back("texture '" + texture->name + "' not written with ." + ext + " (use .gltf or .glb)");
  }
  if (ext == "obj") {
    write_file_atomic(path, [&](std::ostream& out) { write_obj(out, s, uv); });
  } else if (ext == "ply") {
    write_file_atomic(path, [&](std::ostream& out) { write_ply(out, s); }, true);
  } else {
    std::string bytes;  // made before the file is touched
    if (uv) {
      const SplitSurface split = split_surface(s, *uv);
      bytes = gltf_bytes(path, Surface{split.faces, split.xyz, split.normals, split.attributes, split.texcoords, texture}, ext == "glb");
    } else {
      bytes = gltf_bytes(path, s, ext == "glb");
    }
    write_file_atomic(path, [&](std::ostream& out) { out.write(bytes.data(), static_cast<std::streamsize>(bytes.size())); }, true);
  }
  return notes;
}

}  // namespace sublift
