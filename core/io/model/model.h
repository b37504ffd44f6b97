#pragma once
// Model: a mesh file imported for free-form deformation and written back "as it came", with new
// positions and normals and everything else kept.
//
// Conventions. `positions` are WORLD-space vertex positions, 3 doubles per vertex, one flat array
// over every deformable vertex of the file. `faces` (CSR over the same vertices) is what is drawn:
// the file's polygons for OBJ/PLY/OFF; for glTF the triangles of TRIANGLES, TRIANGLE_STRIP and
// TRIANGLE_FAN primitives (points and lines move with the deformation but are not drawn;
// degenerate triangles are dropped). `normals` are unit world-space vertex normals for display:
// the file's own NORMAL where glTF has one, otherwise area-weighted from `faces`; (0, 0, 0) on a
// vertex of no face.
//
// glTF decisions (docs/file_formats.md):
// - One vertex range per POSITION accessor; primitives sharing an accessor share its range.
// - A range is placed in the world by the first node that instances it (default scene first,
//   depth first, then other scenes, then nodes in no scene). A mesh instanced by several nodes is
//   deformed in that first node's frame and written back through its inverse world matrix, so
//   every other instance shows the same mesh-space change (said in `notes`).
// - Skinned meshes: the bind-pose positions as stored, without skinning and without the node's
//   transform (glTF ignores the transform of a skinned mesh's node).
// - Refused with a clear InputError: non-float POSITION or NORMAL (normalised integers,
//   KHR_mesh_quantization), sparse POSITION/NORMAL accessors, Draco/meshopt compression, POSITION
//   or NORMAL bytes that overlap the bytes of another accessor, image or sparse block.
// - External files (buffers, images) are read only from the model's own folder: `..`, absolute
//   paths, URI schemes and symlinks leading out are refused (buffers: error; images: not read,
//   said in `notes`). Images are never decoded; their bytes are written back unchanged.
#include <array>
#include <cstddef>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "core/base/csr.h"
#include "core/base/surface_mesh.h"

namespace sublift {

enum class ModelFormat { Gltf, Glb, Obj, Ply, Off };

/// glTF only: one POSITION accessor's vertices [first_vertex, first_vertex + num_vertices).
struct ModelRange {
  std::size_t first_vertex = 0;
  std::size_t num_vertices = 0;
  int accessor = -1;         // POSITION accessor
  int normal_accessor = -1;  // NORMAL accessor recomputed on export, -1 when the file has none
  std::vector<std::pair<int, int>> primitives;  // (mesh, primitive) pairs that use the accessor
  int node = -1;             // the node whose world matrix places the range (-1: no node, mesh space)
  bool skinned = false;      // the node has a skin: positions taken as stored
  bool has_colors = false;   // a primitive gave it COLOR_0 (Model::colors)
  bool has_texcoords = false;  // a primitive gave it TEXCOORD_0 (Model::texcoords)
  std::array<double, 16> world{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};  // column-major
};

/// What export needs to write the file back (the tinygltf model or the original bytes).
struct ModelSource;

struct Model {
  std::string path;  // as given to import_model
  ModelFormat format = ModelFormat::Obj;
  std::vector<double> positions;  // world space, 3 per vertex
  std::vector<double> normals;    // world space, unit or zero, 3 per vertex
  Csr faces;                      // drawable polygons (glTF: triangles) over the vertices
  // glTF COLOR_0 as read (RGBA, 0..1, 4 per vertex; vertices of ranges without one white);
  // empty when no primitive has one. Carried by read_shape; FFD export leaves colours as stored.
  std::vector<float> colors;
  // glTF application-specific SCALAR float attributes ("_QUALITY"), one value per vertex each
  // (vertices of ranges without one 0), in the order first met; read_shape carries them.
  std::vector<std::pair<std::string, std::vector<float>>> custom;
  // glTF TEXCOORD_0 as stored (s, t with t running down the image; 2 per vertex, vertices of
  // ranges without one 0); empty when no primitive has one. read_shape carries them as UVs.
  std::vector<float> texcoords;
  std::vector<ModelRange> ranges;  // glTF only
  std::vector<std::string> notes;  // decisions and repairs the user should know about
  std::shared_ptr<const ModelSource> source;

  std::size_t num_vertices() const { return positions.size() / 3; }
};

/// True for .gltf, .glb, .obj, .ply and .off (any case).
bool model_format_supported(const std::string& path);

/// Reads a model by extension (case-insensitive). OBJ/PLY/OFF go through the validating import
/// layer (mesh_import.h); glTF through tinygltf locked to the model's folder, every accessor used
/// checked before it is read. Throws InputError (naming the file and the element) or IoError.
Model import_model(const std::string& path);

/// Writes `model` with the vertices moved to `world_positions` (3 per vertex, model order) to
/// `path`, in the source's format family (.gltf <-> .glb allowed, otherwise the same extension).
/// Positions and normals change; everything else is kept as it was. Normals are recomputed
/// (area-weighted over the deformed faces) only where a face they belong to moved. The file is
/// replaced atomically. Throws InputError (format change, sizes, non-finite or unrepresentable
/// values) or IoError.
void export_model(const Model& model, std::span<const double> world_positions, const std::string& path);

/// The base-colour texture of a glTF's triangles (read_shape carries it with the UVs): when
/// every triangle primitive uses one material whose baseColorTexture reads TEXCOORD_0, its image
/// bytes as stored (a file beside the model, a data URI or a buffer view), media type, sampler
/// and factors; else empty, and why is added to `notes` (nothing said for an untextured model).
SurfaceTexture gltf_surface_texture(const Model& model, std::vector<std::string>& notes);

/// Unit world-space display normals of the model at `world_positions`: area-weighted over
/// `faces`, glTF vertices split at UV seams (same original position and normal) smoothed together
/// and split ones with different original normals kept apart (hard edges stay hard).
std::vector<double> model_normals(const Model& model, std::span<const double> world_positions);

}  // namespace sublift
