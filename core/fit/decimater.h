#pragma once
// Internal to core/fit: OpenMesh's DecimaterT loop (DecimaterT_impl.hh: a heap of vertices keyed
// by their cheapest legal collapse, the old one-ring re-ranked after each collapse) for the
// fitting base's two modules, the quadric and the fused shape guard (decimation_shape.h), asking
// the quadric first. DecimaterT asks every outgoing halfedge's legality (the link condition, the
// library's tests) and then the modules, before it compares priorities: three quarters of a 1 M
// decimation went there (perf). Here the halfedges are checked in order of their quadric error,
// and the first that passes wins: the same halfedge as DecimaterT's (the first of the least legal
// error), so the heap gets the same keys in the same order and the base is the same
// (tests/fit/decimation_mesh_test.cpp compares the two decimaters on every vertex and face). The
// heap's keys live in flat arrays instead of mesh properties.
#include <algorithm>
#include <cfloat>
#include <cstdint>
#include <cstddef>
#include <utility>
#include <vector>

#include "core/fit/openmesh_kernel.h"  // before any other OpenMesh header
#include <OpenMesh/Tools/Decimater/BaseDecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>
#include <OpenMesh/Tools/Utils/HeapT.hh>

#include "core/base/parallel.h"
#include "core/fit/decimation_mesh.h"
#include "core/fit/decimation_shape.h"

namespace sublift::fit_detail {

class Decimater : public OpenMesh::Decimater::BaseDecimaterT<Mesh> {
 public:
  using Quadric = OpenMesh::Decimater::ModQuadricT<Mesh>;

  /// With both modules added; set them up through quadric() and shape(), then initialize().
  explicit Decimater(Mesh& m) : BaseDecimaterT<Mesh>(m), mesh_(m) {
    add(quadric_);
    add(shape_);
  }

  Quadric& quadric() { return module(quadric_); }
  ModFaceShape& shape() { return module(shape_); }

  /// DecimaterT::decimate_to_faces: collapses until at most `nv` vertices or `nf` faces remain
  /// (both counting deleted ones, as OpenMesh does until garbage collection) or nothing gives
  /// way; returns the collapses made.
  std::size_t decimate_to_faces(std::size_t nv, std::size_t nf);
  /// DecimaterT::decimate_to: the same with no face bound.
  std::size_t decimate_to(std::size_t nv) { return decimate_to_faces(nv, 0); }

 private:
  using VertexHandle = Mesh::VertexHandle;
  using HalfedgeHandle = Mesh::HalfedgeHandle;
  struct Keys {
    Decimater* d;
    bool less(VertexHandle a, VertexHandle b) const { return d->priority_[a.idx()] < d->priority_[b.idx()]; }
    bool greater(VertexHandle a, VertexHandle b) const { return d->priority_[a.idx()] > d->priority_[b.idx()]; }
    int get_heap_position(VertexHandle v) const { return d->heap_position_[v.idx()]; }
    void set_heap_position(VertexHandle v, int pos) { d->heap_position_[v.idx()] = pos; }
  };
  using Heap = OpenMesh::Utils::HeapT<VertexHandle, Keys>;

  struct Candidate {
    float prio;
    std::uint32_t walk;  // its place in the walk round the vertex
    HalfedgeHandle h;
  };
  // v's collapse (DecimaterT::heap_vertex's choice, the quadric asked first): its halfedge
  // (invalid: none) and priority. Reads the mesh only, so vertices may be asked concurrently,
  // unless v has more neighbours than Mesh::is_collapse_ok keeps (it tags their status then).
  std::pair<HalfedgeHandle, float> choose(VertexHandle v, std::vector<Candidate>& candidates);
  // v's choice recorded and v placed in (or taken out of) the heap.
  void place(Heap& heap, VertexHandle v, std::pair<HalfedgeHandle, float> choice);
  // DecimaterT::heap_vertex.
  void heap_vertex(Heap& heap, VertexHandle v) { place(heap, v, choose(v, candidates_)); }
  std::vector<Candidate> candidates_;  // heap_vertex's, kept for its storage
  // ModQuadricT's quadrics (private there): the mesh's one vertex property of their type, so a
  // halfedge's error is asked without building its CollapseInfo (null: not found, ask the module).
  using Quadrics = std::vector<OpenMesh::Geometry::QuadricT<double>>;
  const Quadrics* quadrics_ = nullptr;
  const Quadrics* find_quadrics() const;

