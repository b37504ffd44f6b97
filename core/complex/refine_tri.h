#pragma once
// 1-to-4 triangle refinement (topology only), the splitting step shared by Lounsbery, DeRose &
// Warren's triangle-mesh schemes (paper 004 sec. 4.1-4.2, Figure 2): a new vertex at the midpoint
// of every edge, each triangle split into three corner triangles and a middle one. Closed and open
// meshes alike: boundary and crease edges are split like any other edge; what makes them
// features is their inherited feature dim, which the lifting steps read.
//
// Coarse triangle f with corners (a0, a1, a2) at its corner slots 0, 1, 2 and face_edges
// (e0, e1, e2), e_k running a_k -> a_{k+1}; m_k = nv + e_k is the midpoint of e_k:
//
//                      a2
//                      /\                     a_k: corners of coarse face f
//                     /  \                    m_k: midpoints (nv + e_k)
//                    / F2 \                   faces, counterclockwise as the parent:
//                   /      \                    F0 = 4f+0 = (a0, m0, m2)
//               m2 /___i1___\ m1                F1 = 4f+1 = (a1, m1, m0)
//                 /\        /\                  F2 = 4f+2 = (a2, m2, m1)
//                /  \  F3  /  \                 F3 = 4f+3 = (m0, m1, m2)
//               / F0 i2  i0 F1 \              inner edges, run as F3 runs:
//              /      \  /      \               i0 = 2ne + 3f + 0: m0 -> m1
//             /________\/________\              i1 = 2ne + 3f + 1: m1 -> m2
//           a0         m0         a1            i2 = 2ne + 3f + 2: m2 -> m0
//
// Child numbering (the engine's class order [v | e], as refine.h; old vertices first, so 004's
// subdivision matrix P^j = [O^j; N^j] (eq. 8) has its O rows first and its N rows after):
//   vertices  old vertex i -> i; midpoint of coarse edge e -> nv + e
//   edges     2e, 2e+1: halves of coarse edge e (2e touches edge_verts[2e], both run from
//             edge_verts[2e] towards edge_verts[2e+1]); then 3 inner edges per coarse face:
//             i_k = 2ne + 3f + k runs m_k -> m_{k+1} (the middle triangle's edge from its
//             corner k; it cuts off the parent's corner a_{k+1}, parallel to e_{k+2})
//   faces     4f + k for k = 0, 1, 2: the corner triangle (a_k, m_k, m_{k-1}) at corner k;
//             4f + 3: the middle triangle (m0, m1, m2). face_edges follow the corners as
//             everywhere: corner triangle k -> (half of e_k at a_k, i_{k-1} run backwards,
//             half of e_{k-1} at a_k); middle -> (i_0, i_1, i_2). Indices k-1, k+1 mod 3.
// Feature dims: children inherit their parent's (old vertex: its own; midpoint and halves: the
// edge's; inner edges and the four faces: the face's), as refine.h does.
// Counts: V' = V + E, E' = 2E + 3F, F' = 4F; the Euler characteristic is kept.
#include "core/complex/complex.h"

namespace sublift {

/// The 1-to-4 split of `coarse`, a surface (dim 2, no cells) whose faces are all triangles.
/// Reads only the downward rows (faces, face_edges, edge_verts, dims), so coarse's derived rows
/// may be absent. Throws TopologyError for another dim, cells, a face that is not a triangle
/// (naming the face and its corner count) or a face whose edges do not join its corners. With
/// `adjacency` false the result's derived rows are left empty (call build_adjacency later).
/// Linear time; the orientation of every face is kept.
Complex refine_tri(const Complex& coarse, bool adjacency = true);

}  // namespace sublift
