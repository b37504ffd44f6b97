#include "core/io/mesh/mesh_export.h"

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

namespace {

void write_obj(std::ostream& out, const SurfaceMesh& m) {
  out << "# written by Sublift\n";
  for (const glm::dvec3& p : m.positions) write_xyz_line(out, "v ", &p.x);
  for (std::size_t f = 0; f < m.num_faces(); ++f) {
    out << 'f';
    for (std::uint32_t v : m.face(f)) out << ' ' << v + 1;
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

// The body OFF and ASCII PLY share: a line per vertex, then per face its size and 0-based corners.
void write_points_and_faces(std::ostream& out, const SurfaceMesh& m) {
  for (const glm::dvec3& p : m.positions) write_xyz_line(out, "", &p.x);
  for (std::size_t f = 0; f < m.num_faces(); ++f) {
    out << m.face_size(f);
    for (std::uint32_t v : m.face(f)) out << ' ' << v;
    out << '\n';
  }
}

void write_off(std::ostream& out, const SurfaceMesh& m) {
  out << "OFF\n" << m.num_vertices() << ' ' << m.num_faces() << " 0\n";
  write_points_and_faces(out, m);
}

void write_ply(std::ostream& out, const SurfaceMesh& m) {
  out << "ply\nformat ascii 1.0\ncomment written by Sublift\nelement vertex " << m.num_vertices()
      << "\nproperty double x\nproperty double y\nproperty double z\nelement face " << m.num_faces()
      << "\nproperty list uint int vertex_indices\nend_header\n";
  write_points_and_faces(out, m);
}

}  // namespace

void write_surface_mesh(const std::string& path, const SurfaceMesh& mesh) {
  const std::string ext = file_extension(path);
  void (*writer)(std::ostream&, const SurfaceMesh&) = nullptr;
  if (ext == "obj") writer = write_obj;
  else if (ext == "off") writer = write_off;
  else if (ext == "ply") writer = write_ply;
  else throw InputError(path, 0, "cannot write '." + ext + "' (expected .obj, .off or .ply)");
  if (ext != "obj" && mesh.num_faces() == 0 && mesh.num_polylines() > 0)
    throw InputError(path, 0, "." + ext + " cannot hold polylines (a curve); write .obj");
  check_writable_positions(path, mesh.positions);
  write_file_atomic(path, [&](std::ostream& out) { writer(out, mesh); });
}

}  // namespace sublift
