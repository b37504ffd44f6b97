#pragma once
// Folded faces of a fitted net (issue 17: a fit must fold none). A face is folded when it turns
// away from the way the input faces there (the caller says which way that is per face: fitting
// takes the vertex normals of the input face nearest the face's centre). The fitting moves
// never fold a face (keep_unfolded); folds that come anyway (from the subdivision itself at a
// sharp corner of a jagged boundary, where the smoothed boundary curve crosses the first inner
// row, and from thin parts) are untangled.
#include <functional>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "core/complex/complex.h"
#include "core/fit/feature_lines.h"
#include "core/multires/limit.h"

namespace sublift {

/// Per face, the way the input faces there, for the points x (3 per vertex).
using FacingFn = std::function<std::vector<glm::dvec3>(std::span<const double> x)>;
/// p onto the input, along n, moving no farther than `reach` (else p itself).
using ProjectFn = std::function<glm::dvec3(const glm::dvec3& p, const glm::dvec3& n, double reach)>;

/// Whether face f over x turns away from `facing` (its area vector has no positive part along it).
bool turned(const Csr& faces, std::size_t f, std::span<const double> x, const glm::dvec3& facing);

/// Per face of `faces` over x, whether it is turned (1) or not (0); computed in parallel.
std::vector<std::uint8_t> turned_faces(const Csr& faces, std::span<const double> x, const std::vector<glm::dvec3>& facing);
/// How many faces are turned.
std::size_t count_turned(const Csr& faces, std::span<const double> x, const std::vector<glm::dvec3>& facing);

/// Takes back the moves (from `before` to `after`) that fold a face: each such face's corners
/// move half as far, up to four times, then not at all. A face folded before may move: it can
/// only come right.
void keep_unfolded(const Csr& faces, const std::vector<glm::dvec3>& facing, std::span<const double> before, std::vector<double>& after);

/// Moves the points of folded faces of `c` (derived rows built) until they come right, up to
/// `rounds` rounds. Each such point goes to the centre of its star's kernel (where all its faces
/// face their way, in the plane square to their mean facing), projected onto the input (a crease
/// or boundary point: onto its feature line) when that keeps its star unfolded; where the
/// kernel is empty (a star bent over a crease), to the best of a few points towards its
/// neighbours. Corners stay; no move folds another face.
/// `facing`: the input's way at each face (from input_facing at x; the moves are small).
void untangle(const Complex& c, const ProjectFn& project, const FeatureLines& lines, const std::vector<glm::dvec3>& facing,
              std::vector<double>& x, int rounds = 8);

/// The same for the limit surface y = L x of an approximating scheme, moving the control points
/// x: the limit points of folded limit faces are untangled as above; the control points around
/// them (the moved points' and their neighbours') change by the least squares solution of
/// L dx = dy over every limit point they reach (dy: the untangling moves, zero elsewhere), so the
/// rest of the limit surface stays. A round is kept only when fewer faces fold, of the limit
/// surface and the net together (a limit surface can come right only with its net folded).
/// `net_facing` (optional): set to facing_of(x) of the x returned.
void untangle_limit(const Complex& c, const LimitStencils& ls, const ProjectFn& project, const FeatureLines& lines, const FacingFn& facing_of,
                    std::vector<double>& x, std::vector<glm::dvec3>* net_facing = nullptr, int rounds = 4);

}  // namespace sublift
