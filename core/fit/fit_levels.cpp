#include "core/fit/fit_levels.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <future>
#include <optional>
#include <tuple>

#include <glm/geometric.hpp>

#include "core/base/bounds.h"
#include "core/base/memory_budget.h"
#include "core/base/errors.h"
#include "core/base/parallel.h"
#include "core/base/points.h"
#include "core/base/stopwatch.h"
#include "core/base/triangle_bvh.h"
#include "core/complex/complex_build.h"
#include "core/complex/polygon_normal.h"
#include "core/fit/feature_lines.h"
#include "core/fit/folds.h"
#include "core/fit/net_solve.h"
#include "core/multires/limit.h"

namespace sublift {

namespace {

// Level j's net subdivided to level j + 1: one synthesis step with the level's wavelets zero.
std::vector<double> subdivided(const Hierarchy& h, int j, std::span<const double> x) {
  std::vector<double> y(std::size_t(h.num_vertices(j + 1)) * 3, 0.0);
  std::copy(x.begin(), x.end(), y.begin());
  synthesize_transition(h, j, y.data(), 3, false, /*wavelets_zero=*/true);
  return y;
}

// Where p lands on the input: the nearer of the first hits along +n and -n on the side of the
// input that faces like n (the parametrisation of the subdivided surface carries over, so
// points spread as the coarse faces do, and a thin part's two sides stay apart), unless the
// closest point of that side is much nearer (the ray grazes the surface, or leaves a region
// the coarse surface cuts across) or no ray hits; then that closest point.
struct Projector {
  const TriangleBvh& input;

  // `reach`: no point moves farther (a longer move lands on another part of the surface and
  // leaves a spike in the net); with nothing that near, p stays for the solve to pull.
  // `hint` (optional): the input face found for this point last time, updated (the answer does
  // not depend on it; the search is shorter).
  glm::dvec3 operator()(const glm::dvec3& p, const glm::dvec3& n, double reach, std::uint32_t* hint = nullptr) const {
    const std::uint32_t from = hint ? *hint : UINT32_MAX;
    TriangleBvh::Closest c = input.closest(p, glm::dot(n, n) > 0.0 ? &n : nullptr, from);
    if (!std::isfinite(c.distance)) c = input.closest(p, nullptr, from);
    if (hint) *hint = c.face;
    if (c.distance > reach) return p;
    if (glm::dot(n, n) == 0.0) return c.point;
    // 3x: a ray may meet the surface at a slant; farther than that it is another part's surface.
    const double limit = std::min(reach, 3.0 * c.distance + 1e-12 * input.diagonal());
    const auto [up, down] = input.nearest_hits(p, n, n, limit, c.face);
    if (down <= limit && down < up) return p - down * n;
    if (up <= limit) return p + up * n;
    return c.point;
  }
};

// Closest-point hints (TriangleBvh::closest): per point, the face it was nearest last time
// (in and out); empty: none. Points and surfaces move little between the rounds of a level, so
// a search started there opens a fraction of the boxes.
std::uint32_t hint_of(std::span<const std::uint32_t> hints, std::uint32_t i) { return hints.empty() ? UINT32_MAX : hints[i]; }

// RMS and largest distance from the points x to `to`, over `diag`.
std::pair<double, double> distances(const TriangleBvh& to, std::span<const double> x, double diag, std::span<std::uint32_t> hints = {}) {
  const std::uint32_t n = static_cast<std::uint32_t>(x.size() / 3);
  std::vector<double> d(n);
  parallel_for(n, 2048, [&](std::uint32_t b, std::uint32_t e) {
    for (std::uint32_t v = b; v < e; ++v) {
      const TriangleBvh::Closest cl = to.closest(at(x, v), nullptr, hint_of(hints, v));
      d[v] = cl.distance / diag;
      if (!hints.empty()) hints[v] = cl.face;
    }
  });
  double sum = 0, worst = 0;
  for (double v : d) sum += v * v, worst = std::max(worst, v);
  return {n ? std::sqrt(sum / n) : 0.0, worst};
}

// Per face of the net (`faces` over x), the way the input faces there: the mean of the vertex
// normals of the input face closest to the face's centroid (a scan's noise flips single small
// triangles; their vertex normals hold). The answers for the last two point sets asked are kept:
// a face whose corners have not moved since gets the same answer without a search (the answer
// depends on the centroid alone), and fitting asks again after moving a few points (untangling)
// or none (the report after the last round).
class Facings {
 public:
  Facings(const TriangleBvh& input, std::span<const double> normals, const Csr& input_faces)
      : input_(input), normals_(normals), input_faces_(input_faces) {}

