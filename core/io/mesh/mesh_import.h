#pragma once
// The one import layer for surface meshes (OBJ, OFF, PLY ASCII and binary). Every reader here
// is our own bounded parser: counts are checked against the file size before anything is
// allocated, numbers must be finite, indices in range. Structural faults throw InputError
// (file, line, reason). Repairable faults (bad faces, isolated vertices, unknown tags) load and
// are itemised in ImportReport. Vertices are never renumbered: the mesh keeps file order.
#include <cstddef>
#include <string>
#include <vector>

#include "core/base/import_report.h"
#include "core/base/surface_mesh.h"

namespace sublift {

/// Limits that keep a hostile file from costing unbounded time or memory.
struct ImportLimits {
  std::size_t max_line_length = 1 << 20;   // bytes; longer lines are an error
  std::size_t max_face_size = 1 << 16;     // corners of one polygon
};

/// Reads OBJ, OFF or PLY, chosen by extension (case-insensitive). Throws InputError or IoError.
LoadedMesh import_surface_mesh(const std::string& path, const ImportLimits& limits = {});

/// The same from memory; `name` is used in messages and to pick the format by extension.
LoadedMesh import_surface_mesh_from_memory(const std::string& name, const std::string& bytes,
                                           const ImportLimits& limits = {});

}  // namespace sublift
