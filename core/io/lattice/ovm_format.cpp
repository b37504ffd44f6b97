#include "core/io/lattice/ovm_format.h"

#include <algorithm>
#include <cmath>
#include <ostream>
#include <vector>

#include "core/base/errors.h"
#include "core/base/file_io.h"
#include "core/base/magnitude.h"
#include "core/base/text_lines.h"
#include "core/complex/cell_shapes.h"
#include "core/complex/shape_builder.h"
#include "core/io/mesh/mesh_export.h"

namespace sublift {
namespace {

constexpr std::size_t kMaxLineLength = std::size_t(1) << 20;

// The entity kinds of OpenVolumeMesh's property blocks, with the name a report uses.
struct PropertyKind {
  std::string_view key, name;
};
constexpr PropertyKind kPropertyKinds[] = {{"vprop", "vertex"},     {"eprop", "edge"},  {"heprop", "half-edge"},
                                           {"fprop", "face"},       {"hfprop", "half-face"},
                                           {"cprop", "cell"},       {"mprop", "mesh"}};

class OvmReader {
 public:
  OvmReader(std::string_view bytes, const std::string& file) : bytes_(bytes), file_(file), lines_(bytes, file, kMaxLineLength) {}

  Shape read() {
    header();
    const std::int64_t nv = count("Vertices", 6);  // "0 0 0\n"
    read_vertices(nv);
    const std::int64_t ne = count("Edges", 4);
    read_edges(ne, nv);
    const std::int64_t nf = count("Faces", 8);  // "3 0 2 4\n"
    read_faces(nf, ne);
    const std::int64_t nc = count("Polyhedra", 8);
    read_cells(nc);
    read_properties(nv, ne, nf, nc);
    report_faces_outside_cells();
    if (builder_.num_cells() == 0)
      throw InputError(file_, 0, nv == 0 ? "no vertices and no cells" : "no cells (a lattice needs at least one)");
    builder_.build(file_, static_cast<std::uint32_t>(nv), vertex_lines_, TagPolicy::Strict, shape_);
    return std::move(shape_);
  }

 private:
  std::size_t ln() const { return lines_.line_number(); }
  std::size_t bytes_left() const { return bytes_.size() - lines_.offset(); }

  // The next non-blank line's tokens; `what` says what the file ended before.
  void need_line(const std::string& what) {
    if (!next_tokens(lines_, tok_)) throw InputError(file_, ln(), "the file ends before " + what);
  }

  void header() {
    need_line("its 'OVM ASCII' header");
    const std::string first = to_lower(tok_[0]);
    if (first == "vertices") {  // OpenVolumeMesh reads a file without the header too
      shape_.report.add("no 'OVM ASCII' header line", ln());
      pending_section_ = true;
      return;
    }
    if (first != "ovm") throw InputError(file_, ln(), "not an OpenVolumeMesh file: the first line must be 'OVM ASCII'");
    if (tok_.size() > 1 && to_lower(tok_[1]) == "binary")
      throw InputError(file_, ln(), "binary .ovm files are not supported; save the lattice as OVM ASCII");
    if (tok_.size() > 2 || (tok_.size() == 2 && to_lower(tok_[1]) != "ascii"))
      throw InputError(file_, ln(), "the header must be 'OVM ASCII'");
  }

  // A section keyword line and its count line; the count must fit in what is left of the file
  // at `min_bytes` per record, so nothing is reserved for a count the file cannot hold.
  std::int64_t count(const std::string& section, std::size_t min_bytes) {
    if (!pending_section_) need_line("its '" + section + "' section");
    pending_section_ = false;
    if (tok_.size() != 1 || to_lower(tok_[0]) != to_lower(section))
      throw InputError(file_, ln(), "expected the '" + section + "' section, found '" + printable(tok_[0]) + "'");
    need_line("the count of its " + to_lower(section));
    const auto n = tok_.size() == 1 ? parse_int(tok_[0]) : std::nullopt;
    if (!n || *n < 0) throw InputError(file_, ln(), "the " + to_lower(section) + " count must be one non-negative integer");
    if (static_cast<double>(*n) * static_cast<double>(min_bytes) > static_cast<double>(bytes_left()) + 1.0)
      throw InputError(file_, ln(), std::to_string(*n) + " " + to_lower(section) + " cannot fit in the " +
                                        std::to_string(bytes_left()) + " bytes left in the file");
    if (*n > 0x7ffffffeLL) throw InputError(file_, ln(), "too many " + to_lower(section));
    return *n;
  }

