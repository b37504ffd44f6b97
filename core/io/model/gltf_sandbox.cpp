#include "core/io/model/gltf_sandbox.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <system_error>

#include <nlohmann/json.hpp>

#include "core/base/binary_cursor.h"
#include "core/base/errors.h"
#include "core/base/file_io.h"

namespace sublift {
namespace fs = std::filesystem;
namespace {

constexpr std::size_t kMaxExternalBytes = std::size_t(1) << 31;  // tinygltf lengths are 32-bit

// "scheme:..." (letters, digits, + - . before the colon, first a letter): a URL, not a file name.
bool has_scheme(std::string_view rel) {
  const std::size_t colon = rel.find(':');
  if (colon == std::string_view::npos || colon == 0 || rel.find('/') < colon) return false;
  if (!std::isalpha(static_cast<unsigned char>(rel[0]))) return false;
  for (std::size_t i = 0; i < colon; ++i) {
    const char c = rel[i];
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '+' && c != '-' && c != '.') return false;
  }
  return true;
}

// True when `path` lies lexically and physically (symlinks resolved) inside the sandbox folder.
// Refusals of URIs that tinygltf joined under the folder are recorded.
bool inside(const std::string& path, GltfSandbox& box) {
  const std::string prefix = box.folder + "/";
  // tinygltf also tries "./uri" relative to the working directory: never inside, never recorded.
  if (path.compare(0, prefix.size(), prefix) != 0) return false;
  const std::string rel = path.substr(prefix.size());
  auto refuse = [&]() {
    box.refused.push_back(rel);
    return false;
  };
  if (rel.empty()) return false;
  if (rel.front() == '/' || has_scheme(rel)) return refuse();  // absolute path or URL
  const fs::path parts(rel);
  if (std::any_of(parts.begin(), parts.end(), [](const fs::path& c) { return c == ".."; })) return refuse();
  std::error_code ec;
  const fs::path real = fs::weakly_canonical(fs::path(path), ec);
  if (ec) return false;
  const std::string r = real.string();
  if (r.compare(0, prefix.size(), prefix) != 0) return refuse();  // a symlink leads out
  return true;
}

bool sandbox_file_exists(const std::string& path, void* user) {
  auto& box = *static_cast<GltfSandbox*>(user);
  if (!inside(path, box)) return false;
  std::error_code ec;
  return fs::is_regular_file(path, ec);
}

std::string sandbox_expand(const std::string& path, void*) { return path; }  // no ~, no $VARS

bool sandbox_read(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  auto& box = *static_cast<GltfSandbox*>(user);
  if (!inside(path, box)) {
    if (err) *err += "refused: outside the model's folder";
    return false;
  }
  try {
    const std::string bytes = read_file_bytes(path, kMaxExternalBytes);
    out->assign(bytes.begin(), bytes.end());
    return true;
  } catch (const IoError& e) {
    if (err) *err += e.what();
    return false;
  }
}

bool sandbox_write(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "writing through tinygltf is disabled";
  return false;
}

// Keeps the encoded bytes (PNG, JPEG, ...) instead of decoding them.
bool keep_image_bytes(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void*) {
  // An image in a buffer view stays there; tinygltf 2.7 hands over its bytes without checking
  // the view against the buffer, so they are not touched here (the views are checked later).
  if (image->bufferView >= 0) return true;
  if (size > 0) image->image.assign(bytes, bytes + size);
  image->as_is = true;
  return true;
}

// Standard base64 with padding.
std::string base64_encode(const std::vector<unsigned char>& in) {
  static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((in.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < in.size(); i += 3) {
    const std::uint32_t v = (std::uint32_t(in[i]) << 16) | (std::uint32_t(in[i + 1]) << 8) | in[i + 2];
    for (int k = 3; k >= 0; --k) out.push_back(kAlphabet[(v >> (6 * k)) & 63]);
  }
  if (i < in.size()) {
    const bool two = i + 1 < in.size();
    const std::uint32_t v = (std::uint32_t(in[i]) << 16) | (two ? std::uint32_t(in[i + 1]) << 8 : 0);
    out.push_back(kAlphabet[(v >> 18) & 63]);
    out.push_back(kAlphabet[(v >> 12) & 63]);
    out.push_back(two ? kAlphabet[(v >> 6) & 63] : '=');
    out.push_back('=');
  }
  return out;
}

bool write_image_as_read(const std::string*, const std::string*, const tinygltf::Image* image, bool,
                         std::string* out_uri, void*) {
  if (!image->uri.empty()) {  // an external file: the same reference
    *out_uri = image->uri;
    return true;
  }
  if (image->bufferView >= 0 || image->image.empty()) return false;
  const std::string mime = image->mimeType.empty() ? "application/octet-stream" : image->mimeType;
  *out_uri = "data:" + mime + ";base64," + base64_encode(image->image);
  return true;
}

std::uint32_t le32(std::string_view b, std::size_t at) { return load_endian<std::uint32_t>(b.data() + at, false); }

void put_le32(std::string& b, std::size_t at, std::uint32_t v) { store_endian(b.data() + at, v, false); }

}  // namespace

void lock_down(tinygltf::TinyGLTF& loader, GltfSandbox& sandbox) {
  tinygltf::FsCallbacks cb;
  cb.FileExists = &sandbox_file_exists;
  cb.ExpandFilePath = &sandbox_expand;
  cb.ReadWholeFile = &sandbox_read;
  cb.WriteWholeFile = &sandbox_write;
  cb.user_data = &sandbox;
  loader.SetFsCallbacks(cb);
  loader.SetImageLoader(&keep_image_bytes, nullptr);
}

void write_images_as_read(tinygltf::TinyGLTF& writer) { writer.SetImageWriter(&write_image_as_read, nullptr); }

std::size_t check_glb_container(std::string_view b, const std::string& file) {
  if (b.size() < 20) throw InputError(file, 0, "GLB file of " + std::to_string(b.size()) + " bytes is shorter than its 20-byte header");
  if (b.substr(0, 4) != "glTF") throw InputError(file, 0, "not a GLB file (magic is not 'glTF')");
  const std::uint32_t version = le32(b, 4), length = le32(b, 8);
  if (version != 2) throw InputError(file, 0, "GLB container version " + std::to_string(version) + " (only 2 is supported)");
  if (length > b.size())
    throw InputError(file, 0, "GLB header declares " + std::to_string(length) + " bytes but the file has " + std::to_string(b.size()));
  const std::uint64_t json_len = le32(b, 12);
  if (le32(b, 16) != 0x4E4F534Au) throw InputError(file, 0, "GLB first chunk (byte offset 12) is not JSON");
  const std::uint64_t json_end = 20 + json_len;
  if (json_len == 0 || json_end > length)
    throw InputError(file, 0, "GLB JSON chunk of " + std::to_string(json_len) + " bytes does not fit in " + std::to_string(length) + " bytes");
  if (json_end < length) {
    if (json_end + 8 > length) throw InputError(file, 0, "GLB chunk header at byte offset " + std::to_string(json_end) + " is truncated");
    const std::uint64_t bin_len = le32(b, json_end);
    if (le32(b, json_end + 4) != 0x004E4942u)
      throw InputError(file, 0, "GLB second chunk (byte offset " + std::to_string(json_end) + ") is not BIN");
    if (json_end + 8 + bin_len > length)
      throw InputError(file, 0, "GLB BIN chunk declares " + std::to_string(bin_len) + " bytes but only " +
                                    std::to_string(length - json_end - 8) + " follow (byte offset " + std::to_string(json_end) + ")");
  }
  return length;
}

void check_json_depth(std::string_view json, const std::string& file, int max_depth) {
  int depth = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < json.size(); ++i) {
    const char c = json[i];
    if (in_string) {
      if (c == '\\') ++i;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > max_depth)
        throw InputError(file, 0, "JSON nests deeper than " + std::to_string(max_depth) + " levels (byte offset " + std::to_string(i) + ")");
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
}

std::string percent_decode(std::string_view uri) {
  auto hex = [](char c) -> int {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
  };
  std::string out;
  for (std::size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && hex(uri[i + 1]) >= 0 && hex(uri[i + 2]) >= 0) {
      out.push_back(static_cast<char>(hex(uri[i + 1]) * 16 + hex(uri[i + 2])));
      i += 2;
    } else {
      out.push_back(uri[i]);
    }
  }
  return out;
}

std::string fix_null_objects(std::string bytes, bool glb) {
  std::string_view text = bytes;
  std::size_t json_at = 0, json_len = bytes.size();
  if (glb) {
    json_len = le32(bytes, 12);
    json_at = 20;
    text = std::string_view(bytes).substr(json_at, json_len);
  }
  if (text.find("null") == std::string_view::npos) return bytes;  // the common case: nothing to fix
  nlohmann::json doc = nlohmann::json::parse(text);
  bool changed = false;
  for (auto& [key, value] : doc.items()) {
    if (!value.is_array()) continue;
    for (auto& element : value)
      if (element.is_null()) {
        element = nlohmann::json::object();
        changed = true;
      }
  }
  if (!changed) return bytes;
  std::string fixed = glb ? doc.dump() : doc.dump(2);
  if (!glb) return fixed + "\n";
  while (fixed.size() % 4) fixed.push_back(' ');  // GLB chunks end on 4-byte boundaries
  std::string out = bytes.substr(0, 20);
  out += fixed;
  out += bytes.substr(json_at + json_len);
  put_le32(out, 8, static_cast<std::uint32_t>(out.size()));
  put_le32(out, 12, static_cast<std::uint32_t>(fixed.size()));
  return out;
}

}  // namespace sublift
