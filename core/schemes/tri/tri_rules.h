#pragma once
// The averaging step of paper 004's triangle schemes (sec. 4.2: "all primal subdivision schemes
// share the splitting step; they differ only in the weights used in the averaging step") as
// sparse stencils over the 1-to-4 split of core/complex/refine_tri.h. One row per fine vertex, items are
// coarse vertex indices in increasing order (each once, no zero weights), weights aligned with
// the items; every row's weights sum to 1.
//
// Fine numbering (refine_tri.h): old vertex i -> i, midpoint of coarse edge e -> nv + e.
// Layout: new_rows.row(e) / new_weights give fine vertex nv + e; old_rows / old_weights give
// fine vertex i. For the interpolating schemes (Linear, Butterfly) old_rows has no rows at all:
// old vertices are kept as they are.
//
// Words used below. A *feature edge* is a boundary edge (one face) or an edge with edge_dim 1
// (crease). A *feature vertex* is a vertex on a feature edge. An endpoint a of a feature edge
// *continues* the curve when a has exactly two feature edges and vertex_dim(a) != 0; the other
// end of its other feature edge is then the curve neighbour across a.
//
// ---- Linear (polyhedral subdivision, 004 sec. 4.1, Fig. 2) ---------------------------------
//   edge (a0, a1):      1/2 a0 + 1/2 a1
//
// ---- Butterfly: Zorin, Schroeder & Sweldens' modified butterfly (SIGGRAPH '96), exactly as
//      OpenMesh's Subdivider::Uniform::ModifiedButterflyT computes it --------------------------
//   Old vertices are kept. A new vertex on edge (a0, a1):
//
//   (1) interior edge, 8-point rule, when both ends have valence 6, or one end is a feature
//       vertex and the other has valence 6, or both ends are feature vertices:
//
//              c1 ---- b1 ---- c2        1/2 a0 + 1/2 a1 + 1/8 (b0 + b1)
//                \    /  \    /            - 1/16 (c0 + c1 + c2 + c3)
//                 \  /    \  /
//                  a1 ---- a0             c0..c3: the vertices across the wing edges
//                 /  \    /  \            (a1,b0), (a1,b1), (a0,b1), (a0,b0). Across a
//                /    \  /    \           feature wing edge (a, b) there is no such vertex; it
//              c0 ---- b0 ---- c3         is made by symmetry: a + b - (the other end of e).
//
//   (2) interior edge otherwise, K-point rule: every end a of valence K != 6 that is not a
//       feature vertex contributes its stencil; when both do, the two are averaged (1/2 each):
//         a_center weight 3/4 (K >= 5: 1 - sum of the s_j), ring vertex r_j (j = 0..K-1 around
//         a, r_0 = the other end of the edge) weight
//           K = 3:  s = 5/12, -1/12, -1/12
//           K = 4:  s = 3/8, 0, -1/8, 0
//           K >= 5: s_j = (1/4 + cos(2 pi j / K) + 1/2 cos(4 pi j / K)) / K
//
//                   r2 ---- r1           (K = 5 drawn; weights are symmetric in j <-> K - j,
//                  /  \    /  \           so the turning direction does not matter)
//                r3 -- a ---- r0 = other end of the edge
//                  \  /    \  /
//                   r4 -----
//
//   (3) feature edge (boundary, as OpenMesh; crease, our extension), the 4-point rule along the
//       feature curve:    -1/16 x0 + 9/16 a0 + 9/16 a1 - 1/16 x1
//                            x0 ---- a0 ---- a1 ---- x1
//       x0 is the curve neighbour across a0 when a0 continues the curve (on a boundary loop:
//       the next boundary vertex, which is what OpenMesh takes); otherwise (the curve ends at
//       a0: a dart, a corner tag, three or more feature edges) x0 = 2 a0 - a1, the reflection,
//       which gives 7/16 a0 + 5/8 a1 - 1/16 x1; both ends reflected give the midpoint. Likewise
//       for x1 across a1.
//   A crease therefore acts like a cut: rules (1)-(2) treat crease vertices like OpenMesh's
//   boundary vertices and crease wing edges like its boundary wings, so on a mesh whose creases
//   form closed curves through crease vertices the result is OpenMesh's on the mesh cut open
//   along them. Without creases and corner tags, on a manifold mesh, it is OpenMesh's result.
//   Cost: the K-point rule reads the whole ring for each of a vertex's K edges, so a vertex of
//   valence K puts K^2 weights into the butterfly's rows (as OpenMesh's loop does K^2 work).
//   Where OpenMesh is undefined we choose: a vertex of valence < 3 or whose faces do not form
//   one fan (non-manifold vertex) is treated as a feature vertex; vertex_dim 0 alone (a corner
//   tag on no feature edge) changes nothing, old vertices being interpolated anyway.
//
// ---- Loop: as OpenSubdiv's Sdc Loop scheme with VTX_BOUNDARY_EDGE_ONLY, every feature edge
//      infinitely sharp, vertex_dim-0 vertices infinitely sharp corners --------------------------
//   edge, smooth (not a feature edge):   3/8 a0 + 3/8 a1 + 1/8 b0 + 1/8 b1   (b: opposite corners)
//   edge, feature:                       1/2 a0 + 1/2 a1
//   vertex v, by its number s of feature edges:
//     smooth (s = 0) or dart (s = 1), valence n (faces = edges here):
//         (1 - n beta) v + beta * each edge neighbour, Loop's original
//         beta = (5/8 - (3/8 + 1/4 cos(2 pi / n))^2) / n   (n = 6: beta = 1/16, v weight 5/8)
//     crease (s = 2):   3/4 v + 1/8 x0 + 1/8 x1   (x: the other ends of the two feature edges)
//     corner (s > 2, vertex_dim 0, no edge at all, or a non-manifold vertex, which OpenSubdiv
//     sharpens too):   v
//
// Peers (tests/schemes/tri_rules_test.cpp): Butterfly vs OpenMesh ModifiedButterflyT, Loop vs OpenSubdiv
// Far (TopologyRefiner + PrimvarRefiner). See docs/triangle_schemes.md.
#include <cstdint>
#include <memory>
#include <vector>

