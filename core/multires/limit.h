#pragma once
// Limit positions and limit normals of a hierarchy's finest level (docs/engine.md, "Limit
// positions and normals").
//
// A limit stencil expresses where a finest-level control vertex ends up after infinitely many
// zero-detail synthesis steps, as weights on the control vertices of its closed star. Regular
// configurations use exact rational B-spline masks: (1/6, 2/3, 1/6) on curves and creases,
// (1, 4, 1)^2 / 36 on regular quad vertices, (1, 4, 1)^3 / 216 on regular hex vertices, identity
// at corners (feature dim 0, which the scheme interpolates). Every other configuration
// (extraordinary vertices, darts, curve junctions, irregular lattice vertices, n-gons at level 0)
// is solved by probing the engine's own synthesis on a small patch around the vertex: the local
// subdivision matrix S of the vertex's feature-filtered star is read off the executor's sparse
// synthesis with unit impulses, and the limit stencil is the left eigenvector of S for eigenvalue
// 1 (exact tangent stencils: the left eigenvectors of a double subdominant eigenvalue). Results
// are cached per configuration; the cost grows about linearly with the valence (limit_solve.h).
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/complex/complex.h"
#include "core/base/csr.h"
#include "core/multires/hierarchy.h"

namespace sublift {

struct LimitStencils {
  Csr rows;                        // row v: control vertices of the finest level read by limit(v)
  std::vector<double> weights;     // aligned with rows.items
  Csr tangent_rows;                // row v: control vertices read by the two tangent stencils; empty row = no exact tangent there
  std::vector<double> du, dv;      // aligned with tangent_rows.items
  Csr users;                       // transpose of rows ∪ tangent_rows: control vertex -> limit vertices that read it
  std::size_t extraordinary = 0;   // vertices whose stencil came from an eigenvector
  std::size_t configurations = 0;  // distinct configurations solved (cache size)
  std::vector<std::int8_t> tangent_sign;  // per vertex: +1/-1 orients tu x tv like the faces (orient_tangents); empty = decide per call
  std::size_t unsolved = 0;        // vertices whose configuration had no dominant eigenvalue 1 (identity used)
  // What the last eval_limit_subset found from its two lists, replayed while they come in the
  // same (a drag moves the same control points every frame); one caller at a time.
  struct SubsetPlan {
    std::vector<std::uint32_t> control, limit_in, fresh, appended;
    std::uint64_t replays = 0;
  };
  mutable SubsetPlan subset_plan;
};

/// Stencils for the finest level of h (its complex may lack adjacency; build it on a copy then).
LimitStencils build_limit_stencils(const Hierarchy& h);

/// limit[3v..3v+2] for every finest vertex from control (3 doubles per vertex).
void eval_limit(const LimitStencils& s, const double* control, double* limit);

/// Recomputes only the limit vertices that read a changed control vertex; appends them to
/// changed_limit (no duplicates, also not of entries already there).
void eval_limit_subset(const LimitStencils& s, const double* control, std::span<const std::uint32_t> changed_control,
                       double* limit, std::vector<std::uint32_t>& changed_limit);

/// Unit normals (3 doubles per vertex) of a surface given by `faces` (CSR corner lists,
/// orientation as stored) at positions `limit`: exact ones from the tangent stencils where
/// available (oriented to agree with the faces), else area-weighted face normals. Vertices on no
/// face and without tangents get (0, 0, 0).
void limit_normals(const LimitStencils& s, const Csr& faces, const double* control, const double* limit, double* normals);

/// Records, per vertex with exact tangents, whether tu x tv must be flipped to agree with the
/// faces around it (a property of the star's combinatorics, not of the shape): afterwards the
/// subset normals of those vertices read only their tangent stencils, which keeps a drag's
/// normal update cheap. Call once after building, with the current shape.
void orient_tangents(LimitStencils& s, const Csr& faces, const double* control, const double* limit);

/// The same for the vertices in `vertices` only (`vertex_faces` = transpose of `faces`).
void limit_normals_subset(const LimitStencils& s, const Csr& faces, const Csr& vertex_faces, const double* control,
                          const double* limit, std::span<const std::uint32_t> vertices, double* normals);

/// How an extraordinary configuration's eigenproblem is solved (docs/limit_stencils.md). Both read
/// the star's local subdivision matrix off sparse impulses through the engine (cost linear in the
/// patch). Dense: Eigen's full eigen-analysis of that matrix (every configuration, cubic in the
/// star size). Structured: the position by power iteration, and the tangents and spectrum from the
/// per-frequency blocks of a uniform fan's rotational symmetry (no tangents for other large stars:
/// their normals come from the faces). Auto: dense for stars of up to kLimitDenseStar vertices.
enum class LimitSolver { Auto, Dense, Structured };
inline constexpr std::size_t kLimitDenseStar = 65;  // valence 32 among quads: the dense solve takes ~8 ms there

/// The solution of one vertex's local eigenproblem (limit_solve.h).
struct PatchSolution {
  bool ok = false;                      // S had a simple dominant eigenvalue 1
  std::vector<double> weights, du, dv;  // limit-position and tangent weights (du, dv empty: no exact tangents)
  std::vector<double> spectrum;         // |eigenvalues| of the local subdivision matrix, descending (empty: not computed)
};

/// The eigenvector path for one vertex, whatever its configuration (for tests and tools); the
/// weights are aligned with `vertices`.
struct ProbedStencil : PatchSolution {
  std::vector<std::uint32_t> vertices;  // vertices of `c` the stencils read (vertices[0] = v)
};

/// Probes the cubic scheme's zero-detail synthesis on the feature-filtered star of vertex `v` of
/// `c` (which needs adjacency) and solves the local eigenproblem.
ProbedStencil probe_limit_stencil(const Complex& c, std::uint32_t v, LimitSolver solver = LimitSolver::Auto);

}  // namespace sublift
