#include <cmath>

#include "core/base/errors.h"
#include "core/base/file_io.h"
#include "core/base/magnitude.h"
#include "core/io/model/model_source.h"
#include "core/complex/polygon_normal.h"

namespace sublift {
namespace {

bool format_of(const std::string& path, ModelFormat& f) {
  const std::string ext = file_extension(path);
  if (ext == "gltf") f = ModelFormat::Gltf;
  else if (ext == "glb") f = ModelFormat::Glb;
  else if (ext == "obj") f = ModelFormat::Obj;
  else if (ext == "ply") f = ModelFormat::Ply;
  else if (ext == "off") f = ModelFormat::Off;
  else return false;
  return true;
}

bool is_gltf(ModelFormat f) { return f == ModelFormat::Gltf || f == ModelFormat::Glb; }

const char* extension_name(ModelFormat f) {
  switch (f) {
    case ModelFormat::Gltf: return ".gltf";
    case ModelFormat::Glb: return ".glb";
    case ModelFormat::Obj: return ".obj";
    case ModelFormat::Ply: return ".ply";
    case ModelFormat::Off: return ".off";
  }
  return "";
}

}  // namespace

bool model_format_supported(const std::string& path) {
  ModelFormat f;
  return format_of(path, f);
}

Model import_model(const std::string& path) {
  ModelFormat f;
  if (!format_of(path, f))
    throw InputError(path, 0, "unsupported model format '." + file_extension(path) +
                                  "' (expected .gltf, .glb, .obj, .ply or .off)");
  return is_gltf(f) ? import_gltf_model(path, f) : import_mesh_model(path, f);
}

void export_model(const Model& model, std::span<const double> world_positions, const std::string& path) {
  ModelFormat f;
  if (!format_of(path, f))
    throw InputError(path, 0, "unsupported model format '." + file_extension(path) +
                                  "' (expected .gltf, .glb, .obj, .ply or .off)");
  if (!model.source) throw InputError(path, 0, "the model has no source to write back (not made by import_model)");
  const bool same_family = is_gltf(f) ? is_gltf(model.format) : f == model.format;
  if (!same_family)
    throw InputError(path, 0, std::string("cannot export a model read from ") + extension_name(model.format) +
                                  " as " + extension_name(f) + ": export keeps the source's format" +
                                  (is_gltf(model.format) ? " (.gltf or .glb)" : ""));
  if (world_positions.size() != model.positions.size())
    throw InputError(path, 0, std::to_string(world_positions.size() / 3) + " positions given for a model of " +
                                  std::to_string(model.num_vertices()) + " vertices");
  check_writable_positions(path, world_positions);
  if (is_gltf(f)) export_gltf_model(model, world_positions, path);
  else export_mesh_model(model, world_positions, path);
}

std::vector<double> grouped_normals(const Csr& faces, std::span<const double> xyz,
                                    std::span<const std::uint32_t> rep) {
  const std::size_t nv = xyz.size() / 3;
  std::vector<double> sum(3 * nv, 0.0);
  accumulate_face_normals(faces, xyz.data(), sum.data());
  if (!rep.empty()) {  // gather each group's sum on its representative, then hand it back
    for (std::size_t v = 0; v < nv; ++v)
      if (rep[v] != v)
        for (int k = 0; k < 3; ++k) sum[3 * rep[v] + k] += sum[3 * v + k];
    for (std::size_t v = 0; v < nv; ++v)
      if (rep[v] != v)
        for (int k = 0; k < 3; ++k) sum[3 * v + k] = sum[3 * rep[v] + k];
  }
  for (std::size_t v = 0; v < nv; ++v) {
    double* n = &sum[3 * v];
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (len > 0 && std::isfinite(len)) {
      for (int k = 0; k < 3; ++k) n[k] /= len;
    } else {
      n[0] = n[1] = n[2] = 0.0;
    }
  }
  return sum;
}

std::vector<double> model_normals(const Model& model, std::span<const double> world_positions) {
  if (world_positions.size() != model.positions.size())
    throw InputError(model.path, 0, "model_normals: positions do not match the model's vertex count");
  std::span<const std::uint32_t> rep;
  if (model.source) rep = model.source->smooth_rep;
  return grouped_normals(model.faces, world_positions, rep);
}

}  // namespace sublift