  std::int64_t index(std::string_view t, std::int64_t limit, const char* what) {
    const auto v = parse_int(t);
    if (!v) throw InputError(file_, ln(), "'" + printable(t) + "' is not a " + what + " index");
    if (*v < 0 || *v >= limit)
      throw InputError(file_, ln(), std::string(what) + " index " + printable(t) + " out of range (0.." +
                                        std::to_string(limit - 1) + ")");
    return *v;
  }

  void read_vertices(std::int64_t nv) {
    shape_.positions.reserve(static_cast<std::size_t>(nv) * 3);
    vertex_lines_.reserve(static_cast<std::size_t>(nv));
    for (std::int64_t i = 0; i < nv; ++i) {
      need_line("vertex " + std::to_string(i) + " of " + std::to_string(nv));
      if (tok_.size() != 3) throw InputError(file_, ln(), "a vertex line is 'x y z'");
      for (const std::string_view t : tok_) {
        const auto d = parse_double(t);
        if (!d) throw InputError(file_, ln(), "'" + printable(t) + "' is not a finite number");
        if (!in_supported_range(*d))
          throw InputError(file_, ln(), "coordinate " + printable(t) + " exceeds the supported magnitude " + max_coordinate_text());
        shape_.positions.push_back(*d);
      }
      vertex_lines_.push_back(ln());
    }
  }

  void read_edges(std::int64_t ne, std::int64_t nv) {
    edges_.reserve(static_cast<std::size_t>(ne) * 2);
    for (std::int64_t e = 0; e < ne; ++e) {
      need_line("edge " + std::to_string(e) + " of " + std::to_string(ne));
      if (tok_.size() != 2) throw InputError(file_, ln(), "an edge line is 'from to' (two vertex indices)");
      const std::int64_t a = index(tok_[0], nv, "vertex"), b = index(tok_[1], nv, "vertex");
      if (a == b) throw InputError(file_, ln(), "edge " + std::to_string(e) + " joins vertex " + std::to_string(a) + " to itself");
      edges_.push_back(a);
      edges_.push_back(b);
    }
  }

  // Half-edge h runs from(h) -> to(h): 2e is edges_[2e] -> edges_[2e + 1], 2e + 1 the reverse.
  std::int64_t from(std::int64_t h) const { return edges_[static_cast<std::size_t>(h)]; }
  std::int64_t to(std::int64_t h) const { return edges_[static_cast<std::size_t>(h ^ 1)]; }

  void read_faces(std::int64_t nf, std::int64_t ne) {
    face_offsets_.reserve(static_cast<std::size_t>(nf) + 1);
    face_lines_.reserve(static_cast<std::size_t>(nf));
    for (std::int64_t f = 0; f < nf; ++f) {
      need_line("face " + std::to_string(f) + " of " + std::to_string(nf));
      const auto d = parse_int(tok_[0]);
      if (!d || *d < 3) throw InputError(file_, ln(), "a face line starts with its number of half-edges (at least 3)");
      if (static_cast<std::size_t>(*d) + 1 != tok_.size())
        throw InputError(file_, ln(), "face " + std::to_string(f) + " says " + std::to_string(*d) + " half-edges and lists " +
                                          std::to_string(tok_.size() - 1));
      hes_.clear();
      for (std::size_t k = 1; k < tok_.size(); ++k) hes_.push_back(index(tok_[k], 2 * ne, "half-edge"));
      for (std::size_t k = 0; k < hes_.size(); ++k) {
        const std::int64_t h = hes_[k], next = hes_[(k + 1) % hes_.size()];
        if (to(h) != from(next))
          throw InputError(file_, ln(), "face " + std::to_string(f) + ": its half-edges do not form a loop (half-edge " +
                                            std::to_string(h) + " ends at vertex " + std::to_string(to(h)) + ", the next, " +
                                            std::to_string(next) + ", starts at vertex " + std::to_string(from(next)) + ")");
        face_loops_.push_back(from(h));
      }
      face_offsets_.push_back(face_loops_.size());
      face_lines_.push_back(ln());
    }
    face_used_.assign(static_cast<std::size_t>(nf), 0);
  }

