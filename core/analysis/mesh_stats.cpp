#include "core/analysis/mesh_stats.h"

#include <algorithm>
#include <numeric>
#include <string>
#include <vector>

#include <glm/common.hpp>

#include "core/base/edge_key.h"
#include "core/base/small_sort.h"

namespace sublift {
namespace {

struct UnionFind {
  std::vector<std::uint32_t> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  std::uint32_t find(std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(std::uint32_t a, std::uint32_t b) { parent[find(a)] = find(b); }
};

// One directed use of an edge by a face corner: edge from corner c to the next corner.
struct HalfEdge {
  std::uint64_t key;      // min(a,b) << 32 | max(a,b)
  std::uint32_t corner;   // index into face_indices of the edge's start corner
  bool forward;           // a < b
};

}  // namespace

MeshStats compute_mesh_stats(const SurfaceMesh& mesh) {
  MeshStats s;
  const std::size_t nv = mesh.num_vertices();
  const std::size_t nf = mesh.num_faces();
  const std::size_t nc = mesh.face_indices.size();
  s.vertices = nv;
  s.faces = nf;

  // next[c]: the corner after c in its face, so edge c runs face_indices[c] -> face_indices[next[c]].
  std::vector<std::uint32_t> next(nc);
  for (std::size_t f = 0; f < nf; ++f) {
    const std::uint32_t b = mesh.face_offsets[f], e = mesh.face_offsets[f + 1];
    ++s.face_sizes[e - b];
    for (std::uint32_t c = b; c < e; ++c) {
      next[c] = c + 1 < e ? c + 1 : b;
    }
  }
  // The half-edges in (key, corner) order: a counting sort by the lower vertex (corners stay in
  // order within it), then each vertex's few by the higher one, stably (a sort of all of them
  // was a second and a half of importing a million vertices).
  std::vector<std::uint32_t> start(nv + 1, 0);
  for (std::uint32_t c = 0; c < nc; ++c) ++start[std::min(mesh.face_indices[c], mesh.face_indices[next[c]]) + std::size_t(1)];
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<HalfEdge> half(nc);
  {
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for (std::uint32_t c = 0; c < nc; ++c) {
      const std::uint32_t a = mesh.face_indices[c], b = mesh.face_indices[next[c]];
      half[fill[std::min(a, b)]++] = {edge_key(a, b), c, a < b};
    }
  }
  const auto by_key = [](const HalfEdge& x, const HalfEdge& y) { return x.key < y.key; };
  for (std::size_t v = 0; v < nv; ++v) stable_sort_small(half.begin() + start[v], half.begin() + start[v + 1], by_key);

  std::vector<char> used(nv, 0);
  for (std::uint32_t v : mesh.face_indices) used[v] = 1;
  std::vector<std::uint32_t> valence(nv, 0);
  UnionFind fans(nc);        // corners around a vertex joined across manifold edges
  UnionFind parts(nv);       // vertices joined by edges
  UnionFind boundary(nv);    // vertices joined by boundary edges
  std::vector<char> on_boundary(nv, 0);
  std::vector<char> nonmanifold_vertex(nv, 0);
  for (std::size_t i = 0; i < half.size();) {
    std::size_t j = i;
    while (j < half.size() && half[j].key == half[i].key) ++j;
    const std::size_t uses = j - i;
    const auto a = static_cast<std::uint32_t>(half[i].key >> 32);
    const auto b = static_cast<std::uint32_t>(half[i].key & 0xffffffffu);
    ++s.edges;
    ++valence[a];
    ++valence[b];
    parts.unite(a, b);
    std::size_t fwd = 0;
    for (std::size_t k = i; k < j; ++k) fwd += half[k].forward;
    if (fwd > 1 || uses - fwd > 1) {
      if (s.misoriented_edges++ < MeshStats::kFirstElements) s.first_misoriented_edges.emplace_back(a, b);
    }
    if (uses == 1) {
      ++s.boundary_edges;
      boundary.unite(a, b);
      on_boundary[a] = on_boundary[b] = 1;
    } else if (uses == 2) {
      // Join the two faces' corners at each end of the edge into one fan.
      const std::uint32_t c0 = half[i].corner, c1 = half[i + 1].corner;
      const std::uint32_t c0n = next[c0], c1n = next[c1];
      for (std::uint32_t x : {c0, c0n})
        for (std::uint32_t y : {c1, c1n})
          if (mesh.face_indices[x] == mesh.face_indices[y]) fans.unite(x, y);
    } else {
      if (s.non_manifold_edges++ < MeshStats::kFirstElements) s.first_non_manifold_edges.emplace_back(a, b);
      nonmanifold_vertex[a] = nonmanifold_vertex[b] = 1;
    }
    i = j;
  }
  // A manifold vertex has all its corners in one fan.
  std::vector<std::uint32_t> fan_root(nv, UINT32_MAX);
  for (std::uint32_t c = 0; c < nc; ++c) {
    const std::uint32_t v = mesh.face_indices[c];
    const std::uint32_t r = fans.find(c);
    if (fan_root[v] == UINT32_MAX) fan_root[v] = r;
    else if (fan_root[v] != r) nonmanifold_vertex[v] = 1;
  }
  std::vector<char> on_line(nv, 0);
  s.polylines = mesh.num_polylines();
  for (std::size_t l = 0; l < mesh.num_polylines(); ++l) {
    const auto p = mesh.polyline(l);
    s.polyline_segments += p.size() - 1;
    s.closed_polylines += p.front() == p.back();
    for (std::uint32_t v : p) on_line[v] = 1;
  }
  bool any_used = false;
  s.components = 0;
  s.boundary_loops = 0;
  for (std::uint32_t v = 0; v < nv; ++v) {
    if (!used[v]) {
      s.isolated_vertices += !on_line[v];
      continue;
    }
    ++s.used_vertices;
    ++s.valences[valence[v]];
    if (nonmanifold_vertex[v] && s.non_manifold_vertices++ < MeshStats::kFirstElements)
      s.first_non_manifold_vertices.push_back(v);
    if (parts.find(v) == v) ++s.components;
    if (on_boundary[v] && boundary.find(v) == v) ++s.boundary_loops;
    const glm::dvec3& p = mesh.positions[v];
    s.bbox_min = any_used ? glm::min(s.bbox_min, p) : p;
    s.bbox_max = any_used ? glm::max(s.bbox_max, p) : p;
    any_used = true;
  }
  for (int pass = 0; pass < 2 && !any_used; ++pass)  // no face: the polylines', else all vertices
    for (std::uint32_t v = 0; v < nv; ++v) {
      if (pass == 0 && !on_line[v]) continue;
      const glm::dvec3& p = mesh.positions[v];
      s.bbox_min = any_used ? glm::min(s.bbox_min, p) : p;
      s.bbox_max = any_used ? glm::max(s.bbox_max, p) : p;
      any_used = true;
    }
  s.euler_characteristic = static_cast<long long>(s.used_vertices) - static_cast<long long>(s.edges) +
                           static_cast<long long>(s.faces);
  return s;
}

namespace {

// "(vertex 4)", "(vertices 4, 9, ...)", "(edges 1-2, 3-4)": the first elements of `count`.
template <class T, class Name>
std::string first_of(const std::vector<T>& first, std::size_t count, const char* one, const char* many, Name name) {
  std::string s = std::string(" (") + (count == 1 ? one : many) + " ";
  for (std::size_t i = 0; i < first.size(); ++i) s += (i ? ", " : "") + name(first[i]);
  return s + (count > first.size() ? ", ...; 0-based)" : "; 0-based)");
}

std::string edge_name(const std::pair<std::uint32_t, std::uint32_t>& e) {
  return std::to_string(e.first) + "-" + std::to_string(e.second);
}

}  // namespace

std::vector<ImportWarning> topology_warnings(const MeshStats& s) {
  std::vector<ImportWarning> out;
  auto vertex_name = [](std::uint32_t v) { return std::to_string(v); };
  if (s.non_manifold_vertices)
    out.push_back({"non-manifold vertex: its faces do not form one fan" +
                       first_of(s.first_non_manifold_vertices, s.non_manifold_vertices, "vertex", "vertices", vertex_name),
                   s.non_manifold_vertices, {}});
  if (s.non_manifold_edges)
    out.push_back({"non-manifold edge: in more than two faces" +
                       first_of(s.first_non_manifold_edges, s.non_manifold_edges, "edge", "edges", edge_name),
                   s.non_manifold_edges, {}});
  if (s.misoriented_edges)
    out.push_back({"misoriented edge: two faces run it the same way, so the faces are not consistently oriented" +
                       first_of(s.first_misoriented_edges, s.misoriented_edges, "edge", "edges", edge_name),
                   s.misoriented_edges, {}});
  return out;
}

std::vector<ImportWarning> topology_warnings(const Complex& c) {
  if (c.dim != 2) return {};
  SurfaceMesh m;
  m.positions.assign(c.num_vertices, glm::dvec3(0.0));  // topology only
  m.face_offsets = c.faces.offsets;
  m.face_indices = c.faces.items;
  return topology_warnings(compute_mesh_stats(m));
}

void add_topology_warnings(ImportReport& report, const Complex& c) {
  for (ImportWarning& w : topology_warnings(c)) report.warnings.push_back(std::move(w));
}

void add_topology_warnings(ImportReport& report, const SurfaceMesh& mesh) {
  for (ImportWarning& w : topology_warnings(compute_mesh_stats(mesh))) report.warnings.push_back(std::move(w));
}

}  // namespace sublift
