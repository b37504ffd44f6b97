#pragma once
// Where the new vertices of one refinement sit on the coarse level. The 1-to-4 schemes need no
// table (refine.h numbers them [v | e | f | c]: vertex nv + e sits on edge e, ...); a sqrt(2)
// step (refine_sqrt2.h) makes points only on its curve edges and faces, so it lists them. Local
// detail frames (detail_frames.h) are built on these sites.
#include <cstdint>
#include <vector>

namespace sublift {

/// The sites of one sqrt(2) step: a curve point on its curve edge, a face point on its face.
struct ChildSites {
  std::vector<std::uint32_t> site;        // per new vertex (index - coarse vertex count): coarse
                                          // edge e, or num_edges + face
  std::vector<std::uint32_t> edge_child;  // per coarse edge: its new vertex or UINT32_MAX
  std::vector<std::uint32_t> face_child;  // per coarse face: its new vertex or UINT32_MAX
};

}  // namespace sublift
