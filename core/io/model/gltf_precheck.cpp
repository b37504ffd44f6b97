#include "core/io/model/gltf_precheck.h"

#include <algorithm>
#include <cstdint>

#include <nlohmann/json.hpp>

#include "core/base/errors.h"
#include "core/base/text_lines.h"

namespace sublift {
namespace {

// glTF 2.0, bufferView.byteStride: minimum 4, maximum 252, a multiple of 4.
constexpr std::int64_t kMinStride = 4, kMaxStride = 252;

bool is_base64(unsigned char c) {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '+' || c == '/';
}

// Bytes the base64 payload decodes to; throws naming the first byte that is not base64.
std::uint64_t decoded_length(std::string_view data, std::size_t data_at, const std::string& who, const std::string& file) {
  std::size_t n = data.size();
  std::size_t pad = 0;
  while (n > 0 && pad < 2 && data[n - 1] == '=') --n, ++pad;
  for (std::size_t i = 0; i < n; ++i)
    if (!is_base64(static_cast<unsigned char>(data[i])))
      throw InputError(file, 0, who + ": data URI is not base64: '" + printable(data.substr(i, 1)) + "' at character " +
                                    std::to_string(data_at + i) + " of the uri");
  if ((n + pad) % 4 != 0 && pad > 0)
    throw InputError(file, 0, who + ": data URI is not base64: its padding does not end a group of 4 characters");
  if (n % 4 == 1) throw InputError(file, 0, who + ": data URI is not base64: " + std::to_string(n) + " characters cannot end a group");
  return std::uint64_t(n / 4) * 3 + (n % 4 == 0 ? 0 : n % 4 - 1);
}

}  // namespace

void precheck_gltf_json(std::string_view json, const std::string& file) {
  const nlohmann::json j = nlohmann::json::parse(json, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded() || !j.is_object()) return;
  if (const auto b = j.find("buffers"); b != j.end() && b->is_array()) {
    for (std::size_t i = 0; i < b->size(); ++i) {
      const nlohmann::json& buf = (*b)[i];
      if (!buf.is_object()) continue;
      const auto uri = buf.find("uri");
      const auto length = buf.find("byteLength");
      if (uri == buf.end() || !uri->is_string() || length == buf.end() || !length->is_number_unsigned()) continue;
      const std::string& u = uri->get_ref<const std::string&>();
      if (u.compare(0, 5, "data:") != 0) continue;
      const std::string who = "buffer " + std::to_string(i);
      const std::size_t comma = u.find(',');
      if (comma == std::string::npos || comma < 7 ||
          u.compare(comma - 7, 7, ";base64") != 0)
        throw InputError(file, 0, who + ": data URI '" + printable(u.substr(0, std::min(comma, u.size())), 64) +
                                      "' is not base64-encoded (';base64,' expected)");
      const std::uint64_t have = decoded_length(std::string_view(u).substr(comma + 1), comma + 1, who, file);
      const std::uint64_t want = length->get<std::uint64_t>();
      if (have != want)
        throw InputError(file, 0, who + ": data URI holds " + std::to_string(have) + " bytes, byteLength says " + std::to_string(want));
    }
  }
  if (const auto v = j.find("bufferViews"); v != j.end() && v->is_array()) {
    for (std::size_t i = 0; i < v->size(); ++i) {
      const nlohmann::json& view = (*v)[i];
      if (!view.is_object()) continue;
      const auto s = view.find("byteStride");
      if (s == view.end() || !s->is_number()) continue;
      const double stride = s->get<double>();
      const bool ok = stride == static_cast<double>(static_cast<std::int64_t>(stride)) && stride >= kMinStride &&
                      stride <= kMaxStride && static_cast<std::int64_t>(stride) % 4 == 0;
      if (!ok)
        throw InputError(file, 0, "bufferView " + std::to_string(i) + ": byteStride " + printable(s->dump()) +
                                      " is not allowed (glTF allows " + std::to_string(kMinStride) + ".." +
                                      std::to_string(kMaxStride) + ", a multiple of 4)");
    }
  }
}

}  // namespace sublift
