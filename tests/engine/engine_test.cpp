// The one executor (core/engine/executor.h), checked once for every scheme of the registry:
// perfect reconstruction (bit-exact in integer mode), sparse = dense in both directions, and
// the adjoint = the rows of the analysis operator.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "core/base/errors.h"
#include "core/engine/executor.h"
#include "core/engine/stencil_rows.h"
#include "core/io/lattice/shape_io.h"
#include "core/multires/hierarchy.h"
#include "core/schemes/registry.h"
#include "tests/test_shapes.h"

using namespace sublift;

namespace {

std::string asset(const std::string& name) { return std::string(SUBLIFT_ASSETS_DIR) + "/" + name; }

// Bundled bases each scheme refines: lattices and curves only for the Split refinement.
std::vector<std::string> bases_for(const SchemeInfo& s) {
  if (s.triangles_only) return {"octahedron.obj", "tri_crease_grid.obj"};
  if (s.surfaces_only) return {"cube.obj", "crease_grid_flat.obj", "pyramid.obj"};
  return {"cube.obj", "crease_grid_flat.obj", "pyramid_cell.lattice", "curves/curve.obj"};
}



class Engine : public ::testing::TestWithParam<Scheme> {
 protected:
  const SchemeInfo& info() const { return scheme_info(GetParam()); }
  int levels() const { return 2 * info().levels_per_split; }
  // Loop's analysis is a BiCGSTAB solve (relative residual 1e-12): less exact than the others.
  double tolerance() const { return info().limit == LimitRule::LoopMasks ? 1e-9 : 1e-12; }
  Hierarchy hierarchy(const std::string& name, int J, int channels, bool integer = false) const {
    Shape s = read_shape(asset(name));
    return make_hierarchy(std::move(s.base), J, GetParam(), channels, integer);
  }
};

TEST_P(Engine, PerfectReconstruction) {
  for (const std::string& name : bases_for(info())) {
    SCOPED_TRACE(name);
    Hierarchy h = hierarchy(name, levels(), 3);
    const std::vector<double> coeffs = sublift::testing::random_coefficients(h.coeffs.size(), 5, false);
    h.coeffs = coeffs;
    const std::vector<double> fine = synthesize(h, h.finest_level());
    analyze(h, fine);
    EXPECT_LT(sublift::testing::max_abs_diff(h.coeffs, coeffs), tolerance());
    if (!info().integer) continue;
    Hierarchy hi = hierarchy(name, levels(), 2, true);
    const std::vector<double> ic = sublift::testing::random_coefficients(hi.coeffs.size(), 9, true);
    hi.coeffs = ic;
    const std::vector<double> ifine = synthesize(hi, hi.finest_level());
    for (double v : ifine) ASSERT_EQ(v, std::round(v));
    analyze(hi, ifine);
    EXPECT_EQ(hi.coeffs, ic);  // bit for bit
  }
}

TEST_P(Engine, IntegerModeIsRefusedWhereTheSchemeHasNone) {
  if (info().integer) GTEST_SKIP() << info().name << " has an integer mode";
  EXPECT_THROW(hierarchy(bases_for(info()).front(), 1, 3, true), Error);
}

// A change on a few vertices of level j+1, run sparsely, equals the dense run of the whole
// (mostly zero) array, both ways, on every transition of the hierarchy.
TEST_P(Engine, SparseEqualsDense) {
  for (const std::string& name : bases_for(info())) {
    SCOPED_TRACE(name);
    const Hierarchy h = hierarchy(name, levels(), 3);
    for (int j = 0; j < h.finest_level(); ++j) {
      const auto J = static_cast<std::size_t>(j);
      const Transition& t = h.transitions[J];
      const SparseIndex index = build_sparse_index(t);
      const std::uint32_t n = h.num_vertices(j + 1);
      std::mt19937 rng(31 + j);
      std::uniform_int_distribution<std::uint32_t> pick(0, n - 1);
      for (bool analysis : {false, true}) {
        SparseDelta d;
        d.reset(n);
        std::vector<double> dense(std::size_t(n) * 3, 0.0);
        for (int k = 0; k < 4; ++k) {  // old and new vertices alike
          const std::uint32_t v = k == 0 ? 0 : k == 1 ? n - 1 : pick(rng);
          double* x = d.at(v);
          for (int c = 0; c < 3; ++c) dense[std::size_t(v) * 3 + c] = x[c] = 0.5 + k + c;
        }
        if (analysis) {
          run_analysis_sparse(t, h.levels[J], index, d);
          run_analysis(t, h.levels[J], dense.data(), 3, false);
        } else {
          run_synthesis_sparse(t, h.levels[J], index, d);
          run_synthesis(t, h.levels[J], dense.data(), 3, false);
        }
        EXPECT_LT(sublift::testing::max_abs_diff(d.x, dense), tolerance()) << "level " << j << (analysis ? " analysis" : " synthesis");
        // Everything non-zero is on the list.
        std::vector<std::uint8_t> listed(n, 0);
        for (std::uint32_t v : d.list) listed[v] = 1;
        for (std::uint32_t v = 0; v < n; ++v) {
          if (!listed[v]) {
            ASSERT_EQ(d.x[std::size_t(v) * 3], 0.0) << "vertex " << v << " changed but is not listed";
          }
        }
      }
    }
  }
}

// A drag runs the same list every frame: the second run replays the rows the first found
// (SparsePlan) and gives the same bits; another list is found afresh and equals a new index's.
TEST_P(Engine, ReplayedSparseRunsEqualFreshOnes) {
  const Hierarchy h = hierarchy(bases_for(info()).front(), levels(), 3);
  for (int j = 0; j < h.finest_level(); ++j) {
    const auto J = static_cast<std::size_t>(j);
    const Transition& t = h.transitions[J];
    const bool has_matrix = std::any_of(t.steps.begin(), t.steps.end(),
                                        [](const Step& s) { return std::holds_alternative<MatrixStep>(s.op); });
    const std::uint32_t n = h.num_vertices(j + 1);
    const SparseIndex kept = build_sparse_index(t);
    for (bool analysis : {false, true}) {
      const auto run = [&](const SparseIndex& index, std::uint32_t first, double value) {
        SparseDelta d;
        d.reset(n);
        for (std::uint32_t v : {first, (first + n / 3) % n, n - 1})
          for (int c = 0; c < 3; ++c) d.at(v)[c] = value + c;
        if (analysis) run_analysis_sparse(t, h.levels[J], index, d);
        else run_synthesis_sparse(t, h.levels[J], index, d);
        return std::make_pair(d.x, d.list);
      };
      const std::uint64_t before = kept.plans[analysis].replays;
      const auto first = run(kept, 0, 1.5);
      const auto again = run(kept, 0, -0.25);  // same list, other values
      EXPECT_EQ(kept.plans[analysis].replays, before + (has_matrix ? 0 : 1)) << "level " << j;
      EXPECT_EQ(again.second, first.second) << "level " << j;
      EXPECT_EQ(again.first, run(build_sparse_index(t), 0, -0.25).first) << "level " << j << (analysis ? " analysis" : " synthesis");
      const auto other = run(kept, 1, 2.0);  // another list: found afresh
      EXPECT_EQ(other.first, run(build_sparse_index(t), 1, 2.0).first) << "level " << j;
    }
  }
}

// Analysis is linear: column i of its matrix A is the analysis of unit vector e_i. The adjoint
// applied to e_k must give row k of A, entry for entry.
TEST_P(Engine, AdjointIsTheAnalysisRows) {
  const Hierarchy h = hierarchy(bases_for(info()).front(), 1, 1);
  const Transition& t = h.transitions[0];
  const std::uint32_t n = h.num_vertices(1);
  std::vector<std::vector<double>> column(n);
  for (std::uint32_t i = 0; i < n; ++i) {
    column[i].assign(n, 0.0);
    column[i][i] = 1.0;
    run_analysis(t, h.levels[0], column[i].data(), 1, false);
  }
  double worst = 0;
  for (std::uint32_t k = 0; k < n; ++k) {
    std::vector<double> row(n, 0.0);
    row[k] = 1.0;
    run_analysis_adjoint(t, h.levels[0], row.data());
    for (std::uint32_t i = 0; i < n; ++i) worst = std::max(worst, std::abs(row[i] - column[i][k]));
  }
  EXPECT_LT(worst, tolerance());
}

// Zero wavelets: the skip rule gives what the full run gives, bit for bit.
TEST_P(Engine, SkippingZeroWaveletsChangesNothing) {
  const Hierarchy h = hierarchy(bases_for(info()).front(), 1, 3);
  const std::uint32_t nv = h.num_vertices(0), n = h.num_vertices(1);
  std::vector<double> x = sublift::testing::random_coefficients(std::size_t(n) * 3, 3, false);
  std::fill(x.begin() + std::ptrdiff_t(nv) * 3, x.end(), 0.0);
  std::vector<double> skipped = x;
  run_synthesis(h.transitions[0], h.levels[0], x.data(), 3, false, false);
  run_synthesis(h.transitions[0], h.levels[0], skipped.data(), 3, false, true);
  EXPECT_EQ(skipped, x);
}

// The dense loops fold a Scale step into the Centroid steps before it (folded_scale_classes): the
// same transition with an empty step in between, which keeps the Scale step's own pass, gives
// the same bits both ways.
TEST_P(Engine, FoldedScaleIsBitForBitTheScaleStep) {
  bool any_scale = false;
  for (const std::string& name : bases_for(info())) {
    SCOPED_TRACE(name);
    const Hierarchy h = hierarchy(name, 2, 3);
    for (int j = 0; j < h.finest_level(); ++j) {
      const Transition& t = h.transitions[static_cast<std::size_t>(j)];
      Transition apart = t;
      const auto scale = std::find_if(apart.steps.begin(), apart.steps.end(),
                                      [](const Step& s) { return std::holds_alternative<ScaleStep>(s.op); });
      if (scale == apart.steps.end()) {
        EXPECT_EQ(folded_scale_classes(t), 0u);
        continue;
      }
      any_scale = true;
      apart.steps.insert(scale, Step{WeightedStep{}, false, false});
      ASSERT_EQ(folded_scale_classes(apart), 0u);
      // Bertram's cubic s-lift writes v and e last on a surface, and f too in a lattice; a
      // curve's e are read by the s-lift after their last write, so they keep their pass.
      const unsigned expected = h.levels[static_cast<std::size_t>(j)].num_cells() ? 7u : h.levels[static_cast<std::size_t>(j)].num_faces() ? 3u : 1u;
      EXPECT_EQ(folded_scale_classes(t), expected) << "level " << j;
      const std::uint32_t n = h.num_vertices(j + 1);
      for (bool analysis : {false, true}) {
        std::vector<double> x = sublift::testing::random_coefficients(std::size_t(n) * 3, 11 + j, false), y = x;
        if (analysis) {
          run_analysis(t, h.levels[static_cast<std::size_t>(j)], x.data(), 3, false);
          run_analysis(apart, h.levels[static_cast<std::size_t>(j)], y.data(), 3, false);
        } else {
          run_synthesis(t, h.levels[static_cast<std::size_t>(j)], x.data(), 3, false);
          run_synthesis(apart, h.levels[static_cast<std::size_t>(j)], y.data(), 3, false);
        }
        EXPECT_EQ(0, std::memcmp(x.data(), y.data(), x.size() * sizeof(double))) << "level " << j << (analysis ? " analysis" : " synthesis");
      }
    }
  }
  if (!any_scale) GTEST_SKIP() << info().name << " has no Scale step";
}

INSTANTIATE_TEST_SUITE_P(EveryScheme, Engine, ::testing::ValuesIn([] {
                           std::vector<Scheme> all;
                           for (const SchemeInfo& s : all_schemes()) all.push_back(s.id);
                           return all;
                         }()),
                         [](const ::testing::TestParamInfo<Scheme>& p) {
                           std::string n = scheme_name(p.param);
                           std::replace(n.begin(), n.end(), '-', '_');
                           return n;
                         });

}  // namespace

