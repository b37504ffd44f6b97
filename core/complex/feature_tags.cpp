#include "core/complex/feature_tags.h"

#include "core/complex/complex_build.h"

namespace sublift {

// Uses the same untagged_* rules as assign_feature_dims (complex_build.h);
// tests/feature_tags_test.cpp checks that assign_feature_dims(derive_feature_tags(c)) gives c's dims.
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
  // A primitive needs a tag where its dim is lower than what topology alone would give it
  // (assign_feature_dims lowers, never raises).
  for (std::uint32_t f = 0; f < c.num_faces(); ++f)
    if (c.face_dim[f] < untagged_face_dim(c, f)) {
      auto r = c.faces.row(f);
      tags.feature_faces.emplace_back(r.begin(), r.end());
    }
  if (!c.edge_sharpness.empty() || !c.vertex_sharpness.empty()) {  // semi-sharp: every tag with its sharpness
    for (std::uint32_t e = 0; e < c.num_edges() && e < c.edge_sharpness.size(); ++e)
      if (c.edge_sharpness[e] > 0) {
        tags.crease_edges.emplace_back(c.edge_verts[2 * e], c.edge_verts[2 * e + 1]);
        tags.crease_sharpness.push_back(c.edge_sharpness[e]);
      }
    for (std::uint32_t v = 0; v < c.num_vertices && v < c.vertex_sharpness.size(); ++v)
      if (c.vertex_sharpness[v] > 0) {
        tags.corner_vertices.push_back(v);
        tags.corner_sharpness.push_back(c.vertex_sharpness[v]);
      }
    return tags;
  }
  for (std::uint32_t e = 0; e < c.num_edges(); ++e)
    if (c.edge_dim[e] < untagged_edge_dim(c, e)) tags.crease_edges.emplace_back(c.edge_verts[2 * e], c.edge_verts[2 * e + 1]);
  for (std::uint32_t v = 0; v < c.num_vertices; ++v)
    if (c.vertex_dim[v] < untagged_vertex_dim(c, v)) tags.corner_vertices.push_back(v);
  return tags;
}

}  // namespace sublift
