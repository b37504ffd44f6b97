#pragma once
// Internal to core/fit: the OpenMesh mesh a fitting base is decimated on, the decimater with
// the base's modules, and the decimation of a large mesh in slabs side by side (issue 17: the
// decimater is serial, and at a million vertices it was two thirds of a fit).
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

namespace sublift::fit_detail {

struct Traits : OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
};
using Mesh = OpenMesh::TriMesh_ArrayKernelT<Traits>;
using Decimater = OpenMesh::Decimater::DecimaterT<Mesh>;

/// A decimater on `m` (vertex, edge and face status requested) with the base's modules: quadric
/// error, no face normal turned by more than `max_normal_deviation_deg`, triangles no thinner
/// than aspect ratio 10. Initialised, ready to run.
std::unique_ptr<Decimater> make_decimater(Mesh& m, double max_normal_deviation_deg);

struct JoinedParts {
  Mesh mesh;                         // statuses requested; feature flags and corner locks as in the input
  std::vector<std::uint32_t> input_of;  // the input vertex of each of its vertices
};

/// Decimates `m` (the whole input: feature flags set, corners locked, nothing deleted) in
/// `parts` slabs of faces along its longest axis, each in a mesh of its own on its own thread,
/// down to about `keep` vertices in all, and joins what is left. Each slab carries the faces of
/// the others that touch it, with their vertices locked: so every collapse a slab takes sees
/// the same one-rings, boundaries and link condition as in the whole mesh, and the slabs fit
/// together again. The result is the same whatever the thread count. Returns nothing when OpenMesh
/// cannot hold a slab (a vertex whose faces in it are more than one fan) or the join changed the
/// topology; the caller then decimates the whole mesh.
std::optional<JoinedParts> decimate_in_parts(const Mesh& m, std::uint32_t parts, std::uint32_t keep,
                                             double max_normal_deviation_deg);

}  // namespace sublift::fit_detail
