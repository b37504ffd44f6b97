#include "core/io/lattice/shape_io.h"

#include "core/complex/polygon_normal.h"
#include "core/io/model/surface_export.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>

#include "core/complex/complex_build.h"
#include "core/complex/face_varying.h"
#include "core/base/errors.h"
#include "core/complex/feature_tags.h"
#include "core/base/file_io.h"
#include "core/io/lattice/lattice_format.h"
#include "core/io/lattice/ovm_format.h"
#include "core/io/mesh/mesh_export.h"
#include "core/io/mesh/mesh_import.h"
#include "core/io/model/model.h"
#include "core/io/model/surface_export.h"
#include "core/io/model/weld.h"
#include "core/complex/polygon_normal.h"
#include "core/io/lattice/vtk_format.h"

namespace sublift {
namespace {

namespace fs = std::filesystem;

constexpr std::string_view kShapeFormats = ".obj, .off, .ply, .gltf, .glb (surfaces), .lattice, .ovm or .vtk";  // read and written
constexpr std::string_view kReadFormats = ".obj, .off, .ply, .gltf, .glb, .lattice, .ovm or .vtk";

Shape shape_from_mesh(const std::string& name, LoadedMesh loaded) {
  Shape shape;
  shape.report = std::move(loaded.report);
  shape.attributes = std::move(loaded.mesh.attributes);
  shape.uv = std::move(loaded.mesh.uv);
  const SurfaceMesh& m = loaded.mesh;
  shape.positions.reserve(3 * m.num_vertices());
  for (const glm::dvec3& p : m.positions) shape.positions.insert(shape.positions.end(), {p.x, p.y, p.z});
  try {
    if (m.num_faces() > 0) {
      if (m.num_polylines() > 0)
        shape.report.add("polylines ignored: the file has faces, so it is a surface (tag creases with 't crease')", 0);
      shape.base = complex_from_surface_mesh(m, &shape.report);
    } else {
      Csr lines;
      lines.offsets = m.line_offsets;
      lines.items = m.line_indices;
      const FeatureTags tags = feature_tags_from_obj(m.tags, shape.report);
      if (!tags.crease_edges.empty()) shape.report.add("crease tags ignored: every edge of a curve is a curve feature", 0);
      FeatureTags corners;
      corners.corner_vertices = tags.corner_vertices;
      shape.base = complex_from_polylines(static_cast<std::uint32_t>(m.num_vertices()), lines, corners);
    }
  } catch (const TopologyError& e) {
    throw InputError(name, 0, e.what());
  }
  return shape;
}

// A glTF's triangles as a surface, in world space, welded by weld_by_position (weld.h: the same
// vertices and order as the frames of sample_gltf_animation).
Shape shape_from_gltf(const std::string& path) {
  const Model model = import_model(path);
  if (model.faces.rows() == 0) throw InputError(path, 0, "no triangles to open as a surface (points and lines only)");
  LoadedMesh loaded;
  SurfaceMesh& m = loaded.mesh;
  const PositionWeld weld = weld_by_position(model.positions, model.faces);  // glTF faces are triangles
  m.positions.reserve(weld.first.size());
  for (std::uint32_t v : weld.first) m.positions.emplace_back(model.positions[3 * v], model.positions[3 * v + 1], model.positions[3 * v + 2]);
  m.face_offsets = weld.faces.offsets;
  m.face_indices = weld.faces.items;
  for (std::size_t k = 0; k < weld.dropped; ++k) loaded.report.add("triangles whose corners welded together (dropped)", 0);
  for (const std::string& n : model.notes) loaded.report.add(n, 0);
  if (!model.colors.empty()) {  // COLOR_0 as attributes red, green, blue (and alpha unless all 1), 0..1
    bool alpha = false;
    std::size_t parted = 0;
    for (std::size_t v = 0; v < model.num_vertices(); ++v) {
      alpha = alpha || model.colors[4 * v + 3] != 1.0f;
      const std::uint32_t f = weld.first[weld.welded[v]];
      parted += f != v && !std::equal(&model.colors[4 * v], &model.colors[4 * v] + 4, &model.colors[4 * std::size_t(f)]);
    }
    const char* names[4] = {"red", "green", "blue", "alpha"};
    for (int k = 0; k < (alpha ? 4 : 3); ++k) {
      VertexAttribute a{names[k], "float", {}};
      for (std::uint32_t v : weld.first) a.values.push_back(model.colors[4 * std::size_t(v) + std::size_t(k)]);
      m.attributes.push_back(std::move(a));
    }
    if (parted > 0)
      loaded.report.note_not_kept(std::to_string(parted) + " glTF vertices whose COLOR_0 differs from another copy at the same position (the first copy's colour kept)", 0);
  }
  for (const auto& [semantic, values] : model.custom) {  // "_QUALITY" -> attribute "quality"
    VertexAttribute a{"", "float", {}};
    for (std::size_t i = 1; i < semantic.size(); ++i) a.name += char(std::tolower(static_cast<unsigned char>(semantic[i])));
    if (a.name.empty()) a.name = "custom";
    for (std::uint32_t v : weld.first) a.values.push_back(values[v]);
    m.attributes.push_back(std::move(a));
  }
  // TEXCOORD_0 as face-varying UVs, one UV point per glTF vertex, v up as OBJ has it (glTF's t
  // runs down the image: v = 1 - t); the split of the file's vertices at seams is kept this way.
  const bool uvs = !model.texcoords.empty();
  SurfaceTexture texture;
  if (uvs) {
    m.uv.points.resize(2 * model.num_vertices());
    for (std::size_t v = 0; v < model.num_vertices(); ++v) {
      m.uv.points[2 * v] = double(model.texcoords[2 * v]);
      m.uv.points[2 * v + 1] = 1.0 - double(model.texcoords[2 * v + 1]);
    }
    m.uv.corners.reserve(m.face_indices.size());
    for (std::uint32_t t : weld.source)
      for (std::uint32_t v : model.faces.row(t)) m.uv.corners.push_back(v);
    std::vector<std::string> notes;
    texture = gltf_surface_texture(model, notes);
    for (const std::string& n : notes) loaded.report.note_not_kept(n, 0);
  }
  if (m.positions.size() < model.num_vertices())
    loaded.report.add("glTF vertices welded by position: " + std::to_string(model.num_vertices()) + " into " +
                          std::to_string(m.positions.size()) + " (the file splits them at seams of normals and UVs)",
                      0);
  std::vector<std::string> lost{"normals"};
  if (!uvs) lost.push_back("UVs");
  if (model.colors.empty()) lost.push_back("colours");
  if (texture.empty()) lost.push_back("materials");
  lost.push_back("nodes");
  std::string what = "glTF meshes opened as one surface without their ";
  for (std::size_t k = 0; k < lost.size(); ++k) what += (k == 0 ? "" : k + 1 == lost.size() ? " or " : ", ") + lost[k];
  loaded.report.note_not_kept(what, 0);
  Shape shape = shape_from_mesh(path, std::move(loaded));
  shape.texture = std::move(texture);
  return shape;
}

// OUT.mtl naming the texture, written beside OUT.obj as OUT_<name> (the image's bytes as read);
// returns the library's file name for `mtllib`.
std::string write_obj_material(const std::string& obj_path, const SurfaceTexture& t) {
  const fs::path out(obj_path);
  const std::string stem = out.stem().string();
  std::string image = t.name;
  for (char& ch : image)
    if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '.' && ch != '-' && ch != '_') ch = '_';
  if (image.empty() || image.find('.') == std::string::npos) image += t.mime_type == "image/jpeg" ? ".jpg" : ".png";
  image = stem + "_" + image;
  const std::string mtl = stem + ".mtl";
  write_file_atomic((out.parent_path() / image).string(), [&](std::ostream& o) { o.write(t.bytes.data(), std::streamsize(t.bytes.size())); }, true);
  write_file_atomic((out.parent_path() / mtl).string(), [&](std::ostream& o) {
    o << "# written by Sublift\nnewmtl texture\nKd " << format_double(t.base_colour[0]) << ' ' << format_double(t.base_colour[1]) << ' '
      << format_double(t.base_colour[2]) << "\nmap_Kd " << image << '\n';
  });
  return mtl;
}

// Polylines covering every edge of a curve once: maximal chains through vertices on exactly
// two edges, then the closed loops that remain (first vertex repeated at the end).
void curve_polylines(const Complex& c, SurfaceMesh& m) {
  const Csr ve = c.vertex_edges.rows() == c.num_vertices ? c.vertex_edges : [&] {
    Csr e;
    e.offsets.resize(c.num_edges() + 1);
    for (std::uint32_t i = 0; i <= c.num_edges(); ++i) e.offsets[i] = 2 * i;
    e.items = c.edge_verts;
    return transpose(e, c.num_vertices);
  }();
  std::vector<char> done(c.num_edges(), 0);
  std::vector<std::uint32_t> chain;
  auto walk = [&](std::uint32_t v, std::uint32_t e) {
    chain.assign(1, v);
    for (;;) {
      done[e] = 1;
      v = c.edge_verts[2 * e] == v ? c.edge_verts[2 * e + 1] : c.edge_verts[2 * e];
      chain.push_back(v);
      if (ve.size(v) != 2) break;
      const auto r = ve.row(v);
      const std::uint32_t next = r[0] == e ? r[1] : r[0];
      if (done[next]) break;
      e = next;
    }
    m.add_polyline(chain);
  };
  for (std::uint32_t v = 0; v < c.num_vertices; ++v)
    if (ve.size(v) != 2)
      for (std::uint32_t e : ve.row(v))
        if (!done[e]) walk(v, e);
  for (std::uint32_t e = 0; e < c.num_edges(); ++e)
    if (!done[e]) walk(c.edge_verts[2 * e], e);
}

}  // namespace

