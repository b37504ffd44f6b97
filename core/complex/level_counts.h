#pragma once
// How big a refined complex gets, before building it: exact vertex counts of every level of
// repeated refine() (refine.h) from a few sums over the base, so that commands can refuse a
// request that would not fit in memory before allocating anything.
//
// Per level, with V E F C the counts, SF the face corners, CF CE CV the sums over cells of their
// faces, edges and vertices: V' = V+E+F+C, E' = 2E+SF+CF, F' = SF+CE, C' = CV, SF' = 4F',
// CF' = 4CE, CE' = 8CE, CV' = 2CV+4CE (a child cell at a vertex of degree n has 2n quads, 4n
// edges and 2n+2 vertices). Exact when every cell's boundary is a sphere (closed cells).
#include <vector>

#include "core/complex/complex.h"

namespace sublift {

/// Vertex counts of levels 0..levels of refining `c` (doubles: large requests do not wrap).
/// Needs only c's downward connectivity.
std::vector<double> predicted_vertex_counts(const Complex& c, int levels);
/// Face counts of the same levels.
std::vector<double> predicted_face_counts(const Complex& c, int levels);

}  // namespace sublift
