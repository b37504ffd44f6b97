#pragma once
// Internal to core/fit: the OpenMesh mesh a fitting base is decimated on (base_mesh.cpp).
#include <cstddef>

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

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
    constexpr std::size_t kKept = 32;
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
};

}  // namespace sublift::fit_detail
