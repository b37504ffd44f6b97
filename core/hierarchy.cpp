#include "core/hierarchy.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/errors.h"
#include "core/level_counts.h"
#include "core/refine.h"
#include "core/refine_sqrt2.h"
#include "core/refine_tri.h"
#include "core/sqrt2_sparse.h"
#include "core/tri_transform.h"

namespace sublift {

std::string scheme_name(Scheme s) {
  switch (s) {
    case Scheme::Linear: return "linear";
    case Scheme::Cubic: return "cubic";
    case Scheme::Sqrt2: return "sqrt2";
    case Scheme::LinearTri: return "linear-tri";
    case Scheme::Butterfly: return "butterfly";
    case Scheme::Loop: return "loop";
  }
  return "?";
}

Scheme parse_scheme(const std::string& name) {
  if (name == "linear") return Scheme::Linear;
  if (name == "cubic") return Scheme::Cubic;
  if (name == "sqrt2") return Scheme::Sqrt2;
  if (name == "linear-tri") return Scheme::LinearTri;
  if (name == "butterfly") return Scheme::Butterfly;
  if (name == "loop") return Scheme::Loop;
  throw std::invalid_argument("unknown scheme '" + name +
                              "' (expected linear, cubic, sqrt2, linear-tri, butterfly or loop)");
}

LiftProgram scheme_program(Scheme s) {
  if (scheme_has_transitions(s))
    throw std::logic_error("the " + scheme_name(s) + " scheme has no lifting program (it uses explicit transitions)");
  return s == Scheme::Linear ? linear_program() : cubic_program();
}

std::size_t Hierarchy::bytes() const {
  std::size_t b = coeffs.capacity() * sizeof(double);
  for (const Complex& c : levels) b += c.bytes();
  for (const LiftTables& t : tables) b += t.bytes();
  for (const Sqrt2Transition& t : sqrt2)
    for (const Sqrt2Substep& s : t.steps)
      b += (s.target.capacity() + s.sources.offsets.capacity() + s.sources.items.capacity()) * 4 + s.weights.capacity() * 8;
  for (const ChildSites& s : sites) b += (s.site.capacity() + s.edge_child.capacity() + s.face_child.capacity()) * 4;
  return b;
}

namespace {

TriScheme tri_scheme(Scheme s) {
  return s == Scheme::Loop ? TriScheme::Loop : s == Scheme::Butterfly ? TriScheme::Butterfly : TriScheme::Linear;
}

ChildSites sites_of(const Complex& coarse, const Sqrt2Children& ch) {
  ChildSites s;
  s.edge_child.assign(coarse.num_edges(), UINT32_MAX);
  s.face_child.assign(coarse.num_faces(), UINT32_MAX);
  const std::uint32_t nc = ch.curve_step ? static_cast<std::uint32_t>(ch.curve_edges.size()) : 0;
  s.site.reserve(nc + ch.point_faces.size());
  for (std::uint32_t k = 0; k < nc; ++k) {
    s.site.push_back(ch.curve_edges[k]);
    s.edge_child[ch.curve_edges[k]] = coarse.num_vertices + k;
  }
  for (std::uint32_t k = 0; k < ch.point_faces.size(); ++k) {
    s.site.push_back(coarse.num_edges() + ch.point_faces[k]);
    s.face_child[ch.point_faces[k]] = ch.first_face_point + k;
  }
  return s;
}

}  // namespace

void append_level(Hierarchy& h, bool adjacency) {
  Complex& parent = h.levels.back();
  if (parent.vertex_edges.rows() != parent.num_vertices) build_adjacency(parent);
  const int j = h.finest_level();
  if (h.scheme == Scheme::Sqrt2) {
    const double next = double(parent.num_vertices) + double(parent.num_edges()) + double(parent.num_faces());
    if (next > 4.0e9) throw Error("level " + std::to_string(j + 1) + " would have more than 2^32 vertices");
    Sqrt2Step step = refine_sqrt2(parent, h.first_level + j);
    h.sqrt2.push_back(build_sqrt2_transition(parent, step.fine, step.children));
    h.sites.push_back(sites_of(parent, step.children));
    (void)adjacency;  // refine_sqrt2 builds the derived rows anyway
    h.levels.push_back(std::move(step.fine));
    return;
  }
  if (scheme_is_tri(h.scheme)) {
    const double next = double(parent.num_vertices) + double(parent.num_edges());
    if (next > 4.0e9) throw Error("level " + std::to_string(j + 1) + " would have more than 2^32 vertices");
    // The wavelets read the child's neighbourhoods too; its derived rows go again if not wanted.
    Complex child = refine_tri(parent, true);
    TriTransitionResult r = build_tri_transition(parent, child, tri_scheme(h.scheme), h.disc);
    if (!adjacency)
      for (Csr* rows : {&child.vertex_edges, &child.vertex_faces, &child.vertex_cells, &child.edge_faces, &child.edge_cells,
                        &child.face_cells, &child.cell_verts, &child.cell_edges})
        *rows = Csr{};
    ChildSites s;
    const std::uint32_t nv = parent.num_vertices, ne = parent.num_edges();
    s.site.resize(ne);
    s.edge_child.resize(ne);
    s.face_child.assign(parent.num_faces(), UINT32_MAX);
    for (std::uint32_t e = 0; e < ne; ++e) {
      s.site[e] = e;
      s.edge_child[e] = nv + e;
    }
    // ||psi|| in units of a base face's area: a level-j face has 4^-j of it.
    const double area = std::pow(0.25, j);
    h.wavelet_norms.resize(std::size_t(nv) - h.levels.front().num_vertices);
    for (double n2 : r.norm2) h.wavelet_norms.push_back(std::sqrt(std::max(0.0, n2 * area)));
    h.sqrt2.push_back(std::move(r.transition));
    h.sites.push_back(std::move(s));
    h.levels.push_back(std::move(child));
    return;
  }
  const double next = double(parent.num_child_vertices());
  if (next > 4.0e9) throw Error("level " + std::to_string(j + 1) + " would have more than 2^32 vertices");
  h.tables.push_back(build_lift_tables(parent));
  Complex child = refine(parent, adjacency);
  h.levels.push_back(std::move(child));
}

void pop_level(Hierarchy& h) {
  if (h.levels.size() < 2) throw Error("the hierarchy has no level to remove");
  h.levels.pop_back();
  if (scheme_has_transitions(h.scheme)) {
    h.sqrt2.pop_back();
    h.sites.pop_back();
    if (!h.wavelet_norms.empty())
      h.wavelet_norms.resize(std::size_t(h.levels.back().num_vertices) - h.levels.front().num_vertices);
  } else {
    h.tables.pop_back();
  }
}

Hierarchy make_hierarchy(Complex base, int levels, Scheme scheme, int channels, bool integer, int first_level, int disc) {
  const int most = scheme == Scheme::Sqrt2 ? 32 : 16;
  if (levels < 0 || levels > most)
    throw Error("number of levels must be in 0.." + std::to_string(most) + ", got " + std::to_string(levels));
  if (channels < 1) throw Error("at least one channel is needed");
  if (scheme == Scheme::Sqrt2 && (base.dim != 2 || base.num_cells() != 0))
    throw Error("the sqrt2 scheme refines surfaces only; this is a " +
                std::string(base.dim == 1 ? "curve" : base.dim == 3 ? "volume lattice" : "complex") +
                " (use linear or cubic)");
  if (scheme_is_tri(scheme) && (base.dim != 2 || base.num_cells() != 0))
    throw Error("the " + scheme_name(scheme) + " scheme refines triangle meshes only; this is a " +
                std::string(base.dim == 1 ? "curve" : base.dim == 3 ? "volume lattice" : "complex") +
                " (use linear or cubic)");
  if (scheme == Scheme::Loop && integer)
    throw Error("integer mode needs an interpolating scheme; loop's analysis solves a linear system (use butterfly or linear-tri)");
  if (first_level < 0) throw Error("the first sqrt(2) level must not be negative");
  Hierarchy h;
  h.scheme = scheme;
  h.integer = integer;
  h.channels = channels;
  h.first_level = scheme == Scheme::Sqrt2 ? first_level : 0;
  if (disc < 1 || disc > 3) throw Error("the wavelet disc must have 1, 2 or 3 rings, got " + std::to_string(disc));
  h.disc = disc;
  if (base.vertex_edges.rows() != base.num_vertices) build_adjacency(base);
  h.levels.reserve(static_cast<std::size_t>(levels) + 1);
  h.levels.push_back(std::move(base));
  for (int j = 0; j < levels; ++j) append_level(h, /*adjacency=*/j + 1 < levels);
  h.coeffs.assign(std::size_t(h.levels.back().num_vertices) * std::size_t(channels), 0.0);
  return h;
}

void synthesize_transition(const Hierarchy& h, int j, double* x, int channels, bool integer, bool wavelets_zero) {
  const auto J = static_cast<std::size_t>(j);
  if (scheme_has_transitions(h.scheme)) {
    // The update sub-step (steps[0]) reads only wavelets.
    const Sqrt2Transition& t = h.sqrt2[J];
    if (!wavelets_zero) return sqrt2_synthesize(t, x, channels, integer);
    for (std::size_t k = 1; k < t.steps.size(); ++k) sqrt2_run_step(t.steps[k], x, channels, 1.0, integer);
    if (t.smooth) loop_smooth(*t.smooth, x, channels);
    return;
  }
  const LiftProgram program = scheme_program(h.scheme);
  // A leading s-lift only reads wavelet coefficients (e/f/c classes): when a level has none, it
  // adds exactly zero and is skipped (000 sec. 4: "the first lifting operation does not have an
  // impact"). Pure subdivision then costs what the subdivision rules cost.
  const bool skip = wavelets_zero && !program.empty() && program.front().op == LiftOp::SLift;
  const LiftProgram run(program.begin() + (skip ? 1 : 0), program.end());
  lift_synthesize(h.levels[J], h.tables[J], run, x, channels, integer);
}

void analyze_transition(const Hierarchy& h, int j, double* x, int channels, bool integer) {
  const auto J = static_cast<std::size_t>(j);
  if (scheme_has_transitions(h.scheme)) return sqrt2_analyze(h.sqrt2[J], x, channels, integer);
  lift_analyze(h.levels[J], h.tables[J], scheme_program(h.scheme), x, channels, integer);
}

std::vector<double> predicted_level_counts(const Complex& c, int levels, Scheme scheme, int first_level) {
  if (scheme_is_tri(scheme)) {
    // V' = V + E, E' = 2E + 3F, F' = 4F.
    double v = c.num_vertices, e = c.num_edges(), f = c.num_faces();
    std::vector<double> out{v};
    for (int l = 1; l <= levels; ++l) {
      v += e;
      e = 2 * e + 3 * f;
      f *= 4;
      out.push_back(v);
    }
    return out;
  }
  if (scheme != Scheme::Sqrt2) return predicted_vertex_counts(c, levels);
  std::vector<double> out{double(c.num_vertices)};
  if (first_level % 2 == 0) {
    // Two sqrt(2) steps are one 1-to-4 step; the odd level between adds one point per face.
    const int splits = (levels + 1) / 2;
    const std::vector<double> v = predicted_vertex_counts(c, splits);
    const std::vector<double> f = predicted_face_counts(c, splits);
    for (int l = 1; l <= levels; ++l) out.push_back(l % 2 == 0 ? v[std::size_t(l / 2)] : v[std::size_t(l / 2)] + f[std::size_t(l / 2)]);
    return out;
  }
  // From an odd level: one point per curve edge and quad (exact when c has its derived rows;
  // else at most one per edge and face), then an estimate of twice as many per level.
  double n = double(c.num_vertices);
  if (c.edge_faces.rows() == c.num_edges()) {
    for (std::uint32_t e = 0; e < c.num_edges(); ++e) n += sqrt2_is_curve_edge(c, e) ? 1 : 0;
    for (std::uint32_t f = 0; f < c.num_faces(); ++f) n += c.faces.size(f) == 4 ? 1 : 0;
  } else {
    n += double(c.num_edges()) + double(c.num_faces());
  }
  for (int l = 1; l <= levels; ++l, n *= 2) out.push_back(n);
  return out;
}

void set_base(Hierarchy& h, std::span<const double> base_values) {
  const std::size_t n = std::size_t(h.num_vertices(0)) * h.channels;
  if (base_values.size() != n)
    throw Error("base needs " + std::to_string(n) + " values, got " + std::to_string(base_values.size()));
  std::fill(h.coeffs.begin(), h.coeffs.end(), 0.0);
  std::copy(base_values.begin(), base_values.end(), h.coeffs.begin());
}

void analyze(Hierarchy& h, std::span<const double> finest_values) {
  if (finest_values.size() != h.coeffs.size())
    throw Error("finest level needs " + std::to_string(h.coeffs.size()) + " values, got " +
                std::to_string(finest_values.size()));
  std::copy(finest_values.begin(), finest_values.end(), h.coeffs.begin());
  for (int j = h.finest_level() - 1; j >= 0; --j) analyze_transition(h, j, h.coeffs.data(), h.channels, h.integer);
}

std::vector<double> synthesize(const Hierarchy& h, int level) {
  if (level < 0 || level > h.finest_level())
    throw Error("level " + std::to_string(level) + " is outside 0.." + std::to_string(h.finest_level()));
  std::vector<double> x(h.coeffs.begin(), h.coeffs.begin() + std::size_t(h.num_vertices(level)) * h.channels);
  for (int j = 0; j < level; ++j) {
    const auto b = x.begin() + std::size_t(h.num_vertices(j)) * h.channels;
    const auto e = x.begin() + std::size_t(h.num_vertices(j + 1)) * h.channels;
    const bool zero = std::all_of(b, e, [](double v) { return v == 0.0; });
    synthesize_transition(h, j, x.data(), h.channels, h.integer, zero);
  }
  return x;
}

static double norm(const double* v, int ch) {
  double s = 0;
  for (int c = 0; c < ch; ++c) s += v[c] * v[c];
  return std::sqrt(s);
}

std::vector<LevelStats> level_stats(const Hierarchy& h) {
  std::vector<LevelStats> out;
  for (int j = 0; j < h.finest_level(); ++j) {
    LevelStats s;
    s.level = j;
    s.vertices = h.num_vertices(j);
    const std::uint32_t b = h.num_vertices(j), e = h.num_vertices(j + 1);
    s.wavelets = e - b;
    double sum2 = 0;
    for (std::uint32_t i = b; i < e; ++i) {
      const double n = norm(&h.coeffs[std::size_t(i) * h.channels], h.channels);
      s.wavelet_max = std::max(s.wavelet_max, n);
      sum2 += n * n;
    }
    s.wavelet_rms = s.wavelets ? std::sqrt(sum2 / s.wavelets) : 0.0;
    out.push_back(s);
  }
  return out;
}

std::size_t keep_largest(Hierarchy& h, double fraction) {
  if (!(fraction >= 0.0 && fraction <= 1.0)) throw Error("keep fraction must be in [0, 1]");
  struct Entry {
    double magnitude;
    std::uint32_t index;
  };
  std::vector<Entry> all;
  const int dim = h.levels.front().dim;
  // Each level multiplies the cell count by 2^dim (sqrt2: by 2).
  const double per_level = h.scheme == Scheme::Sqrt2 ? 1.0 : double(dim);
  const std::uint32_t nv0 = h.num_vertices(0);
  const bool exact = h.wavelet_norms.size() + nv0 == h.num_vertices(h.finest_level());
  for (int j = 0; j < h.finest_level(); ++j) {
    const double scale = std::pow(2.0, -0.5 * j * per_level);  // L2 norm of a level-j basis function
    for (std::uint32_t i = h.num_vertices(j); i < h.num_vertices(j + 1); ++i)
      all.push_back({norm(&h.coeffs[std::size_t(i) * h.channels], h.channels) * (exact ? h.wavelet_norms[i - nv0] : scale), i});
  }
  const auto keep = static_cast<std::size_t>(std::llround(fraction * double(all.size())));
  if (keep < all.size()) {
    std::nth_element(all.begin(), all.begin() + keep, all.end(), [](const Entry& a, const Entry& b) {
      return a.magnitude != b.magnitude ? a.magnitude > b.magnitude : a.index < b.index;
    });
    for (std::size_t k = keep; k < all.size(); ++k)
      std::fill_n(h.coeffs.begin() + std::size_t(all[k].index) * h.channels, h.channels, 0.0);
  }
  return std::min(keep, all.size());
}

}  // namespace sublift
