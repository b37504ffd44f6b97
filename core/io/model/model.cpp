#include <algorithm>
#include <cmath>

#include "core/base/errors.h"
#include "core/base/file_io.h"
#include "core/base/magnitude.h"
#include "core/io/model/model_source.h"
#include "core/complex/polygon_normal.h"

namespace sublift {
namespace {

constexpr const char* kExtensions[] = {"gltf", "glb", "obj", "ply", "off"};  // in ModelFormat order

bool is_gltf(ModelFormat f) { return f == ModelFormat::Gltf || f == ModelFormat::Glb; }

std::string extension_name(ModelFormat f) { return std::string(".") + kExtensions[static_cast<int>(f)]; }

// The format of `path` by its extension; throws InputError for any other.
ModelFormat format_of(const std::string& path) {
  const std::string ext = file_extension(path);
  for (int k = 0; k < 5; ++k)
    if (ext == kExtensions[k]) return static_cast<ModelFormat>(k);
  throw InputError(path, 0, "unsupported model format '." + ext + "' (expected .gltf, .glb, .obj, .ply or .off)");
}

}  // namespace

bool model_format_supported(const std::string& path) {
  const std::string ext = file_extension(path);
  return std::find(std::begin(kExtensions), std::end(kExtensions), ext) != std::end(kExtensions);
}

Model import_model(const std::string& path) {
  const ModelFormat f = format_of(path);
  return is_gltf(f) ? import_gltf_model(path, f) : import_mesh_model(path, f);
}

void export_model(const Model& model, std::span<const double> world_positions, const std::string& path) {
  const ModelFormat f = format_of(path);
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
