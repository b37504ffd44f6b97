#include "core/complex/refine_tri.h"

#include <algorithm>
#include <string>

#include "core/base/errors.h"
#include "core/complex/complex_build.h"

namespace sublift {

namespace {

// Throws unless every face is a triangle whose edges join its corners (face_edges aligned with
// faces): the split below indexes three slots per face and trusts those edges.
void check_triangles(const Complex& p) {
  if (p.face_edges.offsets != p.faces.offsets)
    throw TopologyError("triangle refinement: face_edges are not aligned with faces");
  const std::uint32_t nf = p.num_faces(), ne = p.num_edges();
  for (std::uint32_t f = 0; f < nf; ++f) {
    const std::uint32_t n = p.faces.size(f);
    if (n != 3)
      throw TopologyError("triangle refinement needs triangles: face " + std::to_string(f) + " has " +
                          std::to_string(n) + " corners");
    const std::uint32_t b = p.faces.offsets[f];
    for (std::uint32_t k = 0; k < 3; ++k) {
      const std::uint32_t e = p.face_edges.items[b + k];
      const std::uint32_t u = p.faces.items[b + k], w = p.faces.items[b + (k + 1) % 3];
      if (e >= ne || !((p.edge_verts[2 * e] == u && p.edge_verts[2 * e + 1] == w) ||
                       (p.edge_verts[2 * e] == w && p.edge_verts[2 * e + 1] == u)))
        throw TopologyError("triangle refinement: edge slot " + std::to_string(k) + " of face " + std::to_string(f) +
                            " does not join its corners " + std::to_string(u) + " and " + std::to_string(w));
    }
  }
}

}  // namespace

Complex refine_tri(const Complex& p, bool adjacency) {
  if (p.dim != 2 || p.num_cells() != 0)
    throw TopologyError("triangle refinement needs a surface (dim 2, no cells), got dim " + std::to_string(p.dim) +
                        " with " + std::to_string(p.num_cells()) + " cells");
  check_triangles(p);
  const std::uint32_t nv = p.num_vertices, ne = p.num_edges(), nf = p.num_faces();
  const std::uint32_t M0 = nv;          // first midpoint vertex
  const std::uint32_t inner0 = 2 * ne;  // first inner edge

  Complex c;
  c.dim = 2;
  c.num_vertices = nv + ne;

  // Vertices inherit the feature dim of the primitive they come from.
  c.vertex_dim.resize(c.num_vertices);
  std::copy(p.vertex_dim.begin(), p.vertex_dim.end(), c.vertex_dim.begin());
  std::copy(p.edge_dim.begin(), p.edge_dim.end(), c.vertex_dim.begin() + M0);

  // Edges: halves of coarse edges (2e touches edge_verts[2e]), then 3 inner edges per face.
  const std::uint32_t num_child_edges = inner0 + 3 * nf;
  c.edge_verts.resize(2 * std::size_t(num_child_edges));
  c.edge_dim.resize(num_child_edges);
  for (std::uint32_t e = 0; e < ne; ++e) {
    std::uint32_t* ev = &c.edge_verts[4 * std::size_t(e)];
    ev[0] = p.edge_verts[2 * e], ev[1] = M0 + e, ev[2] = M0 + e, ev[3] = p.edge_verts[2 * e + 1];
    c.edge_dim[2 * e] = c.edge_dim[2 * e + 1] = p.edge_dim[e];
  }

  // The half of coarse edge e that touches its end vertex v.
  auto half = [&](std::uint32_t e, std::uint32_t v) { return p.edge_verts[2 * e] == v ? 2 * e : 2 * e + 1; };

  // Faces: every child is a triangle, so offsets are 3i and face_edges shares them.
  c.faces.offsets.resize(4 * std::size_t(nf) + 1);
  for (std::uint32_t i = 0; i <= 4 * nf; ++i) c.faces.offsets[i] = 3 * i;
  c.faces.items.resize(12 * std::size_t(nf));
  c.face_edges.items.resize(12 * std::size_t(nf));
  c.face_dim.resize(4 * std::size_t(nf));
  for (std::uint32_t f = 0; f < nf; ++f) {
    const std::uint32_t* a = &p.faces.items[p.faces.offsets[f]];  // 3 corners, checked above
    const std::uint32_t* e = &p.face_edges.items[p.faces.offsets[f]];
    const std::uint32_t m[3] = {M0 + e[0], M0 + e[1], M0 + e[2]};
    const std::uint32_t i0 = inner0 + 3 * f;
    const std::uint8_t dim = p.face_dim[f];
    // Inner edge k runs m_k -> m_{k+1}, as the middle triangle runs.
    for (std::uint32_t k = 0; k < 3; ++k) {
      c.edge_verts[2 * std::size_t(i0 + k)] = m[k];
      c.edge_verts[2 * std::size_t(i0 + k) + 1] = m[(k + 1) % 3];
      c.edge_dim[i0 + k] = dim;
    }
    std::uint32_t* fv = &c.faces.items[12 * std::size_t(f)];
    std::uint32_t* fe = &c.face_edges.items[12 * std::size_t(f)];
    // Corner triangle k = (a_k, m_k, m_{k-1}); its middle edge is inner k-1 run backwards.
    for (std::uint32_t k = 0; k < 3; ++k) {
      const std::uint32_t prev = (k + 2) % 3;
      fv[3 * k] = a[k], fv[3 * k + 1] = m[k], fv[3 * k + 2] = m[prev];
      fe[3 * k] = half(e[k], a[k]), fe[3 * k + 1] = i0 + prev, fe[3 * k + 2] = half(e[prev], a[k]);
    }
    fv[9] = m[0], fv[10] = m[1], fv[11] = m[2];
    fe[9] = i0, fe[10] = i0 + 1, fe[11] = i0 + 2;
    std::fill_n(&c.face_dim[4 * std::size_t(f)], 4, dim);
  }
  c.face_edges.offsets = c.faces.offsets;
  // Semi-sharp features as refine() has them (the halves of edge e are 2e and 2e + 1 here too).
  if (!p.edge_sharpness.empty() || !p.vertex_sharpness.empty()) return inherit_sharpness(p, std::move(c), adjacency);
  if (adjacency) build_adjacency(c);
  return c;
}

}  // namespace sublift
