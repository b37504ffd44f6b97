#include "core/engine/executor.h"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>
#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <string>
#include <unordered_map>

#include "core/base/errors.h"
#include "core/base/parallel.h"
#include "core/engine/stencil_rows.h"

namespace sublift {

namespace {

// ---------------------------------------------------------------------------------------------
// Centroid groups resolved against the parent complex: raw row pointers for the hot loops.

struct Group {
  const std::uint32_t* offsets = nullptr;
  const std::uint32_t* items = nullptr;
  std::uint32_t stride = 0;  // rows of fixed size (edge_verts) when offsets == nullptr
  std::uint32_t source_base = 0;
  double weight[4] = {0, 0, 0, 0};
};

const Csr& incidence(const Complex& p, Incidence r) {
  switch (r) {
    case Incidence::Faces: return p.faces;
    case Incidence::FaceEdges: return p.face_edges;
    case Incidence::CellVerts: return p.cell_verts;
    case Incidence::CellEdges: return p.cell_edges;
    case Incidence::CellFaces: return p.cell_faces;
    case Incidence::VertexEdges: return p.vertex_edges;
    case Incidence::VertexFaces: return p.vertex_faces;
    case Incidence::VertexCells: return p.vertex_cells;
    case Incidence::EdgeFaces: return p.edge_faces;
    case Incidence::EdgeCells: return p.edge_cells;
    case Incidence::FaceCells: return p.face_cells;
    case Incidence::EdgeVerts: break;
  }
  throw std::logic_error("edge_verts are pairs, not rows");
}

// Rows `r` (or the owned copy) as raw pointers; edge_verts as rows of two.
void resolve_rows(const Complex& p, const Transition& t, Incidence r, int owned, const std::uint32_t*& offsets,
                  const std::uint32_t*& items, std::uint32_t& stride) {
  if (owned >= 0) {
    const Csr& rows = t.owned[static_cast<std::size_t>(owned)];
    offsets = rows.offsets.data(), items = rows.items.data(), stride = 0;
  } else if (r == Incidence::EdgeVerts) {
    offsets = nullptr, items = p.edge_verts.data(), stride = 2;
  } else {
    const Csr& rows = incidence(p, r);
    offsets = rows.offsets.data(), items = rows.items.data(), stride = 0;
  }
}

Group resolve(const Complex& p, const Transition& t, const CentroidGroup& g, double sign) {
  Group r;
  resolve_rows(p, t, g.rows, g.owned, r.offsets, r.items, r.stride);
  r.source_base = g.source_base;
  for (int m = 0; m < 4; ++m) r.weight[m] = sign * g.weight[m];
  return r;
}

const std::uint8_t* dims_of(const Complex& p, FeatureDims d) {
  switch (d) {
    case FeatureDims::Vertex: return p.vertex_dim.data();
    case FeatureDims::Edge: return p.edge_dim.data();
    case FeatureDims::Face: return p.face_dim.data();
    case FeatureDims::None: break;
  }
  return nullptr;
}

// 1/n for small n without a division in the hot loop.
constexpr int kInvTable = 64;
const std::array<double, kInvTable> kInv = [] {
  std::array<double, kInvTable> t{};
  for (int i = 1; i < kInvTable; ++i) t[i] = 1.0 / double(i);
  return t;
}();
inline double inv(std::uint32_t n) { return n < kInvTable ? kInv[n] : 1.0 / double(n); }

inline void group_row(const Group& gr, std::uint32_t i, std::uint32_t& b, std::uint32_t& len) {
  if (gr.offsets) {
    b = gr.offsets[i];
    len = gr.offsets[i + 1] - b;
  } else {
    b = i * gr.stride;
    len = gr.stride;
  }
}

// acc += sum over groups of weight_g(m) times the centroid of row i of group g (C channels, 0 =
// `ch` at run time; `sum` is scratch). False when no group has a row for i. The dense and the
// sparse loops evaluate a row through this one function, so they agree.
template <int C, int G>
inline bool accumulate_row(const Group* groups, std::uint32_t i, int m, const double* x, int ch, double* sum,
                           double* acc) {
  const int cc = C > 0 ? C : ch;
  bool any = false;
  for (int g = 0; g < G; ++g) {
    const Group& gr = groups[g];
    const double wm = gr.weight[m];
    std::uint32_t b, len;
    group_row(gr, i, b, len);
    if (len == 0 || wm == 0.0) continue;
    any = true;
    for (int c = 0; c < cc; ++c) sum[c] = 0.0;
    const std::uint32_t* idx = gr.items + b;
    for (std::uint32_t k = 0; k < len; ++k) {
      const double* q = x + std::size_t(gr.source_base + idx[k]) * cc;
      for (int c = 0; c < cc; ++c) sum[c] += q[c];
    }
    const double w = wm * inv(len);
    for (int c = 0; c < cc; ++c) acc[c] += w * sum[c];
  }
  return any;
}

// Targets per chunk handed to a thread: large enough to amortise the hand-out, small enough
// to balance two cores when one is busy with something else.
constexpr std::uint32_t kGrain = 8192;

// A Scale step's factors for one class, applied inside the Centroid step that last writes the
// class (ScaleFold): synthesis x = (x + acc) * f, analysis x = x * (1 / f) + acc.
struct FoldedScale {
  const std::uint8_t* dims = nullptr;  // the class's feature dims; nullptr: no scale here
  double factor[4] = {1, 1, 1, 1};     // already inverted for analysis
  bool first = false;                  // analysis: scale before adding
};

// x[target] += sum_g weight_g(m) * centroid_g (weights carry the sign), for targets [0, n) of
// one class, scaled by `fs` when it has dims. G and C are template parameters so the loops
// unroll; C == 0: channels at run time.
template <int C, int G, bool Integer>
void gather(std::uint32_t n, std::uint32_t target_base, const std::uint8_t* target_m, const Group* groups_in,
            double* x, int channels, double sign, const FoldedScale& fs) {
  const int ch = C > 0 ? C : channels;
  std::array<Group, G> groups;
  for (int g = 0; g < G; ++g) groups[g] = groups_in[g];
  parallel_for(n, kGrain, [&, groups](std::uint32_t begin, std::uint32_t end) {
    std::vector<double> heap(C > 0 ? 0 : 2 * std::size_t(ch));
    double stack[C > 0 ? 2 * C : 1];
    double* acc = C > 0 ? stack : heap.data();
    double* sum = C > 0 ? stack + C : heap.data() + ch;
    for (std::uint32_t i = begin; i < end; ++i) {
      const int m = target_m ? target_m[i] : 0;
      for (int c = 0; c < ch; ++c) acc[c] = 0.0;
      const bool any = accumulate_row<C, G>(groups.data(), i, m, x, ch, sum, acc);
      double* dst = x + std::size_t(target_base + i) * ch;
      if (fs.dims) {  // never in integer mode, where Scale steps are skipped
        const double f = fs.factor[fs.dims[i]];
        if (!any)
          for (int c = 0; c < ch; ++c) dst[c] *= f;
        else if (fs.first)
          for (int c = 0; c < ch; ++c) dst[c] = dst[c] * f + acc[c];
        else
          for (int c = 0; c < ch; ++c) dst[c] = (dst[c] + acc[c]) * f;
        continue;
      }
      if (!any) continue;
      if constexpr (Integer) {
        for (int c = 0; c < ch; ++c) dst[c] += sign * std::floor(sign * acc[c] + 0.5);
      } else {
        for (int c = 0; c < ch; ++c) dst[c] += acc[c];
      }
    }
  });
}

template <int C, int G>
void gather_mode(std::uint32_t n, std::uint32_t tb, const std::uint8_t* tm, const Group* g, double* x, int ch,
                 double sign, bool integer, const FoldedScale& fs) {
  if (integer) gather<C, G, true>(n, tb, tm, g, x, ch, sign, fs);
  else gather<C, G, false>(n, tb, tm, g, x, ch, sign, fs);
}

template <int G>
void gather_channels(std::uint32_t n, std::uint32_t tb, const std::uint8_t* tm, const Group* g, double* x, int ch,
                     double sign, bool integer, const FoldedScale& fs) {
  switch (ch) {
    case 1: return gather_mode<1, G>(n, tb, tm, g, x, ch, sign, integer, fs);
    case 3: return gather_mode<3, G>(n, tb, tm, g, x, ch, sign, integer, fs);
    case 4: return gather_mode<4, G>(n, tb, tm, g, x, ch, sign, integer, fs);
    default: return gather_mode<0, G>(n, tb, tm, g, x, ch, sign, integer, fs);
  }
}

void run_centroid(const CentroidStep& s, const Complex& p, const Transition& t, double* x, int ch, double sign,
                  bool integer, const FoldedScale& fs = {}) {
  if (!s.count || !s.num_groups) return;
  Group g[3];
  for (int k = 0; k < s.num_groups; ++k) g[k] = resolve(p, t, s.groups[k], sign);
  const std::uint8_t* m = dims_of(p, s.target_dims);
  switch (s.num_groups) {
    case 1: return gather_channels<1>(s.count, s.target_base, m, g, x, ch, sign, integer, fs);
    case 2: return gather_channels<2>(s.count, s.target_base, m, g, x, ch, sign, integer, fs);
    default: return gather_channels<3>(s.count, s.target_base, m, g, x, ch, sign, integer, fs);
  }
}

// ---------------------------------------------------------------------------------------------
// Weighted steps.

void run_weighted(const WeightedStep& s, double* x, int ch, double sign, bool integer) {
  const std::uint32_t rows = static_cast<std::uint32_t>(s.target.size());
  parallel_for(rows, 512, [&](std::uint32_t begin, std::uint32_t end) {
    double acc[64];  // channels are at most 64 (project_io.h)
    std::vector<double> big(ch > 64 ? ch : 0);
    double* a = ch > 64 ? big.data() : acc;
    for (std::uint32_t r = begin; r < end; ++r) {
      for (int c = 0; c < ch; ++c) a[c] = 0.0;
      const double* w = row_weights(s, r);
      for (std::uint32_t k = s.sources.offsets[r]; k < s.sources.offsets[r + 1]; ++k, ++w) {
        const double wk = *w;
        const double* src = x + std::size_t(s.sources.items[k]) * ch;
        for (int c = 0; c < ch; ++c) a[c] += wk * src[c];
      }
      double* dst = x + std::size_t(s.target[r]) * ch;
      // Integer mode: the same rounded increment both ways, as the centroid rows.
      for (int c = 0; c < ch; ++c) dst[c] += sign * (integer ? std::floor(a[c] + 0.5) : a[c]);
    }
  });
}

// ---------------------------------------------------------------------------------------------
// Scale steps: diagonal, so the same loop serves every mode.

template <class Visit>
void for_each_scaled(const ScaleStep& s, const Complex& p, bool inverse, Visit visit) {
  static constexpr FeatureDims kDims[3] = {FeatureDims::Vertex, FeatureDims::Edge, FeatureDims::Face};
  for (int t = 0; t < 3; ++t) {
    if (!s.count[t]) continue;
    double factor[4];
    for (int m = 0; m < 4; ++m) factor[m] = inverse ? 1.0 / s.factor[t][m] : s.factor[t][m];
    visit(s.base[t], s.count[t], dims_of(p, kDims[t]), factor);
  }
}

// `folded`: bit t set when class t's scale is applied by a Centroid step instead (ScaleFold).
void run_scale(const ScaleStep& s, const Complex& p, double* x, int ch, bool inverse, unsigned folded = 0) {
  for_each_scaled(s, p, inverse, [&](std::uint32_t base, std::uint32_t n, const std::uint8_t* dims, const double* f) {
    for (int t = 0; t < 3; ++t)
      if ((folded >> t & 1u) && base == s.base[t] && n == s.count[t]) return;
    parallel_for(n, kGrain, [&](std::uint32_t b, std::uint32_t e) {
      for (std::uint32_t i = b; i < e; ++i) {
        const double fi = f[dims[i]];
        if (fi == 1.0) continue;
        double* v = x + std::size_t(base + i) * ch;
        for (int c = 0; c < ch; ++c) v[c] *= fi;
      }
    });
  });
}

// ---------------------------------------------------------------------------------------------
// Matrix steps (Loop's vertex rule).

void run_matrix(const MatrixStep& m, double* x, int ch) {
  std::vector<double> u(x, x + std::size_t(m.n) * ch);
  for (std::uint32_t i = 0; i < m.n; ++i)
    for (int c = 0; c < ch; ++c) {
      double s = 0;
      for (std::uint32_t q = m.rows.offsets[i]; q < m.rows.offsets[i + 1]; ++q)
        s += m.weights[q] * u[std::size_t(m.rows.items[q]) * ch + c];
      x[std::size_t(i) * ch + c] = s;
    }
}

// One solve per channel, the channels on the pool's threads at once: each is the same serial
// solve whatever the thread count, so the values do not depend on it. A solver per channel
// (Eigen's keeps its iteration count and error in itself).
template <class Matrix>
void solve_channels(const Matrix& A, std::uint32_t n, double* x, int ch, const char* what) {
  std::vector<double> residual(static_cast<std::size_t>(ch), 0.0);
  std::vector<std::exception_ptr> failed(static_cast<std::size_t>(ch));  // rethrown below: bodies must not throw
  parallel_for(static_cast<std::uint32_t>(ch), 1, [&](std::uint32_t begin, std::uint32_t end) {
    try {
      // The solver refers to A (a compressed matrix or a Map of one) without copying it.
      Eigen::BiCGSTAB<Eigen::SparseMatrix<double, Eigen::RowMajor, int>, Eigen::DiagonalPreconditioner<double>> solver;
      solver.setTolerance(1e-15);
      solver.setMaxIterations(1000);
      solver.compute(A);
      Eigen::VectorXd b(n), u(n);
      for (std::uint32_t c = begin; c < end; ++c) {
        for (std::uint32_t i = 0; i < n; ++i) b(i) = x[std::size_t(i) * ch + c];
        if (b.squaredNorm() == 0) continue;
        u = solver.solve(b);
        const double rel = (A * u - b).norm() / b.norm();
        residual[c] = rel;
        if (!(rel < 1e-12)) continue;  // thrown below
        for (std::uint32_t i = 0; i < n; ++i) x[std::size_t(i) * ch + c] = u(i);
      }
    } catch (...) {  // out of memory, say
      failed[begin] = std::current_exception();
    }
  });
  for (const std::exception_ptr& e : failed)
    if (e) std::rethrow_exception(e);
  for (const double rel : residual)
    if (!(rel < 1e-12))
      throw Error(std::string("Loop analysis: the sparse solve of the vertex rule did not converge (") + what +
                  ", relative residual " + std::to_string(rel) + ")");
}

// P as Eigen sees it, over the step's own arrays: no copy is kept. The rows are sorted and their
// indices below 2^31 (make_matrix_step), and int may alias uint32_t.
using RowMajorMap = Eigen::Map<const Eigen::SparseMatrix<double, Eigen::RowMajor, int>>;
RowMajorMap matrix_of(const MatrixStep& m) {
  return RowMajorMap(static_cast<int>(m.n), static_cast<int>(m.n), static_cast<int>(m.rows.items.size()),
                     reinterpret_cast<const int*>(m.rows.offsets.data()),
                     reinterpret_cast<const int*>(m.rows.items.data()), m.weights.data());
}

void unrun_matrix(const MatrixStep& m, double* x, int ch) { solve_channels(matrix_of(m), m.n, x, ch, "P"); }

template <class... F>
struct Overload : F... {
  using F::operator()...;
};
template <class... F>
Overload(F...) -> Overload<F...>;

// A Scale step's classes folded into the Centroid steps that last write them before it, so the
// dense loops make one pass fewer over those classes (Bertram's cubic s-scale: the v and e
// classes, 3/4 of a surface's fine vertices). A class folds when that step's targets are the
// class and only Centroid steps that neither read nor write it lie between: then x = (x + acc)
// * f rounds exactly as x += acc there and x *= f later, and analysis's x = x * (1/f) + acc
// exactly as its x *= 1/f first and x += acc later. Bit for bit the unfolded run.
struct ScaleFold {
  std::size_t scale = SIZE_MAX;  // the Scale step's index
  int into[3] = {-1, -1, -1};    // per class: the Centroid step that applies its factors
  unsigned mask() const { return (into[0] >= 0) | (into[1] >= 0) << 1 | (into[2] >= 0) << 2; }
};

ScaleFold plan_scale_fold(const Transition& t) {
  ScaleFold f;
  for (std::size_t k = 0; k < t.steps.size() && f.scale == SIZE_MAX; ++k)
    if (std::holds_alternative<ScaleStep>(t.steps[k].op)) f.scale = k;
  if (f.scale == SIZE_MAX) return f;
  const ScaleStep& sc = std::get<ScaleStep>(t.steps[f.scale].op);
  for (int c = 0; c < 3; ++c) {
    if (!sc.count[c]) continue;
    const std::uint32_t lo = sc.base[c], hi = sc.base[c] + sc.count[c];
    for (std::size_t k = f.scale; k-- > 0;) {
      const auto* cs = std::get_if<CentroidStep>(&t.steps[k].op);
      if (!cs) break;  // another kind of step: keep the Scale step's own pass
      bool reads = false;
      for (int g = 0; g < cs->num_groups; ++g)
        reads |= cs->groups[g].source_base < hi && cs->groups[g].source_base + cs->groups[g].source_count > lo;
      if (reads) break;
      const bool writes = cs->count && cs->target_base < hi && cs->target_base + cs->count > lo;
      if (writes) {
        if (cs->target_base == lo && cs->count == sc.count[c] && cs->num_groups) f.into[c] = static_cast<int>(k);
        break;
      }
    }
  }
  return f;
}

FoldedScale folded_scale(const ScaleFold& f, const Transition& t, const Complex& p, std::size_t k, bool inverse) {
  static constexpr FeatureDims kDims[3] = {FeatureDims::Vertex, FeatureDims::Edge, FeatureDims::Face};
  FoldedScale fs;
  for (int c = 0; c < 3; ++c) {
    if (f.into[c] != static_cast<int>(k)) continue;
    const ScaleStep& sc = std::get<ScaleStep>(t.steps[f.scale].op);
    fs.dims = dims_of(p, kDims[c]);
    for (int m = 0; m < 4; ++m) fs.factor[m] = inverse ? 1.0 / sc.factor[c][m] : sc.factor[c][m];
    fs.first = inverse;
  }
  return fs;
}

// Step k forwards (synthesis) or inverted (analysis); `fold` as planned for this run (empty in
// integer mode, where Scale steps are skipped).
void run_step(const Transition& t, std::size_t k, const Complex& p, double* x, int ch, bool integer, bool inverse,
              const ScaleFold& fold) {
  const double sign = inverse ? -1.0 : 1.0;
  std::visit(Overload{[&](const WeightedStep& w) { run_weighted(w, x, ch, sign, integer); },
                      [&](const CentroidStep& c) {
                        run_centroid(c, p, t, x, ch, sign, integer, folded_scale(fold, t, p, k, inverse));
                      },
                      [&](const ScaleStep& sc) {
                        if (!integer) run_scale(sc, p, x, ch, inverse, k == fold.scale ? fold.mask() : 0u);
                      },
                      [&](const MatrixStep& m) {
                        if (integer)
                          throw Error("integer mode needs an interpolating scheme; a vertex-rule solve is not exact in integers");
                        if (inverse) unrun_matrix(m, x, ch);
                        else run_matrix(m, x, ch);
                      }},
             t.steps[k].op);
}

// ---------------------------------------------------------------------------------------------
// Sparse mode.

constexpr std::uint32_t kSparseGrain = 2048;

void find_centroid_rows(const CentroidStep& s, const Group* rev, SparseDelta& d, std::vector<std::uint32_t>& rows);
void evaluate_centroid_rows(const CentroidStep& s, const Complex& p, const Group* g, SparseDelta& d,
                            const std::vector<std::uint32_t>& rows);

// Found rows in row order: their stencils and targets are then read in forward sweeps instead
// of at random (each row writes its own target, so the values are the same in any order), and
// the change's list, extended in this order, stays in order for the next step's search.
void sort_rows(std::vector<std::uint32_t>& rows) { std::sort(rows.begin(), rows.end()); }

// The centroid rows reading a changed source are found (`find`) into `rows` through the
// reverse incidences, or `rows` holds them already (found for the same change before:
// SparsePlan); they are evaluated on the change as the dense loop evaluates them.
void sparse_centroid(const CentroidStep& s, const Complex& p, const Transition& t, double sign, SparseDelta& d,
                     std::vector<std::uint32_t>& rows, bool find) {
  if (!s.count || !s.num_groups) return;
  Group g[3], rev[3];  // rev: the reverse rows (source -> targets)
  const int G = s.num_groups;
  for (int k = 0; k < G; ++k) {
    g[k] = resolve(p, t, s.groups[k], sign);
    resolve_rows(p, t, s.groups[k].reverse, -1, rev[k].offsets, rev[k].items, rev[k].stride);
  }
  if (find) find_centroid_rows(s, rev, d, rows);
  evaluate_centroid_rows(s, p, g, d, rows);
}

void find_centroid_rows(const CentroidStep& s, const Group* rev, SparseDelta& d, std::vector<std::uint32_t>& rows) {
  const int G = s.num_groups;
  const std::uint32_t epoch = ++d.epoch;
  rows.clear();
  const std::size_t n_list = d.list.size();
  for (std::size_t q = 0; q < n_list; ++q) {
    const std::uint32_t v = d.list[q];
    for (int k = 0; k < G; ++k) {
      const std::uint32_t b = s.groups[k].source_base;
      if (v < b || v >= b + s.groups[k].source_count) continue;
      std::uint32_t rb, len;
      group_row(rev[k], v - b, rb, len);
      const std::uint32_t* row = rev[k].items + rb;
      for (std::uint32_t i = 0; i < len; ++i) {
        std::uint32_t& st = d.stamp[s.target_base + row[i]];
        if (st != epoch) {
          st = epoch;
          rows.push_back(row[i]);
        }
      }
    }
  }
  sort_rows(rows);
}

// Rows are independent (each writes its own target, reads other classes).
void evaluate_centroid_rows(const CentroidStep& s, const Complex& p, const Group* g, SparseDelta& d,
                            const std::vector<std::uint32_t>& rows) {
  const int G = s.num_groups;
  const std::uint8_t* dims = dims_of(p, s.target_dims);
  const std::uint32_t nc = static_cast<std::uint32_t>(rows.size());
  parallel_for(nc, kSparseGrain, [&](std::uint32_t begin, std::uint32_t end) {
    for (std::uint32_t q = begin; q < end; ++q) {
      const std::uint32_t i = rows[q];
      const int m = dims ? dims[i] : 0;
      double acc[3] = {0, 0, 0}, sum[3];
      switch (G) {
        case 1: accumulate_row<3, 1>(g, i, m, d.x.data(), 3, sum, acc); break;
        case 2: accumulate_row<3, 2>(g, i, m, d.x.data(), 3, sum, acc); break;
        default: accumulate_row<3, 3>(g, i, m, d.x.data(), 3, sum, acc); break;
      }
      double* dst = d.x.data() + std::size_t(s.target_base + i) * 3;
      for (int c = 0; c < 3; ++c) dst[c] += acc[c];
    }
  });
  for (const std::uint32_t i : rows) d.at(s.target_base + i);
}

// Rows of a weighted step reading a listed vertex; targets are never sources of the same step,
// so the order of the rows does not matter.
void sparse_weighted(const WeightedStep& s, const Csr& readers, double sign, SparseDelta& d,
                     std::vector<std::uint32_t>& rows, bool find) {
  if (find) {
    const std::uint32_t epoch = ++d.epoch;
    rows.clear();
    for (const std::uint32_t v : d.list)
      for (const std::uint32_t r : readers.row(v)) {
        std::uint32_t& st = d.stamp[s.target[r]];
        if (st != epoch) {
          st = epoch;
          rows.push_back(r);
        }
      }
    sort_rows(rows);
  }
  for (const std::uint32_t r : rows) {
    double acc[3] = {0, 0, 0};
    const double* w = row_weights(s, r);
    for (std::uint32_t k = s.sources.offsets[r]; k < s.sources.offsets[r + 1]; ++k, ++w) {
      const double* src = d.x.data() + std::size_t(s.sources.items[k]) * 3;
      for (int c = 0; c < 3; ++c) acc[c] += *w * src[c];
    }
    double* dst = d.at(s.target[r]);
    for (int c = 0; c < 3; ++c) dst[c] += sign * acc[c];
  }
}

void sparse_scale(const ScaleStep& s, const Complex& p, bool inverse, SparseDelta& d) {
  for_each_scaled(s, p, inverse, [&](std::uint32_t base, std::uint32_t n, const std::uint8_t* dims, const double* f) {
    for (const std::uint32_t v : d.list) {
      if (v < base || v >= base + n) continue;
      const double fi = f[dims[v - base]];
      if (fi == 1.0) continue;
      double* x = d.x.data() + std::size_t(v) * 3;
      for (int c = 0; c < 3; ++c) x[c] *= fi;
    }
  });
}

// Forwards the rows reading a changed old vertex change; the solve is global (every old
// vertex may change).
void sparse_matrix(const MatrixStep& m, const Csr& readers, SparseDelta& d) {
  std::unordered_map<std::uint32_t, std::array<double, 3>> du;
  for (std::uint32_t v : d.list)
    if (v < m.n) {
      double* x = d.x.data() + std::size_t(v) * 3;
      du[v] = {x[0], x[1], x[2]};
      x[0] = x[1] = x[2] = 0.0;
    }
  std::vector<std::uint32_t> rows;
  for (const auto& [k, value] : du)
    for (std::uint32_t i : readers.row(k)) rows.push_back(i);
  std::sort(rows.begin(), rows.end());
  rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
  for (std::uint32_t i : rows) {
    double acc[3] = {0, 0, 0};
    for (std::uint32_t q = m.rows.offsets[i]; q < m.rows.offsets[i + 1]; ++q)
      if (const auto it = du.find(m.rows.items[q]); it != du.end())
        for (int c = 0; c < 3; ++c) acc[c] += m.weights[q] * it->second[static_cast<std::size_t>(c)];
    double* x = d.at(i);
    for (int c = 0; c < 3; ++c) x[c] = acc[c];
  }
}

void sparse_unmatrix(const MatrixStep& m, SparseDelta& d) {
  std::vector<double> b(std::size_t(m.n) * 3, 0.0);
  bool any = false;
  for (std::uint32_t v : d.list)
    if (v < m.n) {
      for (int c = 0; c < 3; ++c) b[std::size_t(v) * 3 + c] = d.x[std::size_t(v) * 3 + c];
      any = true;
    }
  if (!any) return;
  unrun_matrix(m, b.data(), 3);
  for (std::uint32_t i = 0; i < m.n; ++i) {
    const double* u = b.data() + std::size_t(i) * 3;
    if (u[0] == 0.0 && u[1] == 0.0 && u[2] == 0.0 && !d.in_list[i]) continue;
    double* x = d.at(i);
    for (int c = 0; c < 3; ++c) x[c] = u[c];
  }
}

// Step k of the sparse mode, forwards or inverted; `rows`: the rows it reaches, found first
// when `find` (else found before).
void run_sparse_step(const Transition& t, const Complex& p, const SparseIndex& index, std::size_t k, bool inverse,
                     SparseDelta& d, std::vector<std::uint32_t>& rows, bool find) {
  const double sign = inverse ? -1.0 : 1.0;
  std::visit(Overload{[&](const WeightedStep& w) { sparse_weighted(w, index.readers[k], sign, d, rows, find); },
                      [&](const CentroidStep& c) { sparse_centroid(c, p, t, sign, d, rows, find); },
                      [&](const ScaleStep& sc) { sparse_scale(sc, p, inverse, d); },
                      [&](const MatrixStep& m) {
                        if (inverse) sparse_unmatrix(m, d);
                        else sparse_matrix(m, index.readers[k], d);
                      }},
             t.steps[k].op);
}

// ---------------------------------------------------------------------------------------------
// Adjoint of the analysis: the analysis row x_t -= w x_s becomes x_s -= w x_t.

void adjoint_centroid(const CentroidStep& s, const Complex& p, const Transition& t, double* y) {
  Group g[3];
  for (int k = 0; k < s.num_groups; ++k) g[k] = resolve(p, t, s.groups[k], -1.0);
  const std::uint8_t* dims = dims_of(p, s.target_dims);
  for (std::uint32_t i = 0; i < s.count; ++i) {
    const double yt = y[s.target_base + i];
    if (yt == 0.0) continue;
    const int m = dims ? dims[i] : 0;
    for (int k = 0; k < s.num_groups; ++k) {
      const Group& gr = g[k];
      std::uint32_t b, len;
      group_row(gr, i, b, len);
      if (len == 0 || gr.weight[m] == 0.0) continue;
      const double c = gr.weight[m] * inv(len) * yt;
      for (std::uint32_t q = 0; q < len; ++q) y[gr.source_base + gr.items[b + q]] += c;
    }
  }
}

void adjoint_weighted(const WeightedStep& s, double* y) {
  for (std::uint32_t r = 0; r < s.target.size(); ++r) {
    const double yt = y[s.target[r]];
    if (yt == 0.0) continue;
    const double* w = row_weights(s, r);
    for (std::uint32_t k = s.sources.offsets[r]; k < s.sources.offsets[r + 1]; ++k, ++w)
      y[s.sources.items[k]] -= *w * yt;
  }
}

}  // namespace

MatrixStep make_matrix_step(std::uint32_t n, Csr rows, std::vector<double> weights) {
  if (rows.rows() != n) throw std::logic_error("make_matrix_step: " + std::to_string(rows.rows()) + " rows for " +
                                               std::to_string(n) + " vertices");
  if (rows.items.size() > std::size_t(INT32_MAX)) throw std::logic_error("make_matrix_step: too many terms for Eigen");
  // Each row's columns strictly increasing, as a compressed Eigen matrix has them: stencil rows
  // come so; any other row is put so as a stencil row is (append_stencil_row: sorted, repeated
  // columns summed in the order given).
  bool increasing = true;
  for (std::uint32_t i = 0; i < n && increasing; ++i)
    for (std::uint32_t q = rows.offsets[i]; q + 1 < rows.offsets[i + 1]; ++q)
      increasing &= rows.items[q] < rows.items[q + 1];
  if (!increasing) {
    Csr sorted;
    std::vector<double> sorted_weights;
    std::vector<StencilTerm> row;
    for (std::uint32_t i = 0; i < n; ++i) {
      row.clear();
      for (std::uint32_t q = rows.offsets[i]; q < rows.offsets[i + 1]; ++q) row.emplace_back(rows.items[q], weights[q]);
      append_stencil_row(row, sorted, sorted_weights);
    }
    rows = std::move(sorted);
    weights = std::move(sorted_weights);
  }
  MatrixStep m;
  m.n = n;
  m.rows = std::move(rows);
  m.weights = std::move(weights);
  return m;
}

void Transition::add(WeightedStep s) {
  const bool reads = std::any_of(s.sources.items.begin(), s.sources.items.end(), [&](std::uint32_t v) { return v < num_coarse; });
  const bool writes = std::any_of(s.target.begin(), s.target.end(), [&](std::uint32_t v) { return v >= num_coarse; });
  steps.push_back({std::move(s), reads, writes});
}
void Transition::add(CentroidStep s) {
  const bool reads =
      std::any_of(s.groups, s.groups + s.num_groups, [&](const CentroidGroup& g) { return g.source_base < num_coarse; });
  const bool writes = s.target_base >= num_coarse && s.count;
  steps.push_back({std::move(s), reads, writes});
}
void Transition::add(ScaleStep s) { steps.push_back({std::move(s), true, true}); }
void Transition::add(MatrixStep s) { steps.push_back({std::move(s), true, false}); }

std::size_t Transition::bytes() const {
  std::size_t b = 0;
  for (const Csr& rows : owned) b += rows.bytes();
  for (const Step& s : steps) {
    if (const auto* w = std::get_if<WeightedStep>(&s.op))
      b += w->target.capacity() * 4 + w->sources.bytes() + w->weights.capacity() * 8 + w->weight_at.capacity() * 4;
    else if (const auto* m = std::get_if<MatrixStep>(&s.op))
      b += m->rows.bytes() + m->weights.capacity() * 8;
  }
  return b;
}

void run_synthesis(const Transition& t, const Complex& p, double* x, int ch, bool integer, bool new_zero) {
  // While the new values are zero, a step that reads only them adds exact zeros (000 sec. 4:
  // "the first lifting operation does not have an impact"): pure subdivision then costs what
  // the subdivision rules cost.
  ScaleFold fold = integer ? ScaleFold{} : plan_scale_fold(t);
  bool zero = new_zero;
  for (std::size_t k = 0; k < t.steps.size(); ++k) {
    const Step& s = t.steps[k];
    if (zero && !s.reads_coarse) {
      for (int& into : fold.into)
        if (into == static_cast<int>(k)) into = -1;  // skipped: the Scale step scales the class
      continue;
    }
    zero = zero && !s.writes_new;
    run_step(t, k, p, x, ch, integer, false, fold);
  }
}

void run_analysis(const Transition& t, const Complex& p, double* x, int ch, bool integer) {
  const ScaleFold fold = integer ? ScaleFold{} : plan_scale_fold(t);
  for (std::size_t k = t.steps.size(); k-- > 0;) run_step(t, k, p, x, ch, integer, true, fold);
}

unsigned folded_scale_classes(const Transition& t) { return plan_scale_fold(t).mask(); }

SparseIndex build_sparse_index(const Transition& t) {
  SparseIndex idx;
  idx.readers.reserve(t.steps.size());
  for (const Step& s : t.steps) {
    if (const auto* w = std::get_if<WeightedStep>(&s.op)) idx.readers.push_back(transpose(w->sources, t.num_fine));
    else if (const auto* m = std::get_if<MatrixStep>(&s.op)) idx.readers.push_back(transpose(m->rows, m->n));
    else idx.readers.emplace_back();
  }
  return idx;
}

// A drag moves the same vertices every frame, so each step reaches the same rows: they are kept
// (SparseIndex::plans) and replayed while the change comes in on the same list. Without a Matrix
// step the list grows by topology alone (every row found is listed), so the same input list
// means the same rows at every step.
static void run_sparse(const Transition& t, const Complex& p, const SparseIndex& index, SparseDelta& d, bool inverse) {
  const bool plannable = std::none_of(t.steps.begin(), t.steps.end(),
                                      [](const Step& s) { return std::holds_alternative<MatrixStep>(s.op); });
  SparsePlan& plan = index.plans[inverse ? 1 : 0];
  const bool replay = plannable && plan.valid && plan.input == d.list;
  if (replay) {
    ++plan.replays;
  } else if (plannable) {
    plan.valid = false;  // until the run has found every step's rows
    plan.input = d.list;
    plan.rows.resize(t.steps.size());  // each step's rows are cleared as they are found
  }
  // Found straight into the plan (no copy), or into the change's scratch list when the run
  // cannot be planned.
  const auto one = [&](std::size_t k) {
    run_sparse_step(t, p, index, k, inverse, d, plannable ? plan.rows[k] : d.candidates, !replay);
  };
  if (inverse)
    for (std::size_t k = t.steps.size(); k-- > 0;) one(k);
  else
    for (std::size_t k = 0; k < t.steps.size(); ++k) one(k);
  plan.valid = plannable;
}

void run_synthesis_sparse(const Transition& t, const Complex& p, const SparseIndex& index, SparseDelta& d) {
  run_sparse(t, p, index, d, false);
}

void run_analysis_sparse(const Transition& t, const Complex& p, const SparseIndex& index, SparseDelta& d) {
  run_sparse(t, p, index, d, true);
}

void run_analysis_adjoint(const Transition& t, const Complex& p, double* y) {
  // Analysis runs the inverted steps backwards; its adjoint runs their transposes forwards.
  for (const Step& s : t.steps)
    std::visit(Overload{[&](const WeightedStep& w) { adjoint_weighted(w, y); },
                        [&](const CentroidStep& c) { adjoint_centroid(c, p, t, y); },
                        [&](const ScaleStep& sc) { run_scale(sc, p, y, 1, true); },  // diagonal
                        [&](const MatrixStep& m) {
                          // P^T only here (the dual basis), so it is not kept.
                          const Eigen::SparseMatrix<double, Eigen::RowMajor> Pt = matrix_of(m).transpose();
                          solve_channels(Pt, m.n, y, 1, "P^T");
                        }},
               s.op);
}

void SparseDelta::reset(std::uint32_t n) {
  clear();
  if (x.size() != std::size_t(n) * 3) {
    x.assign(std::size_t(n) * 3, 0.0);
    in_list.assign(n, 0);
    stamp.assign(n, 0);
    epoch = 0;
  }
}

void SparseDelta::clear() {
  for (const std::uint32_t v : list) {
    std::fill_n(x.data() + std::size_t(v) * 3, 3, 0.0);
    in_list[v] = 0;
  }
  list.clear();
}

}  // namespace sublift
