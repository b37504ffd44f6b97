#pragma once
// Internal to the glTF import: checks on the JSON that tinygltf 2.7 reports wrongly, made before
// it sees the file, so that the message names the fault. tinygltf says "Failed to decode 'uri'"
// for a data URI that is valid base64 but shorter or longer than its buffer's byteLength, and
// "byteStride must be the multiple of 4" for a stride of 256 (a multiple of 4: the limit is 252).
#include <string>
#include <string_view>

namespace sublift {

/// Throws InputError (naming `file`) for a buffer whose data: URI is not base64 or decodes to
/// another length than its byteLength ("buffer 0: data URI holds 20 bytes, byteLength says 44"),
/// and for a bufferView byteStride outside 4..252 or not a multiple of 4. JSON that does not
/// parse is left to tinygltf's own message.
void precheck_gltf_json(std::string_view json, const std::string& file);

}  // namespace sublift
