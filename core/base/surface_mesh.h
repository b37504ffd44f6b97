#pragma once
// SurfaceMesh: a polygon mesh as flat arrays, vertices and faces in file order.
//
// Layout: `positions[v]` for v in [0, num_vertices()); faces in CSR form, face f has the
// corners face_indices[face_offsets[f] .. face_offsets[f+1]) in their file order (the
// orientation the file gives). Invariants after import: face_offsets.front() == 0, offsets are
// increasing by at least 3, every index < num_vertices(), no face repeats a vertex, positions
// are finite. Non-manifold edges and vertices are allowed here (they are reported, not fixed).
// Polylines (OBJ `l` lines, curves) use the same CSR form in line_offsets/line_indices: each
// has at least 2 vertices, every index < num_vertices(), no vertex twice in a row and no segment
// used twice (in this polyline or an earlier one); first == last closes it.
// `tags` keeps OpenSubdiv-style `t` lines (crease, corner, ...) with 0-based vertex indices;
// `attributes` the per-vertex values beside positions (colours, scalars); `uv` the texture
// coordinates of the face corners.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace sublift {

/// A value per vertex that a file carries beside its position (PLY `red green blue alpha`,
/// `quality` and other scalar vertex properties, OBJ `v x y z r g b` colours): subdivision and
/// analysis carry it as a channel of its own, writers give it back under its name.
struct VertexAttribute {
  std::string name;            // the file's property name ("red", "quality", ...)
  std::string type;            // PLY type to write it back as ("uchar", "float", ...)
  std::vector<double> values;  // one per vertex, in the file's units (uchar colours 0..255)
};

/// Face-varying texture coordinates (OBJ `vt`, glTF TEXCOORD_0): `points` holds u, v per UV
/// point, `corners` one index into the points per face corner, laid out as the faces' corners
/// (face_indices; a Complex's faces.items). Two faces meeting at a vertex with different indices
/// there have a seam between them. Empty: the surface has none.
struct FaceVaryingUV {
  std::vector<double> points;          // 2 per UV point
  std::vector<std::uint32_t> corners;  // one per face corner
  bool empty() const { return corners.empty(); }
  std::size_t num_points() const { return points.size() / 2; }
};

/// "" when `uv` fits faces of `face_corners` corners in all: one index per corner, each below
/// the points, the points finite; else what is wrong (the one check readers, writers and
/// projects share).
std::string uv_problem(std::size_t face_corners, const FaceVaryingUV& uv);

/// The base-colour texture a surface's UVs map (glTF baseColorTexture): the image file's bytes
/// as read, undecoded, its media type, and the material and sampler values that go with it
/// (glTF's numbers, so a glTF written back looks as the source did). Empty bytes: none.
struct SurfaceTexture {
  std::string mime_type;  // "image/png", "image/jpeg"
  std::string bytes;
  std::string name;       // the image's file name or name ("" if none), for messages and file names
  double base_colour[4] = {1, 1, 1, 1};
  double metallic = 1.0, roughness = 1.0;
  int mag_filter = -1, min_filter = -1, wrap_s = 10497, wrap_t = 10497;  // -1: unset; 10497 REPEAT
  bool double_sided = false;
  bool empty() const { return bytes.empty(); }
};

/// One OpenSubdiv-style tag line: `t name ni/nf/ns ints... floats... strings...`.
struct MeshTag {
  std::string name;
  std::vector<std::int64_t> ints;
  std::vector<double> floats;
  std::vector<std::string> strings;
  std::size_t line = 0;  // 1-based source line, 0 if made in code
};

struct SurfaceMesh {
  std::vector<glm::dvec3> positions;
  std::vector<std::uint32_t> face_offsets{0};
  std::vector<std::uint32_t> face_indices;
  std::vector<std::uint32_t> line_offsets{0};
  std::vector<std::uint32_t> line_indices;
  std::vector<MeshTag> tags;
  std::vector<VertexAttribute> attributes;  // each with one value per vertex
  FaceVaryingUV uv;                         // texture coordinates per face corner (or none)

  std::size_t num_vertices() const { return positions.size(); }
  std::size_t num_faces() const { return face_offsets.size() - 1; }
  std::size_t face_size(std::size_t f) const { return face_offsets[f + 1] - face_offsets[f]; }
  /// Corners of face f, in file order.
  std::span<const std::uint32_t> face(std::size_t f) const {
    return {face_indices.data() + face_offsets[f], face_size(f)};
  }
  /// Appends a face; the caller guarantees the invariants above.
  void add_face(std::span<const std::uint32_t> corners) {
    face_indices.insert(face_indices.end(), corners.begin(), corners.end());
    face_offsets.push_back(static_cast<std::uint32_t>(face_indices.size()));
  }
  std::size_t num_polylines() const { return line_offsets.size() - 1; }
  /// Vertices of polyline l, in file order.
  std::span<const std::uint32_t> polyline(std::size_t l) const {
    return {line_indices.data() + line_offsets[l], line_offsets[l + 1] - line_offsets[l]};
  }
  /// Appends a polyline; the caller guarantees the invariants above.
  void add_polyline(std::span<const std::uint32_t> vertices) {
    line_indices.insert(line_indices.end(), vertices.begin(), vertices.end());
    line_offsets.push_back(static_cast<std::uint32_t>(line_indices.size()));
  }
};

}  // namespace sublift