  Mesh& mesh_;
  Quadric::Handle quadric_;
  ModFaceShape::Handle shape_;
  std::vector<float> priority_;
  std::vector<int> heap_position_;
  std::vector<HalfedgeHandle> target_;
};

inline std::pair<Decimater::HalfedgeHandle, float> Decimater::choose(VertexHandle v, std::vector<Candidate>& candidates) {
  // Every outgoing halfedge's quadric error, then the checks in order of error (ties in the order
  // of the walk): the first that passes is DecimaterT's choice, the least legal error, the first
  // of equals; on average about one halfedge is checked.
  Quadric& q = quadric();
  candidates.clear();
  if (quadrics_) {
    // ModQuadricT::collapse_priority's arithmetic: the two ends' quadrics summed, at the far end.
    const double max_err = q.max_err();
    for (const HalfedgeHandle h : mesh_.voh_range(v)) {
      const VertexHandle v1 = mesh_.to_vertex_handle(h);
      OpenMesh::Geometry::QuadricT<double> sum = (*quadrics_)[static_cast<std::size_t>(v.idx())];
      sum += (*quadrics_)[static_cast<std::size_t>(v1.idx())];
      const double err = sum(mesh_.point(v1));
      const float prio = float((err < max_err) ? err : float(Quadric::ILLEGAL_COLLAPSE));
      if (prio >= 0.0f && prio < FLT_MAX) candidates.push_back({prio, static_cast<std::uint32_t>(candidates.size()), h});
    }
  } else {
    for (const HalfedgeHandle h : mesh_.voh_range(v)) {
      const CollapseInfo ci(mesh_, h);
      const float prio = q.collapse_priority(ci);
      if (prio >= 0.0f && prio < FLT_MAX) candidates.push_back({prio, static_cast<std::uint32_t>(candidates.size()), h});
    }
  }
  std::sort(candidates.begin(), candidates.end(),
            [](const Candidate& a, const Candidate& b) { return a.prio < b.prio || (a.prio == b.prio && a.walk < b.walk); });
  ModFaceShape& s = shape();
  HalfedgeHandle target;
  float best = -1;
  for (const Candidate& k : candidates) {
    const CollapseInfo ci(mesh_, k.h);
    if (!is_collapse_legal(ci) || s.collapse_priority(ci) < 0.0f) continue;
    target = k.h;
    best = k.prio;
    break;
  }
  return {target, best};
}

inline void Decimater::place(Heap& heap, VertexHandle v, std::pair<HalfedgeHandle, float> choice) {
  const auto [target, best] = choice;
  target_[v.idx()] = target;
  if (target.is_valid()) {
    priority_[v.idx()] = best;
    if (heap.is_stored(v)) heap.update(v);
    else heap.insert(v);
  } else {
    if (heap.is_stored(v)) heap.remove(v);
    priority_[v.idx()] = -1;
  }
}

inline const Decimater::Quadrics* Decimater::find_quadrics() const {
  const Quadrics* found = nullptr;
  for (auto it = mesh_.vprops_begin(); it != mesh_.vprops_end(); ++it)
    if (const auto* p = dynamic_cast<const OpenMesh::PropertyT<OpenMesh::Geometry::QuadricT<double>>*>(*it)) {
      if (found) return nullptr;  // two: not knowing which is the module's, ask the module
      found = &p->data_vector();
    }
  return found && found->size() == mesh_.n_vertices() ? found : nullptr;
}

inline std::size_t Decimater::decimate_to_faces(std::size_t target_nv, std::size_t target_nf) {
  if (!is_initialized()) return 0;
  quadrics_ = find_quadrics();
  if (target_nv >= mesh_.n_vertices() || target_nf >= mesh_.n_faces()) return 0;
  std::size_t nv = mesh_.n_vertices(), nf = mesh_.n_faces(), collapses = 0;
  priority_.assign(nv, 0.0f);
  heap_position_.assign(nv, -1);
  target_.assign(nv, HalfedgeHandle());
  Heap heap(Keys{this});
  heap.reserve(nv);
  // Every vertex's first choice, in parallel (a long-ringed vertex's after, alone), then each
  // placed in the heap in vertex order, as DecimaterT's loop does.
  std::vector<std::pair<HalfedgeHandle, float>> first(nv, {HalfedgeHandle(), -1.0f});
  std::vector<std::uint8_t> alone(nv, 0);
  parallel_for(static_cast<std::uint32_t>(nv), 4096, [&](std::uint32_t b, std::uint32_t e) {
    std::vector<Candidate> candidates;
    for (std::uint32_t i = b; i < e; ++i) {
      const VertexHandle v(static_cast<int>(i));
      if (mesh_.status(v).deleted()) continue;
      if (mesh_.valence(v) > Mesh::kKeptRing) alone[i] = 1;
      else first[i] = choose(v, candidates);
    }
  });
  for (const VertexHandle v : mesh_.vertices()) {
    heap.reset_heap_position(v);
    if (mesh_.status(v).deleted()) continue;
    const std::size_t i = static_cast<std::size_t>(v.idx());
    place(heap, v, alone[i] ? choose(v, candidates_) : first[i]);
  }
  const bool update_normals = mesh_.has_face_normals();
  std::vector<VertexHandle> support;
  while (!heap.empty() && target_nv < nv && target_nf < nf) {
    const VertexHandle vp = heap.front();
    const HalfedgeHandle v0v1 = target_[vp.idx()];
    heap.pop_front();
    CollapseInfo ci(mesh_, v0v1);
    if (!is_collapse_legal(ci)) continue;  // (checked again, as DecimaterT does)
    support.clear();
    for (const VertexHandle w : mesh_.vv_range(ci.v0)) support.push_back(w);
    ++collapses;
    --nv;
    nf -= (mesh_.is_boundary(ci.v0v1) || mesh_.is_boundary(ci.v1v0)) ? 1 : 2;
    preprocess_collapse(ci);
    mesh_.collapse(v0v1);
    if (update_normals)
      for (const Mesh::FaceHandle f : mesh_.vf_range(ci.v1))
        if (!mesh_.status(f).deleted()) mesh_.set_normal(f, mesh_.calc_face_normal(f));
    postprocess_collapse(ci);
    for (const VertexHandle w : support) heap_vertex(heap, w);
    if (!notify_observer(collapses)) return collapses;
  }
  return collapses;
}

}  // namespace sublift::fit_detail
