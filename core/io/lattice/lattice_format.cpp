#include "core/io/lattice/lattice_format.h"

#include <cmath>
#include <ostream>
#include <vector>

#include "core/complex/cell_shapes.h"
#include "core/base/errors.h"
#include "core/complex/feature_tags.h"
#include "core/base/file_io.h"
#include "core/base/magnitude.h"
#include "core/io/mesh/mesh_export.h"
#include "core/complex/shape_builder.h"
#include "core/base/text_lines.h"

namespace sublift {
namespace {

constexpr std::size_t kMaxLineLength = std::size_t(1) << 20;
constexpr std::string_view kMagic = "sublift-lattice";

bool shape_keyword(std::string_view k, CellShape& s) {
  if (k == "hex") s = CellShape::Hexahedron;
  else if (k == "wedge") s = CellShape::Wedge;
  else if (k == "pyramid") s = CellShape::Pyramid;
  else if (k == "tet") s = CellShape::Tetrahedron;
  else return false;
  return true;
}

}  // namespace

Shape read_lattice(std::string_view bytes, const std::string& file) {
  Shape shape;
  ShapeBuilder builder;
  std::vector<std::size_t> vertex_lines;
  std::vector<std::string_view> tok;
  std::vector<std::int64_t> ids;
  LineReader lines(bytes, file, kMaxLineLength);
  std::string_view line;
  if (!lines.next(line)) throw InputError(file, 0, "empty file (expected 'sublift-lattice 1' on the first line)");
  split_tokens(line, tok);
  if (tok.empty() || tok[0] != kMagic)
    throw InputError(file, 1, "not a Sublift lattice: the first line must be 'sublift-lattice 1'");
  if (tok.size() != 2 || !parse_int(tok[1]))
    throw InputError(file, 1, "the first line must be 'sublift-lattice VERSION'");
  if (*parse_int(tok[1]) != 1)
    throw InputError(file, 1, "unsupported .lattice version " + printable(tok[1]) + " (this Sublift reads version 1)");

  std::size_t open_cell = 0;  // line of the `cell` being read, 0 outside
  std::size_t cells = 0;
  auto read_ids = [&](std::size_t ln) {  // the vertex indices after the keyword
    ids.clear();
    for (std::size_t k = 1; k < tok.size(); ++k) {
      auto v = parse_int(tok[k]);
      if (!v) throw InputError(file, ln, "'" + printable(tok[k]) + "' is not a vertex index");
      if (*v < 0 || *v > 0xfffffffeLL)
        throw InputError(file, ln, "vertex index " + printable(tok[k]) + " out of range (indices are 0-based)");
      ids.push_back(*v);
    }
  };
  while (next_tokens(lines, tok)) {
    const std::size_t ln = lines.line_number();
    const std::string_view key = tok[0];
    CellShape cs;
    if (open_cell && key != "f" && key != "end")
      throw InputError(file, open_cell, "cell is not closed: '" + printable(key, 16) + "' on line " +
                                            std::to_string(ln) + " before its 'end'");
    if (key == "v") {
      if (tok.size() != 4) throw InputError(file, ln, "a vertex line is 'v x y z'");
      for (int k = 1; k <= 3; ++k) {
        auto d = parse_double(tok[k]);
        if (!d) throw InputError(file, ln, "'" + printable(tok[k]) + "' is not a finite number");
        if (std::abs(*d) > kMaxCoordinate)
          throw InputError(file, ln, "coordinate " + printable(tok[k]) + " exceeds the supported magnitude " + max_coordinate_text());
        shape.positions.push_back(*d);
      }
      vertex_lines.push_back(ln);
      if (vertex_lines.size() > 0xfffffffeu) throw InputError(file, ln, "too many vertices");
    } else if (shape_keyword(key, cs)) {
      read_ids(ln);
      const int n = cell_shape_vertex_count(cs);
      if (ids.size() != static_cast<std::size_t>(n))
        throw InputError(file, ln, "'" + printable(key) + "' takes " + std::to_string(n) + " vertex indices, got " +
                                       std::to_string(ids.size()));
      builder.begin_cell(ln, "cell " + std::to_string(cells++) + " (" + cell_shape_name(cs) + ")");
      std::vector<std::int64_t> loop;
      for (const auto& f : cell_shape_faces(cs)) {
        loop.clear();
        for (int i : f) loop.push_back(ids[static_cast<std::size_t>(i)]);
        builder.add_cell_face(loop, ln);
      }
    } else if (key == "cell") {
      if (tok.size() != 1) throw InputError(file, ln, "'cell' stands alone on its line; faces follow as 'f' lines");
      open_cell = ln;
      builder.begin_cell(ln, "cell " + std::to_string(cells++));
    } else if (key == "f") {
      if (!open_cell) throw InputError(file, ln, "'f' outside a 'cell' ... 'end' block");
      read_ids(ln);
      builder.add_cell_face(ids, ln);
    } else if (key == "end") {
      if (!open_cell) throw InputError(file, ln, "'end' without a 'cell'");
      if (tok.size() != 1) throw InputError(file, ln, "'end' stands alone on its line");
      open_cell = 0;
    } else if (key == "corner") {
      read_ids(ln);
      if (ids.size() != 1) throw InputError(file, ln, "'corner' takes one vertex index");
      builder.add_corner(ids[0], ln);
    } else if (key == "crease") {
      read_ids(ln);
      if (ids.size() < 2) throw InputError(file, ln, "'crease' takes a chain of at least 2 vertex indices");
      builder.add_crease(ids, ln);
    } else if (key == "feature_face") {
      read_ids(ln);
      if (ids.size() < 3) throw InputError(file, ln, "'feature_face' takes a loop of at least 3 vertex indices");
      builder.add_feature_face(ids, ln);
    } else {
      throw InputError(file, ln, "unknown statement '" + printable(key) +
                                     "' (expected v, hex, wedge, pyramid, tet, cell, f, end, corner, crease, feature_face)");
    }
  }
  if (open_cell) throw InputError(file, open_cell, "cell is not closed: the file ends before its 'end'");
  if (builder.num_cells() == 0)
    throw InputError(file, 0, vertex_lines.empty() ? "no vertices and no cells" : "no cells (a lattice needs at least one)");
  builder.build(file, static_cast<std::uint32_t>(vertex_lines.size()), vertex_lines, TagPolicy::Strict, shape);
  return shape;
}

void write_lattice(const std::string& path, const Complex& c, std::span<const double> xyz) {
  if (c.dim != 3) throw InputError(path, 0, "a .lattice holds volumes; this shape has dimension " + std::to_string(c.dim));
  if (xyz.size() != 3 * static_cast<std::size_t>(c.num_vertices))
    throw InputError(path, 0, "positions do not match the vertex count");
  check_writable_positions(path, xyz);
  const FeatureTags tags = derive_feature_tags(c);
  write_file_atomic(path, [&](std::ostream& out) {
    out << kMagic << " 1\n# written by Sublift: " << c.num_vertices << " vertices, " << c.num_cells()
        << " cells; vertex indices are 0-based\n";
    for (std::uint32_t v = 0; v < c.num_vertices; ++v) write_xyz_line(out, "v ", &xyz[3 * v]);
    const auto oriented = oriented_lattice_loops(c, xyz);
    for (std::uint32_t k = 0; k < c.num_cells(); ++k) {
      const auto& loops = oriented[k];
      if (const auto h = hexahedron_vertices(loops)) {
        out << "hex";
        for (std::uint32_t v : *h) out << ' ' << v;
        out << '\n';
        continue;
      }
      out << "cell\n";
      for (const auto& l : loops) {
        out << 'f';
        for (std::uint32_t v : l) out << ' ' << v;
        out << '\n';
      }
      out << "end\n";
    }
    for (const auto& f : tags.feature_faces) {
      out << "feature_face";
      for (std::uint32_t v : f) out << ' ' << v;
      out << '\n';
    }
    for (auto [a, b] : tags.crease_edges) out << "crease " << a << ' ' << b << '\n';
    for (std::uint32_t v : tags.corner_vertices) out << "corner " << v << '\n';
  });
}

}  // namespace sublift
