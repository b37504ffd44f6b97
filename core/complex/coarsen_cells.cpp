// Coarsening a hexahedral lattice that is one 1-to-8 split (refine.h) of a lattice of simple
// cells (every cell vertex with three cell edges): each child cell is (old vertex, 3 edge points,
// 3 face points, cell point), the labels its corners get from their distance to the old vertex.
// Across a face the labels step by one: a face holding the old vertex (V, E, F, E) has the next
// class opposite it (E, F, C, F), and back. Other cells (the type-n children of pyramids and
// octahedra) are not detected (docs/rebuild.md).
#include <algorithm>
#include <string>

#include "core/complex/coarsen.h"

namespace sublift::detect {

namespace {

bool in_row(std::span<const std::uint32_t> row, std::uint32_t x) { return std::find(row.begin(), row.end(), x) != row.end(); }

}  // namespace

Attempt coarsen_hexes(const Complex& c, const std::vector<std::uint32_t>& input, int candidate) {
  Attempt at;
  const std::uint32_t n = c.num_vertices, ncell = c.num_cells();
  auto fail = [&](std::uint32_t v, std::string why) { return failed(at, input[v], std::move(why)); };
  std::vector<std::uint8_t> lab(n, kNone), seen(ncell, 0);
  std::uint32_t clash = UINT32_MAX;
  auto set = [&](std::uint32_t v, std::uint8_t l) {
    if (lab[v] == kNone) {
      lab[v] = l;
      ++at.progress;
      return true;
    }
    if (lab[v] != l && clash == UINT32_MAX) clash = v;
    return lab[v] == l;
  };
  // Seed: distances in cell 0's edge graph from the chosen corner.
  {
    const auto verts = c.cell_verts.row(0);
    const std::uint32_t v0 = verts[static_cast<std::size_t>(candidate)];
    set(v0, V);
    for (std::uint8_t d = 0; d < 3; ++d)
      for (std::uint32_t e : c.cell_edges.row(0)) {
        const std::uint32_t a = c.edge_verts[2 * e], b = c.edge_verts[2 * e + 1];
        if (lab[a] == d && lab[b] == kNone) set(b, std::uint8_t(d + 1));
        if (lab[b] == d && lab[a] == kNone) set(a, std::uint8_t(d + 1));
      }
  }
  std::vector<std::uint32_t> queue{0};
  seen[0] = 1;
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const std::uint32_t g = queue[head];
    for (std::uint32_t f : c.cell_faces.row(g)) {
      for (std::uint32_t h : c.face_cells.row(f)) {
        if (seen[h]) continue;
        const auto corners = c.faces.row(f);
        int olds = 0, centres = 0;
        for (std::uint32_t x : corners) olds += lab[x] == V, centres += lab[x] == C;
        if (olds + centres != 1) return fail(corners[0], "the cells around vertex " + std::to_string(input[corners[0]]) + " do not follow a 1-to-8 split");
        const int step = olds ? 1 : -1;  // away from the old vertex, or back towards it
        for (std::uint32_t x : corners)
          for (std::uint32_t e : c.vertex_edges.row(x)) {
            const std::uint32_t y = edge_other_end(c, e, x);
            if (in_row(corners, y) || !in_row(c.cell_edges.row(h), e)) continue;
            if (!set(y, std::uint8_t(lab[x] + step)))
              return fail(clash, "the cells around vertex " + std::to_string(input[clash]) + " do not follow a 1-to-8 split");
          }
        seen[h] = 1;
        queue.push_back(h);
      }
    }
  }
  for (std::uint32_t v = 0; v < n; ++v)
    if (lab[v] == kNone) return fail(v, "vertex " + std::to_string(input[v]) + " is not reached (lattices of several pieces are not detected)");

