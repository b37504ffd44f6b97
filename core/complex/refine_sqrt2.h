#pragma once
// sqrt(2) refinement of polygon meshes (topology only), paper 001 sec. 3-4 (Wang & Ma, after
// Li-Ma-Bao's interpolatory sqrt(2) subdivision): one new face point per face, old vertices
// kept, one new face along each old edge. Any polygon mesh becomes a quad mesh after one step.
//
// Curves (boundary edges, tagged creases, non-manifold edges: every edge of feature dim 1 or
// not shared by exactly two faces) are kept at odd levels and refined at even levels (001
// sec. 4). Which rule a step uses follows from the level index j of its input:
//   keep step   (j even -> j+1 odd):  face point per face; quad per inner edge; a curve edge is
//                                     kept and gets one triangle per face beside it
//   curve step  (j odd  -> j+1 even): a curve point per curve edge (its 4-point point, 001
//                                     eq. 11); face point per quad; the triangles get no point
//                                     of their own: their new point is the curve point
// Two steps give exactly the Catmull-Clark (1-to-4) topology of refine.h, boundaries and creases
// included. Boundary face F = (s, r, q, p) with curve edge p-q; k = face point of F,
// g = face point of the neighbour across s-r, e_xy = face point of the odd quad along x-y:
//
//      level j (even)             level j+1 (odd)                level j+2 (even)
//
//   p =========== q          p ============= q            p ====== b ====== q   b: curve point
//   |             |          : \     T     / :            |        |        |      of p-q
//   |             |          :   \       /   :            |        |        |
//   |      F      |    ->    :     \   /     :     ->     e_ps --- k --- e_qr   the 4 quads of
//   |             |          :       k       :            |        |        |   F's 1-to-4 split
//   |             |          :     /   \     :            |        |        |
//   s ----------- r          :   /       \   :            s ---- e_sr ----- r
//                            : /           \ :
//                            s . . . . . . . r          (e_sr: face point of the odd quad
//                              \           /              (s, g, r, k) along s-r)
//                                 \     /
//                                    g
//   At level j+1 the triangle T = (q, p, k) hangs on the kept curve edge p-q; the old inner edges
//   s-r, r-q, p-s are now diagonals of quads (x, face point, y, face point). At the curve step
//   T's new point is b, so the quads along T's inner edges p-k and q-k are (p, e_ps, k, b) and
//   (q, b, k, e_qr): the corner quads of a 1-to-4 split. A crease edge has a triangle on either
//   side and one curve point shared by both, so the surface stays joined along the crease.
//
// Child numbering (the engine's class order [v | e | f], as refine.h):
//   vertices  old vertex i -> i; curve steps: curve point of curve_edges[k] -> nv + k; face
//             point of point_faces[k] -> first_face_point + k (keep steps: every face, in order;
//             curve steps: every quad, in order)
//   edges     keep steps: kept curve edge k -> k, then one per face-corner slot s of the
//             coarse faces (corner -> its face point) -> num_curve_edges + s.
//             curve steps: halves 2k, 2k+1 of curve_edges[k] (2k touches edge_verts[2e]), then
//             per coarse face in order: a quad's 4 corner-to-face-point edges (by corner slot)
//             or a triangle's one edge from its apex to the curve point
//   faces     per coarse edge e in order (fine_face_edge maps back): an inner edge a-b
//             (a = edge_verts[2e]) with face A running a->b and B running b->a gives the quad
//             (a, c_B, b, c_A), c = new point of the face; on keep steps a curve edge gives the
//             triangle (x, y, c_X) for each face X beside it, running x->y as X does
// Feature dims: children inherit the dim of their parent (old vertex, face, curve edge); the
// quad along an edge takes the edge's dim. Orientation is kept.
#include <cstdint>
#include <vector>

#include "core/complex/complex.h"
#include "core/base/csr.h"

namespace sublift {

/// Whether edge e of `c` (adjacency built) is a curve of 001 sec. 4, refined by the 4-point
/// rule: a boundary, crease or cusp edge (feature dim <= 1), or any edge without exactly two
/// faces (it cannot carry a quad). The refinement and the transform share this one test.
inline bool sqrt2_is_curve_edge(const Complex& c, std::uint32_t e) {
  return c.edge_dim[e] <= 1 || c.edge_faces.size(e) != 2;
}

/// What each child of one sqrt(2) step comes from, so the lifting steps can find their stencils.
/// Vertex indices below are of the coarse level unless said otherwise.
struct Sqrt2Children {
  static constexpr std::uint32_t kNone = UINT32_MAX;  // no curve neighbour (curve ends there)

  bool curve_step = false;              // true when the input level is odd (curves refined)
  std::vector<std::uint32_t> curve_edges;  // coarse edges refined as curves, in edge order
  // Curve steps: 4 per curve point, (a, p, q, b) along the curve: p, q = the edge's ends in
  // edge_verts order, a = p's other curve neighbour, b = q's; kNone where the curve ends (a
  // corner, dart or branch), i.e. 001 eq. 11 case (b). Empty on keep steps.
  std::vector<std::uint32_t> curve_stencils;
  std::uint32_t first_face_point = 0;   // fine index of the first face point
  std::vector<std::uint32_t> point_faces;  // per face point: its coarse face
  Csr point_corners;                    // per face point: the face's corners, counterclockwise
  std::vector<std::uint32_t> fine_face_edge;  // per fine face: the coarse edge it grows along
};

/// One refined level with its child description.
struct Sqrt2Step {
  Complex fine;
  Sqrt2Children children;
};

/// Refines `coarse`, which is level `level` of a sqrt(2) hierarchy (a surface: dim 2, no cells;
/// any polygons at even levels; quads and one-curve-edge triangles at odd levels, as this
/// function makes them). Uses coarse's derived rows, building them on a copy when absent; the
/// fine level has them built. Throws TopologyError for other dims, an odd level with other
/// faces, or an inner edge whose two faces run the same way (not consistently oriented).
Sqrt2Step refine_sqrt2(const Complex& coarse, int level);

/// Levels 0..J (J >= 0, odd allowed) of base, each with its derived rows built. A negative
/// level or J throws std::invalid_argument.
std::vector<Complex> build_sqrt2_levels(const Complex& base, int J);

}  // namespace sublift
