// The base-colour texture of a glTF surface (model.h: gltf_surface_texture).
#include <cctype>
#include <cstring>
#include <set>
#include <utility>

#include <tiny_gltf.h>

#include "core/io/model/model.h"
#include "core/io/model/model_source.h"

namespace sublift {
namespace {

std::string mime_of(const tinygltf::Image& image) {
  if (!image.mimeType.empty()) return image.mimeType;
  std::string uri = image.uri;
  for (char& c : uri) c = char(std::tolower(static_cast<unsigned char>(c)));
  const auto ends = [&](const char* e) { return uri.size() >= std::strlen(e) && uri.compare(uri.size() - std::strlen(e), std::string::npos, e) == 0; };
  if (ends(".png")) return "image/png";
  if (ends(".jpg") || ends(".jpeg")) return "image/jpeg";
  return "";
}

}  // namespace

SurfaceTexture gltf_surface_texture(const Model& model, std::vector<std::string>& notes) {
  SurfaceTexture t;
  if (!model.source || (model.format != ModelFormat::Gltf && model.format != ModelFormat::Glb)) return t;
  const tinygltf::Model& g = model.source->gltf;
  std::set<int> materials;  // of the primitives the surface is made of (triangle modes)
  for (const ModelRange& r : model.ranges)
    for (const auto& [mesh, prim] : r.primitives) {
      const tinygltf::Primitive& p = g.meshes[std::size_t(mesh)].primitives[std::size_t(prim)];
      if (p.mode < 0 || p.mode >= TINYGLTF_MODE_TRIANGLES) materials.insert(p.material);
    }
  if (materials.empty() || (materials.size() == 1 && *materials.begin() < 0)) return t;
  if (materials.size() > 1) {
    notes.push_back(std::to_string(materials.size()) + " materials on the surface's triangles: opened as one surface without them (its texture is not kept)");
    return t;
  }
  const int mi = *materials.begin();
  if (mi >= int(g.materials.size())) return t;
  const tinygltf::Material& mat = g.materials[std::size_t(mi)];
  const tinygltf::TextureInfo& info = mat.pbrMetallicRoughness.baseColorTexture;
  const std::string what = "material " + std::to_string(mi) + (mat.name.empty() ? "" : " '" + mat.name.substr(0, 64) + "'");
  if (info.index < 0) return t;  // an untextured material: named with the materials not kept
  if (info.texCoord != 0 || info.index >= int(g.textures.size())) {
    notes.push_back(what + ": its base-colour texture reads TEXCOORD_" + std::to_string(info.texCoord) + " or names no texture: not kept");
    return t;
  }
  const tinygltf::Texture& tex = g.textures[std::size_t(info.index)];
  if (tex.source < 0 || tex.source >= int(g.images.size())) {
    notes.push_back(what + ": its texture names no image: not kept");
    return t;
  }
  const tinygltf::Image& image = g.images[std::size_t(tex.source)];
  if (image.bufferView >= 0) {  // the views were checked against their buffers at import
    const tinygltf::BufferView& v = g.bufferViews[std::size_t(image.bufferView)];
    const auto& data = g.buffers[std::size_t(v.buffer)].data;
    t.bytes.assign(reinterpret_cast<const char*>(data.data()) + v.byteOffset, v.byteLength);
  } else {
    t.bytes.assign(image.image.begin(), image.image.end());
  }
  t.mime_type = mime_of(image);
  if (t.bytes.empty() || (t.mime_type != "image/png" && t.mime_type != "image/jpeg")) {
    notes.push_back(what + ": its image " + std::to_string(tex.source) + " was not read or is not PNG or JPEG: texture not kept");
    return {};
  }
  const std::size_t slash = image.uri.find_last_of('/');
  t.name = !image.uri.empty() && image.uri.compare(0, 5, "data:") != 0 ? image.uri.substr(slash == std::string::npos ? 0 : slash + 1) : image.name;
  for (int k = 0; k < 4 && k < int(mat.pbrMetallicRoughness.baseColorFactor.size()); ++k) t.base_colour[k] = mat.pbrMetallicRoughness.baseColorFactor[std::size_t(k)];
  t.metallic = mat.pbrMetallicRoughness.metallicFactor;
  t.roughness = mat.pbrMetallicRoughness.roughnessFactor;
  t.double_sided = mat.doubleSided;
  if (tex.sampler >= 0 && tex.sampler < int(g.samplers.size())) {
    const tinygltf::Sampler& s = g.samplers[std::size_t(tex.sampler)];
    t.mag_filter = s.magFilter, t.min_filter = s.minFilter, t.wrap_s = s.wrapS, t.wrap_t = s.wrapT;
  }
  const std::pair<const char*, int> others[] = {{"normalTexture", mat.normalTexture.index},
                                                {"occlusionTexture", mat.occlusionTexture.index},
                                                {"emissiveTexture", mat.emissiveTexture.index},
                                                {"metallicRoughnessTexture", mat.pbrMetallicRoughness.metallicRoughnessTexture.index}};
  for (const auto& [other, index] : others)
    if (index >= 0) notes.push_back(what + ": its " + other + " is not kept (only the base colour)");
  return t;
}

}  // namespace sublift
