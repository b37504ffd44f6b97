#pragma once
// A coarse base mesh for fitting any triangle mesh (issue 17, docs/fit.md): OpenMesh's
// decimation framework (quadric error, no normal flips, a bound on triangle shape) collapses
// edges down to a target vertex count. Collapses are only taken where OpenMesh's link condition
// holds, so genus, boundary loops and pieces stay; sharp edges (dihedral angle above a
// threshold) and boundaries are feature edges that only collapse along themselves, and come out
// as crease tags.
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "core/base/csr.h"
#include "core/complex/complex_build.h"

namespace sublift {

/// The most faces around one input vertex a fit takes: every collapse next to such a vertex
/// walks its whole fan, so a wider one (a 70,000-face fan in the bad-input corpus) makes the
/// decimation quadratic (a fan of 1,000 takes half a minute). Real meshes stay below it (a
/// 512-segment UV sphere's poles reach it).
constexpr std::uint32_t kMaxFitValence = 512;

struct BaseMeshOptions {
  std::uint32_t target_vertices = 0;  // 0: 1/64 of the input's, at least 24
  std::uint32_t target_faces = 0;     // > 0: instead of a vertex count, at most this many faces
  double feature_angle_deg = 60.0;    // edges whose faces meet at a sharper angle are creases
  double max_normal_deviation_deg = 60.0;  // no collapse turns a face normal further
  bool quads = false;                 // pair the triangles into quads (base_quads.h); target_faces
                                      // then counts the polygons (still at most: the decimation
                                      // goes on while the pairing leaves too many triangles)
  std::function<bool(double)> progress = {};  // the decimation's progress (0-1) now and then; false
                                         // cancels it (Cancelled is thrown)
};

struct BaseMesh {
  std::uint32_t num_vertices = 0;
  Csr faces;                          // triangles (quad-dominant with `quads`), oriented as the input
  std::vector<double> positions;      // 3 per vertex
  std::vector<std::uint32_t> input_vertex;  // the input vertex each base vertex is
  FeatureTags tags;                   // creases (sharp input edges kept) and corners, in base vertex numbers
  long long euler_before = 0, euler_after = 0;   // V - E + F of the input and of the base
  std::size_t boundary_loops_before = 0, boundary_loops_after = 0;
  std::vector<std::uint32_t> input_feature_edges;  // those edges, 2 input vertices each
  std::size_t input_lines = 0;                     // feature lines of 8 or more of them
  std::vector<std::uint32_t> input_line_vertices;  // their vertices (what a fit must keep sharp)
};

/// The base of `faces` (triangles; other polygons are fanned) with `positions` (3 per vertex).
/// Throws TopologyError for non-manifold input (OpenMesh cannot hold it: the face is named), a
/// vertex with more than kMaxFitValence faces around it,
/// an empty mesh, or a target above the input's vertex (or face) count; Cancelled when
/// `options.progress` answers false.
BaseMesh decimate_to_base(std::uint32_t num_vertices, const Csr& faces, std::span<const double> positions,
                          const BaseMeshOptions& options = {});

}  // namespace sublift
