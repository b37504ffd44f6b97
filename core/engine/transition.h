#pragma once
// A level transition as data (DESIGN.md "The math"; docs/architecture.md). Level j+1's values
// sit in one array in the fine level's layout, `channels` doubles per vertex: the first
// `num_coarse` vertices are level j's (scaling coefficients after analysis), the rest the new
// vertices (wavelet coefficients after analysis). A transition is a short list of steps in
// synthesis order; every scheme compiles its transitions into them (core/schemes/), and one
// executor (core/engine/executor.h) runs them forwards, backwards, in integer mode, on a sparse
// change and as the adjoint of the analysis. Anchor: OpenSubdiv's Far::StencilTable, one table
// form that one UpdateValues runs for every scheme.
//
// Step kinds (each reads only values that no row of the same step writes):
//   Weighted  row r: x[target[r]] += sum_k weights[k] x[sources[k]]        (explicit stencils)
//   Centroid  target i of one class += sum_g w_g(m_i) * mean of its row in group g
//             (Bertram's compact form, 000 eq. 3.16-3.17: rows are the parent complex's
//             incidences, so no weights are stored; m_i = the target's feature dim)
//   Scale     a class-t vertex of feature dim m *= factor[t][m]           (000 eq. 3.18)
//   Matrix    x_old <- P x_old on the first n vertices; analysis solves P u = x_old (Loop's
//             vertex rule, 004 sec. 6.3: not local)
// Analysis runs the steps backwards, each inverted (-=, /=, the solve). In integer mode each
// row's increment is rounded (floor(x + 1/2)) the same way both ways and Scale is skipped (000
// sec. 4), so analysis and synthesis are exact inverses; Matrix steps have no integer mode.
#include <cstdint>
#include <variant>
#include <vector>

#include "core/base/csr.h"

namespace sublift {

struct WeightedStep {
  std::vector<std::uint32_t> target;  // distinct, never among this step's sources
  Csr sources;                        // fine vertex indices per row
  std::vector<double> weights;        // aligned with sources.items, unless weight_at is set
  // Rows may share their weights (a regular region's rows are one pattern): row r's weights
  // then start at weights[weight_at[r]]. Empty: row r's start at weights[sources.offsets[r]].
  std::vector<std::uint32_t> weight_at;
};
/// Row r's weights, sources.size(r) of them.
inline const double* row_weights(const WeightedStep& s, std::size_t r) {
  return s.weights.data() + (s.weight_at.empty() ? s.sources.offsets[r] : s.weight_at[r]);
}

/// Incidence rows of the parent complex (core/complex/complex.h) a centroid group reads.
enum class Incidence : std::uint8_t {
  EdgeVerts,  // flat pairs, rows of two
  Faces, FaceEdges, CellVerts, CellEdges, CellFaces,
  VertexEdges, VertexFaces, VertexCells, EdgeFaces, EdgeCells, FaceCells,
};
/// Which of the parent's feature-dim arrays holds a class's feature dims.
enum class FeatureDims : std::uint8_t { None, Vertex, Edge, Face };

struct CentroidGroup {
  Incidence rows = Incidence::Faces;  // target (local index) -> sources (local index)
  std::int16_t owned = -1;            // >= 0: Transition::owned[owned] replaces `rows`
  Incidence reverse = Incidence::Faces;  // source -> targets, for the sparse mode; may reach
                                         // more targets than a filtered `rows` (they add zero)
  std::uint32_t source_base = 0, source_count = 0;
  double weight[4] = {0, 0, 0, 0};  // per feature dim m of the target
};

struct CentroidStep {
  std::uint32_t target_base = 0, count = 0;
  FeatureDims target_dims = FeatureDims::None;  // None: every target uses weight[0]
  std::uint8_t num_groups = 0;
  CentroidGroup groups[3];
};

struct ScaleStep {
  std::uint32_t base[3] = {0, 0, 0}, count[3] = {0, 0, 0};  // classes v, e, f (cells stay)
  double factor[3][4] = {};                                   // [class t][feature dim m]
};

struct MatrixStep {
  std::uint32_t n = 0;
  Csr rows;  // P's rows over the first n vertices, columns strictly increasing in each
  std::vector<double> weights;
};
/// A Matrix step of n rows, sorted and merged where they are not (analysis solves with P as
/// it stands in these arrays: nothing else is kept).
MatrixStep make_matrix_step(std::uint32_t n, Csr rows, std::vector<double> weights);

struct Step {
  std::variant<WeightedStep, CentroidStep, ScaleStep, MatrixStep> op;
  // For skipping work on zero inputs (executor.h): whether the step reads a coarse value and
  // whether it writes a new one.
  bool reads_coarse = true, writes_new = true;
};

struct Transition {
  std::uint32_t num_coarse = 0, num_fine = 0;
  std::vector<Step> steps;  // synthesis order
  std::vector<Csr> owned;   // feature-filtered copies of incidence rows (CentroidGroup::owned)

  /// Appends a step and works out its reads/writes flags.
  void add(WeightedStep s);
  void add(CentroidStep s);
  void add(ScaleStep s);
  void add(MatrixStep s);
  std::size_t bytes() const;
};

}  // namespace sublift