  void read_cells(std::int64_t nc) {
    const auto nf = static_cast<std::int64_t>(face_lines_.size());
    for (std::int64_t k = 0; k < nc; ++k) {
      need_line("polyhedron " + std::to_string(k) + " of " + std::to_string(nc));
      const auto d = parse_int(tok_[0]);
      if (!d || *d < 4) throw InputError(file_, ln(), "a polyhedron line starts with its number of half-faces (at least 4)");
      if (static_cast<std::size_t>(*d) + 1 != tok_.size())
        throw InputError(file_, ln(), "polyhedron " + std::to_string(k) + " says " + std::to_string(*d) +
                                          " half-faces and lists " + std::to_string(tok_.size() - 1));
      // The builder checks closure and reports inconsistently oriented cells (and keeps them).
      builder_.begin_cell(ln(), "cell " + std::to_string(k));
      for (std::size_t i = 1; i < tok_.size(); ++i) {
        const std::int64_t hf = index(tok_[i], 2 * nf, "half-face"), f = hf / 2;
        face_used_[static_cast<std::size_t>(f)] = 1;
        loop_.assign(face_loops_.begin() + static_cast<std::ptrdiff_t>(f == 0 ? 0 : face_offsets_[f - 1]),
                     face_loops_.begin() + static_cast<std::ptrdiff_t>(face_offsets_[f]));
        if (hf & 1) std::reverse(loop_.begin(), loop_.end());
        builder_.add_cell_face(loop_, ln());
      }
    }
  }

  void read_properties(std::int64_t nv, std::int64_t ne, std::int64_t nf, std::int64_t nc) {
    while (next_tokens(lines_, tok_)) {
      const std::size_t line = ln();
      const std::string key = to_lower(tok_[0]);
      const PropertyKind* kind = nullptr;
      for (const PropertyKind& p : kPropertyKinds)
        if (p.key == key) kind = &p;
      if (!kind || tok_.size() < 3)
        throw InputError(file_, line, "expected a property block ('vprop TYPE \"name\"', or eprop, heprop, fprop, hfprop, cprop, mprop), found '" +
                                          printable(tok_[0]) + "'");
      // The name is everything between the first and the last quote.
      const std::string_view rest(tok_[2].data(), static_cast<std::size_t>(tok_.back().data() + tok_.back().size() - tok_[2].data()));
      const std::size_t q0 = rest.find('"'), q1 = rest.rfind('"');
      if (q0 == std::string_view::npos || q1 == q0) throw InputError(file_, line, "a property's name is written in double quotes");
      const std::string name(rest.substr(q0 + 1, q1 - q0 - 1)), type = to_lower(tok_[1]);
      const std::int64_t n = key == "vprop" ? nv : key == "eprop" ? ne : key == "heprop" ? 2 * ne : key == "fprop" ? nf
                           : key == "hfprop" ? 2 * nf : key == "cprop" ? nc : 1;
      // A vertex property of one number per vertex is a material value: an attribute channel.
      const bool scalar = key == "vprop" && (type == "double" || type == "float" || type == "int" || type == "uint" ||
                                             type == "short" || type == "ushort" || type == "char" || type == "uchar");
      VertexAttribute a{name, type, {}};
      if (scalar) a.values.reserve(std::size_t(n));
      for (std::int64_t i = 0; i < n; ++i) {
        if (!next_tokens(lines_, tok_))
          throw InputError(file_, line, std::string(kind->name) + " property \"" + printable(name) + "\" needs " + std::to_string(n) +
                                            " values; the file ends after " + std::to_string(i));
        if (!scalar) continue;
        const auto x = tok_.size() == 1 ? parse_double(tok_[0]) : std::nullopt;
        if (!x || !std::isfinite(*x) || std::abs(*x) > kMaxCoordinate)
          throw InputError(file_, ln(), "vertex property \"" + printable(name) + "\": value " + std::to_string(i) + " is not one finite number within " +
                                            max_coordinate_text());
        a.values.push_back(*x);
      }
      if (scalar)
        shape_.attributes.push_back(std::move(a));
      else
        shape_.report.note_not_kept(std::string(kind->name) + " property \"" + printable(name) + "\" (" + printable(type) + ")", line);
    }
  }

