#pragma once
// Building a Complex from what the files give: polygons, polylines or cells as face loops, plus
// feature tags. Edges and shared faces are found here; feature dimensionalities follow the rules
// of docs/features.md (boundaries become features automatically; tags add creases, corners and
// inner feature surfaces).
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/complex/complex.h"
#include "core/base/import_report.h"
#include "core/base/surface_mesh.h"

namespace sublift {

/// User-tagged features, in vertex indices of the base.
struct FeatureTags {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> crease_edges;  // dim 1 edges
  std::vector<std::uint32_t> corner_vertices;                          // dim 0 vertices
  std::vector<std::vector<std::uint32_t>> feature_faces;               // dim 2 faces (lattices)
  // OpenSubdiv sharpness per crease edge / corner (empty: all infinitely sharp); finite values
  // make semi-sharp features (Complex::edge_sharpness).
  std::vector<float> crease_sharpness = {}, corner_sharpness = {};  // (= {}: brace lists may stop before them)
};

/// Reads OpenSubdiv `t crease` (sharpness > 0, chains allowed) and `t corner` tags, sharpness
/// 10 and above as infinitely sharp, below as semi-sharp; other tags and zero-sharpness ones are
/// itemised in `report` and ignored, fractional sharpness named (the fraction is not blended).
FeatureTags feature_tags_from_obj(const std::vector<MeshTag>& tags, ImportReport& report);

/// A surface complex (dim 2) from polygons. Throws TopologyError for a face of fewer than 3
/// vertices, a repeated vertex in a face, an index out of range, or a crease tag naming two
/// vertices that share no edge.
Complex complex_from_polygons(std::uint32_t num_vertices, const Csr& faces, const FeatureTags& tags = {});

/// The same from an imported mesh and its OBJ tags (unknown tags reported in `report`).
Complex complex_from_surface_mesh(const SurfaceMesh& mesh, ImportReport* report = nullptr);

/// A curve complex (dim 1) from polylines (each a chain of vertices; first == last closes it).
Complex complex_from_polylines(std::uint32_t num_vertices, const Csr& polylines, const FeatureTags& tags = {});

/// A volume complex (dim 3) from cells given as face loops: `cell_faces.row(c)` indexes
/// `face_loops`; a face shared by two cells may be listed twice (either orientation) and is
/// merged. Throws TopologyError for an unclosed cell (an edge not used by exactly two of its
/// faces), a face of fewer than 3 vertices, or dangling indices.
Complex complex_from_cells(std::uint32_t num_vertices, const Csr& face_loops, const Csr& cell_faces,
                           const FeatureTags& tags = {});

/// The feature dim a face, edge or vertex gets from topology alone, before tags lower it (faces
/// need face_cells; edges need face dims set; vertices need edge dims set). Shared by
/// assign_feature_dims and by writers that work out which tags reproduce a complex's dims.
std::uint8_t untagged_face_dim(const Complex& c, std::uint32_t f);
std::uint8_t untagged_edge_dim(const Complex& c, std::uint32_t e);
std::uint8_t untagged_vertex_dim(const Complex& c, std::uint32_t v);

/// Sets edge/face/vertex feature dims from topology and tags (see docs/features.md); called by
/// the builders above, public for code that edits features. Semi-sharp tags fill
/// c.edge_sharpness / c.vertex_sharpness.
void assign_feature_dims(Complex& c, const FeatureTags& tags);

/// Derives the edge and vertex dims of a surface again from its sharpness (an edge a crease and
/// a vertex a corner while >= 1; otherwise by topology), as refine() does for each new level.
/// Needs the derived rows. Does nothing without sharpness.
void apply_sharpness(Complex& c);

/// The refinement step's semi-sharp rule, shared by refine() and refine_tri() (their child
/// numbering agrees where it matters: the halves of parent edge e are edges 2e and 2e + 1, old
/// vertex v stays v): the halves of an edge of sharpness s get s - 1, a vertex keeps s - 1, new
/// edges and vertices 0, and `child`'s dims are derived again (apply_sharpness). Returns `child`
/// as is when `parent` has no sharpness; with `adjacency` false its derived rows are dropped again.
Complex inherit_sharpness(const Complex& parent, Complex child, bool adjacency);

}  // namespace sublift
