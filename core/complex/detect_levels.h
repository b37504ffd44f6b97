#pragma once
// Finding the levels of a mesh that another tool subdivided (docs/rebuild.md): in any vertex and
// face order, in linear time, for the 1-to-4 quad split of polygon meshes (refine.h on
// surfaces: linear and cubic schemes), the 1-to-4 triangle split (refine_tri.h: linear-tri,
// butterfly, Loop) and sqrt(2) steps of closed meshes (refine_sqrt2.h). Each coarsening labels every vertex an old vertex, an edge point or a face
// point (Taubin 2002, "Detecting and reconstructing subdivision connectivity"), one connected
// component at a time, then checks the labels locally; engine_order() then maps the input's
// vertices onto Sublift's own refinement of the base found.
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "core/base/csr.h"
#include "core/complex/complex.h"

namespace sublift {

enum class SplitKind : std::uint8_t {
  Quads,      // 1-to-4 quad split (refine.h): old vertices, edge points, face points
  Triangles,  // 1-to-4 triangle split (refine_tri.h): old vertices, edge points
  Sqrt2,      // one sqrt(2) step (refine_sqrt2.h): old vertices, face points, curve points
  Hexes,      // the 1-to-8 split of a volume lattice of simple cells (refine.h on lattices):
              // old vertices, edge, face and cell points
};

/// One coarsening M_l -> M_{l-1} of the whole mesh: what each vertex of M_l is in M_{l-1}.
struct Coarsening {
  enum Kind : std::uint8_t { Old, EdgePoint, FacePoint, CellPoint };
  std::vector<std::uint8_t> kind;  // per vertex of M_l
  // Old: a = its vertex of M_{l-1}; EdgePoint: a, b = the ends of its edge; FacePoint: a = its
  // face of M_{l-1}; CellPoint: a = its cell of M_{l-1}.
  std::vector<std::uint32_t> a, b;
  std::uint32_t coarse_vertices = 0;  // M_{l-1}
  Csr coarse_faces;                   // M_{l-1}, oriented as the input (lattices: face loops)
  Csr coarse_cells;                   // lattices: each cell of M_{l-1} as indices of coarse_faces
  std::vector<std::uint32_t> input_vertex;  // an input vertex id for each vertex of M_{l-1}
};

/// What one connected component allows on its own.
struct ComponentLevels {
  std::uint32_t vertices = 0, faces = 0;  // at the finest level
  std::uint32_t first_vertex = 0;         // its smallest input vertex id, to name it
  int levels = 0;                         // levels it holds alone (up to the limit asked)
  std::string stop;                       // why not more; empty when the limit was reached
};

struct DetectedLevels {
  SplitKind split = SplitKind::Quads;
  int levels = 0;
  std::uint32_t base_vertices = 0;
  Csr base_faces;                  // the level-0 mesh (= steps.front().coarse_faces)
  Csr base_cells;                  // lattices: the base's cells as indices of base_faces
  std::vector<Coarsening> steps;   // steps[l]: M_{l+1} -> M_l, l = 0..levels-1
  int first_level = 0;             // sqrt(2): the level index of the base (1 when it is an odd
                                   // level, keeping its boundary edges; make_hierarchy's first_level)
  std::vector<ComponentLevels> components;
  std::string stop;                // why the whole mesh has no more levels (the first
                                   // component that stops there); empty when the limit was met
  std::uint32_t stop_vertex = UINT32_MAX;  // an input vertex near that, for highlighting
};

/// Finds up to `max_levels` levels (fewer where the mesh has fewer; every component gets the
/// levels all of them hold). `positions` (3 per vertex, may be empty) break ties between
/// labellings that topology cannot tell apart (a regular torus): the one whose edge points lie
/// nearest the midpoints of their edges wins, which is the exact one for bilinear data. Throws
/// TopologyError for faces of fewer than 3 corners, indices out of range, or a vertex in no face.
/// `keep_going` (may be empty) is asked before each coarsening with the fraction of the work
/// done so far; false throws Cancelled.
DetectedLevels detect_levels(std::uint32_t num_vertices, const Csr& faces, SplitKind split, int max_levels,
                             std::span<const double> positions = {},
                             const std::function<bool(double)>& keep_going = {});

/// The same for a volume lattice (`fine` with adjacency): the 1-to-8 split, whose children of a
/// cell are hexahedra where every cell vertex has three cell edges (tetrahedra, prisms, hexahedra
/// and other simple polyhedra; docs/rebuild.md says why others are left out). The lattice is
/// one piece. The base is complex_from_cells(base_vertices, base_faces, base_cells).
DetectedLevels detect_volume_levels(const Complex& fine, int max_levels, std::span<const double> positions = {},
                                    const std::function<bool(double)>& keep_going = {});

/// engine[i]: the vertex of Sublift's level-L complex (refine.h / refine_tri.h order, L =
/// d.levels) that input vertex i is. `levels[0..L]` are the hierarchy's complexes built from
/// complex_from_polygons(d.base_vertices, d.base_faces), all but the last with adjacency.
/// Throws TopologyError if the input is not that refinement (a check, not expected).
std::vector<std::uint32_t> engine_order(const DetectedLevels& d, std::span<const Complex> levels);

}  // namespace sublift
