#include "core/complex/refine.h"

#include "core/complex/complex_build.h"

#include <algorithm>

namespace sublift {

Complex refine(const Complex& p, bool adjacency) {
  const std::uint32_t nv = p.num_vertices, ne = p.num_edges(), nf = p.num_faces(), nc = p.num_cells();
  const std::uint32_t E0 = nv, F0 = nv + ne, C0 = nv + ne + nf;  // first child vertex per class
  const std::uint32_t corners = static_cast<std::uint32_t>(p.faces.items.size());
  const std::uint32_t cell_face_slots = static_cast<std::uint32_t>(p.cell_faces.items.size());
  const std::uint32_t face_edge0 = 2 * ne;                   // first face-interior edge
  const std::uint32_t cell_edge0 = face_edge0 + corners;     // first cell-interior edge

  Complex c;
  c.dim = p.dim;
  c.num_vertices = p.num_child_vertices();

  // Vertices inherit the feature dim of the primitive they come from.
  c.vertex_dim.resize(c.num_vertices);
  std::copy(p.vertex_dim.begin(), p.vertex_dim.end(), c.vertex_dim.begin());
  std::copy(p.edge_dim.begin(), p.edge_dim.end(), c.vertex_dim.begin() + E0);
  std::copy(p.face_dim.begin(), p.face_dim.end(), c.vertex_dim.begin() + F0);
  std::fill(c.vertex_dim.begin() + C0, c.vertex_dim.end(), std::uint8_t{3});

  // Edges: halves of parent edges, face-interior (e -> f), cell-interior (f -> c).
  const std::uint32_t num_child_edges = cell_edge0 + cell_face_slots;
  c.edge_verts.resize(2 * std::size_t(num_child_edges));
  c.edge_dim.resize(num_child_edges);
  for (std::uint32_t e = 0; e < ne; ++e) {
    const std::uint32_t a = p.edge_verts[2 * e], b = p.edge_verts[2 * e + 1];
    std::uint32_t* ev = &c.edge_verts[4 * std::size_t(e)];
    ev[0] = a, ev[1] = E0 + e, ev[2] = E0 + e, ev[3] = b;
    c.edge_dim[2 * e] = c.edge_dim[2 * e + 1] = p.edge_dim[e];
  }
  for (std::uint32_t f = 0; f < nf; ++f)
    for (std::uint32_t i = p.faces.offsets[f]; i < p.faces.offsets[f + 1]; ++i) {
      c.edge_verts[2 * std::size_t(face_edge0 + i)] = E0 + p.face_edges.items[i];
      c.edge_verts[2 * std::size_t(face_edge0 + i) + 1] = F0 + f;
      c.edge_dim[face_edge0 + i] = p.face_dim[f];
    }
  for (std::uint32_t k = 0; k < nc; ++k)
    for (std::uint32_t s = p.cell_faces.offsets[k]; s < p.cell_faces.offsets[k + 1]; ++s) {
      c.edge_verts[2 * std::size_t(cell_edge0 + s)] = F0 + p.cell_faces.items[s];
      c.edge_verts[2 * std::size_t(cell_edge0 + s) + 1] = C0 + k;
      c.edge_dim[cell_edge0 + s] = 3;
    }

  // The half of parent edge e that touches its end vertex v.
  auto half = [&](std::uint32_t e, std::uint32_t v) { return p.edge_verts[2 * e] == v ? 2 * e : 2 * e + 1; };

  // Faces: one quad per parent face corner, then one per cell edge.
  std::uint32_t cell_edge_slots = static_cast<std::uint32_t>(p.cell_edges.items.size());
  const std::uint32_t num_child_faces = corners + (nc ? cell_edge_slots : 0);
  c.faces.offsets.resize(num_child_faces + 1);
  for (std::uint32_t i = 0; i <= num_child_faces; ++i) c.faces.offsets[i] = 4 * i;
  c.faces.items.resize(4 * std::size_t(num_child_faces));
  c.face_edges.items.resize(4 * std::size_t(num_child_faces));
  c.face_dim.resize(num_child_faces);
  for (std::uint32_t f = 0; f < nf; ++f) {
    const std::uint32_t b = p.faces.offsets[f], n = p.faces.offsets[f + 1] - b;
    for (std::uint32_t i = 0; i < n; ++i) {
      const std::uint32_t prev = i ? i - 1 : n - 1;
      const std::uint32_t v = p.faces.items[b + i];
      const std::uint32_t e_next = p.face_edges.items[b + i], e_prev = p.face_edges.items[b + prev];
      std::uint32_t* fv = &c.faces.items[4 * std::size_t(b + i)];
      std::uint32_t* fe = &c.face_edges.items[4 * std::size_t(b + i)];
      fv[0] = v, fv[1] = E0 + e_next, fv[2] = F0 + f, fv[3] = E0 + e_prev;
      fe[0] = half(e_next, v), fe[1] = face_edge0 + b + i, fe[2] = face_edge0 + b + prev, fe[3] = half(e_prev, v);
      c.face_dim[b + i] = p.face_dim[f];
    }
  }
  if (nc) {
    // Per cell: for each of its edges the two faces (and the corner slots) that contain it.
    std::vector<std::uint32_t> slot_f, slot_i;  // per cell edge: face-local corner slots
    for (std::uint32_t k = 0; k < nc; ++k) {
      const auto cedges = p.cell_edges.row(k);
      const auto cfaces = p.cell_faces.row(k);
      slot_f.assign(2 * cedges.size(), UINT32_MAX);
      slot_i.assign(2 * cedges.size(), 0);
      for (std::uint32_t j = 0; j < cfaces.size(); ++j) {
        const std::uint32_t f = cfaces[j];
        for (std::uint32_t s = p.face_edges.offsets[f]; s < p.face_edges.offsets[f + 1]; ++s) {
          const std::uint32_t e = p.face_edges.items[s];
          const auto l = static_cast<std::uint32_t>(std::lower_bound(cedges.begin(), cedges.end(), e) - cedges.begin());
          const std::uint32_t slot = slot_f[2 * l] == UINT32_MAX ? 2 * l : 2 * l + 1;
          slot_f[slot] = j;       // which cell face (local)
          slot_i[slot] = s;       // global face-corner slot of the edge in that face
        }
      }
      for (std::uint32_t l = 0; l < cedges.size(); ++l) {
        const std::uint32_t face_index = corners + p.cell_edges.offsets[k] + l;
        const std::uint32_t j1 = slot_f[2 * l], j2 = slot_f[2 * l + 1];
        const std::uint32_t s1 = slot_i[2 * l], s2 = slot_i[2 * l + 1];
        std::uint32_t* fv = &c.faces.items[4 * std::size_t(face_index)];
        std::uint32_t* fe = &c.face_edges.items[4 * std::size_t(face_index)];
        fv[0] = E0 + cedges[l], fv[1] = F0 + cfaces[j1], fv[2] = C0 + k, fv[3] = F0 + cfaces[j2];
        fe[0] = face_edge0 + s1;
        fe[1] = cell_edge0 + p.cell_faces.offsets[k] + j1;
        fe[2] = cell_edge0 + p.cell_faces.offsets[k] + j2;
        fe[3] = face_edge0 + s2;
        c.face_dim[face_index] = 3;
      }
    }
    // Cells: one per cell vertex, bounded by the corner quads of the cell's faces at that
    // vertex and the interior quads of the cell's edges at that vertex.
    c.cell_faces.offsets.assign(1, 0);
    c.cell_faces.items.reserve(std::size_t(p.cell_verts.items.size()) * 6);
    for (std::uint32_t k = 0; k < nc; ++k) {
      const auto cverts = p.cell_verts.row(k);
      const auto cedges = p.cell_edges.row(k);
      for (std::uint32_t v : cverts) {
        for (std::uint32_t f : p.cell_faces.row(k))
          for (std::uint32_t s = p.faces.offsets[f]; s < p.faces.offsets[f + 1]; ++s)
            if (p.faces.items[s] == v) c.cell_faces.items.push_back(s);
        for (std::uint32_t l = 0; l < cedges.size(); ++l) {
          const std::uint32_t e = cedges[l];
          if (p.edge_verts[2 * e] == v || p.edge_verts[2 * e + 1] == v)
            c.cell_faces.items.push_back(corners + p.cell_edges.offsets[k] + l);
        }
        c.cell_faces.offsets.push_back(static_cast<std::uint32_t>(c.cell_faces.items.size()));
      }
    }
  }
  c.face_edges.offsets = c.faces.offsets;
  // Semi-sharp features: children of a sharp edge (and the vertex itself) one level less sharp,
  // the dims derived again from that (Complex::edge_sharpness; OpenSubdiv's uniform rule).
  if ((!p.edge_sharpness.empty() || !p.vertex_sharpness.empty()) && p.dim == 2) return inherit_sharpness(p, std::move(c), adjacency);
  if (adjacency) build_adjacency(c);
  return c;
}

}  // namespace sublift
