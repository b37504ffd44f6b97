#pragma once
// Topological selection tools of the modeler (issue 19): linked (Ctrl+L, L), grow and shrink
// (Ctrl+numpad +/-), invert (Ctrl+I), edge loops and rings (Alt+click, Ctrl+Alt+click), and
// picking the net edge under the mouse. Pure functions on a level's Complex; selections are
// ascending vertex lists.
//
// Loops. The loop through an edge continues at each end with the one edge of that vertex that
// shares no face with the edge coming in, when there is exactly one: across a regular quad
// vertex (valence 4) that is the opposite edge, along a boundary it is the next boundary edge,
// in a hexahedral lattice the edge straight on, on a curve the next edge through a valence-2
// vertex. It stops at irregular vertices (valence 3 or 5 in a quad mesh, triangle fans) and
// when it closes. Rings (surfaces): the edge opposite in each quad face, face after face, until
// a non-quad face, a boundary or the start.
#include <cstdint>
#include <span>
#include <vector>

#include "core/complex/complex.h"
#include "core/edit/picking.h"

namespace sublift {

std::vector<unsigned> select_linked(const Complex& c, std::span<const unsigned> selection);
/// The selection plus every vertex joined to it by an edge.
std::vector<unsigned> grow_selection(const Complex& c, std::span<const unsigned> selection);
/// The selection without the vertices that have an unselected edge neighbour.
std::vector<unsigned> shrink_selection(const Complex& c, std::span<const unsigned> selection);
std::vector<unsigned> invert_selection(std::uint32_t num_vertices, std::span<const unsigned> selection);

/// Edges of the loop / ring through edge e (e first, then in walking order).
std::vector<std::uint32_t> edge_loop(const Complex& c, std::uint32_t e);
std::vector<std::uint32_t> edge_ring(const Complex& c, std::uint32_t e);
/// The vertices of `edges`, ascending and unique.
std::vector<unsigned> edge_vertices(const Complex& c, std::span<const std::uint32_t> edges);
/// The edge joining a and b, or -1.
std::int64_t find_edge(const Complex& c, std::uint32_t a, std::uint32_t b);

/// The net edge nearest to (mx, my) on screen within `radius_px` (distance to the projected
/// segment), among the edges of the points `index` holds near the mouse (so with !xray an edge
/// with both ends hidden is not picked); -1 when none. `positions` are the level's control points.
std::int64_t pick_edge(const PickIndex& index, const PickView& view, std::span<const double> positions,
                       const Complex& c, double mx, double my, double radius_px, bool xray);

}  // namespace sublift
