#include "core/fit/base_mesh.h"

#include "core/fit/openmesh_kernel.h"  // before any other OpenMesh header
#include <OpenMesh/Tools/Decimater/Observer.hh>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <set>
#include <numbers>

#include "core/base/errors.h"
#include "core/fit/base_quads.h"
#include "core/fit/decimater.h"
#include "core/fit/decimation_mesh.h"

namespace sublift {

namespace {

using fit_detail::Decimater;
using fit_detail::Mesh;

long long euler(const Mesh& m) {
  return static_cast<long long>(m.n_vertices()) - static_cast<long long>(m.n_edges()) + static_cast<long long>(m.n_faces());
}

std::size_t boundary_loops(const Mesh& m) {
  std::vector<char> seen(m.n_halfedges(), 0);
  std::size_t loops = 0;
  for (auto h : m.halfedges()) {
    if (!m.is_boundary(h) || seen[static_cast<std::size_t>(h.idx())]) continue;
    if (m.has_edge_status() && m.status(m.edge_handle(h)).deleted()) continue;
    ++loops;
    for (auto g = h; !seen[static_cast<std::size_t>(g.idx())]; g = m.next_halfedge_handle(g)) seen[static_cast<std::size_t>(g.idx())] = 1;
  }
  return loops;
}

// The crease tags from the input's lines. A feature vertex only collapses along its line, so
// each run of input feature edges between two surviving vertices became one base edge; that
// edge is a crease (unless a boundary). OpenMesh's edge flags alone lose some: when the two
// edges of a triangle beside a collapsed edge merge, the one kept may be the unflagged one (on
// fandisk a whole crease ended at a base vertex that way).
void add_chain_creases(BaseMesh& out, const std::vector<std::uint32_t>& base_of) {
  const std::size_t nv = base_of.size();
  std::vector<std::vector<std::uint32_t>> along(nv);  // input feature neighbours
  for (std::size_t k = 0; k + 1 < out.input_feature_edges.size(); k += 2) {
    along[out.input_feature_edges[k]].push_back(out.input_feature_edges[k + 1]);
    along[out.input_feature_edges[k + 1]].push_back(out.input_feature_edges[k]);
  }
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;  // base edges and their face counts
  for (std::size_t f = 0; f < out.faces.rows(); ++f) {
    const auto r = out.faces.row(f);
    for (std::size_t k = 0; k < r.size(); ++k) ++uses[std::minmax(r[k], r[(k + 1) % r.size()])];
  }
  std::set<std::pair<std::uint32_t, std::uint32_t>> creases;
  for (const auto& [a, b] : out.tags.crease_edges) creases.insert(std::minmax(a, b));
  for (std::uint32_t a = 0; a < nv; ++a) {
    if (base_of[a] == UINT32_MAX) continue;
    for (std::uint32_t first : along[a]) {
      std::uint32_t prev = a, cur = first;
      for (std::size_t steps = 0; base_of[cur] == UINT32_MAX && along[cur].size() == 2 && steps < nv; ++steps) {
        const std::uint32_t next = along[cur][0] == prev ? along[cur][1] : along[cur][0];
        prev = cur, cur = next;
      }
      if (base_of[cur] == UINT32_MAX || cur == a) continue;
      const auto e = std::minmax(base_of[a], base_of[cur]);
      const auto it = uses.find(e);
      if (it != uses.end() && it->second == 2) creases.insert(e);
    }
  }
  out.tags.crease_edges.assign(creases.begin(), creases.end());
}

// OpenMesh's decimation observer: the collapses done so far, as a fraction of those expected,
// to the caller's callback, whose false stops the decimation. A quad base's extra rounds count
// their collapses from 0 again: the fraction reported never goes back.
struct Progress : OpenMesh::Decimater::Observer {
  const std::function<bool(double)>& report;
  std::size_t expected;
  double last = 0.0;
  bool cancelled = false;
  Progress(const std::function<bool(double)>& r, std::size_t e)
      : Observer(std::max<std::size_t>(1, e / 100)), report(r), expected(std::max<std::size_t>(1, e)) {}
  void notify(std::size_t step) override {
    last = std::max(last, std::min(1.0, double(step) / double(expected)));
    cancelled = !report(last);
  }
  bool abort() const override { return cancelled; }
};

}  // namespace

BaseMesh decimate_to_base(std::uint32_t num_vertices, const Csr& faces, std::span<const double> positions,
                          const BaseMeshOptions& options) {
  if (faces.rows() == 0) throw TopologyError("the mesh has no faces to fit");
  if (positions.size() != 3 * std::size_t(num_vertices)) throw Error("decimate_to_base: positions do not match the vertices");
  {
    std::vector<std::uint32_t> around(num_vertices, 0);
    for (std::uint32_t v : faces.items)
      if (v < num_vertices && ++around[v] > kMaxFitValence)
        throw TopologyError("vertex " + std::to_string(v) + " has more than " + std::to_string(kMaxFitValence) +
                            " faces around it; fitting takes vertices of at most that many (the decimation would take quadratic time)");
  }
  Mesh m;
  std::vector<Mesh::VertexHandle> vh(num_vertices);
  for (std::uint32_t v = 0; v < num_vertices; ++v) vh[v] = m.add_vertex({positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]});
  for (std::size_t f = 0; f < faces.rows(); ++f) {
    const auto row = faces.row(f);
    for (std::size_t k = 1; k + 1 < row.size(); ++k)
      if (!m.add_face(vh[row[0]], vh[row[k]], vh[row[k + 1]]).is_valid())
        throw TopologyError("face " + std::to_string(f) + " makes the mesh non-manifold (an edge with more than two faces, or a flipped neighbour)");
  }
  // Loose vertices are not part of the surface.
  BaseMesh out;
  out.euler_before = euler(m);
  for (auto v : m.vertices())
    if (m.is_isolated(v)) --out.euler_before;
  out.boundary_loops_before = boundary_loops(m);
  std::uint32_t used = 0;
  for (auto v : m.vertices()) used += !m.is_isolated(v);
  const std::uint32_t target = options.target_vertices ? options.target_vertices : std::max<std::uint32_t>(24, used / 64);
  if (options.target_faces == 0 && target > used)
    throw TopologyError("a base of " + std::to_string(target) + " vertices is more than the mesh's " + std::to_string(used));
  // Quads: two triangles per polygon asked for (the pairing leaves some triangles, so about).
  const std::size_t target_triangles = std::size_t(options.target_faces) * (options.quads ? 2 : 1);
  if (options.target_faces > m.n_faces())
    throw TopologyError("a base of " + std::to_string(options.target_faces) + " faces is more than the mesh's " + std::to_string(m.n_faces()));