Shape read_shape_from_memory(const std::string& name, const std::string& bytes) {
  const std::string ext = file_extension(name);
  if (ext == "lattice") return read_lattice(bytes, name);
  if (ext == "ovm") return read_ovm(bytes, name);
  if (ext == "vtk") return read_vtk(bytes, name);
  if (ext == "obj" || ext == "off" || ext == "ply") return shape_from_mesh(name, import_surface_mesh_from_memory(name, bytes));
  if (ext == "gltf" || ext == "glb") throw InputError(name, 0, "a glTF is read from its file (its buffers and images live beside it)");
  throw InputError(name, 0, "unsupported format '." + ext + "' (expected " + std::string(kReadFormats) + ")");
}

Shape read_shape(const std::string& path) {
  const std::string ext = file_extension(path);
  if (ext == "gltf" || ext == "glb") return shape_from_gltf(path);  // reads its buffers from its own folder
  if (ext != "lattice" && ext != "ovm" && ext != "vtk" && ext != "obj" && ext != "off" && ext != "ply")
    throw InputError(path, 0, "unsupported format '." + ext + "' (expected " + std::string(kReadFormats) + ")");
  return read_shape_from_memory(path, read_file_bytes(path));
}

std::string shape_output_problem(const std::string& path, int dim) {
  const std::string ext = file_extension(path);
  const std::string what = dim == 3 ? "lattice" : dim == 2 ? "surface" : "curve";
  const bool volume_only = ext == "lattice" || ext == "ovm";
  if (ext == "vtk") return "";
  if ((ext == "gltf" || ext == "glb") && dim != 2) return "a " + what + " cannot be written as ." + ext + "; use .obj or .vtk";
  if (ext == "gltf" || ext == "glb") return "";
  if (!volume_only && ext != "obj" && ext != "off" && ext != "ply")
    return "cannot write '." + ext + "' (expected " + std::string(kShapeFormats) + ")";
  if (dim == 3 && !volume_only) return "a lattice cannot be written as ." + ext + "; use .lattice, .ovm or .vtk";
  if (dim != 3 && volume_only) return "a ." + ext + " holds volumes; write this " + what + " as .obj or .vtk";
  if (dim == 1 && ext != "obj") return "a curve cannot be written as ." + ext + "; use .obj or .vtk";
  return "";
}

