#include "core/io/mesh/mesh_import.h"

#include "core/base/errors.h"
#include "core/base/file_io.h"
#include "core/io/mesh/mesh_readers.h"

namespace sublift {

LoadedMesh import_surface_mesh_from_memory(const std::string& name, const std::string& bytes,
                                           const ImportLimits& limits) {
  const std::string ext = file_extension(name);
  if (ext == "obj") return read_obj(bytes, name, limits);
  if (ext == "off") return read_off(bytes, name, limits);
  if (ext == "ply") return read_ply(bytes, name, limits);
  throw InputError(name, 0, "unsupported mesh format '." + ext + "' (expected .obj, .off or .ply)");
}

LoadedMesh import_surface_mesh(const std::string& path, const ImportLimits& limits) {
  const std::string ext = file_extension(path);
  if (ext != "obj" && ext != "off" && ext != "ply")
    throw InputError(path, 0, "unsupported mesh format '." + ext + "' (expected .obj, .off or .ply)");
  return import_surface_mesh_from_memory(path, read_file_bytes(path), limits);
}

}  // namespace sublift
