#include "core/fit/decimate_parts.h"

#include <OpenMesh/Tools/Decimater/ModAspectRatioT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalFlippingT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>

#include <algorithm>
#include <cmath>
#include <unordered_set>

#include "core/base/parallel.h"

namespace sublift::fit_detail {

namespace {

std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
  return (std::uint64_t(std::min(a, b)) << 32) | std::max(a, b);
}

long long euler_and_loops(const Mesh& m, std::size_t& loops) {
  long long v = 0, e = 0, f = 0;
  for (auto h : m.vertices()) v += !m.status(h).deleted() && !m.is_isolated(h);
  for (auto h : m.edges()) e += !m.status(h).deleted();
  for (auto h : m.faces()) f += !m.status(h).deleted();
  std::vector<char> seen(m.n_halfedges(), 0);
  loops = 0;
  for (auto h : m.halfedges()) {
    if (!m.is_boundary(h) || m.status(m.edge_handle(h)).deleted() || seen[static_cast<std::size_t>(h.idx())]) continue;
    ++loops;
    for (auto g = h; !seen[static_cast<std::size_t>(g.idx())]; g = m.next_halfedge_handle(g)) seen[static_cast<std::size_t>(g.idx())] = 1;
  }
  return v - e + f;
}

void request_status(Mesh& m) {
  m.request_vertex_status();
  m.request_edge_status();
  m.request_face_status();
  m.request_face_normals();
}

// What one slab leaves: its own faces (input vertex numbers) and its feature edges.
struct SlabResult {
  std::vector<std::uint32_t> triangles;
  std::vector<std::uint64_t> features;
  bool ok = false;
};

SlabResult decimate_slab(const Mesh& m, const std::vector<std::uint32_t>& slab_of, std::uint32_t slab, double keep_fraction,
                         double max_normal_deviation_deg) {
  SlabResult r;
  const std::size_t nv = m.n_vertices(), nf = m.n_faces();
  std::vector<char> touched(nv, 0);
  for (std::size_t f = 0; f < nf; ++f)
    if (slab_of[f] == slab)
      for (auto v : m.fv_range(Mesh::FaceHandle(static_cast<int>(f)))) touched[static_cast<std::size_t>(v.idx())] = 1;
  Mesh pm;
  request_status(pm);
  std::vector<int> local(nv, -1);
  std::vector<std::uint32_t> input_of;
  std::vector<char> own;  // per slab face: the slab's own (else another's, touching it: all locked)
  std::size_t locked = 0;
  for (std::size_t f = 0; f < nf; ++f) {
    const auto fh = Mesh::FaceHandle(static_cast<int>(f));
    const bool mine = slab_of[f] == slab;
    if (!mine) {
      bool touches = false;
      for (auto v : m.fv_range(fh)) touches |= touched[static_cast<std::size_t>(v.idx())] != 0;
      if (!touches) continue;
    }
    Mesh::VertexHandle tri[3];
    int k = 0;
    for (auto v : m.fv_range(fh)) {
      int& l = local[static_cast<std::size_t>(v.idx())];
      if (l < 0) {
        l = static_cast<int>(input_of.size());
        input_of.push_back(static_cast<std::uint32_t>(v.idx()));
        const auto lv = pm.add_vertex(m.point(v));
        pm.status(lv).set_feature(m.status(v).feature());
        pm.status(lv).set_locked(m.status(v).locked());
      }
      const auto lv = Mesh::VertexHandle(l);
      if (!mine && !pm.status(lv).locked()) pm.status(lv).set_locked(true);
      tri[k++] = lv;
    }
    if (!pm.add_face(tri[0], tri[1], tri[2]).is_valid()) return r;  // not one fan in the slab
    own.push_back(mine);
  }
  for (auto v : pm.vertices()) locked += pm.status(v).locked();
  for (auto e : pm.edges()) {
    const auto h = pm.halfedge_handle(e, 0);
    const auto a = Mesh::VertexHandle(static_cast<int>(input_of[static_cast<std::size_t>(pm.from_vertex_handle(h).idx())]));
    const auto b = Mesh::VertexHandle(static_cast<int>(input_of[static_cast<std::size_t>(pm.to_vertex_handle(h).idx())]));
    pm.status(e).set_feature(m.status(m.edge_handle(m.find_halfedge(a, b))).feature());
  }
  pm.update_face_normals();
  const auto free_vertices = pm.n_vertices() - locked;
  auto dec = make_decimater(pm, max_normal_deviation_deg);
  dec->decimate_to(locked + static_cast<std::size_t>(std::ceil(keep_fraction * double(free_vertices))));
  for (auto f : pm.faces()) {
    if (pm.status(f).deleted() || !own[static_cast<std::size_t>(f.idx())]) continue;
    for (auto v : pm.fv_range(f)) r.triangles.push_back(input_of[static_cast<std::size_t>(v.idx())]);
  }
  for (auto e : pm.edges()) {
    if (pm.status(e).deleted() || !pm.status(e).feature()) continue;
    const auto h = pm.halfedge_handle(e, 0);
    r.features.push_back(edge_key(input_of[static_cast<std::size_t>(pm.from_vertex_handle(h).idx())],
                                  input_of[static_cast<std::size_t>(pm.to_vertex_handle(h).idx())]));
  }
  r.ok = true;
  return r;
}

}  // namespace

