#include "core/complex/refine_sqrt2.h"

#include <initializer_list>
#include <stdexcept>
#include <string>

#include "core/base/errors.h"

namespace sublift {

namespace {

constexpr std::uint32_t kNone = Sqrt2Children::kNone;

// The slot of edge e in face f.
std::uint32_t edge_slot(const Complex& c, std::uint32_t f, std::uint32_t e) {
  for (std::uint32_t s = c.face_edges.offsets[f]; s < c.face_edges.offsets[f + 1]; ++s)
    if (c.face_edges.items[s] == e) return s;
  throw TopologyError("sqrt(2) refinement: face " + std::to_string(f) + " does not hold edge " + std::to_string(e));
}

// The two faces of inner edge e = (a, b): A runs a->b at slot sa, B runs b->a at slot sb.
struct Sides {
  std::uint32_t A, sa, B, sb;
};
Sides sides(const Complex& c, std::uint32_t e) {
  const std::uint32_t a = c.edge_verts[2 * e];
  const auto fs = c.edge_faces.row(e);
  const std::uint32_t s0 = edge_slot(c, fs[0], e), s1 = edge_slot(c, fs[1], e);
  const bool first_forward = c.faces.items[s0] == a, second_forward = c.faces.items[s1] == a;
  if (first_forward == second_forward)
    throw TopologyError("sqrt(2) refinement: the two faces of edge " + std::to_string(e) +
                        " run the same way (mesh not consistently oriented)");
  return first_forward ? Sides{fs[0], s0, fs[1], s1} : Sides{fs[1], s1, fs[0], s0};
}

void push_face(Complex& c, std::initializer_list<std::uint32_t> vs, std::initializer_list<std::uint32_t> es,
               std::uint8_t dim) {
  c.faces.items.insert(c.faces.items.end(), vs);
  c.faces.offsets.push_back(static_cast<std::uint32_t>(c.faces.items.size()));
  c.face_edges.items.insert(c.face_edges.items.end(), es);
  c.face_edges.offsets.push_back(static_cast<std::uint32_t>(c.face_edges.items.size()));
  c.face_dim.push_back(dim);
}

// p's other neighbour along the curve through edge e, or kNone where the curve ends there
// (cusp, dart, branch: anything but a curve vertex with exactly two curve edges).
std::uint32_t curve_neighbour(const Complex& c, std::uint32_t p, std::uint32_t e) {
  if (c.vertex_dim[p] != 1) return kNone;
  std::uint32_t other = kNone;
  int count = 0;
  for (std::uint32_t x : c.vertex_edges.row(p))
    if (sqrt2_is_curve_edge(c, x)) {
      ++count;
      if (x != e) other = x;
    }
  if (count != 2 || other == kNone) return kNone;
  return edge_other_end(c, other, p);
}

// The curve edges of p in order into ch.curve_edges; per edge its index there, kNone off curves.
std::vector<std::uint32_t> list_curve_edges(const Complex& p, Sqrt2Children& ch) {
  std::vector<std::uint32_t> curve_index(p.num_edges(), kNone);
  for (std::uint32_t e = 0; e < p.num_edges(); ++e)
    if (sqrt2_is_curve_edge(p, e)) {
      curve_index[e] = static_cast<std::uint32_t>(ch.curve_edges.size());
      ch.curve_edges.push_back(e);
    }
  return curve_index;
}

// Room for the fine level's faces, edges and corners: the steps append them one by one.
void reserve_fine(Complex& c, std::size_t faces, std::size_t edges, std::size_t corners) {
  c.faces.offsets.reserve(faces + 1);
  c.face_edges.offsets.reserve(faces + 1);
  c.face_dim.reserve(faces);
  c.faces.items.reserve(corners);
  c.face_edges.items.reserve(corners);
  c.edge_verts.reserve(2 * edges);
  c.edge_dim.reserve(edges);
}

Complex start_fine(const Complex& p, std::uint32_t num_vertices) {
  Complex c;
  c.dim = 2;
  c.num_vertices = num_vertices;
  c.vertex_dim.assign(p.vertex_dim.begin(), p.vertex_dim.end());
  return c;
}

// Even level -> odd level: curves kept, one triangle per face beside a curve edge.
Sqrt2Step keep_step(const Complex& p) {
  const std::uint32_t nv = p.num_vertices, ne = p.num_edges(), nf = p.num_faces();
  Sqrt2Step out;
  Sqrt2Children& ch = out.children;
  ch.curve_step = false;
  ch.first_face_point = nv;
  ch.point_faces.resize(nf);
  for (std::uint32_t f = 0; f < nf; ++f) ch.point_faces[f] = f;
  ch.point_corners = p.faces;
  const std::vector<std::uint32_t> curve_index = list_curve_edges(p, ch);
  const std::uint32_t nc = static_cast<std::uint32_t>(ch.curve_edges.size());

  Complex c = start_fine(p, nv + nf);
  reserve_fine(c, ne + nc, std::size_t(nc) + p.faces.items.size(), 4 * std::size_t(ne + nc));
  c.vertex_dim.insert(c.vertex_dim.end(), p.face_dim.begin(), p.face_dim.end());
  // Edges: kept curve edges, then corner slot s -> (corner, face point).
  for (std::uint32_t e : ch.curve_edges) {
    c.edge_verts.insert(c.edge_verts.end(), {p.edge_verts[2 * e], p.edge_verts[2 * e + 1]});
    c.edge_dim.push_back(p.edge_dim[e]);
  }
  for (std::uint32_t f = 0; f < nf; ++f)
    for (std::uint32_t s = p.faces.offsets[f]; s < p.faces.offsets[f + 1]; ++s) {
      c.edge_verts.insert(c.edge_verts.end(), {p.faces.items[s], nv + f});
      c.edge_dim.push_back(p.face_dim[f]);
    }
  auto corner_edge = [&](std::uint32_t s) { return nc + s; };

  // Faces along the coarse edges.
  for (std::uint32_t e = 0; e < ne; ++e) {
    if (curve_index[e] == kNone) {
      const Sides sd = sides(p, e);
      const std::uint32_t a = p.edge_verts[2 * e], b = p.edge_verts[2 * e + 1];
      push_face(c, {a, nv + sd.B, b, nv + sd.A},
                {corner_edge(face_next_slot(p, sd.B, sd.sb)), corner_edge(sd.sb), corner_edge(face_next_slot(p, sd.A, sd.sa)),
                 corner_edge(sd.sa)},
                p.edge_dim[e]);
      ch.fine_face_edge.push_back(e);
      continue;
    }
    for (std::uint32_t x : p.edge_faces.row(e)) {
      const std::uint32_t s = edge_slot(p, x, e), t = face_next_slot(p, x, s);
      push_face(c, {p.faces.items[s], p.faces.items[t], nv + x}, {curve_index[e], corner_edge(t), corner_edge(s)},
                p.face_dim[x]);
      ch.fine_face_edge.push_back(e);
    }
  }
  build_adjacency(c);
  out.fine = std::move(c);
  return out;
}

// Odd level -> even level: a curve point per curve edge replaces the triangles' face points.
Sqrt2Step curve_step(const Complex& p) {
  const std::uint32_t nv = p.num_vertices, ne = p.num_edges(), nf = p.num_faces();
  Sqrt2Step out;
  Sqrt2Children& ch = out.children;
  ch.curve_step = true;
  const std::vector<std::uint32_t> curve_index = list_curve_edges(p, ch);
  const std::uint32_t nc = static_cast<std::uint32_t>(ch.curve_edges.size());
  ch.first_face_point = nv + nc;

  // Faces: quads without curve edges get a face point; triangles with one curve edge take the
  // curve point. tri_slot[f] = slot of the curve edge in triangle f, kNone for quads.
  std::vector<std::uint32_t> tri_slot(nf, kNone), new_point(nf), inner_base(nf);
  std::uint32_t inner = 2 * nc;  // first fine edge inside a coarse face
  for (std::uint32_t f = 0; f < nf; ++f) {
    std::uint32_t curves = 0, slot = kNone;
    for (std::uint32_t s = p.faces.offsets[f]; s < p.faces.offsets[f + 1]; ++s)
      if (curve_index[p.face_edges.items[s]] != kNone) ++curves, slot = s;
    inner_base[f] = inner;
    if (p.faces.size(f) == 4 && curves == 0) {
      new_point[f] = ch.first_face_point + static_cast<std::uint32_t>(ch.point_faces.size());
      ch.point_faces.push_back(f);
      const auto row = p.faces.row(f);
      ch.point_corners.items.insert(ch.point_corners.items.end(), row.begin(), row.end());
      ch.point_corners.offsets.push_back(static_cast<std::uint32_t>(ch.point_corners.items.size()));
      inner += 4;
    } else if (p.faces.size(f) == 3 && curves == 1) {
      tri_slot[f] = slot;
      new_point[f] = nv + curve_index[p.face_edges.items[slot]];
      inner += 1;
    } else {
      throw TopologyError("sqrt(2) refinement: face " + std::to_string(f) +
                          " of an odd level is neither a quad inside the surface nor a triangle on one curve edge");
    }
  }

  Complex c = start_fine(p, ch.first_face_point + static_cast<std::uint32_t>(ch.point_faces.size()));
  reserve_fine(c, ne, inner, 4 * std::size_t(ne));
  for (std::uint32_t e : ch.curve_edges) c.vertex_dim.push_back(p.edge_dim[e]);
  for (std::uint32_t f : ch.point_faces) c.vertex_dim.push_back(p.face_dim[f]);

  // Edges: curve halves (2k touches edge_verts[2e]), then per coarse face its inner edges.
  for (std::uint32_t k = 0; k < nc; ++k) {
    const std::uint32_t e = ch.curve_edges[k];
    c.edge_verts.insert(c.edge_verts.end(), {p.edge_verts[2 * e], nv + k, nv + k, p.edge_verts[2 * e + 1]});
    c.edge_dim.insert(c.edge_dim.end(), {p.edge_dim[e], p.edge_dim[e]});
  }
  for (std::uint32_t f = 0; f < nf; ++f) {
    if (tri_slot[f] == kNone) {
      for (std::uint32_t v : p.faces.row(f)) c.edge_verts.insert(c.edge_verts.end(), {v, new_point[f]});
      c.edge_dim.insert(c.edge_dim.end(), 4, p.face_dim[f]);
    } else {  // apex (the corner off the curve edge) to the curve point
      const std::uint32_t apex = face_next_slot(p, f, face_next_slot(p, f, tri_slot[f]));
      c.edge_verts.insert(c.edge_verts.end(), {p.faces.items[apex], new_point[f]});
      c.edge_dim.push_back(p.face_dim[f]);
    }
  }
  // The fine edge from the corner at slot s of face f to f's new point.
  auto inner_edge = [&](std::uint32_t f, std::uint32_t s) -> std::uint32_t {
    if (tri_slot[f] == kNone) return inner_base[f] + (s - p.faces.offsets[f]);
    const std::uint32_t ts = tri_slot[f];
    if (s != ts && s != face_next_slot(p, f, ts)) return inner_base[f];  // the apex
    const std::uint32_t e = p.face_edges.items[ts], k = curve_index[e];
    return p.edge_verts[2 * e] == p.faces.items[s] ? 2 * k : 2 * k + 1;  // half touching the corner
  };

  // Faces: one quad per inner coarse edge.
  for (std::uint32_t e = 0; e < ne; ++e) {
    if (curve_index[e] != kNone) continue;
    const Sides sd = sides(p, e);
    const std::uint32_t a = p.edge_verts[2 * e], b = p.edge_verts[2 * e + 1];
    push_face(c, {a, new_point[sd.B], b, new_point[sd.A]},
              {inner_edge(sd.B, face_next_slot(p, sd.B, sd.sb)), inner_edge(sd.B, sd.sb),
               inner_edge(sd.A, face_next_slot(p, sd.A, sd.sa)), inner_edge(sd.A, sd.sa)},
              p.edge_dim[e]);
    ch.fine_face_edge.push_back(e);
  }

  // 4-point stencils (001 eq. 11) along the curves of the coarse level.
  for (std::uint32_t e : ch.curve_edges) {
    const std::uint32_t a = p.edge_verts[2 * e], b = p.edge_verts[2 * e + 1];
    ch.curve_stencils.insert(ch.curve_stencils.end(), {curve_neighbour(p, a, e), a, b, curve_neighbour(p, b, e)});
  }
  build_adjacency(c);
  out.fine = std::move(c);
  return out;
}

}  // namespace

Sqrt2Step refine_sqrt2(const Complex& coarse, int level) {
  if (coarse.dim != 2 || coarse.num_cells() != 0)
    throw TopologyError("sqrt(2) refinement needs a surface (dim 2, no cells), got dim " + std::to_string(coarse.dim));
  if (level < 0) throw std::invalid_argument("sqrt(2) refinement: negative level " + std::to_string(level));
  const bool derived = coarse.edge_faces.rows() == coarse.num_edges() && coarse.vertex_edges.rows() == coarse.num_vertices;
  if (!derived) {
    Complex copy = coarse;
    build_adjacency(copy);
    return refine_sqrt2(copy, level);
  }
  return level % 2 == 0 ? keep_step(coarse) : curve_step(coarse);
}

std::vector<Complex> build_sqrt2_levels(const Complex& base, int J) {
  if (J < 0) throw std::invalid_argument("sqrt(2) refinement: negative finest level " + std::to_string(J));
  std::vector<Complex> levels;
  levels.reserve(static_cast<std::size_t>(J) + 1);
  levels.push_back(base);
  build_adjacency(levels.back());
  for (int j = 0; j < J; ++j) levels.push_back(refine_sqrt2(levels.back(), j).fine);
  return levels;
}

}  // namespace sublift
