#pragma once
// Access to the GLSL files of shaders/, embedded at build time (cmake/EmbedShaders.cmake).
#include <string_view>

namespace sublift {

/// Source of the embedded shader `file_name` (e.g. "mesh.vert"); throws if there is none.
std::string_view embedded_shader(std::string_view file_name);

}  // namespace sublift