  /// A new net (`faces`, which must outlive the calls): nothing kept, no hints.
  void reset(const Csr& faces) {
    faces_ = &faces;
    hints_.assign(faces.rows(), UINT32_MAX);
    for (Kept& k : kept_) k = {};
  }
  /// Per face, the input face to start its next search from.
  void set_hints(std::vector<std::uint32_t> hints) { hints_ = std::move(hints); }

  std::vector<glm::dvec3> operator()(std::span<const double> x) {
    const Csr& faces = *faces_;
    // The kept set with the most points unmoved, else the one asked longest ago.
    const auto unmoved = [&](const Kept& k, std::size_t v) {
      return k.points.size() == x.size() && std::equal(&x[3 * v], &x[3 * v] + 3, &k.points[3 * v]);
    };
    std::array<std::vector<std::uint8_t>, 2> unmoved_at;
    for (std::size_t k = 0; k < kept_.size(); ++k) {
      unmoved_at[k].assign(x.size() / 3, 0);
      if (kept_[k].points.size() != x.size()) continue;
      parallel_for(static_cast<std::uint32_t>(x.size() / 3), 8192, [&](std::uint32_t b, std::uint32_t e) {
        for (std::uint32_t v = b; v < e; ++v) unmoved_at[k][v] = unmoved(kept_[k], v);
      });
    }
    std::size_t best = kept_[0].asked <= kept_[1].asked ? 0 : 1, best_count = 0;
    for (std::size_t k = 0; k < kept_.size(); ++k) {
      const std::size_t count = static_cast<std::size_t>(std::count(unmoved_at[k].begin(), unmoved_at[k].end(), std::uint8_t(1)));
      if (count > best_count) best = k, best_count = count;
    }
    const std::vector<std::uint8_t>& same = unmoved_at[best];
    Kept& kept = kept_[best];
    std::vector<glm::dvec3> out(faces.rows());
    parallel_for(static_cast<std::uint32_t>(faces.rows()), 2048, [&](std::uint32_t b, std::uint32_t e) {
      for (std::uint32_t f = b; f < e; ++f) {
        const auto r = faces.row(f);
        if (best_count && std::all_of(r.begin(), r.end(), [&](std::uint32_t v) { return same[v] != 0; })) {
          out[f] = kept.facing[f];
          continue;
        }
        glm::dvec3 m(0.0);
        for (std::uint32_t v : r) m += at(x, v);
        const TriangleBvh::Closest cl = input_.closest(m / double(r.size()), nullptr, hint_of(hints_, f));
        if (!hints_.empty()) hints_[f] = cl.face;
        glm::dvec3 n(0.0);
        for (std::uint32_t v : input_faces_.row(cl.face)) n += at(normals_, v);
        out[f] = n;
      }
    });
    kept.points.assign(x.begin(), x.end());
    kept.facing = out;
    kept.asked = ++asked_;
    return out;
  }

  const Csr* faces() const { return faces_; }

  /// The faces of the net over x that are folded over: turned away from the way the input faces.
  std::uint32_t folded(std::span<const double> x) {
    return static_cast<std::uint32_t>(count_turned(*faces_, x, (*this)(x)));
  }