// A row's terms written sorted by source, a repeated source's weights summed in the order they
// were added and exact zeros left out: the same, bit for bit, as a stable sort and a sum, for
// rows of 1 to 40 terms (the 8-term sorting network, the insertion sort, the stable sort) with
// many repeats and weights that cancel.
TEST(StencilRows, AppendEqualsStableSortAndSum) {
  std::mt19937 rng(11);
  for (std::size_t n = 1; n <= 40; ++n)
    for (int trial = 0; trial < 300; ++trial) {
      std::vector<StencilTerm> terms;
      const std::uint32_t range = trial % 3 == 0 ? 1u << 30 : static_cast<std::uint32_t>(n / 2 + 2);
      for (std::size_t i = 0; i < n; ++i) {
        const double w = trial % 5 == 0 && i > 0 && rng() % 2 ? -terms[i - 1].second : std::ldexp(double(rng() % 1000) - 500, -(int(rng() % 9)));
        terms.emplace_back(trial % 5 == 0 && i > 0 && rng() % 2 ? terms[i - 1].first : static_cast<std::uint32_t>(rng() % range), w);
      }
      // The reference sorts nothing: each source's weights summed in the order the terms come
      // (what a stable sort keeps), read back by source.
      std::map<std::uint32_t, double> sum;
      for (const StencilTerm& t : terms) sum[t.first] += t.second;
      Csr want, got;
      std::vector<double> want_w, got_w;
      for (const auto& [v, w] : sum)
        if (w != 0.0) want.items.push_back(v), want_w.push_back(w);
      want.offsets.push_back(static_cast<std::uint32_t>(want.items.size()));
      append_stencil_row(terms, got, got_w);
      ASSERT_EQ(got.items, want.items) << n << " terms, trial " << trial;
      ASSERT_EQ(got.offsets, want.offsets);
      ASSERT_EQ(got_w, want_w) << n << " terms, trial " << trial;
    }
}

