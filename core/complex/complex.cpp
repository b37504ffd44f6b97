#include "core/complex/complex.h"

#include <algorithm>
#include <string>

#include "core/base/errors.h"

namespace sublift {

std::size_t Complex::bytes() const {
  std::size_t b = (edge_verts.capacity()) * 4 + vertex_dim.capacity() + edge_dim.capacity() + face_dim.capacity();
  for (const Csr* c : {&faces, &face_edges, &cell_faces, &vertex_edges, &vertex_faces, &vertex_cells, &edge_faces,
                       &edge_cells, &face_cells, &cell_verts, &cell_edges})
    b += c->bytes();
  return b;
}

void build_adjacency(Complex& c) {
  c.vertex_edges = transpose_pairs(c.edge_verts, c.num_vertices);
  c.vertex_faces = transpose(c.faces, c.num_vertices);
  c.edge_faces = transpose(c.face_edges, c.num_edges());
  c.face_cells = transpose(c.cell_faces, c.num_faces());
  // Cells' vertices and edges: the distinct ones over their faces, sorted.
  c.cell_verts.clear();
  c.cell_edges.clear();
  std::vector<std::uint32_t> tmp;
  for (std::uint32_t k = 0; k < c.num_cells(); ++k) {
    for (int pass = 0; pass < 2; ++pass) {
      tmp.clear();
      for (std::uint32_t f : c.cell_faces.row(k)) {
        auto r = pass == 0 ? c.faces.row(f) : c.face_edges.row(f);
        tmp.insert(tmp.end(), r.begin(), r.end());
      }
      std::sort(tmp.begin(), tmp.end());
      tmp.erase(std::unique(tmp.begin(), tmp.end()), tmp.end());
      Csr& out = pass == 0 ? c.cell_verts : c.cell_edges;
      out.items.insert(out.items.end(), tmp.begin(), tmp.end());
      out.offsets.push_back(static_cast<std::uint32_t>(out.items.size()));
    }
  }
  c.vertex_cells = transpose(c.cell_verts, c.num_vertices);
  c.edge_cells = transpose(c.cell_edges, c.num_edges());
}

void validate(const Complex& c) {
  auto fail = [](const std::string& what) { throw TopologyError("invalid complex: " + what); };
  if (c.dim < 1 || c.dim > 3) fail("dimension " + std::to_string(c.dim));
  if (c.vertex_dim.size() != c.num_vertices || c.edge_dim.size() != c.num_edges() ||
      c.face_dim.size() != c.num_faces())
    fail("feature-dimension arrays do not match the primitive counts");
  for (std::uint32_t e = 0; e < c.num_edges(); ++e) {
    const std::uint32_t a = c.edge_verts[2 * e], b = c.edge_verts[2 * e + 1];
    if (a >= c.num_vertices || b >= c.num_vertices) fail("edge " + std::to_string(e) + " names a missing vertex");
    if (a == b) fail("edge " + std::to_string(e) + " is a loop");
    if (c.edge_dim[e] < 1 || c.edge_dim[e] > c.dim) fail("edge " + std::to_string(e) + " has feature dim " + std::to_string(c.edge_dim[e]));
  }
  if (c.face_edges.offsets != c.faces.offsets) fail("face_edges not aligned with faces");
  for (std::uint32_t f = 0; f < c.num_faces(); ++f) {
    const auto vs = c.faces.row(f);
    const auto es = c.face_edges.row(f);
    const std::string name = "face " + std::to_string(f);
    if (vs.size() < 3) fail(name + " has fewer than 3 edges");
    for (std::size_t i = 0; i < vs.size(); ++i) {
      const std::uint32_t e = es[i];
      if (e >= c.num_edges()) fail(name + " names a missing edge");
      const std::uint32_t a = vs[i], b = vs[(i + 1) % vs.size()];
      const std::uint32_t x = c.edge_verts[2 * e], y = c.edge_verts[2 * e + 1];
      if (!((x == a && y == b) || (x == b && y == a))) fail(name + " is not a closed cycle of its edges");
      for (std::size_t j = i + 1; j < es.size(); ++j)
        if (es[j] == e) fail(name + " repeats edge " + std::to_string(e));
    }
    if (c.face_dim[f] < 2 || c.face_dim[f] > c.dim) fail(name + " has feature dim " + std::to_string(c.face_dim[f]));
  }
  for (std::uint32_t k = 0; k < c.num_cells(); ++k) {
    const std::string name = "cell " + std::to_string(k);
    if (c.cell_faces.size(k) < 4) fail(name + " has fewer than 4 faces");
    for (std::uint32_t f : c.cell_faces.row(k))
      if (f >= c.num_faces()) fail(name + " names a missing face");
    // Closed: every edge of the cell is used by exactly two of its faces.
    for (std::uint32_t e : c.cell_edges.row(k)) {
      int uses = 0;
      for (std::uint32_t f : c.cell_faces.row(k))
        for (std::uint32_t fe : c.face_edges.row(f)) uses += fe == e;
      if (uses != 2) fail(name + " is not closed: edge " + std::to_string(e) + " is used by " + std::to_string(uses) + " of its faces");
    }
  }
  for (std::uint32_t v = 0; v < c.num_vertices; ++v)
    if (c.vertex_dim[v] > c.dim) fail("vertex " + std::to_string(v) + " has feature dim " + std::to_string(c.vertex_dim[v]));
}

}  // namespace sublift
