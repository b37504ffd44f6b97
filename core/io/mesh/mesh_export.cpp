#include "core/io/mesh/mesh_export.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>

#include "core/base/errors.h"
#include "core/base/file_io.h"
#include "core/base/magnitude.h"

namespace sublift {

std::string format_double(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

void write_xyz_line(std::ostream& out, const char* prefix, const double* p) {
  out << prefix << format_double(p[0]) << ' ' << format_double(p[1]) << ' ' << format_double(p[2]) << '\n';
}

std::string attributes_not_written(const std::string& ext, std::span<const VertexAttribute> attributes) {
  const auto colour = [](const VertexAttribute& a) { return a.name == "red" || a.name == "green" || a.name == "blue"; };
  const auto colours = std::count_if(attributes.begin(), attributes.end(), colour);
  std::string dropped;
  for (const VertexAttribute& a : attributes) {
    // glTF: red, green, blue (alpha) as COLOR_0, the rest as "_NAME" attributes (surface_export.h).
    // VTK as POINT_DATA, OVM as vertex properties (core/io/lattice).
    if (ext == "ply" || ext == "gltf" || ext == "glb" || ext == "vtk" || ext == "ovm" || (ext == "obj" && colour(a) && colours == 3)) continue;
    dropped += (dropped.empty() ? "" : ", ") + a.name;
  }
  return dropped;
}

namespace {

// The attribute named `name`, or null.
const VertexAttribute* find_attribute(const SurfaceMesh& m, std::string_view name) {
  for (const VertexAttribute& a : m.attributes)
    if (a.name == name) return &a;
  return nullptr;
}

// An attribute value as its PLY type holds it: integer types rounded to the nearest and held to
// their range (a subdivided uchar colour is a mean of colours, so it stays in range anyway).
std::string attribute_text(const VertexAttribute& a, std::size_t v) {
  struct Range {
    std::string_view type;
    double lo, hi;
  };
  static constexpr Range kRanges[] = {{"char", -128, 127},       {"uchar", 0, 255},          {"short", -32768, 32767},
                                      {"ushort", 0, 65535},      {"int", -2147483648.0, 2147483647.0},
                                      {"uint", 0, 4294967295.0}};
  for (const Range& r : kRanges)
    if (a.type == r.type) return std::to_string(std::llround(std::clamp(a.values[v], r.lo, r.hi)));
  return format_double(a.values[v]);
}

void write_obj(std::ostream& out, const SurfaceMesh& m, const std::string& mtllib) {
  out << "# written by Sublift\n";
  if (!mtllib.empty()) out << "mtllib " << mtllib << '\n';
  const VertexAttribute *r = find_attribute(m, "red"), *g = find_attribute(m, "green"), *b = find_attribute(m, "blue");
  for (std::size_t v = 0; v < m.num_vertices(); ++v) {
    if (r && g && b) {  // `v x y z r g b`, colours 0..1 as OBJ readers expect them (PLY's uchar ones are 0..255)
      const auto unit = [&](const VertexAttribute* a) { return a->values[v] / (a->type == "uchar" ? 255.0 : a->type == "ushort" ? 65535.0 : 1.0); };
      const double p[6] = {m.positions[v].x, m.positions[v].y, m.positions[v].z, unit(r), unit(g), unit(b)};
      out << "v " << format_double(p[0]) << ' ' << format_double(p[1]) << ' ' << format_double(p[2]) << ' ';
      write_xyz_line(out, "", p + 3);
    } else {
      write_xyz_line(out, "v ", &m.positions[v].x);
    }
  }
  const bool uv = !m.uv.empty();
  if (uv)
    for (std::size_t k = 0; k < m.uv.num_points(); ++k)
      out << "vt " << format_double(m.uv.points[2 * k]) << ' ' << format_double(m.uv.points[2 * k + 1]) << '\n';
  if (!mtllib.empty()) out << "usemtl texture\n";
  for (std::size_t f = 0; f < m.num_faces(); ++f) {
    out << 'f';
    for (std::uint32_t k = m.face_offsets[f]; k < m.face_offsets[f + 1]; ++k) {
      out << ' ' << m.face_indices[k] + 1;
      if (uv) out << '/' << m.uv.corners[k] + 1;
    }
    out << '\n';
  }
  for (std::size_t l = 0; l < m.num_polylines(); ++l) {
    out << 'l';
    for (std::uint32_t v : m.polyline(l)) out << ' ' << v + 1;
    out << '\n';
  }
  for (const MeshTag& t : m.tags) {
    out << "t " << t.name << ' ' << t.ints.size() << '/' << t.floats.size() << '/' << t.strings.size();
    for (auto i : t.ints) out << ' ' << i;
    for (double d : t.floats) out << ' ' << format_double(d);
    for (const auto& s : t.strings) out << ' ' << s;
    out << '\n';
  }
}

// The body OFF and ASCII PLY share: a line per vertex (x y z, then the attributes when asked),
// then per face its size and 0-based corners.
void write_points_and_faces(std::ostream& out, const SurfaceMesh& m, bool attributes) {
  for (std::size_t v = 0; v < m.num_vertices(); ++v) {
    if (!attributes || m.attributes.empty()) {
      write_xyz_line(out, "", &m.positions[v].x);
      continue;
    }
    out << format_double(m.positions[v].x) << ' ' << format_double(m.positions[v].y) << ' ' << format_double(m.positions[v].z);
    for (const VertexAttribute& a : m.attributes) out << ' ' << attribute_text(a, v);
    out << '\n';
  }
  for (std::size_t f = 0; f < m.num_faces(); ++f) {
    out << m.face_size(f);
    for (std::uint32_t v : m.face(f)) out << ' ' << v;
    out << '\n';
  }
}

void write_off(std::ostream& out, const SurfaceMesh& m, const std::string&) {
  out << "OFF\n" << m.num_vertices() << ' ' << m.num_faces() << " 0\n";
  write_points_and_faces(out, m, false);
}

void write_ply(std::ostream& out, const SurfaceMesh& m, const std::string&) {
  out << "ply\nformat ascii 1.0\ncomment written by Sublift\nelement vertex " << m.num_vertices()
      << "\nproperty double x\nproperty double y\nproperty double z\n";
  for (const VertexAttribute& a : m.attributes) out << "property " << a.type << ' ' << a.name << '\n';
  out << "element face " << m.num_faces() << "\nproperty list uint int vertex_indices\nend_header\n";
  write_points_and_faces(out, m, true);
}

}  // namespace

void write_surface_mesh(const std::string& path, const SurfaceMesh& mesh, const std::string& mtllib) {
  const std::string ext = file_extension(path);
  void (*writer)(std::ostream&, const SurfaceMesh&, const std::string&) = nullptr;
  if (ext == "obj") writer = write_obj;
  else if (ext == "off") writer = write_off;
  else if (ext == "ply") writer = write_ply;
  else throw InputError(path, 0, "cannot write '." + ext + "' (expected .obj, .off or .ply)");
  if (ext != "obj" && mesh.num_faces() == 0 && mesh.num_polylines() > 0)
    throw InputError(path, 0, "." + ext + " cannot hold polylines (a curve); write .obj");
  check_writable_positions(path, mesh.positions);
  for (const VertexAttribute& a : mesh.attributes) {
    if (a.values.size() != mesh.num_vertices())
      throw InputError(path, 0, "vertex attribute '" + a.name + "' has " + std::to_string(a.values.size()) + " values for " +
                                    std::to_string(mesh.num_vertices()) + " vertices");
    if (const auto i = first_out_of_range(a.values))
      throw InputError(path, 0, "vertex attribute '" + a.name + "' of vertex " + std::to_string(*i) + " " +
                                    out_of_range_text(a.values[*i]) + "; nothing written");
  }
  if (!mesh.uv.empty())
    if (const std::string why = uv_problem(mesh.face_indices.size(), mesh.uv); !why.empty()) throw InputError(path, 0, "texture coordinates: " + why);
  write_file_atomic(path, [&](std::ostream& out) { writer(out, mesh, mtllib); });
}

}  // namespace sublift