std::vector<std::string> write_shape(const std::string& path, const Complex& c, std::span<const double> xyz,
                                     std::span<const VertexAttribute> attributes, const FaceVaryingUV* uv,
                                     const SurfaceTexture* texture) {
  const std::string ext = file_extension(path);
  std::vector<std::string> notes;
  if (xyz.size() != 3 * static_cast<std::size_t>(c.num_vertices))
    throw InputError(path, 0, "positions do not match the vertex count");
  if (const std::string why = shape_output_problem(path, c.dim); !why.empty()) throw InputError(path, 0, why);
  if (uv && uv->empty()) uv = nullptr;
  if (texture && (texture->empty() || !uv)) texture = nullptr;
  if (uv)
    if (const std::string why = uv_problem(c, *uv); !why.empty()) throw InputError(path, 0, "texture coordinates: " + why);
  const bool uv_format = ext == "obj" || ext == "gltf" || ext == "glb";
  if (uv && !uv_format) {
    notes.push_back("." + ext + " cannot hold texture coordinates: " + std::to_string(uv->num_points()) + " UV points not written (use .obj, .gltf or .glb)");
    if (texture) notes.push_back("." + ext + " cannot hold a texture: '" + texture->name + "' not written (use .obj, .gltf or .glb)");
  }
  // What the format cannot hold of the attributes is named (PLY holds them all, OBJ colours).
  if (const std::string dropped = attributes_not_written(ext, attributes); !dropped.empty())
    notes.push_back("." + ext + " cannot hold the vertex attributes " + dropped + ": not written (use " +
                    (c.dim == 3 ? std::string(".vtk or .ovm)") : ".ply" + std::string(ext == "obj" ? "; .obj holds red, green and blue as 'v x y z r g b')" : ")")));
  if (ext == "vtk" || ext == "lattice") {
    if (ext == "vtk")
      write_vtk(path, c, xyz, attributes);
    else
      write_lattice(path, c, xyz);
    return notes;
  }
  if (ext == "ovm") {
    write_ovm(path, c, xyz, attributes);
    if (const FeatureTags tags = derive_feature_tags(c);
        !tags.feature_faces.empty() || !tags.crease_edges.empty() || !tags.corner_vertices.empty())
      notes.push_back(".ovm cannot hold feature tags: " + std::to_string(tags.feature_faces.size()) + " feature faces, " +
                      std::to_string(tags.crease_edges.size()) + " crease edges and " +
                      std::to_string(tags.corner_vertices.size()) + " corners not written (use .lattice or .vtk)");
    return notes;
  }
  if (ext == "gltf" || ext == "glb") {  // a surface's net with area-weighted normals, colours as COLOR_0
    const std::vector<double> normals = area_weighted_normals(c.faces, xyz);
    for (std::string& n : write_surface_with_normals(path, c.faces, xyz, normals, attributes, uv, texture)) notes.push_back(std::move(n));
    if (const FeatureTags tags = derive_feature_tags(c); !tags.crease_edges.empty() || !tags.corner_vertices.empty())
      notes.push_back("." + ext + " cannot hold feature tags: " + std::to_string(tags.crease_edges.size()) + " crease edges and " +
                      std::to_string(tags.corner_vertices.size()) + " corners not written (use .obj or .vtk)");
    return notes;
  }
  SurfaceMesh m;
  m.positions.resize(c.num_vertices);
  for (std::uint32_t v = 0; v < c.num_vertices; ++v) m.positions[v] = {xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]};
  if (c.dim == 2) {
    m.face_offsets = c.faces.offsets;
    m.face_indices = c.faces.items;
  } else {
    curve_polylines(c, m);
  }
  const FeatureTags tags = derive_feature_tags(c);
  // Sharpness 10: what OpenSubdiv treats as infinitely sharp; semi-sharp tags keep their value.
  const auto sharpness = [](const std::vector<float>& s, std::size_t k) {
    return k < s.size() && std::isfinite(s[k]) ? double(s[k]) : 10.0;
  };
  for (std::size_t k = 0; k < tags.crease_edges.size(); ++k)
    m.tags.push_back({"crease", {tags.crease_edges[k].first, tags.crease_edges[k].second}, {sharpness(tags.crease_sharpness, k)}, {}, 0});
  for (std::size_t k = 0; k < tags.corner_vertices.size(); ++k)
    m.tags.push_back({"corner", {tags.corner_vertices[k]}, {sharpness(tags.corner_sharpness, k)}, {}, 0});
  if (ext != "obj" && !m.tags.empty()) {
    notes.push_back("." + ext + " cannot hold feature tags: " + std::to_string(tags.crease_edges.size()) +
                    " crease edges and " + std::to_string(tags.corner_vertices.size()) +
                    " corners not written (use .obj or .vtk)");
    m.tags.clear();
  }
  m.attributes.assign(attributes.begin(), attributes.end());
  std::string mtllib;
  if (uv && ext == "obj") {
    m.uv = *uv;
    if (texture) mtllib = write_obj_material(path, *texture);
  }
  write_surface_mesh(path, m, mtllib);
  return notes;
}

}  // namespace sublift
