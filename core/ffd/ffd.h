#pragma once
// Free-form deformation (issue 6): bind a model's vertices into a lattice once, then move them
// with the lattice.
//
// Binding. Every model vertex is located in one cell of the (undeformed) lattice through a
// uniform grid over the cells' bounding boxes and gets a sparse stencil of (lattice vertex,
// weight) pairs with model_p = sum_k w_k lattice_x_k at rest and sum_k w_k = 1, so any affine
// map of the lattice moves the model by the same map (up to round-off). Stencils are CSR:
// model vertex i weighs stencil.row(i) with weight[stencil.offsets[i] + k].
//   - Hexahedra (6 quads, 8 corners forming a topological cube, any orientation): inverse
//     trilinear map by Newton from the cell centre; the 8 trilinear weights.
//   - Other cells (tetrahedra, pyramids, prisms, general polyhedra), and hexahedra where Newton
//     fails (degenerate, badly inverted): the tet split. Each face edge (a, b) of each face f
//     makes the tetrahedron (cell centroid, face centroid, a, b); centroids are means of the
//     cell's / face's vertices, so their barycentric weights spread evenly to those vertices.
// A vertex is inside a cell when its coordinates are within `tolerance` of the cell
// (trilinear u, v, w in [-tol, 1 + tol], or barycentric coordinates >= -tol); a vertex on a
// shared face goes to the lowest-numbered cell that accepts it. Each stencil lists the cell's
// vertices (a hexahedron's in trilinear corner order, bit 0 = u, bit 1 = v, bit 2 = w).
//
// Outside vertices. Outside::Stay (default) keeps them at their rest position (cell -1, empty
// stencil). Outside::Nearest gives them the cell whose bounding box is nearest (ties, e.g. a
// point inside several boxes, go to the cell whose coordinates are least outside) and that
// cell's extrapolated coordinates, so they follow it affinely. "Nearest" is by bounding box,
// hence approximate near concave or skewed boundaries.
//
// Deformation, in displacement form: p = rest + sum_k w_k (x_k - rest_k) with the lattice's rest
// positions kept from binding, so a lattice back at rest gives every vertex back bit for bit.
// deform() recomputes every vertex; deform_changed() only the vertices whose
// stencil names a changed lattice vertex (through the reverse index `users`, built at bind
// time), with the same arithmetic, so it equals deform() bit for bit and leaves every other
// output value untouched.
#include <cstdint>
#include <span>
#include <vector>

#include "core/complex/complex.h"
#include "core/base/csr.h"

namespace sublift {

enum class Outside : std::uint8_t { Stay, Nearest };

struct FfdOptions {
  Outside outside = Outside::Stay;
  double tolerance = 1e-6;  // parametric slack of the inside test (cell size ~ 1)
};

/// How one model vertex is bound.
enum class Placement : std::uint8_t { Inside, Stay, Nearest };

struct FfdReport {
  std::size_t bound = 0;      // vertices inside a cell
  std::size_t outside = 0;    // vertices in no cell
  std::size_t nearest = 0;    // outside vertices that follow their nearest cell
  std::size_t tet_split = 0;  // vertices bound through the tet split (not trilinear)
  double ms = 0.0;            // binding time, spatial index included
};

struct FfdBinding {
  std::uint32_t num_lattice_vertices = 0;
  std::vector<double> rest;            // model rest positions, 3 per vertex
  std::vector<double> lattice_rest;    // lattice positions at binding, 3 per vertex
  std::vector<std::int32_t> cell;      // lattice cell per model vertex; -1 when it stays
  std::vector<Placement> placement;    // per model vertex
  Csr stencil;                         // model vertex -> lattice vertices it weighs
  std::vector<double> weight;          // aligned with stencil.items
  Csr users;                           // lattice vertex -> model vertices weighing it (ascending)
  FfdReport report;

  std::uint32_t num_model_vertices() const { return static_cast<std::uint32_t>(cell.size()); }
};

/// Binds `model_xyz` (3 per vertex) into the volume complex `lattice` (dim 3; only its downward
/// connectivity is used, so a hierarchy's finest level without adjacency will do) with rest
/// positions `lattice_xyz` (3 per lattice vertex). Throws Error for a complex that is not a
/// volume, mismatched sizes, out-of-range indices or non-finite coordinates.
FfdBinding bind_model(const Complex& lattice, std::span<const double> lattice_xyz, std::span<const double> model_xyz,
                      const FfdOptions& options = {});

/// Model positions for lattice positions `lattice_xyz`: out = rest + sum_k w_k (x_k - rest_k)
/// per bound vertex, the rest position for the others. `out` holds 3 per model vertex. Throws Error on sizes.
void deform(const FfdBinding& b, std::span<const double> lattice_xyz, std::span<double> out);

/// Like deform() for the model vertices whose stencils name a vertex of `changed` (lattice
/// vertex indices, repeats allowed); other entries of `out` are not written. When `touched` is
/// given it receives the recomputed model vertices in ascending order. Throws Error on sizes or
/// an index out of range.
void deform_changed(const FfdBinding& b, std::span<const double> lattice_xyz, std::span<const std::uint32_t> changed,
                    std::span<double> out, std::vector<std::uint32_t>* touched = nullptr);

}  // namespace sublift
