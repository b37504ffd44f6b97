#pragma once
// Internal to core/fit: the OpenMesh mesh a fitting base is decimated on (base_mesh.cpp).
#include <cstddef>

#include "core/fit/openmesh_kernel.h"

namespace sublift::fit_detail {

struct Traits : OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
};

/// OpenMesh's mesh with its collapse check compiled here. The packaged library is built with
/// assertions on, and each status lookup in TriConnectivity::is_collapse_ok builds a std::string
/// of the property's type name to compare (malloc, memcmp, free): two thirds of the decimation's
/// time went there. This is the same check (the link condition and the boundary cases, as
/// OpenMesh documents it), and it hides the library's: the decimater, a template, calls it on this
/// type. tests/fit/decimation_mesh_test.cpp compares the two on every halfedge, through decimations;
/// the bases are byte-identical on the shared scans and the benchmark torus. find_halfedge, which
/// the decimater's legality test calls for every candidate, likewise.
struct Mesh : OpenMesh::TriMesh_ArrayKernelT<Traits> {
  /// is_collapse_ok keeps a ring this long in an array; a vertex with more neighbours is
  /// checked by tagging (status writes: not to be asked on two threads).
  static constexpr std::size_t kKeptRing = 32;

  /// The halfedge from `from` to `to`, or an invalid handle.
  HalfedgeHandle find_halfedge(VertexHandle from, VertexHandle to) const {
    for (const HalfedgeHandle h : voh_range(from))
      if (to_vertex_handle(h) == to) return h;
    return HalfedgeHandle();
  }

  bool is_collapse_ok(HalfedgeHandle v0v1) {
    if (status(edge_handle(v0v1)).deleted()) return false;
    const HalfedgeHandle v1v0 = opposite_halfedge_handle(v0v1);
    const VertexHandle v0 = to_vertex_handle(v1v0), v1 = to_vertex_handle(v0v1);
    if (status(v0).deleted() || status(v1).deleted()) return false;
    // The triangle on each side: its apex, unless both its other edges are boundary edges (the
    // collapse would leave a dangling edge).
    const auto apex = [&](HalfedgeHandle h, VertexHandle& apex_vertex) {
      if (is_boundary(h)) return true;
      const HalfedgeHandle h1 = next_halfedge_handle(h), h2 = next_halfedge_handle(h1);
      apex_vertex = to_vertex_handle(h1);
      return !(is_boundary(opposite_halfedge_handle(h1)) && is_boundary(opposite_halfedge_handle(h2)));
    };
    VertexHandle vl, vr;
    if (!apex(v0v1, vl) || !apex(v1v0, vr) || vl == vr) return false;
    // Link condition: the one-rings of v0 and v1 share the two apexes only. v0's ring is kept
    // in a small array (rings are short) and v1's checked against it: two walks, no status
    // writes (OpenMesh's version tags the rings: three walks and scattered writes).
    constexpr std::size_t kKept = kKeptRing;
    VertexHandle ring[kKept];
    std::size_t n = 0;
    bool long_ring = false;
    for (const VertexHandle w : vv_range(v0)) {
      if (n == kKept) {
        long_ring = true;
        break;
      }
      ring[n++] = w;
    }
    if (long_ring) {  // a vertex of high valence: tag as OpenMesh does
      for (const VertexHandle w : vv_range(v0)) status(w).set_tagged(false);
      for (const VertexHandle w : vv_range(v1)) status(w).set_tagged(true);
      for (const VertexHandle w : vv_range(v0))
        if (status(w).tagged() && w != vl && w != vr) return false;
    } else {
      for (const VertexHandle w : vv_range(v1)) {
        if (w == vl || w == vr) continue;
        for (std::size_t i = 0; i < n; ++i)
          if (ring[i] == w) return false;
      }
    }
    // Two boundary vertices joined through the interior would pinch the surface.
    return !(is_boundary(v0) && is_boundary(v1) && !is_boundary(v0v1) && !is_boundary(v1v0));
  }

