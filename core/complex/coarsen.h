#pragma once
// One coarsening of one connected component (detect_levels.h): the labelling from one of four
// seed choices, its local checks and the coarser mesh. Internal to detect_levels.cpp.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/base/csr.h"
#include "core/complex/detect_levels.h"

namespace sublift::detect {

/// Vertex labels of an attempt: Coarsening's kinds (short, as the labelling code reads them),
/// and kNone for a vertex not labelled yet.
inline constexpr std::uint8_t kNone = 255;
inline constexpr std::uint8_t V = Coarsening::Old, E = Coarsening::EdgePoint, F = Coarsening::FacePoint,
                              C = Coarsening::CellPoint;

/// A connected component in its own numbering (faces all of one split's shape).
struct Mesh {
  std::uint32_t n = 0;
  Csr faces;
  std::vector<std::uint32_t> input;  // input vertex id of each vertex
  std::vector<double> xyz;           // its positions (3 per vertex, this numbering), or empty
};

/// Per vertex: number of faces around it and whether it lies on the boundary.
struct Star {
  Csr vertex_faces;
  std::vector<std::uint8_t> boundary;
};
Star build_star(const Mesh& m);

struct Attempt {
  bool ok = false;
  int score = 0;                // old vertices that are extraordinary: more is likelier right
  std::uint32_t progress = 0;   // vertices labelled before a failure: the best failure is named
  std::string why;              // the failure, in words, naming input vertices
  std::uint32_t where = UINT32_MAX;  // input vertex near the failure
  Coarsening c;                 // in the component's numbering; c.input_vertex filled
  std::vector<double> coarse_xyz;  // the coarser mesh's positions, when the mesh has them
  bool keep_step = false;       // sqrt(2): the fine mesh has a keep step's triangles (its level is odd)
  bool curve_step = false;      // sqrt(2): it has a curve step's boundary points (its level is even)
};

/// candidate 0..3: which seed labelling (the four a component can have). Faces must be quads /
/// triangles.
Attempt coarsen_quads(const Mesh& m, const Star& s, int candidate);
Attempt coarsen_tris(const Mesh& m, const Star& s, int candidate);
/// sqrt(2): candidates 0 and 1 only (the seed vertex is an old vertex or a face point).
Attempt coarsen_sqrt2(const Mesh& m, const Star& s, int candidate);

/// One coarsening of a hexahedral lattice (`fine` with adjacency): candidate 0..7 picks which
/// corner of cell 0 is the old vertex.
Attempt coarsen_hexes(const Complex& fine, const std::vector<std::uint32_t>& input, int candidate);

/// The corners `offset` after v of the faces around v, walked as one closed fan: the face after
/// one is the face whose corner after v is this face's corner before v (corner k+3 of a quad).
/// For a face point of a quad split (offset 2) or a sqrt(2) step (offset 1) these are its face's
/// corners in order. False when the faces do not close into one fan.
bool fan_corners(const Mesh& m, const Star& s, std::uint32_t v, unsigned offset, std::vector<std::uint32_t>& out);

/// True when two of `ends` (the far ends of v's coarse edges) coincide: a doubled coarse edge.
bool has_repeat(std::vector<std::uint32_t>& ends);

/// Fills c.coarse_vertices and c.input_vertex from the old vertices (label Old); `input`: the
/// input vertex id of each fine vertex.
void name_coarse_vertices(std::span<const std::uint32_t> input, const std::vector<std::uint8_t>& labels,
                          const std::vector<std::uint32_t>& coarse_id, std::uint32_t num_coarse, Coarsening& c);

/// Records why `at` failed (near input vertex `where`) and returns it: the coarseners' `return fail(...)`.
inline Attempt failed(Attempt& at, std::uint32_t where, std::string why) {
  at.where = where;
  at.why = std::move(why);
  return at;
}

/// Position of v in face row `q` (q must contain v).
inline unsigned corner_of(std::span<const std::uint32_t> q, std::uint32_t v) {
  unsigned k = 0;
  while (q[k] != v) ++k;
  return k;
}

/// The pass over the old vertices (label Old) the surface coarseners share: names each in c
/// (c.a[v] = its coarse id), adds to at.score each whose face count is not the regular one
/// (`regular_inside`, `regular_boundary`: extraordinary vertices are likelier old), and checks
/// that its coarse edges lead to distinct vertices: far_end(q, k) is the far end of the coarse
/// edge that face q (v at corner k) holds, UINT32_MAX for none. False (at failed, naming the
/// first vertex with a doubled coarse edge) when two lead to the same vertex.
template <class FarEnd>
bool check_old_vertices(const Mesh& m, const Star& s, const std::vector<std::uint8_t>& labels,
                                 const std::vector<std::uint32_t>& coarse_id, unsigned regular_inside,
                                 unsigned regular_boundary, FarEnd far_end, Attempt& at) {
  std::vector<std::uint32_t> ends;
  for (std::uint32_t v = 0; v < m.n; ++v) {
    if (labels[v] != Coarsening::Old) continue;
    at.c.a[v] = coarse_id[v];
    if (s.vertex_faces.size(v) != (s.boundary[v] ? regular_boundary : regular_inside)) ++at.score;
    ends.clear();
    for (std::uint32_t f : s.vertex_faces.row(v)) {
      const auto q = m.faces.row(f);
      const std::uint32_t x = far_end(q, corner_of(q, v));
      if (x != UINT32_MAX) ends.push_back(x);
    }
    if (has_repeat(ends)) {
      failed(at, m.input[v], "two edges of the coarser mesh would join vertex " + std::to_string(m.input[v]) + " to the same vertex");
      return false;
    }
  }
  return true;
}

}  // namespace sublift::detect