#include "core/complex/complex.h"
#include "core/base/csr.h"
#include "core/engine/stencil_rows.h"
#include "core/schemes/scheme.h"

namespace sublift {

/// Rows over coarse vertex indices. new_rows.row(e) / new_weights: the fine vertex nv + e
/// (midpoint of coarse edge e). old_rows/old_weights: fine vertex i (old vertex i); left EMPTY
/// (zero rows) for the interpolating schemes Linear and Butterfly, whose old vertices are kept.
struct TriStencils {
  Csr new_rows;
  std::vector<double> new_weights;
  Csr old_rows;
  std::vector<double> old_weights;
};

/// The scheme's rules over one coarse surface, a fine vertex's row at a time: for callers that
/// read a few rows of a mesh (a face type's subdivided patch reads about a tenth of its rows).
/// The rows are build_tri_stencils' bit for bit (it is made of them).
class TriRowRules {
 public:
  /// `coarse` needs its derived rows and must outlive this. Throws as build_tri_stencils.
  /// `every_row`: what the rules ask of each vertex is worked out for all of them at once, in
  /// parallel (for making every row), else when a row asks it.
  TriRowRules(const Complex& coarse, Scheme s, bool every_row = false);
  ~TriRowRules();
  TriRowRules(const TriRowRules&) = delete;
  TriRowRules& operator=(const TriRowRules&) = delete;

  /// Fine vertex v's terms (refine_tri numbering), in rule order; an old vertex of an
  /// interpolating scheme is itself with weight 1.
  void add_terms(std::uint32_t v, RowBuilder& row) const;
  /// Appends v's row to rows/weights: sources increasing, repeated ones summed.
  void append_row(std::uint32_t v, Csr& rows, std::vector<double>& weights) const;

 private:
  friend TriStencils build_tri_stencils(const Complex& coarse, Scheme s);
  struct Impl;
  std::unique_ptr<const Impl> impl_;
};

/// `coarse`: a triangle surface with its derived rows (build_adjacency; built on a copy when
/// absent). Throws TopologyError naming the face for a non-triangle, the edge for an edge with
/// more than two faces (non-manifold) or none, and for another dim or cells. Linear time.
TriStencils build_tri_stencils(const Complex& coarse, Scheme s);

/// Applies the stencils: fine values (refine_tri order, (nv + ne) * channels, channel-minor)
/// from coarse values (nv * channels). Throws TopologyError when old_rows has neither 0 nor nv
/// rows.
std::vector<double> subdivide_tri(const TriStencils& st, const double* coarse, std::uint32_t nv, int channels);

/// Calls f(coarse vertex, weight) for each term of fine vertex v's row (nv coarse vertices; an
/// old vertex of an interpolating scheme is itself with weight 1).
template <class F>
void for_each_stencil_weight(const TriStencils& st, std::uint32_t nv, std::uint32_t v, F&& f) {
  if (v < nv && st.old_rows.rows() == 0) {
    f(v, 1.0);
    return;
  }
  const Csr& rows = v < nv ? st.old_rows : st.new_rows;
  const std::vector<double>& w = v < nv ? st.old_weights : st.new_weights;
  const std::uint32_t r = v < nv ? v : v - nv;
  for (std::uint32_t q = rows.offsets[r]; q < rows.offsets[r + 1]; ++q) f(rows.items[q], w[q]);
}

}  // namespace sublift
