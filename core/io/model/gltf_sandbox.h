#pragma once
// Internal to the glTF model import/export: tinygltf locked down (TOOLCHAIN.md). Debian's shared
// tinygltf reads any file a model names and decodes every image; here file access goes through
// callbacks that only read regular files inside the model's own folder, images are kept as their
// undecoded bytes, and the inputs tinygltf 2.7 mishandles (GLB chunk lengths, deeply nested JSON)
// are checked before it sees them.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include <tiny_gltf.h>

namespace sublift {

/// The folder a model may read from, and what it tried to read outside of it.
struct GltfSandbox {
  std::string folder;                // canonical absolute folder of the model, no trailing '/'
  std::vector<std::string> refused;  // relative URIs refused (outside the folder, schemes)
};

/// Installs the sandbox's file callbacks (read only inside sandbox.folder, never write) and the
/// image loader that keeps bytes undecoded. `sandbox` must outlive `loader`'s use.
void lock_down(tinygltf::TinyGLTF& loader, GltfSandbox& sandbox);

/// Installs the image writer that writes images back as they came: an external file keeps its
/// URI, an image that came as a data: URI is embedded again from its original bytes.
void write_images_as_read(tinygltf::TinyGLTF& writer);

/// Throws InputError (naming `file`) unless `bytes` is a GLB 2 container whose declared length
/// and chunks fit in the bytes; returns the container's declared length.
std::size_t check_glb_container(std::string_view bytes, const std::string& file);

/// Throws InputError when JSON text nests arrays/objects deeper than `max_depth` (tinygltf 2.7
/// converts JSON to its Value type recursively and overflows the stack on deep nesting).
void check_json_depth(std::string_view json, const std::string& file, int max_depth = 256);

/// Decodes %XX escapes (tinygltf resolves external URIs the same way).
std::string percent_decode(std::string_view uri);

/// tinygltf 2.7 writes an object whose properties all have default values as `null` (and then
/// cannot read its file back): replaces such nulls in the top-level arrays by `{}`. Works on
/// JSON text; `glb` = the bytes are a GLB container (its JSON chunk is fixed and re-padded).
std::string fix_null_objects(std::string bytes, bool glb);

}  // namespace sublift
