#pragma once
// Complex: a cell complex of dimension 1, 2 or 3 (curve, polygon mesh, polyhedral lattice) with
// feature dimensionalities, the topology behind every wavelet level (paper 000 sec. 3-4).
//
// Layout (downward connectivity, as paper 000 sec. 4 stores it):
//   vertices  0..num_vertices-1 (positions live beside the topology, in the hierarchy)
//   edges     edge_verts[2e], edge_verts[2e+1]
//   faces     faces.row(f) = corners in cycle order; face_edges.row(f)[i] is the edge from
//             corner i to corner i+1 (same offsets as faces)
//   cells     cell_faces.row(c) = the faces bounding cell c (a closed polyhedron)
// Derived (build_adjacency): upward rows vertex_edges/vertex_faces/vertex_cells, edge_faces,
// edge_cells, face_cells, and downward cell_verts/cell_edges. Upward rows list indices in
// increasing order.
// Feature dimensionality (paper 000 eq. 3.12): 0 cusp, 1 crease/boundary curve, 2 surface,
// 3 volume; vertex_dim/edge_dim/face_dim (cells are always 3). Invariant: a primitive's dim is
// at least its topological dimension and at most `dim`.
#include <cstdint>
#include <string>
#include <vector>

#include "core/base/csr.h"

namespace sublift {

struct Complex {
  int dim = 2;                           // 1 curve, 2 surface, 3 volume
  std::uint32_t num_vertices = 0;
  std::vector<std::uint32_t> edge_verts; // 2 per edge
  Csr faces;                             // corner vertices per face
  Csr face_edges;                        // edges per face, aligned with `faces`
  Csr cell_faces;                        // faces per cell
  std::vector<std::uint8_t> vertex_dim, edge_dim, face_dim;
  // OpenSubdiv's semi-sharp features (docs/features.md), empty when there are none: the
  // sharpness left at this level per edge and per vertex (0 none, +inf an infinitely sharp tag).
  // An edge is a crease and a vertex a corner while it is >= 1; refine() (Catmull-Clark style)
  // gives children s - 1 and derives their dims again, so a sharpness-s crease is sharp for
  // floor(s) levels and smooth after.
  std::vector<float> edge_sharpness, vertex_sharpness;

  // Derived by build_adjacency().
  Csr vertex_edges, vertex_faces, vertex_cells, edge_faces, edge_cells, face_cells;
  Csr cell_verts, cell_edges;

  std::uint32_t num_edges() const { return static_cast<std::uint32_t>(edge_verts.size() / 2); }
  std::uint32_t num_faces() const { return static_cast<std::uint32_t>(faces.rows()); }
  std::uint32_t num_cells() const { return static_cast<std::uint32_t>(cell_faces.rows()); }
  /// Vertices of the next level: one per vertex, edge, face and cell, in that order.
  std::uint32_t num_child_vertices() const {
    return num_vertices + num_edges() + num_faces() + num_cells();
  }
  /// Retained bytes of all arrays.
  std::size_t bytes() const;
};

/// Corner slots of face f (indices into c.faces.items, also into c.face_edges.items): the slot
/// after and before s in the face's cycle.
inline std::uint32_t face_next_slot(const Complex& c, std::uint32_t f, std::uint32_t s) {
  return s + 1 == c.faces.offsets[f + 1] ? c.faces.offsets[f] : s + 1;
}
inline std::uint32_t face_prev_slot(const Complex& c, std::uint32_t f, std::uint32_t s) {
  return s == c.faces.offsets[f] ? c.faces.offsets[f + 1] - 1 : s - 1;
}

/// The other end of edge e from v.
inline std::uint32_t edge_other_end(const Complex& c, std::uint32_t e, std::uint32_t v) {
  const std::uint32_t a = c.edge_verts[2 * std::size_t(e)];
  return a == v ? c.edge_verts[2 * std::size_t(e) + 1] : a;
}

/// Fills the derived rows of `c` from its downward connectivity.
void build_adjacency(Complex& c);

/// Throws TopologyError naming the first broken invariant (dangling index, face of fewer than
/// 3 edges, edge repeated in a face, face cycle not closed, cell not closed, bad feature dim).
/// Needs build_adjacency() first.
void validate(const Complex& c);

}  // namespace sublift
