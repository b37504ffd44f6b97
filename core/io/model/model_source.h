#pragma once
// Internal to the model import/export (model.cpp, gltf_model.cpp, mesh_model.cpp): what a Model
// keeps of its file so that export can write it back, and the per-format entry points.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "core/io/model/model.h"

namespace sublift {

struct ModelSource {
  // glTF: the document as tinygltf read it (image bytes kept undecoded in Image::image).
  tinygltf::Model gltf;
  std::string folder;  // canonical folder of the source file; external files resolve here
  // Vertex -> first vertex of its smoothing group (glTF: same range, same original position and
  // normal). Empty means every vertex is its own group.
  std::vector<std::uint32_t> smooth_rep;
  // Mesh-space positions as read, 3 floats per vertex (glTF), to tell which vertices moved.
  std::vector<float> mesh_positions;
  // OBJ/PLY/OFF: the file's bytes as read.
  std::string bytes;
};

Model import_gltf_model(const std::string& path, ModelFormat format);
void export_gltf_model(const Model& model, std::span<const double> world_positions, const std::string& path);
Model import_mesh_model(const std::string& path, ModelFormat format);
void export_mesh_model(const Model& model, std::span<const double> world_positions, const std::string& path);

/// Area-weighted unit normals of `faces` over xyz, each vertex taking the sum of its smoothing
/// group (`rep`: vertex -> group representative; empty = one group per vertex). Zero where the sum
/// is zero.
std::vector<double> grouped_normals(const Csr& faces, std::span<const double> xyz,
                                    std::span<const std::uint32_t> rep);

}  // namespace sublift