  void report_faces_outside_cells() {
    for (std::size_t f = 0; f < face_used_.size(); ++f)
      if (!face_used_[f]) shape_.report.add("faces that belong to no polyhedron (ignored)", face_lines_[f]);
  }

  std::string_view bytes_;
  const std::string& file_;
  LineReader lines_;
  std::vector<std::string_view> tok_;
  bool pending_section_ = false;
  Shape shape_;
  ShapeBuilder builder_;
  std::vector<std::size_t> vertex_lines_, face_lines_, face_offsets_;
  std::vector<std::int64_t> edges_, face_loops_, hes_, loop_;
  std::vector<char> face_used_;
};

}  // namespace

Shape read_ovm(std::string_view bytes, const std::string& file) { return OvmReader(bytes, file).read(); }

void write_ovm(const std::string& path, const Complex& c, std::span<const double> xyz, std::span<const VertexAttribute> attributes) {
  if (c.dim != 3) throw InputError(path, 0, "a .ovm holds volumes; this shape has dimension " + std::to_string(c.dim));
  if (xyz.size() != 3 * static_cast<std::size_t>(c.num_vertices))
    throw InputError(path, 0, "positions do not match the vertex count");
  check_writable_positions(path, xyz);
  const auto oriented = oriented_lattice_loops(c, xyz);
  write_file_atomic(path, [&](std::ostream& out) {
    out << "OVM ASCII\nVertices\n" << c.num_vertices << '\n';
    for (std::uint32_t v = 0; v < c.num_vertices; ++v) write_xyz_line(out, "", &xyz[3 * std::size_t(v)]);
    out << "Edges\n" << c.num_edges() << '\n';
    for (std::uint32_t e = 0; e < c.num_edges(); ++e) out << c.edge_verts[2 * e] << ' ' << c.edge_verts[2 * e + 1] << '\n';
    out << "Faces\n" << c.num_faces() << '\n';
    for (std::uint32_t f = 0; f < c.num_faces(); ++f) {
      const auto row = c.faces.row(f), erow = c.face_edges.row(f);  // erow[i] joins row[i] and row[i + 1]
      out << row.size();
      for (std::size_t i = 0; i < row.size(); ++i) out << ' ' << 2 * erow[i] + (c.edge_verts[2 * erow[i]] == row[i] ? 0 : 1);
      out << '\n';
    }
    out << "Polyhedra\n" << c.num_cells() << '\n';
    for (std::uint32_t k = 0; k < c.num_cells(); ++k) {
      const auto faces = c.cell_faces.row(k);
      out << faces.size();
      for (std::size_t i = 0; i < faces.size(); ++i) {
        const auto row = c.faces.row(faces[i]);
        const auto& loop = oriented[k][i];  // outward, as the face runs or reversed; OVM wants the inner side
        const bool outward_as_stored = loop.size() > 1 && loop[0] == row[0] && loop[1] == row[1];
        out << ' ' << 2 * faces[i] + (outward_as_stored ? 1 : 0);
      }
      out << '\n';
    }
    for (const VertexAttribute& a : attributes) {  // material values: vertex properties in double
      std::string name = a.name;
      std::replace(name.begin(), name.end(), '"', '\'');
      out << "vprop double \"" << name << "\"\n";
      for (double x : a.values) out << format_double(x) << '\n';
    }
  });
}

}  // namespace sublift