  m.request_vertex_status();
  m.request_edge_status();
  m.request_face_status();
  m.request_face_normals();
  m.update_face_normals();
  // Feature edges: boundaries and sharp edges; their vertices may only move along them.
  const double cos_limit = std::cos(options.feature_angle_deg * std::numbers::pi / 180.0);
  for (auto e : m.edges()) {
    const auto h = m.halfedge_handle(e, 0);
    bool sharp = m.is_boundary(e);
    if (!sharp) {
      const auto n0 = m.normal(m.face_handle(h)), n1 = m.normal(m.face_handle(m.opposite_halfedge_handle(h)));
      sharp = OpenMesh::dot(n0, n1) < cos_limit;
    }
    if (!sharp) continue;
    m.status(e).set_feature(true);
    m.status(m.to_vertex_handle(h)).set_feature(true);
    m.status(m.from_vertex_handle(h)).set_feature(true);
    out.input_feature_edges.push_back(static_cast<std::uint32_t>(m.from_vertex_handle(h).idx()));
    out.input_feature_edges.push_back(static_cast<std::uint32_t>(m.to_vertex_handle(h).idx()));
  }
  // Corners: where feature lines meet or end, or where one turns by more than the feature angle
  // (a sheet's corners, a box's). They stay through the decimation and are tagged, so the schemes
  // keep them sharp instead of rounding them off.
  // Only on lines of at least kLineEdges edges: a scan's noise makes short sharp runs.
  constexpr std::size_t kLineEdges = 8;
  std::vector<std::uint32_t> line(num_vertices, UINT32_MAX);
  std::vector<std::size_t> line_edges;
  for (auto v0 : m.vertices()) {
    if (!m.status(v0).feature() || line[static_cast<std::size_t>(v0.idx())] != UINT32_MAX) continue;
    const auto id = static_cast<std::uint32_t>(line_edges.size());
    std::size_t ends = 0;  // each edge counted from both ends
    std::vector<Mesh::VertexHandle> stack = {v0};
    line[static_cast<std::size_t>(v0.idx())] = id;
    while (!stack.empty()) {
      const auto v = stack.back();
      stack.pop_back();
      for (auto h : m.voh_range(v)) {
        if (!m.status(m.edge_handle(h)).feature()) continue;
        ++ends;
        const auto w = m.to_vertex_handle(h);
        if (line[static_cast<std::size_t>(w.idx())] == UINT32_MAX) line[static_cast<std::size_t>(w.idx())] = id, stack.push_back(w);
      }
    }
    line_edges.push_back(ends / 2);
  }
  for (std::size_t l : line_edges) out.input_lines += l >= kLineEdges;
  for (auto v : m.vertices())
    if (m.status(v).feature() && line_edges[line[static_cast<std::size_t>(v.idx())]] >= kLineEdges)
      out.input_line_vertices.push_back(static_cast<std::uint32_t>(v.idx()));
  std::vector<std::uint8_t> corner(num_vertices, 0);
  for (auto v : m.vertices()) {
    if (!m.status(v).feature() || line_edges[line[static_cast<std::size_t>(v.idx())]] < kLineEdges) continue;
    std::vector<OpenMesh::Vec3d> out_dirs;
    for (auto h : m.voh_range(v))
      if (m.status(m.edge_handle(h)).feature()) out_dirs.push_back((m.point(m.to_vertex_handle(h)) - m.point(v)).normalized());
    // Two edges straight on make cosine -1; a turn by more than the feature angle, above -cos.
    // A crease that fades out (one feature edge: fandisk's) ends at a corner too: it stays where
    // the crease ends (else the decimation cuts the end off and the fit lets the crease's last
    // point drift over the surface).
    const bool turns = out_dirs.size() == 2 && OpenMesh::dot(out_dirs[0], out_dirs[1]) > -cos_limit;
    if (out_dirs.size() >= 3 || out_dirs.size() == 1 || turns) {
      corner[static_cast<std::size_t>(v.idx())] = 1;
      m.status(v).set_locked(true);
    }
  }
  for (auto v : m.vertices())
    if (m.is_isolated(v)) m.status(v).set_locked(true);