 private:
  struct Kept {
    std::vector<double> points;
    std::vector<glm::dvec3> facing;
    std::uint64_t asked = 0;
  };
  const TriangleBvh& input_;
  std::span<const double> normals_;
  const Csr& input_faces_;
  const Csr* faces_ = nullptr;
  std::vector<std::uint32_t> hints_;
  std::array<Kept, 2> kept_;
  std::uint64_t asked_ = 0;
};

// How strongly the solve holds each net point on its projection: corners stay, crease and
// boundary points stay on the input's lines (the input's pull would round a crease off).
std::vector<double> held(const Complex& c) {
  std::vector<double> w(c.num_vertices, 1.0);
  for (std::uint32_t v = 0; v < c.num_vertices && !c.vertex_dim.empty(); ++v)
    if (c.vertex_dim[v] < 2) w[v] = c.vertex_dim[v] == 0 ? 1e6 : 1e2;
  return w;
}

// One point's move onto the input (docs/fit.md): a corner stays where the base has it; a point
// of a crease or boundary relaxes along it and lands on the input's nearest feature line (unless
// that line is farther than an edge or twice the surface: another feature than this one); any
// other point relaxes tangentially towards its neighbours' mean (the parametrisation evens out,
// the shape stays) and is projected along its normal.
struct Mover {
  const Complex& c;
  const Projector& project;
  const FeatureLines& lines;
  std::uint32_t first_new;
  double relax;
  std::uint32_t* hints = nullptr;  // per net vertex, for Projector (each call writes only its own)

