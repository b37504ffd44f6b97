#pragma once
// One Catmull-Clark-style refinement step of any Complex (paper 000 sec. 3.2-3.4): a new vertex
// per edge, face and cell; quads and hexahedra out (type-n cells where a cell vertex has n > 3
// cell edges).
//
// Child numbering (what the lifting programs and the in-place coefficient layout rely on):
//   vertices  [v | e | f | c]: old vertex i -> i, edge e -> nv + e, face f -> nv + ne + f,
//             cell k -> nv + ne + nf + k
//   edges     2e, 2e+1: halves of parent edge e (2e touches edge_verts[2e]); then one per face
//             corner (e-vertex to f-vertex), then one per cell face (f-vertex to c-vertex)
//   faces     one quad per parent face corner (v, e, f, e'), keeping the parent's orientation;
//             then one per cell edge (e, f1, c, f2)
//   cells     one per parent cell vertex
// Children inherit the feature dimensionality of their parent primitive.
#include "core/complex/complex.h"

namespace sublift {

/// The refined complex. With `adjacency` false the derived rows are left empty (enough for
/// output of the finest level; call build_adjacency later if needed).
Complex refine(const Complex& parent, bool adjacency = true);

}  // namespace sublift
