// Level detection: split into connected components, coarsen each greedily (of the four seed
// labellings that pass the local checks, the one whose old vertices hold the most
// extraordinary vertices: extraordinary vertices of a split mesh are never edge points, and
// preferring them as old vertices picks the cube over the octahedron for a refined cube), then
// join the components' levels. engine_order composes the per-level labels top-down onto
// Sublift's own refinement of the base.
#include "core/complex/detect_levels.h"

#include <algorithm>
#include <string>

#include "core/base/bounds.h"
#include "core/base/errors.h"
#include "core/base/parallel.h"
#include "core/complex/coarsen.h"
#include "core/complex/complex_build.h"
#include "core/complex/refine_sqrt2.h"

namespace sublift {

namespace detect {

Star build_star(const Mesh& m) {
  Star s;
  s.vertex_faces = transpose(m.faces, m.n);
  s.boundary.assign(m.n, 0);
  // A vertex is on the boundary when some neighbour across a face edge is seen only once.
  std::vector<std::uint32_t> nb;
  for (std::uint32_t v = 0; v < m.n; ++v) {
    nb.clear();
    for (std::uint32_t f : s.vertex_faces.row(v)) {
      const auto q = m.faces.row(f);
      const unsigned k = corner_of(q, v), sz = static_cast<unsigned>(q.size());
      nb.push_back(q[(k + 1) % sz]);
      nb.push_back(q[(k + sz - 1) % sz]);
    }
    std::sort(nb.begin(), nb.end());
    for (std::size_t i = 0; i < nb.size();) {
      std::size_t j = i;
      while (j < nb.size() && nb[j] == nb[i]) ++j;
      if (j - i == 1) s.boundary[v] = 1;
      i = j;
    }
  }
  return s;
}

bool fan_corners(const Mesh& m, const Star& s, std::uint32_t v, unsigned offset, std::vector<std::uint32_t>& out) {
  const auto fs = s.vertex_faces.row(v);
  std::uint32_t f = fs[0];
  for (std::size_t step = 0; step < fs.size(); ++step) {
    const auto q = m.faces.row(f);
    const unsigned k = corner_of(q, v);
    out.push_back(q[(k + offset) & 3u]);
    const std::uint32_t before = q[(k + 3) & 3u];
    std::uint32_t next = UINT32_MAX;
    for (std::uint32_t g : fs) {
      const auto r = m.faces.row(g);
      if (r[(corner_of(r, v) + 1) & 3u] == before) next = g;
    }
    if (next == UINT32_MAX || (next == fs[0]) != (step + 1 == fs.size())) return false;
    f = next;
  }
  return true;
}

bool has_repeat(std::vector<std::uint32_t>& ends) {
  std::sort(ends.begin(), ends.end());
  return std::adjacent_find(ends.begin(), ends.end()) != ends.end();
}

void name_coarse_vertices(std::span<const std::uint32_t> input, const std::vector<std::uint8_t>& labels,
                          const std::vector<std::uint32_t>& coarse_id, std::uint32_t num_coarse, Coarsening& c) {
  c.coarse_vertices = num_coarse;
  c.input_vertex.resize(num_coarse);
  for (std::size_t v = 0; v < input.size(); ++v)
    if (labels[v] == Coarsening::Old) c.input_vertex[coarse_id[v]] = input[v];
}

}  // namespace detect

namespace {

using detect::Attempt;
using detect::Mesh;

std::string count_phrase(std::uint32_t n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

// Why a mesh of the wrong face shapes cannot be a split; empty when every face fits.
std::string shape_problem(const Mesh& m, SplitKind split, std::uint32_t& where) {
  const unsigned want = split == SplitKind::Triangles ? 3 : 4;
  std::uint32_t good = 0, tris = 0, quads = 0, other = 0;
  where = UINT32_MAX;
  for (std::size_t f = 0; f < m.faces.rows(); ++f) {
    const unsigned sz = m.faces.size(f);
    if (sz == want || (split == SplitKind::Sqrt2 && sz == 3)) {  // sqrt(2): a keep step's triangles
      ++good;
      continue;
    }
    (sz == 3 ? tris : sz == 4 ? quads : other)++;
    if (where == UINT32_MAX) where = m.input[m.faces.row(f)[0]];
  }
  if (where == UINT32_MAX) return "";
  std::string odd;
  if (tris) odd = count_phrase(tris, "triangle", "triangles");
  if (quads) odd += (odd.empty() ? "" : " and ") + count_phrase(quads, "quad", "quads");
  if (other) odd += (odd.empty() ? "" : " and ") + count_phrase(other, "polygon of more than 4 sides", "polygons of more than 4 sides");
  const char* kind = want == 4 ? "quads" : "triangles";
  const char* maker = split == SplitKind::Quads ? "a quad split" : split == SplitKind::Triangles ? "a triangle split" : "a sqrt(2) step";
  if (good == 0) return std::string("its faces are not ") + kind + ", as " + maker + " makes them";
  return odd + " among " + std::to_string(good) + " " + kind + " near vertex " + std::to_string(where);
}

// Vertex ids sorted along a Morton curve of their positions (30-bit codes, two counting-sort
// passes of 15 bits): neighbours in space, and so mostly in the mesh, get nearby ids.
std::vector<std::uint32_t> morton_order(std::span<const double> p, std::uint32_t n) {
  const auto [lo, hi] = bounding_box(p.data(), n);
  std::vector<std::uint32_t> code(n);
  for (std::uint32_t v = 0; v < n; ++v) {
    std::uint32_t c = 0;
    for (int k = 0; k < 3; ++k) {
      const double span = hi[k] - lo[k];
      const double t = span > 0 ? (p[3 * std::size_t(v) + k] - lo[k]) / span : 0.0;
      auto q = static_cast<std::uint32_t>(std::clamp(t, 0.0, 1.0) * 1023.0);
      for (int b = 0; b < 10; ++b) c |= ((q >> b) & 1u) << (3 * b + k);
    }
    code[v] = c;
  }
  std::vector<std::uint32_t> order(n), tmp(n);
  for (std::uint32_t v = 0; v < n; ++v) tmp[v] = v;
  for (int pass = 0; pass < 2; ++pass) {
    const int shift = 15 * pass;
    std::vector<std::uint32_t> count((1u << 15) + 1, 0);
    for (std::uint32_t v : tmp) ++count[((code[v] >> shift) & 0x7fffu) + 1];
    for (std::size_t i = 1; i < count.size(); ++i) count[i] += count[i - 1];
    for (std::uint32_t v : tmp) order[count[(code[v] >> shift) & 0x7fffu]++] = v;
    tmp.swap(order);
  }
  return tmp;
}

struct Chain {
  std::vector<Attempt> steps;  // steps[t]: the t-th coarsening from the finest
  std::string stop;
  std::uint32_t stop_vertex = UINT32_MAX;
  // sqrt(2): whether the finest level's parity is known (from a keep or curve step) and odd.
  bool parity_known = false, top_odd = false;
};

// How far the new points lie from where linear refinement puts them (squared, summed): edge
// points from the midpoints of their edges, face points from the centroids of their faces.
// The old vertices' positions in the coarse numbering (the next mesh's xyz).
std::vector<double> coarse_xyz(const Mesh& m, const Coarsening& c) {
  std::vector<double> out(3 * std::size_t(c.coarse_vertices));
  for (std::uint32_t v = 0; v < m.n; ++v)
    if (c.kind[v] == Coarsening::Old)
      for (int k = 0; k < 3; ++k) out[3 * std::size_t(c.a[v]) + k] = m.xyz[3 * std::size_t(v) + k];
  return out;
}

double midpoint_residual(const Mesh& m, const Coarsening& c, const std::vector<double>& cx) {
  if (m.xyz.empty()) return 0;
  double r = 0;
  auto pos = [&](std::uint32_t coarse_vertex) { return &cx[3 * std::size_t(coarse_vertex)]; };
  for (std::uint32_t v = 0; v < m.n; ++v) {
    if (c.kind[v] == Coarsening::Old || c.kind[v] == Coarsening::CellPoint) continue;
    double want[3] = {0, 0, 0};
    if (c.kind[v] == Coarsening::EdgePoint) {
      for (int k = 0; k < 3; ++k) want[k] = 0.5 * (pos(c.a[v])[k] + pos(c.b[v])[k]);
    } else {
      const auto corners = c.coarse_faces.row(c.a[v]);
      for (std::uint32_t w : corners)
        for (int k = 0; k < 3; ++k) want[k] += pos(w)[k] / double(corners.size());
    }
    const double* x = &m.xyz[3 * std::size_t(v)];
    for (int k = 0; k < 3; ++k) r += (x[k] - want[k]) * (x[k] - want[k]);
  }
  return r;
}

// Runs the labellings 0..n-1 (two threads take them in turn; `run` must not share state) and
// keeps the best that passes: the highest score, then the lowest midpoint residual of `m`.
// `failed` gets the failure that got furthest, for the message.
template <class Run>
Attempt best_labelling(std::uint32_t n, const Mesh& m, Run run, Attempt& failed) {
  std::vector<Attempt> tries(n);
  std::vector<double> residual(n, 0.0);
  parallel_for(n, 1, [&](std::uint32_t b, std::uint32_t e) {
    for (std::uint32_t cand = b; cand < e; ++cand) {
      try {
        tries[cand] = run(int(cand));
        if (tries[cand].ok && !m.xyz.empty()) {
          tries[cand].coarse_xyz = coarse_xyz(m, tries[cand].c);
          residual[cand] = midpoint_residual(m, tries[cand].c, tries[cand].coarse_xyz);
        }
      } catch (const std::exception& ex) {  // out of memory: parallel_for bodies must not throw
        tries[cand] = Attempt{};
        tries[cand].why = ex.what();
      }
    }
  });
  Attempt best;
  double best_residual = 0;
  for (std::uint32_t cand = 0; cand < n; ++cand) {
    Attempt& a = tries[cand];
    if (a.ok) {
      if (!best.ok || a.score > best.score || (a.score == best.score && residual[cand] < best_residual)) {
        best_residual = residual[cand];
        best = std::move(a);
      }
    } else if (!a.why.empty() && (failed.why.empty() || a.progress > failed.progress)) {
      failed = std::move(a);
    }
  }
  return best;
}

Chain coarsen_component(Mesh m, SplitKind split, int limit, const std::function<bool(std::uint32_t)>& keep_going) {
  Chain ch;
  while (static_cast<int>(ch.steps.size()) < limit) {
    if (keep_going && !keep_going(m.n)) throw Cancelled("rebuild cancelled");
    const std::string below = ch.steps.empty() ? std::string("the mesh")
                                                : "the mesh " + std::to_string(ch.steps.size()) + " level" + (ch.steps.size() == 1 ? "" : "s") + " down";
    std::uint32_t where = UINT32_MAX;
    if (std::string why = shape_problem(m, split, where); !why.empty()) {
      ch.stop = below + ": " + why;
      ch.stop_vertex = where;
      break;
    }
    const detect::Star star = detect::build_star(m);
    // The four labellings are independent (sqrt(2) has two).
    Attempt failed;
    Attempt best = best_labelling(split == SplitKind::Sqrt2 ? 2 : 4, m, [&](int cand) {
      return split == SplitKind::Quads       ? detect::coarsen_quads(m, star, cand)
             : split == SplitKind::Triangles ? detect::coarsen_tris(m, star, cand)
                                             : detect::coarsen_sqrt2(m, star, cand);
    }, failed);
    if (!best.ok) {
      ch.stop = below + ": " + failed.why;
      ch.stop_vertex = failed.where;
      break;
    }
    if (split == SplitKind::Sqrt2 && (best.keep_step || best.curve_step)) {
      // Keep steps leave odd levels, curve steps even ones, and levels alternate.
      const bool fine_odd = best.keep_step;
      const bool expected_odd = ch.parity_known ? (ch.top_odd != (ch.steps.size() % 2 == 1)) : fine_odd;
      if (fine_odd != expected_odd) {
        ch.stop = below + ": its " + (fine_odd ? "triangles" : "boundary points") + " do not fit the sqrt(2) level it would be";
        ch.stop_vertex = m.input[0];
        break;
      }
      if (!ch.parity_known) ch.parity_known = true, ch.top_odd = fine_odd != (ch.steps.size() % 2 == 1);
    }
    Mesh next;
    next.n = best.c.coarse_vertices;
    next.faces = best.c.coarse_faces;
    next.input = best.c.input_vertex;
    next.xyz = std::move(best.coarse_xyz);
    ch.steps.push_back(std::move(best));
    m = std::move(next);
  }
  return ch;
}

}  // namespace

DetectedLevels detect_levels(std::uint32_t num_vertices, const Csr& faces, SplitKind split, int max_levels,
                             std::span<const double> positions, const std::function<bool(double)>& keep_going) {
  if (!positions.empty() && positions.size() != 3 * std::size_t(num_vertices))
    throw Error("detect_levels: " + std::to_string(positions.size()) + " coordinates for " + std::to_string(num_vertices) + " vertices");
  for (std::size_t f = 0; f < faces.rows(); ++f) {
    if (faces.size(f) < 3) throw TopologyError("face " + std::to_string(f) + " has fewer than 3 corners");
    for (std::uint32_t v : faces.row(f))
      if (v >= num_vertices) throw TopologyError("face " + std::to_string(f) + " names vertex " + std::to_string(v) + " of " + std::to_string(num_vertices));
  }
  // With positions, large meshes are first renumbered along a Morton curve (working ids):
  // files come in any order, and every pass below touches neighbours, so even the first one
  // then finds them in cache. in_id maps a working id back to the input's.
  std::vector<std::uint32_t> to_input;
  Csr renumbered;
  const Csr* wf = &faces;
  if (!positions.empty() && num_vertices >= (1u << 16)) {
    to_input = morton_order(positions, num_vertices);
    std::vector<std::uint32_t> rank(num_vertices);
    for (std::uint32_t i = 0; i < num_vertices; ++i) rank[to_input[i]] = i;
    renumbered.offsets = faces.offsets;
    renumbered.items.resize(faces.items.size());
    for (std::size_t j = 0; j < faces.items.size(); ++j) renumbered.items[j] = rank[faces.items[j]];
    wf = &renumbered;
  }
  auto in_id = [&](std::uint32_t w) { return to_input.empty() ? w : to_input[w]; };
  const Csr& work = *wf;
  const Csr vf = transpose(work, num_vertices);
  for (std::uint32_t v = 0; v < num_vertices; ++v)
    if (vf.size(v) == 0) throw TopologyError("vertex " + std::to_string(in_id(v)) + " is in no face; remove loose vertices before rebuilding levels");

  // Connected components (through shared vertices), each numbered in breadth-first order of
  // its vertices and faces: files from other tools come in any order, and the labelling passes
  // touch neighbours, so this order keeps them in cache (4x faster at a million vertices).
  std::vector<std::uint32_t> comp(num_vertices, UINT32_MAX);
  std::vector<std::vector<std::uint32_t>> members, member_faces;
  std::vector<std::uint8_t> face_seen(faces.rows(), 0);
  for (std::uint32_t s = 0; s < num_vertices; ++s) {
    if (comp[s] != UINT32_MAX) continue;
    const auto id = static_cast<std::uint32_t>(members.size());
    members.emplace_back();
    member_faces.emplace_back();
    std::vector<std::uint32_t>& mem = members.back();
    comp[s] = id;
    mem.push_back(s);
    for (std::size_t head = 0; head < mem.size(); ++head)
      for (std::uint32_t f : vf.row(mem[head])) {
        if (face_seen[f]) continue;
        face_seen[f] = 1;
        member_faces[id].push_back(f);
        for (std::uint32_t w : work.row(f))
          if (comp[w] == UINT32_MAX) comp[w] = id, mem.push_back(w);
      }
  }
  std::vector<std::uint32_t> local(num_vertices);
  for (const auto& mem : members)
    for (std::uint32_t i = 0; i < mem.size(); ++i) local[mem[i]] = i;

  DetectedLevels d;
  d.split = split;
  std::vector<Chain> chains;
  std::vector<Mesh> finest(members.size());
  for (std::size_t k = 0; k < members.size(); ++k) {
    Mesh& m = finest[k];
    m.n = static_cast<std::uint32_t>(members[k].size());
    m.input.resize(m.n);
    for (std::uint32_t i = 0; i < m.n; ++i) m.input[i] = in_id(members[k][i]);
    if (!positions.empty()) {
      m.xyz.resize(3 * std::size_t(m.n));
      for (std::uint32_t i = 0; i < m.n; ++i)
        for (int c = 0; c < 3; ++c) m.xyz[3 * std::size_t(i) + c] = positions[3 * std::size_t(m.input[i]) + c];
    }
  }
  for (std::size_t k = 0; k < members.size(); ++k) {
    Mesh& m = finest[k];
    for (std::uint32_t f : member_faces[k]) {
      for (std::uint32_t v : work.row(f)) m.faces.items.push_back(local[v]);
      m.faces.offsets.push_back(static_cast<std::uint32_t>(m.faces.items.size()));
    }
  }
  int levels = max_levels;
  // Work is about 4/3 of the vertices per component (each level a quarter of the one above).
  double done = 0;
  const double total = std::max(1.0, 4.0 / 3.0 * num_vertices);
  const std::function<bool(std::uint32_t)> step = [&](std::uint32_t n) {
    const bool go = !keep_going || keep_going(std::min(1.0, done / total));
    done += n;
    return go;
  };
  for (std::size_t k = 0; k < members.size(); ++k) {
    ComponentLevels cl;
    cl.vertices = finest[k].n;
    cl.faces = static_cast<std::uint32_t>(finest[k].faces.rows());
    cl.first_vertex = *std::min_element(finest[k].input.begin(), finest[k].input.end());
    chains.push_back(coarsen_component(std::move(finest[k]), split, max_levels, step));
    cl.levels = static_cast<int>(chains.back().steps.size());
    cl.stop = chains.back().stop;
    if (cl.levels < levels) {
      levels = cl.levels;
      d.stop = (members.size() > 1 ? "the piece with vertex " + std::to_string(cl.first_vertex) + ": " : std::string()) + cl.stop;
      d.stop_vertex = chains.back().stop_vertex;
    }
    d.components.push_back(std::move(cl));
  }
  if (levels == max_levels) {
    d.stop.clear();
    d.stop_vertex = UINT32_MAX;
  }
  d.levels = levels;
  // sqrt(2): the base's level parity from the pieces whose boundaries fix it; they must agree.
  if (split == SplitKind::Sqrt2) {
    int top = -1;
    for (const Chain& ch : chains)
      if (ch.parity_known) {
        if (top >= 0 && top != int(ch.top_odd)) {
          d.levels = levels = 0;
          d.stop = "its pieces are at sqrt(2) levels of different parity";
          break;
        }
        top = int(ch.top_odd);
      }
    if (top >= 0) d.first_level = (top == 1) != (levels % 2 == 1) ? 1 : 0;
  }

  // Join the components level by level: the finest level keeps the input's numbering, coarser
  // ones put the components one after another.
  std::vector<std::uint32_t> fine_off(members.size(), 0), coarse_off(members.size()), face_off(members.size());
  d.steps.resize(static_cast<std::size_t>(levels));
  for (int t = 0; t < levels; ++t) {  // t-th coarsening from the finest: M_{L-t} -> M_{L-t-1}
    Coarsening& out = d.steps[static_cast<std::size_t>(levels - 1 - t)];
    const std::uint32_t n_fine = t == 0 ? num_vertices : d.steps[static_cast<std::size_t>(levels - t)].coarse_vertices;
    out.kind.resize(n_fine);
    out.a.resize(n_fine);
    out.b.resize(n_fine);
    out.coarse_faces.offsets.assign(1, 0);
    std::uint32_t nv = 0, nf = 0;
    for (std::size_t k = 0; k < members.size(); ++k) {
      coarse_off[k] = nv;
      face_off[k] = nf;
      const Coarsening& c = chains[k].steps[static_cast<std::size_t>(t)].c;
      nv += c.coarse_vertices;
      nf += static_cast<std::uint32_t>(c.coarse_faces.rows());
    }
    out.coarse_vertices = nv;
    out.input_vertex.reserve(nv);
    for (std::size_t k = 0; k < members.size(); ++k) {
      const Coarsening& c = chains[k].steps[static_cast<std::size_t>(t)].c;
      for (std::uint32_t i = 0; i < c.kind.size(); ++i) {
        const std::uint32_t g = t == 0 ? in_id(members[k][i]) : fine_off[k] + i;
        out.kind[g] = c.kind[i];
        const std::uint32_t off = c.kind[i] == Coarsening::FacePoint ? face_off[k] : coarse_off[k];
        out.a[g] = off + c.a[i];
        out.b[g] = off + c.b[i];
      }
      for (std::uint32_t x : c.coarse_faces.items) out.coarse_faces.items.push_back(coarse_off[k] + x);
      for (std::size_t f = 0; f < c.coarse_faces.rows(); ++f)
        out.coarse_faces.offsets.push_back(out.coarse_faces.offsets.back() + c.coarse_faces.size(f));
      out.input_vertex.insert(out.input_vertex.end(), c.input_vertex.begin(), c.input_vertex.end());
    }
    fine_off = coarse_off;
  }
  d.base_vertices = levels > 0 ? d.steps.front().coarse_vertices : num_vertices;
  d.base_faces = levels > 0 ? d.steps.front().coarse_faces : faces;
  return d;
}

DetectedLevels detect_volume_levels(const Complex& fine, int max_levels, std::span<const double> positions,
                                    const std::function<bool(double)>& keep_going) {
  if (fine.dim != 3) throw TopologyError("detect_volume_levels takes a volume lattice");
  DetectedLevels d;
  d.split = SplitKind::Hexes;
  ComponentLevels piece;
  piece.vertices = fine.num_vertices;
  piece.faces = fine.num_faces();
  std::vector<Coarsening> chain;  // from the finest down
  Complex m = fine;
  std::vector<std::uint32_t> input(fine.num_vertices);
  for (std::uint32_t v = 0; v < fine.num_vertices; ++v) input[v] = v;
  double done = 0;
  const double total = std::max(1.0, 8.0 / 7.0 * fine.num_vertices);
  while (static_cast<int>(chain.size()) < max_levels) {
    if (keep_going && !keep_going(std::min(1.0, done / total))) throw Cancelled("rebuild cancelled");
    done += m.num_vertices;
    const std::string below = chain.empty() ? std::string("the lattice")
                                            : "the lattice " + std::to_string(chain.size()) + " level" + (chain.size() == 1 ? "" : "s") + " down";
    std::uint32_t odd = UINT32_MAX;
    for (std::uint32_t k = 0; k < m.num_cells() && odd == UINT32_MAX; ++k)
      if (m.cell_verts.size(k) != 8 || m.cell_faces.size(k) != 6) odd = k;
    if (odd != UINT32_MAX) {
      d.stop = below + ": cell " + std::to_string(odd) + " is not a hexahedron, as a 1-to-8 split of simple cells makes them";
      d.stop_vertex = input[m.cell_verts.row(odd)[0]];
      break;
    }
    Mesh named;  // what midpoint_residual reads: the count and the positions
    named.n = m.num_vertices;
    if (!positions.empty()) {
      named.xyz.resize(3 * std::size_t(m.num_vertices));
      for (std::uint32_t v = 0; v < m.num_vertices; ++v)
        for (int k = 0; k < 3; ++k) named.xyz[3 * std::size_t(v) + k] = positions[3 * std::size_t(input[v]) + k];
    }
    Attempt failed;
    Attempt best = best_labelling(8, named, [&](int cand) { return detect::coarsen_hexes(m, input, cand); }, failed);
    if (!best.ok) {
      d.stop = below + ": " + failed.why;
      d.stop_vertex = failed.where;
      break;
    }
    Complex next;
    try {
      next = complex_from_cells(best.c.coarse_vertices, best.c.coarse_faces, best.c.coarse_cells);
    } catch (const TopologyError& e) {
      d.stop = below + ": the coarser lattice would not be valid (" + e.what() + ")";
      break;
    }
    input = best.c.input_vertex;
    chain.push_back(std::move(best.c));
    m = std::move(next);
  }
  if (static_cast<int>(chain.size()) == max_levels) d.stop.clear(), d.stop_vertex = UINT32_MAX;
  d.levels = static_cast<int>(chain.size());
  piece.levels = d.levels;
  piece.stop = d.stop;
  d.components.push_back(piece);
  d.steps.assign(std::make_move_iterator(chain.rbegin()), std::make_move_iterator(chain.rend()));
  const bool coarser = d.levels > 0;
  d.base_vertices = coarser ? d.steps.front().coarse_vertices : fine.num_vertices;
  d.base_faces = coarser ? d.steps.front().coarse_faces : fine.faces;
  d.base_cells = coarser ? d.steps.front().coarse_cells : fine.cell_faces;
  return d;
}

namespace {

// The cell of c with exactly the vertices `verts` (sorted).
std::uint32_t cell_with(const Complex& c, const std::vector<std::uint32_t>& verts) {
  for (std::uint32_t k : c.vertex_cells.row(verts[0])) {
    const auto row = c.cell_verts.row(k);
    if (row.size() == verts.size() && std::is_permutation(row.begin(), row.end(), verts.begin())) return k;
  }
  throw TopologyError("rebuilt levels: a cell is missing from the engine's level");
}

std::uint32_t edge_between(const Complex& c, std::uint32_t a, std::uint32_t b) {
  for (std::uint32_t e : c.vertex_edges.row(a))
    if (c.edge_verts[2 * e] == b || c.edge_verts[2 * e + 1] == b) return e;
  throw TopologyError("rebuilt levels: no edge " + std::to_string(a) + "-" + std::to_string(b) + " in the engine's level");
}

// The face of c with exactly the corners `corners` (a quad or triangle of a refined level).
std::uint32_t face_with(const Complex& c, std::span<const std::uint32_t> corners) {
  for (std::uint32_t f : c.vertex_faces.row(corners[0])) {
    const auto q = c.faces.row(f);
    if (q.size() != corners.size()) continue;
    bool all = true;
    for (std::uint32_t x : corners) all = all && std::find(q.begin(), q.end(), x) != q.end();
    if (all) return f;
  }
  throw TopologyError("rebuilt levels: a face is missing from the engine's level");
}

}  // namespace

std::vector<std::uint32_t> engine_order(const DetectedLevels& d, std::span<const Complex> levels) {
  const auto L = static_cast<std::size_t>(d.levels);
  if (levels.size() != L + 1) throw Error("engine_order: need levels 0.." + std::to_string(L));
  // sigma: vertices of M_l -> vertices of the engine's level l; tau: faces likewise.
  std::vector<std::uint32_t> sigma(d.base_vertices), tau(d.base_faces.rows()), kappa, next_sigma, corners;
  for (std::uint32_t i = 0; i < sigma.size(); ++i) sigma[i] = i;
  for (std::uint32_t i = 0; i < tau.size(); ++i) tau[i] = i;
  // Lattices: faces of levels[0] are complex_from_cells' merged faces, found by their corners.
  if (d.split == SplitKind::Hexes)
    for (std::size_t f = 0; f < d.base_faces.rows(); ++f) {
      corners.assign(d.base_faces.row(f).begin(), d.base_faces.row(f).end());
      tau[f] = face_with(levels[0], corners);
    }
  auto cells_of = [&](const Csr& cells, const Csr& face_loops, const Complex& c) {
    std::vector<std::uint32_t> out(cells.rows()), verts;
    for (std::size_t k = 0; k < cells.rows(); ++k) {
      verts.clear();
      for (std::uint32_t f : cells.row(k))
        for (std::uint32_t v : face_loops.row(f)) verts.push_back(sigma[v]);
      std::sort(verts.begin(), verts.end());
      verts.erase(std::unique(verts.begin(), verts.end()), verts.end());
      out[k] = cell_with(c, verts);
    }
    return out;
  };
  if (d.split == SplitKind::Hexes) kappa = cells_of(d.base_cells, d.base_faces, levels[0]);
  for (std::size_t l = 1; l <= L; ++l) {
    const Coarsening& st = d.steps[l - 1];
    const Complex& coarse = levels[l - 1];
    const std::uint32_t nv = coarse.num_vertices, ne = coarse.num_edges(), nf = coarse.num_faces();
    // sqrt(2): curve steps (odd coarse levels) number curve points by curve edge and face
    // points by quad (refine_sqrt2.h); keep steps face points by face.
    std::vector<std::uint32_t> curve_rank, face_rank;
    std::uint32_t curves = 0;
    if (d.split == SplitKind::Sqrt2) {
      const bool curve_step = (d.first_level + int(l) - 1) % 2 == 1;
      curve_rank.assign(ne, UINT32_MAX);
      face_rank.resize(nf);
      std::uint32_t quads = 0;
      for (std::uint32_t e = 0; curve_step && e < ne; ++e)
        if (sqrt2_is_curve_edge(coarse, e)) curve_rank[e] = curves++;
      for (std::uint32_t f = 0; f < nf; ++f) face_rank[f] = !curve_step ? f : coarse.faces.size(f) == 4 ? quads++ : UINT32_MAX;
    }
    next_sigma.resize(st.kind.size());
    for (std::size_t v = 0; v < st.kind.size(); ++v) {
      switch (st.kind[v]) {
        case Coarsening::Old: next_sigma[v] = sigma[st.a[v]]; break;
        case Coarsening::EdgePoint: {
          const std::uint32_t e = edge_between(coarse, sigma[st.a[v]], sigma[st.b[v]]);
          next_sigma[v] = nv + (d.split == SplitKind::Sqrt2 ? curve_rank[e] : e);
          break;
        }
        case Coarsening::FacePoint:
          next_sigma[v] = d.split == SplitKind::Sqrt2 ? nv + curves + face_rank[tau[st.a[v]]] : nv + ne + tau[st.a[v]];
          break;
        default: next_sigma[v] = nv + ne + nf + kappa[st.a[v]]; break;
      }
    }
    sigma.swap(next_sigma);
    if (l < L) {  // faces of M_l are the coarse faces of the next step
      const Csr& mf = d.steps[l].coarse_faces;
      tau.resize(mf.rows());
      for (std::size_t f = 0; f < mf.rows(); ++f) {
        corners.clear();
        for (std::uint32_t v : mf.row(f)) corners.push_back(sigma[v]);
        tau[f] = face_with(levels[l], corners);
      }
      if (d.split == SplitKind::Hexes) kappa = cells_of(d.steps[l].coarse_cells, mf, levels[l]);
    }
  }
  // A bijection onto the engine's finest vertices.
  std::vector<std::uint8_t> hit(levels[L].num_vertices, 0);
  if (sigma.size() != hit.size()) throw TopologyError("rebuilt levels: vertex counts differ from the engine's refinement");
  for (std::uint32_t s : sigma) {
    if (s >= hit.size() || hit[s]) throw TopologyError("rebuilt levels: two input vertices land on one vertex of the engine's refinement");
    hit[s] = 1;
  }
  return sigma;
}

}  // namespace sublift
