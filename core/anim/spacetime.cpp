#include "core/anim/spacetime.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <unordered_map>

#include "core/base/edge_key.h"
#include "core/base/errors.h"
#include "core/base/parallel.h"
#include "core/complex/complex_build.h"
#include "core/schemes/registry.h"

namespace sublift {

namespace {

// The cell layer between adjacent vertex layers a and b; cyclic (layers >= 3), the last one
// joins layers - 1 to 0.
std::uint32_t interval_of(std::uint32_t a, std::uint32_t b, std::uint32_t layers, bool cyclic) {
  if (!cyclic) return std::min(a, b);
  return (a + 1) % layers == b ? a : b;
}

// Surface elements of one level looked up by their vertices.
struct SurfaceLookup {
  const Complex& s;
  std::unordered_map<std::uint64_t, std::uint32_t> edge;
  explicit SurfaceLookup(const Complex& c) : s(c) {
    edge.reserve(c.num_edges());
    for (std::uint32_t e = 0; e < c.num_edges(); ++e) edge.emplace(edge_key(c.edge_verts[2 * e], c.edge_verts[2 * e + 1]), e);
  }
  std::uint32_t edge_of(std::uint32_t a, std::uint32_t b) const {
    const auto it = edge.find(edge_key(a, b));
    if (it == edge.end()) throw Error("space-time map: no surface edge " + std::to_string(a) + "-" + std::to_string(b));
    return it->second;
  }
  // The face of these corners (any order), through the faces of the edge of its first two.
  std::uint32_t face_of(std::vector<std::uint32_t> corners) const {
    const std::uint32_t e = edge_of(corners[0], corners[1]);
    std::sort(corners.begin(), corners.end());
    for (std::uint32_t f : s.edge_faces.row(e)) {
      const auto row = s.faces.row(f);
      if (row.size() != corners.size()) continue;
      std::vector<std::uint32_t> sorted(row.begin(), row.end());
      std::sort(sorted.begin(), sorted.end());
      if (sorted == corners) return f;
    }
    throw Error("space-time map: no surface face on edge " + std::to_string(e));
  }
};

// Layer and surface vertex of every lattice vertex of level j + 1 from those of level j.
void map_children(const Complex& lat, const Complex& surf, std::uint32_t layers, bool cyclic, const std::vector<std::uint32_t>& layer,
                  const std::vector<std::uint32_t>& point, std::vector<std::uint32_t>& child_layer,
                  std::vector<std::uint32_t>& child_point) {
  const SurfaceLookup look(surf);
  const std::uint32_t nvs = surf.num_vertices, nes = surf.num_edges();
  const std::uint32_t nv = lat.num_vertices, ne = lat.num_edges(), nf = lat.num_faces();
  child_layer.assign(lat.num_child_vertices(), 0);
  child_point.assign(lat.num_child_vertices(), 0);
  for (std::uint32_t v = 0; v < nv; ++v) child_layer[v] = 2 * layer[v], child_point[v] = point[v];
  for (std::uint32_t e = 0; e < ne; ++e) {
    const std::uint32_t a = lat.edge_verts[2 * e], b = lat.edge_verts[2 * e + 1];
    if (layer[a] == layer[b]) {
      child_layer[nv + e] = 2 * layer[a];
      child_point[nv + e] = nvs + look.edge_of(point[a], point[b]);
    } else {
      child_layer[nv + e] = 2 * interval_of(layer[a], layer[b], layers, cyclic) + 1;
      child_point[nv + e] = point[a];
    }
  }
  std::vector<std::uint32_t> face_surface(nf);  // the layer face's surface face, or the side face's edge
  std::vector<char> side(nf, 0);
  for (std::uint32_t f = 0; f < nf; ++f) {
    const auto row = lat.faces.row(f);
    std::uint32_t lo = layer[row[0]], hi = lo;
    for (std::uint32_t v : row) lo = std::min(lo, layer[v]), hi = std::max(hi, layer[v]);
    const std::uint32_t child = nv + ne + f;
    if (lo == hi) {
      std::vector<std::uint32_t> corners;
      for (std::uint32_t v : row) corners.push_back(point[v]);
      face_surface[f] = look.face_of(std::move(corners));
      child_layer[child] = 2 * lo;
      child_point[child] = nvs + nes + face_surface[f];
      continue;
    }
    side[f] = 1;
    for (std::size_t i = 0; i < row.size(); ++i) {
      const std::uint32_t a = row[i], b = row[(i + 1) % row.size()];
      if (layer[a] != layer[b]) continue;
      face_surface[f] = look.edge_of(point[a], point[b]);
      break;
    }
    child_layer[child] = 2 * interval_of(lo, hi, layers, cyclic) + 1;
    child_point[child] = nvs + face_surface[f];
  }
  for (std::uint32_t k = 0; k < lat.num_cells(); ++k) {
    std::uint32_t sface = 0, interval = 0;
    for (std::uint32_t f : lat.cell_faces.row(k)) {
      if (!side[f]) {
        sface = face_surface[f];
      } else {
        const auto row = lat.faces.row(f);
        std::uint32_t lo = layer[row[0]], hi = lo;
        for (std::uint32_t v : row) lo = std::min(lo, layer[v]), hi = std::max(hi, layer[v]);
        interval = interval_of(lo, hi, layers, cyclic);
      }
    }
    child_layer[nv + ne + nf + k] = 2 * interval + 1;
    child_point[nv + ne + nf + k] = nvs + nes + sface;
  }
}

}  // namespace

Complex sweep_lattice(const Complex& surface, int base_steps, bool cyclic) {
  if (surface.dim != 2) throw Error("a space-time lattice sweeps a surface (this complex has dimension " + std::to_string(surface.dim) + ")");
  if (base_steps < (cyclic ? 3 : 1))
    throw Error(std::string("a ") + (cyclic ? "cyclic" : "open") + " space-time lattice needs at least " + (cyclic ? "3" : "1") +
                " base time steps (got " + std::to_string(base_steps) + ")");
  const std::uint32_t nv = surface.num_vertices, ne = surface.num_edges(), nf = surface.num_faces();
  const std::uint32_t steps = std::uint32_t(base_steps), layers = cyclic ? steps : steps + 1;
  auto id = [&](std::uint32_t t, std::uint32_t p) { return (t % layers) * nv + p; };
  Csr loops, cells;
  for (std::uint32_t t = 0; t < layers; ++t)  // layer faces: t * nf + f
    for (std::uint32_t f = 0; f < nf; ++f) {
      for (std::uint32_t v : surface.faces.row(f)) loops.items.push_back(id(t, v));
      loops.offsets.push_back(std::uint32_t(loops.items.size()));
    }
  for (std::uint32_t t = 0; t < steps; ++t)  // side faces: layers * nf + t * ne + e
    for (std::uint32_t e = 0; e < ne; ++e) {
      const std::uint32_t a = surface.edge_verts[2 * e], b = surface.edge_verts[2 * e + 1];
      loops.items.insert(loops.items.end(), {id(t, a), id(t, b), id(t + 1, b), id(t + 1, a)});
      loops.offsets.push_back(std::uint32_t(loops.items.size()));
    }
  for (std::uint32_t t = 0; t < steps; ++t)
    for (std::uint32_t f = 0; f < nf; ++f) {
      cells.items.push_back(t * nf + f);
      cells.items.push_back(((t + 1) % layers) * nf + f);
      for (std::uint32_t e : surface.face_edges.row(f)) cells.items.push_back(layers * nf + t * ne + e);
      cells.offsets.push_back(std::uint32_t(cells.items.size()));
    }
  // The surface's features swept: a crease or boundary edge stays a crease on the first and last
  // frames (open) and sweeps into a feature face; a corner sweeps into a crease in time. So every
  // layer keeps the surface's feature curves and the caps do not round over their rims.
  FeatureTags tags;
  for (std::uint32_t e = 0; e < ne; ++e) {
    if (surface.edge_dim[e] != 1) continue;
    const std::uint32_t a = surface.edge_verts[2 * e], b = surface.edge_verts[2 * e + 1];
    if (!cyclic)
      for (std::uint32_t t : {0u, layers - 1}) tags.crease_edges.emplace_back(id(t, a), id(t, b));
    for (std::uint32_t t = 0; t < steps; ++t) {
      const auto row = loops.row(layers * nf + t * ne + e);
      tags.feature_faces.emplace_back(row.begin(), row.end());
    }
  }
  for (std::uint32_t p = 0; p < nv; ++p) {
    if (surface.vertex_dim[p] != 0) continue;
    for (std::uint32_t t = 0; t < steps; ++t) tags.crease_edges.emplace_back(id(t, p), id(t + 1, p));
    if (!cyclic) tags.corner_vertices.insert(tags.corner_vertices.end(), {id(0, p), id(layers - 1, p)});
  }
  try {
    return complex_from_cells(layers * nv, loops, cells, tags);
  } catch (const TopologyError& e) {
    throw Error(std::string("sweeping the surface into a space-time lattice: ") + e.what());
  }
}

int SpaceTime::layers(int level) const { return space_time_frames(base_steps, level, cyclic); }

int space_time_frames(int base_steps, int levels, bool cyclic) { return (base_steps << levels) + (cyclic ? 0 : 1); }

std::optional<int> space_time_base_steps(int frames, int levels, bool cyclic) {
  const int intervals = cyclic ? frames : frames - 1;
  const int step = 1 << levels;
  if (intervals < step || intervals % step != 0) return std::nullopt;
  const int k = intervals / step;
  if (k < (cyclic ? 3 : 1)) return std::nullopt;
  return k;
}

namespace {

SpaceTime build_space_time(const Complex& surface, int base_steps, bool cyclic, int levels, Scheme scheme, int channels) {
  if (scheme != Scheme::Linear && scheme != Scheme::Cubic)
    throw Error("a space-time lattice refines with the linear or cubic scheme (not " + scheme_name(scheme) + ")");
  SpaceTime st;
  st.surface = surface;
  st.base_steps = base_steps;
  st.cyclic = cyclic;
  st.lattice = make_hierarchy(sweep_lattice(surface, base_steps, cyclic), levels, scheme, channels);
  st.surface_levels = make_hierarchy(surface, levels, scheme, 3);
  st.layer_vertices.resize(std::size_t(levels) + 1);
  const std::uint32_t nv0 = surface.num_vertices;
  std::vector<std::uint32_t> layer(st.lattice.num_vertices(0)), point(layer.size());
  for (std::uint32_t v = 0; v < layer.size(); ++v) layer[v] = v / nv0, point[v] = v % nv0;
  for (int j = 0;; ++j) {
    const std::uint32_t nvs = st.surface_vertices(j), n = std::uint32_t(st.layers(j));
    if (std::size_t(n) * nvs != layer.size())
      throw Error("space-time map: level " + std::to_string(j) + " has " + std::to_string(layer.size()) + " vertices, not " +
                  std::to_string(n) + " layers of " + std::to_string(nvs));
    auto& lv = st.layer_vertices[std::size_t(j)];
    lv.assign(layer.size(), ~0u);
    for (std::uint32_t v = 0; v < layer.size(); ++v) {
      if (layer[v] >= n || point[v] >= nvs)
        throw Error("space-time map: level " + std::to_string(j) + " vertex " + std::to_string(v) + " maps to layer " +
                    std::to_string(layer[v]) + " point " + std::to_string(point[v]) + " (of " + std::to_string(n) + " x " +
                    std::to_string(nvs) + ")");
      lv[std::size_t(layer[v]) * nvs + point[v]] = v;
    }
    if (std::find(lv.begin(), lv.end(), ~0u) != lv.end())
      throw Error("space-time map: level " + std::to_string(j) + " does not cover every layer vertex");
    if (j == levels) break;
    std::vector<std::uint32_t> child_layer, child_point;
    map_children(st.lattice.levels[std::size_t(j)], st.surface_levels.levels[std::size_t(j)], n, cyclic, layer, point,
                 child_layer, child_point);
    layer.swap(child_layer);
    point.swap(child_point);
  }
  return st;
}

// Base steps within which the ends of an open sweep change a static lattice's finest layers
// (the cubic rule's reach summed over the levels is under 2 base steps; 3 leaves a margin that
// SpaceTimeFit.StaticAnimationHasZeroTimeWavelets checks on a long sweep).
constexpr int kEndReach = 3;
// Doubles of one helper synthesis (one array; the hierarchy holds a second).
constexpr double kFillBudget = 16e6;

// One helper lattice and the finest layers it fills: layer `source[i]` of the helper's finest
// level for the frame of finest layer `target[i]`.
struct FillJob {
  SpaceTime helper;
  std::vector<int> target, source;
};

}  // namespace

SpaceTime make_space_time(const Complex& surface, int base_steps, bool cyclic, int levels, Scheme scheme) {
  return build_space_time(surface, base_steps, cyclic, levels, scheme, 3);
}

std::vector<double> subdivide_frame(const SpaceTime& st, std::span<const double> base_values, int level) {
  const Hierarchy& h = st.surface_levels;
  if (base_values.size() != 3 * std::size_t(h.num_vertices(0)))
    throw Error("a frame holds " + std::to_string(base_values.size() / 3) + " vertices, the base mesh " +
                std::to_string(h.num_vertices(0)));
  std::vector<double> x(3 * std::size_t(h.num_vertices(level)), 0.0);
  std::copy(base_values.begin(), base_values.end(), x.begin());
  for (int j = 0; j < level; ++j) synthesize_transition(h, j, x.data(), 3, false, true);
  return x;
}

std::vector<double> fill_layers(const SpaceTime& st, std::span<const double> frames) {
  const int J = st.levels(), n = st.layers(J), K = st.base_steps, period = 1 << J;
  const std::uint32_t nv0 = st.surface_vertices(0), nvs = st.surface_vertices(J);
  if (frames.size() != std::size_t(n) * nv0 * 3)
    throw Error("the space-time lattice has " + std::to_string(n) + " finest layers of " + std::to_string(nv0) +
                " vertices; the frames hold " + std::to_string(frames.size() / 3) + " vertex positions");
  // Layer t of the static lattice's finest level depends on t only through t mod 2^J and the
  // distance to an open end, so small helpers serve every layer: a 3-step cyclic sweep for the
  // interior, an open sweep of at most 2 kEndReach steps for the ends.
  const Scheme scheme = st.lattice.scheme;
  std::vector<FillJob> jobs;
  auto helper = [&](int steps, bool cyc) {
    jobs.push_back({build_space_time(st.surface, steps, cyc, J, scheme, 3), {}, {}});
    return &jobs.back();
  };
  jobs.reserve(2);
  if (!st.cyclic && K <= 2 * kEndReach) {
    FillJob* all = helper(K, false);
    for (int t = 0; t < n; ++t) all->target.push_back(t), all->source.push_back(t);
  } else {
    FillJob* inner = helper(3, true);
    FillJob* ends = st.cyclic ? nullptr : helper(2 * kEndReach, false);
    const int reach = kEndReach * period, ends_n = ends ? ends->helper.layers(J) : 0;
    for (int t = 0; t < n; ++t) {
      if (ends && t < reach) ends->target.push_back(t), ends->source.push_back(t);
      else if (ends && t > n - 1 - reach) ends->target.push_back(t), ends->source.push_back(t - n + ends_n);
      else inner->target.push_back(t), inner->source.push_back(t % period);
    }
  }
  std::vector<double> finest(3 * std::size_t(st.lattice.num_vertices(J)));
  const auto& lv = st.layer_vertices[std::size_t(J)];
  for (FillJob& job : jobs) {
    const std::size_t helper_vertices = job.helper.lattice.num_vertices(J);
    const std::size_t batch = std::clamp<std::size_t>(std::size_t(kFillBudget / (3.0 * double(helper_vertices))), 1, 32);
    for (std::size_t first = 0; first < job.target.size(); first += batch) {
      const std::size_t count = std::min(batch, job.target.size() - first);
      const int channels = int(3 * count);
      Hierarchy& h = job.helper.lattice;
      if (h.channels != channels) {  // the last batch may be smaller: rebuild with its channel count
        job.helper = build_space_time(st.surface, job.helper.base_steps, job.helper.cyclic, J, scheme, channels);
      }
      const std::uint32_t nl0 = job.helper.lattice.num_vertices(0);
      std::vector<double> base(std::size_t(nl0) * channels);
      for (std::uint32_t v = 0; v < nl0; ++v)
        for (std::size_t b = 0; b < count; ++b) {
          const double* g = &frames[(std::size_t(job.target[first + b]) * nv0 + v % nv0) * 3];
          std::copy_n(g, 3, &base[std::size_t(v) * channels + 3 * b]);
        }
      set_base(job.helper.lattice, base);
      const std::vector<double> x = synthesize(job.helper.lattice, J);
      const auto& hv = job.helper.layer_vertices[std::size_t(J)];
      for (std::size_t b = 0; b < count; ++b) {
        const std::size_t t = std::size_t(job.target[first + b]), src = std::size_t(job.source[first + b]);
        for (std::uint32_t p = 0; p < nvs; ++p)
          std::copy_n(&x[std::size_t(hv[src * nvs + p]) * channels + 3 * b], 3, &finest[3 * std::size_t(lv[t * nvs + p])]);
      }
    }
  }
  return finest;
}

FitReport fit_frames(SpaceTime& st, std::span<const double> frames) {
  const int J = st.levels();
  const std::vector<double> finest = fill_layers(st, frames);
  analyze(st.lattice, finest);
  const std::vector<double> back = synthesize(st.lattice, J);
  FitReport r;
  for (std::size_t i = 0; i < back.size(); ++i) r.max_error = std::max(r.max_error, std::abs(back[i] - finest[i]));
  const std::uint32_t nv0 = st.surface_vertices(0);
  for (int t = 0; t < st.layers(J); ++t) {
    const std::vector<double> own = subdivide_frame(st, frames.subspan(std::size_t(t) * nv0 * 3, std::size_t(nv0) * 3), J);
    const std::vector<double> layer = layer_positions(st, finest, J, t);
    for (std::size_t i = 0; i < own.size(); i += 3)
      r.max_surface_gap = std::max(r.max_surface_gap, std::hypot(own[i] - layer[i], own[i + 1] - layer[i + 1], own[i + 2] - layer[i + 2]));
  }
  return r;
}

std::vector<double> layer_positions(const SpaceTime& st, std::span<const double> level_values, int level, int layer) {
  const std::uint32_t nvs = st.surface_vertices(level);
  if (level_values.size() != 3 * std::size_t(st.lattice.num_vertices(level)) || layer < 0 || layer >= st.layers(level))
    throw Error("layer " + std::to_string(layer) + " of level " + std::to_string(level) + ": values or layer out of range");
  const auto& lv = st.layer_vertices[std::size_t(level)];
  std::vector<double> out(3 * std::size_t(nvs));
  for (std::uint32_t p = 0; p < nvs; ++p)
    std::copy_n(&level_values[3 * std::size_t(lv[std::size_t(layer) * nvs + p])], 3, &out[3 * std::size_t(p)]);
  return out;
}

std::vector<double> frame_positions(const SpaceTime& st, std::span<const double> finest_values, double frame) {
  const int J = st.levels(), n = st.layers(J);
  if (!std::isfinite(frame)) throw Error("frame is not a number");
  double f = st.cyclic ? std::fmod(frame, double(n)) : std::clamp(frame, 0.0, double(n - 1));
  if (f < 0) f += n;
  const int a = std::min(int(std::floor(f)), n - 1), b = st.cyclic ? (a + 1) % n : std::min(a + 1, n - 1);
  const double s = f - a;
  std::vector<double> x = layer_positions(st, finest_values, J, a);
  if (s == 0.0) return x;
  const std::vector<double> y = layer_positions(st, finest_values, J, b);
  for (std::size_t i = 0; i < x.size(); ++i) x[i] += s * (y[i] - x[i]);
  return x;
}

int nearest_layer(const SpaceTime& st, int level, double frame) {
  const int J = st.levels(), stride = 1 << (J - level), n = st.layers(level);
  const long long l = std::llround(frame / stride);
  if (st.cyclic) return int(((l % n) + n) % n);
  return int(std::clamp<long long>(l, 0, n - 1));
}

std::vector<std::uint8_t> time_wavelet_flags(const SpaceTime& st) {
  const int J = st.levels();
  const std::uint32_t nv0 = st.lattice.num_vertices(0);
  std::vector<std::uint8_t> flags(st.lattice.num_vertices(J) - nv0, 0);
  for (int j = 1; j <= J; ++j) {
    const std::uint32_t nvs = st.surface_vertices(j), lo = st.lattice.num_vertices(j - 1);
    const auto& lv = st.layer_vertices[std::size_t(j)];
    for (std::size_t i = 0; i < lv.size(); ++i)
      if (lv[i] >= lo && (i / nvs) % 2 == 1) flags[lv[i] - nv0] = 1;
  }
  return flags;
}

}  // namespace sublift
