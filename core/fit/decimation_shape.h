#pragma once
// Internal to core/fit: OpenMesh's two shape guards for a fitting base's decimation
// (base_mesh.cpp), ModAspectRatioT (binary) and ModNormalFlippingT, as one module. Each walked
// the collapsing vertex's faces on its own, and the flip guard moved the vertex, walked its faces
// and recomputed each face's normal through circulators: together a third of the decimation's
// time at 1 M vertices (perf). Here one walk of v0's outgoing halfedges does both, with the same
// arithmetic in the same order, so every verdict is the library's (tests/fit/decimation_mesh_test.cpp
// asks both on every halfedge through decimations; the bases are byte-identical).
#include <cmath>

#include "core/fit/openmesh_kernel.h"  // before any other OpenMesh header
#include <OpenMesh/Tools/Decimater/ModBaseT.hh>

#include "core/fit/decimation_mesh.h"

namespace sublift::fit_detail {

class ModFaceShape : public OpenMesh::Decimater::ModBaseT<Mesh> {
 public:
  // DECIMATING_MODULE's names (the macro is for class templates).
  using Self = ModFaceShape;
  using Handle = OpenMesh::Decimater::ModHandleT<Self>;
  using Base = OpenMesh::Decimater::ModBaseT<Mesh>;
  using CollapseInfo = Base::CollapseInfo;
  DECIMATER_MODNAME(FaceShape)

  explicit ModFaceShape(Mesh& mesh) : Base(mesh, true) { mesh.add_property(aspect_); }
  ~ModFaceShape() override { mesh().remove_property(aspect_); }

  /// A collapse may leave no face whose aspect ratio (longest edge over its height) exceeds
  /// this, unless it improves the worst one around (ModAspectRatioT in binary mode).
  void set_aspect_ratio(float ratio) { min_aspect_ = 1.f / ratio; }
  /// No face around may turn by more than this (ModNormalFlippingT).
  void set_max_normal_deviation(double degrees) { min_cos_ = std::cos(degrees / 180.0 * M_PI); }

  void initialize() override {
    for (auto f : mesh().faces()) store_aspect(f);
  }

  float collapse_priority(const CollapseInfo& ci) override {
    Mesh& m = mesh();
    // Flat arrays: the decimation adds no element, so they stay put.
    const Mesh::Point* points = m.points();
    const Mesh::Normal* normals = m.property(m.face_normals_pph()).data_vector().data();
    const float* aspect = m.property(aspect_).data_vector().data();
    double r0_min = 1.0, r1_min = 1.0;
    // v0's outgoing halfedges, each face (v0, v3, v2) once: v2 is the previous halfedge's tip.
    const Mesh::HalfedgeHandle start = m.halfedge_handle(ci.v0);
    Mesh::HalfedgeHandle h = start;
    Mesh::VertexHandle v3 = m.to_vertex_handle(h);
    do {
      const Mesh::VertexHandle v2 = v3;
      h = m.cw_rotated_halfedge_handle(h);
      v3 = m.to_vertex_handle(h);
      const Mesh::FaceHandle f = m.face_handle(h);
      if (!f.is_valid()) continue;
      if (const double r0 = aspect[f.idx()]; r0 < r0_min) r0_min = r0;
      if (v2 == ci.v1 || v3 == ci.v1) continue;  // fl or fr: gone after the collapse
      const Mesh::Point &p2 = points[v2.idx()], &p3 = points[v3.idx()];
      if (const double r1 = 1.0 / aspect_ratio(ci.p1, p2, p3); r1 < r1_min) r1_min = r1;
      // The face's normal with v0 at p1, its corners in the order calc_face_normal takes them
      // (from the face's halfedge on).
      const Mesh::HalfedgeHandle first = m.halfedge_handle(f);
      const Mesh::Point n = first == h                           ? normal(p3, p2, ci.p1)
                            : first == m.next_halfedge_handle(h) ? normal(p2, ci.p1, p3)
                                                                 : normal(ci.p1, p3, p2);
      if (OpenMesh::dot(normals[f.idx()], n) < min_cos_) return ILLEGAL_COLLAPSE;
    } while (h != start);
    return (r1_min > r0_min || r1_min > min_aspect_) ? LEGAL_COLLAPSE : ILLEGAL_COLLAPSE;
  }

  /// The faces around v0 get their aspect ratios as they are before the collapse, as
  /// ModAspectRatioT stores them.
  void preprocess_collapse(const CollapseInfo& ci) override {
    for (auto h : mesh().voh_range(ci.v0))
      if (const auto f = mesh().face_handle(h); f.is_valid() && f != ci.fl && f != ci.fr) store_aspect(f);
  }

 private:
  // 1 / the aspect ratio of face f, its corners in face order from its halfedge, as a float:
  // as ModAspectRatioT keeps it (the comparisons with it round the same).
  void store_aspect(Mesh::FaceHandle f) {
    const auto h = mesh().halfedge_handle(f);
    mesh().property(aspect_, f) = static_cast<float>(
        1.0 / aspect_ratio(point(mesh().to_vertex_handle(h)), point(mesh().to_vertex_handle(mesh().next_halfedge_handle(h))),
                           point(mesh().from_vertex_handle(h))));
  }
  const Mesh::Point& point(Mesh::VertexHandle v) { return mesh().point(v); }

  // ModAspectRatioT::aspectRatio, term for term.
  static double aspect_ratio(const Mesh::Point& a, const Mesh::Point& b, const Mesh::Point& c) {
    const Mesh::Point d0 = a - b;
    Mesh::Point d1 = b - c;
    double l2, maxl2 = d0.sqrnorm();
    if ((l2 = d1.sqrnorm()) > maxl2) maxl2 = l2;
    d1 = c - a;
    if ((l2 = d1.sqrnorm()) > maxl2) maxl2 = l2;
    const double a2 = (d0 % d1).sqrnorm();
    return std::sqrt((maxl2 * maxl2) / a2);
  }
  // PolyMeshT::calc_face_normal(p0, p1, p2), term for term.
  static Mesh::Point normal(const Mesh::Point& p0, const Mesh::Point& p1, const Mesh::Point& p2) {
    Mesh::Point p1p0 = p0;
    p1p0 -= p1;
    Mesh::Point p1p2 = p2;
    p1p2 -= p1;
    Mesh::Point n = OpenMesh::cross(p1p2, p1p0);
    const double length = OpenMesh::norm(n);
    return length != 0.0 ? (n *= (1.0 / length), n) : Mesh::Point(0, 0, 0);
  }

  OpenMesh::FPropHandleT<float> aspect_;
  float min_aspect_ = 1.f / 5.f;
  double min_cos_ = 0.0;
};

}  // namespace sublift::fit_detail
