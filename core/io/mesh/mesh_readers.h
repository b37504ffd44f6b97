#pragma once
// Internal to the import layer: one bounded parser per format. Each returns the mesh in file
// order with its report; mesh_import.cpp picks one by extension and runs the shared checks.
#include <string>
#include <string_view>

#include "core/io/mesh/mesh_import.h"

namespace sublift {

/// Largest coordinate magnitude accepted: beyond it products in normals, areas and inner
/// products overflow or lose all precision.
inline constexpr double kMaxCoordinate = 1e30;

LoadedMesh read_obj(std::string_view bytes, const std::string& file, const ImportLimits& limits);
LoadedMesh read_off(std::string_view bytes, const std::string& file, const ImportLimits& limits);
LoadedMesh read_ply(std::string_view bytes, const std::string& file, const ImportLimits& limits);

}  // namespace sublift