  // OpenMesh's decimation with the quadric, and its aspect-ratio and normal-flip guards in one
  // walk (fit_detail::Decimater: DecimaterT's loop asking the quadric first).
  Decimater dec(m);
  dec.quadric().unset_max_err();
  dec.shape().set_aspect_ratio(10.0);
  dec.shape().set_max_normal_deviation(options.max_normal_deviation_deg);
  dec.initialize();
  // Progress about every 1 % of the collapses expected (each removes a vertex and two faces).
  const std::size_t expected = options.target_faces ? (m.n_faces() - std::min(target_triangles, m.n_faces())) / 2 : used - target;
  Progress observer(options.progress, expected);
  if (options.progress) dec.set_observer(&observer);
  if (options.target_faces) dec.decimate_to_faces(0, std::min(target_triangles, m.n_faces()));
  else dec.decimate_to(target + (num_vertices - used));  // loose vertices stay (locked) and are dropped below
  if (observer.cancelled) throw Cancelled("fitting cancelled");

  // The base from what survived (`b` holds what was read before the decimation).
  const auto extract = [&](BaseMesh b) {
    // Surviving vertices keep their input index until garbage collection: read them first.
    std::vector<std::uint32_t> base_of(num_vertices, UINT32_MAX);
    for (auto v : m.vertices()) {
      if (m.status(v).deleted() || m.is_isolated(v)) continue;
      base_of[static_cast<std::size_t>(v.idx())] = static_cast<std::uint32_t>(b.input_vertex.size());
      b.input_vertex.push_back(static_cast<std::uint32_t>(v.idx()));
      const auto p = m.point(v);
      b.positions.insert(b.positions.end(), {p[0], p[1], p[2]});
      if (corner[static_cast<std::size_t>(v.idx())]) b.tags.corner_vertices.push_back(static_cast<std::uint32_t>(b.input_vertex.size() - 1));
    }
    b.num_vertices = static_cast<std::uint32_t>(b.input_vertex.size());
    long long edges = 0;
    for (auto f : m.faces()) {
      if (m.status(f).deleted()) continue;
      for (auto v : m.fv_range(f)) b.faces.items.push_back(base_of[static_cast<std::size_t>(v.idx())]);
      b.faces.offsets.push_back(static_cast<std::uint32_t>(b.faces.items.size()));
    }
    for (auto e : m.edges()) {
      if (m.status(e).deleted()) continue;
      ++edges;
      const auto h = m.halfedge_handle(e, 0);
      if (m.status(e).feature() && !m.is_boundary(e))
        b.tags.crease_edges.emplace_back(base_of[static_cast<std::size_t>(m.from_vertex_handle(h).idx())],
                                         base_of[static_cast<std::size_t>(m.to_vertex_handle(h).idx())]);
    }
    add_chain_creases(b, base_of);
    b.euler_after = static_cast<long long>(b.num_vertices) - edges + static_cast<long long>(b.faces.rows());
    b.boundary_loops_after = boundary_loops(m);
    if (options.quads) pair_into_quads(b);
    return b;
  };
  BaseMesh result = extract(out);
  // Quads with a face target: the pairing leaves some triangles, so the decimation goes on
  // until the polygons are at most the target.
  while (options.quads && options.target_faces && result.faces.rows() > options.target_faces) {
    std::size_t alive = 0;
    for (auto f : m.faces()) alive += !m.status(f).deleted();
    const std::size_t over = result.faces.rows() - options.target_faces;
    if (alive <= 2 * over + 2) break;
    // OpenMesh counts deleted faces until garbage collection: the target is offset by them.
    if (dec.decimate_to_faces(0, alive - 2 * over + (m.n_faces() - alive)) == 0) break;  // nothing more gives way
    result = extract(out);
  }
  if (observer.cancelled) throw Cancelled("fitting cancelled");  // within the quads' extra rounds
  return result;
}

}  // namespace sublift