std::unique_ptr<Decimater> make_decimater(Mesh& m, double max_normal_deviation_deg) {
  auto dec = std::make_unique<Decimater>(m);
  OpenMesh::Decimater::ModQuadricT<Mesh>::Handle quadric;
  OpenMesh::Decimater::ModNormalFlippingT<Mesh>::Handle flips;
  OpenMesh::Decimater::ModAspectRatioT<Mesh>::Handle aspect;
  dec->add(quadric);
  dec->add(flips);
  dec->add(aspect);
  dec->module(quadric).unset_max_err();
  dec->module(flips).set_max_normal_deviation(max_normal_deviation_deg);
  dec->module(aspect).set_aspect_ratio(10.0);
  dec->module(aspect).set_binary(true);
  dec->initialize();
  return dec;
}

std::optional<JoinedParts> decimate_in_parts(const Mesh& m, std::uint32_t parts, std::uint32_t keep,
                                             double max_normal_deviation_deg) {
  const std::size_t nf = m.n_faces();
  // Slabs: the faces in order of their centroids along the longest axis of the bounds.
  OpenMesh::Vec3d lo(HUGE_VAL, HUGE_VAL, HUGE_VAL), hi(-HUGE_VAL, -HUGE_VAL, -HUGE_VAL);
  std::size_t used = 0;
  for (auto v : m.vertices()) {
    if (m.is_isolated(v)) continue;
    ++used;
    lo.minimize(m.point(v));
    hi.maximize(m.point(v));
  }
  const OpenMesh::Vec3d size = hi - lo;
  const int axis = size[0] >= size[1] && size[0] >= size[2] ? 0 : size[1] >= size[2] ? 1 : 2;
  std::vector<std::pair<double, std::uint32_t>> order(nf);
  for (std::size_t f = 0; f < nf; ++f) {
    double c = 0;
    for (auto v : m.fv_range(Mesh::FaceHandle(static_cast<int>(f)))) c += m.point(v)[axis];
    order[f] = {c, static_cast<std::uint32_t>(f)};
  }
  std::sort(order.begin(), order.end());
  std::vector<std::uint32_t> slab_of(nf);
  for (std::size_t k = 0; k < nf; ++k) slab_of[order[k].second] = static_cast<std::uint32_t>(k * parts / nf);
  order = {};

  // Each slab goes a quarter past its share of `keep`, so the whole has room to even out the
  // seams (left dense by the locks) in the last pass.
  const double keep_fraction = std::min(1.0, 1.25 * double(keep) / double(used));
  std::vector<SlabResult> slabs(parts);
  parallel_for(parts, 1, [&](std::uint32_t b, std::uint32_t e) {
    for (std::uint32_t s = b; s < e; ++s) {
      try {
        slabs[s] = decimate_slab(m, slab_of, s, keep_fraction, max_normal_deviation_deg);
      } catch (...) {
        slabs[s].ok = false;  // e.g. out of memory: the caller decimates the whole mesh
      }
    }
  });
  if (!std::all_of(slabs.begin(), slabs.end(), [](const SlabResult& s) { return s.ok; })) return std::nullopt;

  // The join, in input vertex order; halfedge collapses leave the kept vertices where they were.
  JoinedParts j;
  request_status(j.mesh);
  std::vector<int> local(m.n_vertices(), -1);
  for (const auto& s : slabs)
    for (std::uint32_t v : s.triangles) local[v] = 0;
  for (std::size_t v = 0; v < local.size(); ++v) {
    if (local[v] < 0) continue;
    const auto in = Mesh::VertexHandle(static_cast<int>(v));
    local[v] = static_cast<int>(j.input_of.size());
    j.input_of.push_back(static_cast<std::uint32_t>(v));
    const auto lv = j.mesh.add_vertex(m.point(in));
    j.mesh.status(lv).set_feature(m.status(in).feature());
    j.mesh.status(lv).set_locked(m.status(in).locked());
  }
  std::unordered_set<std::uint64_t> features;
  for (const auto& s : slabs) {
    features.insert(s.features.begin(), s.features.end());
    for (std::size_t k = 0; k < s.triangles.size(); k += 3)
      if (!j.mesh
               .add_face(Mesh::VertexHandle(local[s.triangles[k]]), Mesh::VertexHandle(local[s.triangles[k + 1]]),
                         Mesh::VertexHandle(local[s.triangles[k + 2]]))
               .is_valid())
        return std::nullopt;
  }
  for (auto e : j.mesh.edges()) {
    const auto h = j.mesh.halfedge_handle(e, 0);
    const std::uint32_t a = j.input_of[static_cast<std::size_t>(j.mesh.from_vertex_handle(h).idx())];
    const std::uint32_t b = j.input_of[static_cast<std::size_t>(j.mesh.to_vertex_handle(h).idx())];
    j.mesh.status(e).set_feature(features.count(edge_key(a, b)) > 0);
  }
  // A safety net, not a path taken: the slabs' collapses passed the whole mesh's link condition.
  std::size_t loops_before = 0, loops_after = 0;
  if (euler_and_loops(m, loops_before) != euler_and_loops(j.mesh, loops_after) || loops_before != loops_after) return std::nullopt;
  j.mesh.update_face_normals();
  return j;
}

}  // namespace sublift::fit_detail
