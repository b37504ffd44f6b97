#pragma once
// Internal to the import layer: one bounded parser per format. Each returns the mesh in file
// order with its report; mesh_import.cpp picks one by extension and runs the shared checks.
#include <string>
#include <string_view>

#include "core/base/magnitude.h"
#include "core/io/mesh/mesh_import.h"

namespace sublift {

LoadedMesh read_obj(std::string_view bytes, const std::string& file, const ImportLimits& limits);
LoadedMesh read_off(std::string_view bytes, const std::string& file, const ImportLimits& limits);
LoadedMesh read_ply(std::string_view bytes, const std::string& file, const ImportLimits& limits);

}  // namespace sublift