  /// PolyConnectivity::collapse (v0 of v0v1 into v1, the faces on either side removed), step for
  /// step, so every handle ends where the library's would (tests/fit/decimation_mesh_test.cpp
  /// collapses two copies side by side and compares every element). The library's version
  /// checks each handle it touches through calls into the library: a fifth of a decimation's
  /// instructions (callgrind).
  void collapse(HalfedgeHandle v0v1) {
    const HalfedgeHandle h1 = next_halfedge_handle(v0v1);
    const HalfedgeHandle o1 = next_halfedge_handle(opposite_halfedge_handle(v0v1));
    collapse_edge(v0v1);
    // The faces either side are now loops of two edges.
    if (next_halfedge_handle(next_halfedge_handle(h1)) == h1) collapse_loop(next_halfedge_handle(h1));
    if (next_halfedge_handle(next_halfedge_handle(o1)) == o1) collapse_loop(o1);
  }

 private:
  void collapse_edge(HalfedgeHandle h) {
    const HalfedgeHandle hn = next_halfedge_handle(h), hp = prev_halfedge_handle(h);
    const HalfedgeHandle o = opposite_halfedge_handle(h);
    const HalfedgeHandle on = next_halfedge_handle(o), op = prev_halfedge_handle(o);
    const FaceHandle fh = face_handle(h), fo = face_handle(o);
    const VertexHandle vh = to_vertex_handle(h), vo = to_vertex_handle(o);
    for (const HalfedgeHandle in : vih_range(vo)) set_vertex_handle(in, vh);
    set_next_halfedge_handle(hp, hn);
    set_next_halfedge_handle(op, on);
    if (fh.is_valid()) set_halfedge_handle(fh, hn);
    if (fo.is_valid()) set_halfedge_handle(fo, on);
    if (halfedge_handle(vh) == o) set_halfedge_handle(vh, hn);
    adjust_outgoing_halfedge(vh);
    set_isolated(vo);
    status(edge_handle(h)).set_deleted(true);
    status(vo).set_deleted(true);
    if (has_halfedge_status()) {
      status(h).set_deleted(true);
      status(o).set_deleted(true);
    }
  }

  void collapse_loop(HalfedgeHandle h0) {
    const HalfedgeHandle h1 = next_halfedge_handle(h0);
    const HalfedgeHandle o0 = opposite_halfedge_handle(h0), o1 = opposite_halfedge_handle(h1);
    const VertexHandle v0 = to_vertex_handle(h0), v1 = to_vertex_handle(h1);
    const FaceHandle fh = face_handle(h0), fo = face_handle(o0);
    set_next_halfedge_handle(h1, next_halfedge_handle(o0));
    set_next_halfedge_handle(prev_halfedge_handle(o0), h1);
    set_face_handle(h1, fo);
    set_halfedge_handle(v0, h1);
    adjust_outgoing_halfedge(v0);
    set_halfedge_handle(v1, o1);
    adjust_outgoing_halfedge(v1);
    if (fo.is_valid() && halfedge_handle(fo) == o0) set_halfedge_handle(fo, h1);
    if (fh.is_valid()) {
      set_halfedge_handle(fh, HalfedgeHandle());
      status(fh).set_deleted(true);
    }
    status(edge_handle(h0)).set_deleted(true);
    if (has_halfedge_status()) {
      status(h0).set_deleted(true);
      status(o0).set_deleted(true);
    }
  }

  // A boundary vertex's halfedge is its outgoing boundary halfedge (the first met clockwise).
  void adjust_outgoing_halfedge(VertexHandle v) {
    for (const HalfedgeHandle h : voh_range(v))
      if (is_boundary(h)) {
        set_halfedge_handle(v, h);
        break;
      }
  }
};

}  // namespace sublift::fit_detail