  Coarsening& out = at.c;
  out.kind = lab;
  out.a.assign(n, 0);
  out.b.assign(n, 0);
  std::vector<std::uint32_t> coarse_id(n);
  std::uint32_t nv = 0, nf = 0, nc = 0;
  for (std::uint32_t v = 0; v < n; ++v) coarse_id[v] = lab[v] == V ? nv++ : lab[v] == F ? nf++ : lab[v] == C ? nc++ : 0;
  if (nv == 0 || nc == 0) return fail(0, "no vertex of a coarser lattice is left");
  // Edge points between exactly two old vertices.
  for (std::uint32_t v = 0; v < n; ++v) {
    if (lab[v] != E) continue;
    std::uint32_t ends[3];
    unsigned k = 0;
    for (std::uint32_t e : c.vertex_edges.row(v)) {
      const std::uint32_t y = edge_other_end(c, e, v);
      if (lab[y] == V) {
        if (k == 2) return fail(v, "edge point " + std::to_string(input[v]) + " touches more than two vertices of the coarser lattice");
        ends[k++] = y;
      }
    }
    if (k != 2) return fail(v, "edge point " + std::to_string(input[v]) + " does not sit between two vertices of the coarser lattice");
    out.a[v] = coarse_id[ends[0]];
    out.b[v] = coarse_id[ends[1]];
  }
  std::vector<std::uint32_t> others;
  for (std::uint32_t v = 0; v < n; ++v) {
    if (lab[v] != V) continue;
    out.a[v] = coarse_id[v];
    others.clear();
    for (std::uint32_t e : c.vertex_edges.row(v)) {
      const std::uint32_t y = edge_other_end(c, e, v);
      others.push_back(out.a[y] == coarse_id[v] ? out.b[y] : out.a[y]);
    }
    if (has_repeat(others))
      return fail(v, "two edges of the coarser lattice would join vertex " + std::to_string(input[v]) + " to the same vertex");
  }
  // Face points: the quads around one that hold an old vertex lie on its coarse face; walked by
  // their shared edge points (lattice faces need not be oriented alike) they give its corners.
  std::vector<std::uint32_t> outer;
  for (std::uint32_t v = 0; v < n; ++v) {
    if (lab[v] != F) continue;
    out.a[v] = coarse_id[v];
    outer.clear();
    for (std::uint32_t f : c.vertex_faces.row(v)) {
      const auto q = c.faces.row(f);
      if (std::any_of(q.begin(), q.end(), [&](std::uint32_t x) { return lab[x] == V; })) outer.push_back(f);
    }
    if (outer.size() < 3) return fail(v, "face point " + std::to_string(input[v]) + " has " + std::to_string(outer.size()) + " quads on its face; a face needs 3 or more");
    std::uint32_t f = outer[0], from = UINT32_MAX;
    for (std::size_t step = 0; step < outer.size(); ++step) {
      const auto q = c.faces.row(f);
      const unsigned k = corner_of(q, v);
      const std::uint32_t e1 = q[(k + 1) & 3u], e2 = q[(k + 3) & 3u];
      out.coarse_faces.items.push_back(coarse_id[q[(k + 2) & 3u]]);
      const std::uint32_t to = e1 == from ? e2 : e1;
      std::uint32_t next = UINT32_MAX;
      for (std::uint32_t g : outer)
        if (g != f && in_row(c.faces.row(g), to)) next = g;
      if (next == UINT32_MAX || (next == outer[0]) != (step + 1 == outer.size()))
        return fail(v, "the quads around face point " + std::to_string(input[v]) + " do not close into one face");
      from = to;
      f = next;
    }
    out.coarse_faces.offsets.push_back(static_cast<std::uint32_t>(out.coarse_faces.items.size()));
  }
  // Cell points: inside, their face points are the coarse cell's faces.
  for (std::uint32_t v = 0; v < n; ++v) {
    if (lab[v] != C) continue;
    out.a[v] = coarse_id[v];
    const std::size_t before = out.coarse_cells.items.size();
    for (std::uint32_t e : c.vertex_edges.row(v)) {
      const std::uint32_t y = edge_other_end(c, e, v);
      if (lab[y] == F) out.coarse_cells.items.push_back(coarse_id[y]);
    }
    if (out.coarse_cells.items.size() - before < 4)
      return fail(v, "cell point " + std::to_string(input[v]) + " has fewer than 4 faces around it");
    out.coarse_cells.offsets.push_back(static_cast<std::uint32_t>(out.coarse_cells.items.size()));
  }
  for (std::uint32_t v = 0; v < n; ++v)
    if (lab[v] == V && c.vertex_cells.size(v) != 8 && c.vertex_dim[v] == 3) ++at.score;  // extraordinary inside
  name_coarse_vertices(input, lab, coarse_id, nv, out);
  at.ok = true;
  return at;
}

}  // namespace sublift::detect
