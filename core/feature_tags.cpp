#include "core/feature_tags.h"

namespace sublift {

// The rules mirror assign_feature_dims (complex_build.cpp); tests/feature_tags_test.cpp checks
// that assign_feature_dims(derive_feature_tags(c)) reproduces c's dims.
FeatureTags derive_feature_tags(const Complex& in) {
  const bool derived = in.vertex_edges.rows() == in.num_vertices && in.edge_faces.rows() == in.num_edges() &&
                       in.face_cells.rows() == in.num_faces();
  Complex storage;
  if (!derived) {
    storage = in;
    build_adjacency(storage);
  }
  const Complex& c = derived ? in : storage;
  FeatureTags tags;
  // Faces: in a volume, only faces between exactly two cells are dim 3 without a tag.
  if (c.dim == 3)
    for (std::uint32_t f = 0; f < c.num_faces(); ++f)
      if (c.face_dim[f] == 2 && c.face_cells.size(f) == 2) {
        auto r = c.faces.row(f);
        tags.feature_faces.emplace_back(r.begin(), r.end());
      }
  // Edges: what the (now reproduced) face dims give, lowered to 1 by a crease tag.
  for (std::uint32_t e = 0; e < c.num_edges(); ++e) {
    if (c.edge_dim[e] != 1) continue;
    int automatic = c.dim;
    if (c.dim == 1) {
      automatic = 1;
    } else if (c.dim == 2) {
      automatic = c.edge_faces.size(e) == 2 ? 2 : 1;
    } else {
      int surface_faces = 0;
      for (std::uint32_t f : c.edge_faces.row(e)) surface_faces += c.face_dim[f] == 2;
      automatic = surface_faces == 0 ? 3 : surface_faces == 2 ? 2 : 1;
    }
    if (automatic != 1) tags.crease_edges.emplace_back(c.edge_verts[2 * e], c.edge_verts[2 * e + 1]);
  }
  // Vertices: what the edge dims give, lowered to 0 by a corner tag.
  for (std::uint32_t v = 0; v < c.num_vertices; ++v) {
    if (c.vertex_dim[v] != 0) continue;
    int curve_edges = 0;
    int higher = 0;
    for (std::uint32_t e : c.vertex_edges.row(v)) {
      if (c.edge_dim[e] == 1) ++curve_edges;
      else if (higher == 0 || c.edge_dim[e] < higher) higher = c.edge_dim[e];
    }
    const int automatic = curve_edges >= 3 ? 0 : curve_edges == 2 ? 1 : higher;
    if (automatic != 0) tags.corner_vertices.push_back(v);
  }
  return tags;
}

}  // namespace sublift