  glm::dvec3 operator()(std::span<const double> x, std::span<const double> normal, std::uint32_t v) const {
    std::uint32_t* hint = hints ? hints + v : nullptr;
    glm::dvec3 p = at(x, v);
    const glm::dvec3 nv = at(normal, v);
    const std::uint8_t dim = c.vertex_dim.empty() ? 2 : c.vertex_dim[v];
    if (dim == 0) return p;
    double edge = 0;  // the longest edge at v: no move is longer than two of them
    glm::dvec3 mean(0.0), line_mean(0.0);
    int on_line = 0;
    for (std::uint32_t e : c.vertex_edges.row(v)) {
      const glm::dvec3 w = at(x, edge_other_end(c, e, v));
      edge = std::max(edge, glm::distance(p, w));
      mean += w;
      if (c.edge_dim[e] == 1) line_mean += w, ++on_line;
    }
    if (dim == 1) {
      if (v >= first_new && on_line) p += relax * (line_mean / double(on_line) - p);
      const glm::dvec3 on_surface = project(p, nv, 2 * edge, hint);
      const glm::dvec3 q = lines.closest(p);
      return !lines.empty() && glm::distance(q, p) <= std::max(0.5 * edge, 2.0 * glm::distance(on_surface, p)) ? q : on_surface;
    }
    {  // old points too: a coarse level's points are no better placed than the new ones
      glm::dvec3 d = mean / double(c.vertex_edges.size(v)) - p;
      d -= glm::dot(d, nv) * nv;
      p += relax * d;
    }
    return project(p, nv, 2 * edge, hint);
  }
};

}  // namespace

int default_fit_levels(std::uint32_t input_vertices, std::uint32_t base_vertices, Scheme scheme) {
  const int per_split = scheme_info(scheme).levels_per_split;
  if (base_vertices == 0 || input_vertices <= base_vertices) return per_split;
  const double splits = std::log(double(input_vertices) / base_vertices) / std::log(4.0);
  return std::clamp(static_cast<int>(std::lround(splits * per_split)), per_split, 6 * per_split);
}

bool fit_base_quads(Scheme scheme) { return !scheme_info(scheme).triangles_only; }

FitInputIndex index_fit_input(const Csr& faces, std::span<const double> positions) {
  return {TriangleBvh(positions, faces), area_weighted_normals(faces, positions), bbox_diagonal(positions)};
}

Fitted fit_levels(const BaseMesh& base, const Csr& faces, std::span<const double> positions, const FitOptions& o) {
  if (o.progress && !o.progress("indexing the mesh", 0.0)) throw Cancelled("fitting cancelled");
  const auto t0 = std::chrono::steady_clock::now();
  const FitInputIndex index = index_fit_input(faces, positions);
  const double index_ms = ms_since(t0);
  Fitted out = fit_levels(base, faces, positions, o, index);
  for (auto& [stage, ms] : out.stage_ms)
    if (stage == "indexing") ms += index_ms;
  return out;
}

MeshFit fit_mesh(std::uint32_t num_vertices, const Csr& faces, std::span<const double> positions, const BaseMeshOptions& base_options,
                 FitOptions fit) {
  // The index on its own thread (its parallel loops take the pool in turn with the decimation's).
  std::future<FitInputIndex> index = std::async(std::launch::async, [&] { return index_fit_input(faces, positions); });
  MeshFit out;
  const auto t0 = std::chrono::steady_clock::now();
  out.base = decimate_to_base(num_vertices, faces, positions, base_options);  // (on a throw, ~future waits for the index)
  out.base_ms = ms_since(t0);
  if (fit.levels < 0) fit.levels = default_fit_levels(num_vertices, out.base.num_vertices, fit.scheme);
  if (fit.progress && !fit.progress("indexing the mesh", 0.0)) throw Cancelled("fitting cancelled");
  const auto t1 = std::chrono::steady_clock::now();
  const FitInputIndex ready = index.get();
  const double wait_ms = ms_since(t1);
  out.fitted = fit_levels(out.base, faces, positions, fit, ready);
  for (auto& [stage, ms] : out.fitted.stage_ms)
    if (stage == "indexing") ms += wait_ms;
  return out;
}

Fitted fit_levels(const BaseMesh& base, const Csr& faces, std::span<const double> positions, const FitOptions& o,
                  const FitInputIndex& index) {
  if (scheme_info(o.scheme).triangles_only)
    for (std::size_t f = 0; f < base.faces.rows(); ++f)
      if (base.faces.size(f) != 3) throw Error("the " + scheme_name(o.scheme) + " scheme needs a triangle base (BaseMeshOptions::quads off)");
  const auto report = [&](const char* stage, double fraction) {
    if (o.progress && !o.progress(stage, fraction)) throw Cancelled("fitting cancelled");
  };
  Fitted out;
  auto t_stage = std::chrono::steady_clock::now();
  const auto stage_done = [&](const char* name) {
    const auto now = std::chrono::steady_clock::now();
    out.stage_ms.emplace_back(name, std::chrono::duration<double, std::milli>(now - t_stage).count());
    t_stage = now;
  };
  // Up front, before the costly levels: all the levels asked for must fit (a tolerance may stop
  // earlier; append_level checks each level again).
  {
    const Complex c = complex_from_polygons(base.num_vertices, base.faces, base.tags);
    check_memory(predicted_hierarchy_bytes(c, o.levels, o.scheme), "fitting " + std::to_string(o.levels) + " levels");
  }
  const TriangleBvh& input = index.surface;
  const FeatureLines lines(positions, base.input_feature_edges);
  const Projector project{input};
  const std::vector<double>& input_normals = index.normals;
  const double diag = index.diagonal;
  stage_done("indexing");
  // Levels are appended one by one (their setup is the costly part), so a tolerance stops early.
  out.hierarchy = make_hierarchy(complex_from_polygons(base.num_vertices, base.faces, base.tags), 0, o.scheme, 3);
  Hierarchy& h = out.hierarchy;
  set_base(h, base.positions);
  double hierarchy_ms = 0, levels_ms = 0;
  std::optional<LimitStencils> finest_limit;  // built for the limit fit, kept for the report
  std::vector<double> x;
  // Closest-point hints within a level (its faces and vertices keep their numbers there): input
  // vertex -> net face, net face -> input face, net vertex -> input face.
  std::vector<std::uint32_t> input_hint, vertex_hint, move_hint;
  Facings facings(input, input_normals, faces);  // the input's way at the level's net faces
  // The level's net (or limit surface) indexed once, refitted as it moves (TriangleBvh::refit).
  std::optional<TriangleBvh> net_index;
  const auto net_indexed = [&](const Complex& c, std::span<const double> net) -> const TriangleBvh& {
    if (net_index) net_index->refit(net);
    else net_index.emplace(net, c.faces);
    return *net_index;
  };
  const auto measure = [&](int l, const Complex& c, const std::vector<double>& net) {
    FitLevelReport rep;
    rep.level = l;
    rep.vertices = c.num_vertices;
    std::tie(rep.rms, rep.max) = distances(input, net, diag, vertex_hint);
    std::tie(rep.back_rms, rep.back_max) = distances(net_indexed(c, net), positions, diag, input_hint);
    rep.folded = facings.folded(net);
    return rep;
  };
  for (int l = 1; l <= o.levels; ++l) {
    report("fitting levels", double(l - 1) / o.levels);
    const auto t0 = std::chrono::steady_clock::now();
    append_level(h);
    h.coeffs.resize(std::size_t(h.num_vertices(l)) * 3, 0.0);  // the new wavelets, zero
    const auto t1 = std::chrono::steady_clock::now();
    hierarchy_ms += std::chrono::duration<double, std::milli>(t1 - t0).count();
    x = subdivided(h, l - 1, l == 1 ? std::span<const double>(base.positions) : std::span<const double>(x));
    Complex c = h.levels[static_cast<std::size_t>(l)];
    if (c.vertex_edges.rows() != c.num_vertices) build_adjacency(c);
    const std::uint32_t n = c.num_vertices;
    // Net vertex -> the input face its last projection found; the old points keep their numbers,
    // so they start from the coarser level's answers.
    move_hint.resize(n, UINT32_MAX);
    const Mover move{c, project, lines, h.num_vertices(l - 1), o.relax, move_hint.data()};
    const std::vector<double> hold = held(c);
    // An input vertex's search starts from a face around the first corner of the coarser face it
    // was nearest (the old points keep their numbers); any hint gives the same answer, a near one
    // sooner.
    {
      const Csr& coarse = h.levels[static_cast<std::size_t>(l - 1)].faces;
      input_hint.resize(positions.size() / 3, UINT32_MAX);
      for (std::uint32_t& hint : input_hint) {
        const std::uint32_t v = hint < coarse.rows() && coarse.size(hint) > 0 ? coarse.row(hint)[0] : UINT32_MAX;
        hint = v < c.vertex_faces.rows() && c.vertex_faces.size(v) > 0 ? c.vertex_faces.row(v)[0] : UINT32_MAX;
      }
    }
    net_index.reset();  // a new net
    vertex_hint.assign(n, UINT32_MAX);
    facings.reset(h.levels[static_cast<std::size_t>(l)].faces);  // c's faces, kept in h
    std::vector<double> next(x.size());
    for (int round = 0; round < o.relax_rounds; ++round) {
      // Every point onto the input, then the two-way solve (core/fit/net_solve.h); neither step
      // may fold a face over.
      const std::vector<double> normal = area_weighted_normals(c.faces, x);
      parallel_for(n, 1024, [&](std::uint32_t b, std::uint32_t e) {
        for (std::uint32_t v = b; v < e; ++v) put(next, v, move(x, normal, v));
      });
      // A new face's search for the input face under it starts where its first corner's did.
      if (round == 0) {
        std::vector<std::uint32_t> face_hint(c.faces.rows());
        for (std::size_t f = 0; f < c.faces.rows(); ++f) face_hint[f] = move_hint[c.faces.row(f)[0]];
        facings.set_hints(std::move(face_hint));
      }
      // The input's way at each face, from before the moves (they are small): both guards use it.
      const std::vector<glm::dvec3> facing = facings(x);
      keep_unfolded(c.faces, facing, x, next);
      x.swap(next);
      untangle(c, project, lines, facing, x);  // before the solve, which pulls the moved points back
      if (o.two_way) {
        std::vector<double> solved = solve_net(c, {x, x, x, nullptr, input_hint, &net_index}, positions, input_normals, hold, o.weights);
        keep_unfolded(c.faces, facing, x, solved);
        x.swap(solved);
      }
    }
    const auto facing_of = [&](std::span<const double> net) { return facings(net); };
    // An approximating scheme's finest level gets its limit surface fitted; with a tolerance,
    // every level does, since the limit surface is what the tolerance is about there.
    const bool approximating = o.two_way && scheme_info(o.scheme).limit != LimitRule::ControlNet;
    double reach_max = 0;  // the fitted surface's larger distance, both ways
    if (approximating && (o.tolerance > 0 || l == o.levels)) {
      // Its points projected as the net's were (no relaxing), the net solved under it.
      finest_limit = build_limit_stencils(h);
      const LimitStencils& ls = *finest_limit;
      const Mover project_only{c, project, lines, n, 0.0, move_hint.data()};
      std::vector<double> y(x.size()), targets(x.size());
      for (int round = 0; round < o.limit_rounds; ++round) {
        eval_limit(ls, x.data(), y.data());
        const std::vector<double> normal = area_weighted_normals(c.faces, y);
        parallel_for(n, 1024, [&](std::uint32_t b, std::uint32_t e) {
          for (std::uint32_t v = b; v < e; ++v) put(targets, v, project_only(y, normal, v));
        });
        std::vector<glm::dvec3> facing;  // the input's way at x's faces
        untangle_limit(c, ls, project, lines, facing_of, x, &facing);
        eval_limit(ls, x.data(), y.data());
        std::vector<double> solved = solve_net(c, {x, y, targets, &ls, input_hint, &net_index}, positions, input_normals, hold, o.weights);
        keep_unfolded(c.faces, facing, x, solved);
        x.swap(solved);
      }
      untangle_limit(c, ls, project, lines, facing_of, x);
      if (o.tolerance > 0) {
        eval_limit(ls, x.data(), y.data());
        reach_max = std::max(distances(input, y, diag, vertex_hint).second, distances(net_indexed(c, y), positions, diag, input_hint).second);
      }
    }
    for (std::uint32_t v = 0; v < n; ++v)
      if (vertex_hint[v] == UINT32_MAX) vertex_hint[v] = move_hint[v];  // where its last move landed
    FitLevelReport rep = measure(l, c, x);
    if (!approximating) reach_max = std::max(rep.max, rep.back_max);
    const bool reached = o.tolerance > 0 && reach_max <= o.tolerance;
    // With a tolerance, a level four times as dense as the input is the last one tried.
    const bool last = l == o.levels || reached || (o.tolerance > 0 && n >= 4 * (positions.size() / 3));
    rep.ms = ms_since(t1);
    levels_ms += rep.ms;
    out.levels.push_back(rep);
    out.reached_tolerance = reached;
    if (last) break;
  }
  out.stage_ms.emplace_back("hierarchy", hierarchy_ms);
  out.stage_ms.emplace_back("levels", levels_ms);
  t_stage = std::chrono::steady_clock::now();
  if (o.levels == 0) x = synthesize(h, 0);
  report("analysing", 1.0);
  analyze(h, x);
  stage_done("analysis");
  // The limit surface of the finest level (its limit points, as a triangle mesh), both ways.
  if (!finest_limit) finest_limit = build_limit_stencils(h);
  const LimitStencils& ls = *finest_limit;
  std::vector<double> limit(x.size());
  eval_limit(ls, x.data(), limit.data());
  if (scheme_info(o.scheme).limit == LimitRule::ControlNet && !out.levels.empty()) {
    // The limit surface is the finest net, the last level measured (levels are appended as they
    // are fitted): the same points, the same distances and folds.
    const FitLevelReport& last = out.levels.back();
    std::tie(out.limit_rms, out.limit_max, out.limit_back_rms, out.limit_back_max) = std::tuple(last.rms, last.max, last.back_rms, last.back_max);
    out.limit_folded = last.folded;
  } else {
    // The last level's hints hold when it is the finest (no fitted level: none).
    if (facings.faces() != &h.levels.back().faces || vertex_hint.size() * 3 != limit.size()) {
      input_hint = vertex_hint = {};
      facings.reset(h.levels.back().faces);
    }
    std::tie(out.limit_rms, out.limit_max) = distances(input, limit, diag, vertex_hint);
    // The last fitted level is the finest: its index is refitted to the limit points.
    const TriangleBvh& limit_index = net_indexed(h.levels.back(), limit);
    std::tie(out.limit_back_rms, out.limit_back_max) = distances(limit_index, positions, diag, input_hint);
    out.limit_folded = facings.folded(limit);
  }
  // The input's feature lines against the fitted creases and boundaries (their limit curves).
  const Complex& fine = h.levels.back();
  std::vector<std::uint32_t> crease_edges;
  for (std::uint32_t e = 0; e < fine.num_edges() && !fine.edge_dim.empty(); ++e)
    if (fine.edge_dim[e] == 1) crease_edges.insert(crease_edges.end(), {fine.edge_verts[2 * e], fine.edge_verts[2 * e + 1]});
  const FeatureLines fitted_lines(limit, crease_edges);
  for (std::uint32_t v : base.input_line_vertices)
    out.feature_max = std::max(out.feature_max, fitted_lines.empty() ? INFINITY : glm::distance(fitted_lines.closest(at(positions, v)), at(positions, v)) / diag);
  out.feature_lines = base.input_lines;
  stage_done("report");
  out.finest = std::move(x);
  return out;
}

}  // namespace sublift