// A Matrix step's rows given in any order are sorted and a repeated column summed, since the
// solve reads them as a compressed Eigen matrix; synthesis applies P and analysis solves it back.
TEST(MatrixStep, UnsortedRowsAreSortedAndSolvedBack) {
  Csr rows;
  rows.items = {2, 0, 2, 1, 2, 0};  // row 0: x2, x0, x2 again; row 1: x1; row 2: x2, x0
  rows.offsets = {0, 3, 4, 6};
  const std::vector<double> weights = {0.125, 1.0, 0.0625, 2.0, 1.5, 0.25};
  const MatrixStep m = make_matrix_step(3, rows, weights);
  EXPECT_EQ(m.rows.items, (std::vector<std::uint32_t>{0, 2, 1, 0, 2}));
  EXPECT_EQ(m.rows.offsets, (std::vector<std::uint32_t>{0, 2, 3, 5}));
  EXPECT_EQ(m.weights, (std::vector<double>{1.0, 0.1875, 2.0, 0.25, 1.5}));
  Transition t;
  t.num_coarse = t.num_fine = 3;
  t.add(m);
  const Complex none;
  std::vector<double> x = {1.0, -2.0, 4.0};
  run_synthesis(t, none, x.data(), 1, false);
  EXPECT_EQ(x, (std::vector<double>{1.0 + 0.1875 * 4.0, -4.0, 0.25 + 1.5 * 4.0}));
  run_analysis(t, none, x.data(), 1, false);
  EXPECT_NEAR(x[0], 1.0, 1e-14);
  EXPECT_NEAR(x[1], -2.0, 1e-14);
  EXPECT_NEAR(x[2], 4.0, 1e-14);
  EXPECT_THROW(make_matrix_step(4, rows, weights), std::logic_error);  // a row missing
}
