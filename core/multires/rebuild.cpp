#include "core/multires/rebuild.h"

#include <algorithm>
#include <chrono>
#include <string>

#include "core/base/errors.h"
#include "core/base/stopwatch.h"
#include "core/complex/complex_build.h"

namespace sublift {

Scheme rebuild_auto_scheme(const Csr& faces) {
  for (std::size_t f = 0; f < faces.rows(); ++f)
    if (faces.size(f) != 3) return Scheme::Cubic;
  return faces.rows() ? Scheme::Loop : Scheme::Cubic;
}

SplitKind rebuild_split(Scheme s) {
  switch (scheme_info(s).refinement) {
    case Refinement::Split: return SplitKind::Quads;
    case Refinement::Tri: return SplitKind::Triangles;
    case Refinement::Sqrt2: return SplitKind::Sqrt2;
  }
  throw Error("rebuilding levels of the " + scheme_name(s) + " scheme's refinement is not supported (docs/rebuild.md)");
}

CarriedFeatures carry_features_down(const DetectedLevels& d, const FeatureTags& fine) {
  CarriedFeatures out;
  out.creases = fine.crease_edges.size();
  out.corners = fine.corner_vertices.size();
  std::vector<std::pair<std::uint32_t, std::uint32_t>> creases = fine.crease_edges;
  std::vector<std::uint32_t> corners = fine.corner_vertices;
  std::size_t more = 0;
  auto drop = [&](std::string why) {
    if (out.dropped.size() < 8) out.dropped.push_back(std::move(why));
    else ++more;
  };
  for (int l = d.levels - 1; l >= 0; --l) {  // steps[l]: M_{l+1} -> M_l
    const Coarsening& st = d.steps[static_cast<std::size_t>(l)];
    auto input_of = [&](std::uint32_t v) {
      return l + 1 == d.levels ? v : d.steps[static_cast<std::size_t>(l + 1)].input_vertex[v];
    };
    std::vector<std::pair<std::uint32_t, std::uint32_t>> halves;
    for (auto [x, y] : creases) {
      if (st.kind[x] != Coarsening::Old) std::swap(x, y);
      const bool half = st.kind[x] == Coarsening::Old && st.kind[y] == Coarsening::EdgePoint &&
                        (st.a[y] == st.a[x] || st.b[y] == st.a[x]);
      if (!half) {
        drop("crease " + std::to_string(input_of(x)) + "-" + std::to_string(input_of(y)) + " runs inside a face of the mesh " +
             std::to_string(d.levels - l) + " level(s) down");
        continue;
      }
      halves.emplace_back(std::min(st.a[y], st.b[y]), std::max(st.a[y], st.b[y]));
    }
    std::sort(halves.begin(), halves.end());
    creases.clear();
    for (std::size_t i = 0; i < halves.size();) {
      std::size_t j = i;
      while (j < halves.size() && halves[j] == halves[i]) ++j;
      if (j - i == 2) {
        creases.push_back(halves[i]);
      } else {
        const auto& in = st.input_vertex;
        drop("only half of the edge " + std::to_string(in[halves[i].first]) + "-" + std::to_string(in[halves[i].second]) +
             " of the mesh " + std::to_string(d.levels - l) + " level(s) down is creased");
      }
      i = j;
    }
    std::vector<std::uint32_t> kept;
    for (std::uint32_t v : corners) {
      if (st.kind[v] == Coarsening::Old) kept.push_back(st.a[v]);
      else drop("corner at vertex " + std::to_string(input_of(v)) + " is no vertex of the mesh " + std::to_string(d.levels - l) + " level(s) down");
    }
    corners.swap(kept);
  }
  if (more) out.dropped.push_back("and " + std::to_string(more) + " more");
  out.base.crease_edges = std::move(creases);
  out.base.corner_vertices = std::move(corners);
  return out;
}

namespace {

// The stages every rebuild shares: detection, the base and its levels, the analysis; timed and
// reporting progress, and refusing a levels request the mesh does not hold. detect(limit,
// keep_going) finds the levels; base(r) builds the base complex from r.detected.
template <class Detect, class Base>
Rebuilt rebuild_stages(std::uint32_t num_vertices, std::span<const double> positions, Scheme scheme, int levels, bool integer,
                       int disc, const RebuildProgress& progress, const std::string& what, Detect detect, Base base,
                       std::span<const VertexAttribute> attributes) {
  if (positions.size() != 3 * static_cast<std::size_t>(num_vertices))
    throw Error("rebuild: " + std::to_string(positions.size()) + " coordinates for " + std::to_string(num_vertices) + " vertices");
  for (const VertexAttribute& a : attributes)
    if (a.values.size() != num_vertices)
      throw Error("rebuild: attribute " + a.name + " has " + std::to_string(a.values.size()) + " values for " + std::to_string(num_vertices) + " vertices");
  const std::size_t channels = 3 + attributes.size();
  // Shares of the time (bench_rebuild): detection about 3/4, the hierarchy and the analysis the rest.
  auto at = [&](const char* stage, double fraction) {
    if (progress && !progress(stage, fraction)) throw Cancelled("rebuild cancelled");
  };
  using Clock = std::chrono::steady_clock;
  Rebuilt r;
  at("finding levels", 0.0);
  auto t = Clock::now();
  r.detected = detect(levels < 0 ? max_levels(scheme) : levels, [&](double f) { return !progress || progress("finding levels", 0.75 * f); });
  const DetectedLevels& d = r.detected;
  if (levels >= 0 && d.levels < levels)
    throw Error(what + " holds " + std::to_string(d.levels) + " level" + (d.levels == 1 ? "" : "s") + ", not " + std::to_string(levels) +
                ": " + d.stop);
  r.detect_ms = ms_since(t);
  at("building levels", 0.75);
  t = Clock::now();
  r.hierarchy = make_hierarchy(base(r), d.levels, scheme, int(channels), integer, d.first_level, disc);
  r.engine_vertex = engine_order(d, r.hierarchy.levels);
  r.build_ms = ms_since(t);
  at("analysing", 0.9);
  t = Clock::now();
  std::vector<double> x(channels * num_vertices);  // the input's positions (and attributes) in the engine's order
  for (std::size_t i = 0; i < r.engine_vertex.size(); ++i) {
    double* to = &x[channels * std::size_t(r.engine_vertex[i])];
    for (std::size_t k = 0; k < 3; ++k) to[k] = positions[3 * i + k];
    for (std::size_t k = 0; k < attributes.size(); ++k) to[3 + k] = attributes[k].values[i];
  }
  analyze(r.hierarchy, x);
  r.analysis_ms = ms_since(t);
  at("done", 1.0);
  return r;
}

}  // namespace

Rebuilt rebuild_hierarchy(std::uint32_t num_vertices, const Csr& faces, std::span<const double> positions, Scheme scheme,
                          int levels, bool integer, int disc, const FeatureTags& fine_tags, const RebuildProgress& progress,
                          std::span<const VertexAttribute> attributes) {
  const SplitKind split = rebuild_split(scheme);
  const char* what = split == SplitKind::Quads ? "the mesh, as a quad split,"
                     : split == SplitKind::Triangles ? "the mesh, as a triangle split,"
                                                     : "the mesh, in sqrt(2) steps,";
  return rebuild_stages(
      num_vertices, positions, scheme, levels, integer, disc, progress, what,
      [&](int limit, const std::function<bool(double)>& go) { return detect_levels(num_vertices, faces, split, limit, positions, go); },
      [&](Rebuilt& r) {
        r.features = carry_features_down(r.detected, fine_tags);
        return complex_from_polygons(r.detected.base_vertices, r.detected.base_faces, r.features.base);
      },
      attributes);
}

Rebuilt rebuild_volume_hierarchy(const Complex& fine, std::span<const double> positions, Scheme scheme, int levels,
                                 bool integer, const RebuildProgress& progress) {
  if (scheme_info(scheme).surfaces_only) throw Error("the " + scheme_name(scheme) + " scheme refines surfaces only; lattices take linear or cubic");
  return rebuild_stages(
      fine.num_vertices, positions, scheme, levels, integer, 2, progress, "the lattice, as a 1-to-8 split,",
      [&](int limit, const std::function<bool(double)>& go) { return detect_volume_levels(fine, limit, positions, go); },
      [](Rebuilt& r) { return complex_from_cells(r.detected.base_vertices, r.detected.base_faces, r.detected.base_cells); },
      {});
}

}  // namespace sublift
