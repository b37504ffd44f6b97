#include "core/io/lattice/vtk_format.h"

#include <cctype>
#include <algorithm>
#include <cmath>
#include <optional>
#include <ostream>
#include <type_traits>
#include <vector>

#include "core/base/binary_cursor.h"
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

constexpr std::size_t kMaxToken = 256;
constexpr std::int64_t kMaxCount = 0xfffffffeLL;

enum VtkType : int {
  kVertex = 1, kPolyVertex = 2, kLine = 3, kPolyLine = 4, kTriangle = 5, kPolygon = 7, kPixel = 8,
  kQuad = 9, kTetra = 10, kVoxel = 11, kHexahedron = 12, kWedge = 13, kPyramid = 14, kPolyhedron = 42
};

std::string type_name(std::int64_t t) {
  switch (t) {
    case 0: return "VTK_EMPTY_CELL";
    case 1: return "VTK_VERTEX";
    case 2: return "VTK_POLY_VERTEX";
    case 3: return "VTK_LINE";
    case 4: return "VTK_POLY_LINE";
    case 5: return "VTK_TRIANGLE";
    case 6: return "VTK_TRIANGLE_STRIP";
    case 7: return "VTK_POLYGON";
    case 8: return "VTK_PIXEL";
    case 9: return "VTK_QUAD";
    case 10: return "VTK_TETRA";
    case 11: return "VTK_VOXEL";
    case 12: return "VTK_HEXAHEDRON";
    case 13: return "VTK_WEDGE";
    case 14: return "VTK_PYRAMID";
    case 15: return "VTK_PENTAGONAL_PRISM";
    case 16: return "VTK_HEXAGONAL_PRISM";
    case 21: return "VTK_QUADRATIC_EDGE";
    case 22: return "VTK_QUADRATIC_TRIANGLE";
    case 23: return "VTK_QUADRATIC_QUAD";
    case 24: return "VTK_QUADRATIC_TETRA";
    case 25: return "VTK_QUADRATIC_HEXAHEDRON";
    case 26: return "VTK_QUADRATIC_WEDGE";
    case 27: return "VTK_QUADRATIC_PYRAMID";
    case 42: return "VTK_POLYHEDRON";
    default: return "an unknown VTK type";
  }
}

// Bytes of one binary value of a legacy VTK data type; 0 when not supported.
std::size_t type_size(const std::string& t) {
  if (t == "float" || t == "int" || t == "unsigned_int" || t == "vtktypeint32" || t == "vtktypeuint32") return 4;
  if (t == "double" || t == "vtktypeint64" || t == "vtktypeuint64" || t == "vtkidtype") return 8;
  if (t == "short" || t == "unsigned_short") return 2;
  if (t == "char" || t == "unsigned_char" || t == "bit") return 1;
  if (t == "long" || t == "unsigned_long") return 8;
  return 0;
}

// Tokens of a legacy VTK file, with 1-based lines; binary blocks are read in place (big-endian).
class Scanner {
 public:
  Scanner(std::string_view bytes, const std::string& file) : b_(bytes), file_(file) {}
  std::size_t line() const { return line_; }
  std::size_t remaining() const { return b_.size() - pos_; }

  // The raw text of the next line (header lines), without its ending.
  std::string_view raw_line(std::size_t max) {
    const std::size_t start = pos_;
    while (pos_ < b_.size() && b_[pos_] != '\n' && b_[pos_] != '\r') {
      if (pos_ - start >= max) throw InputError(file_, line_, "header line longer than " + std::to_string(max) + " bytes");
      ++pos_;
    }
    std::string_view s = b_.substr(start, pos_ - start);
    const std::size_t before = pos_;
    if (pos_ < b_.size() && b_[pos_] == '\r') ++pos_;
    if (pos_ < b_.size() && b_[pos_] == '\n') ++pos_;
    if (pos_ != before) ++line_;
    return s;
  }

  std::optional<std::string_view> token() {
    while (pos_ < b_.size()) {
      const char c = b_[pos_];
      if (c == '\n') ++line_, ++pos_;
      else if (c == '\r') {
        ++pos_;
        if (pos_ < b_.size() && b_[pos_] == '\n') ++pos_;
        ++line_;
      } else if (c == ' ' || c == '\t' || c == '\v' || c == '\f') ++pos_;
      else break;
    }
    if (pos_ >= b_.size()) return std::nullopt;
    const std::size_t start = pos_;
    while (pos_ < b_.size()) {
      const auto c = static_cast<unsigned char>(b_[pos_]);
      if (c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f') break;
      if (c < 0x20 || c >= 0x7f)
        throw InputError(file_, line_, "binary data where text was expected (byte offset " + std::to_string(pos_) + ")");
      if (pos_ - start >= kMaxToken) throw InputError(file_, line_, "a token longer than 256 bytes");
      ++pos_;
    }
    return b_.substr(start, pos_ - start);
  }

  std::string_view need(const std::string& what) {
    auto t = token();
    if (!t) throw InputError(file_, line_, "unexpected end of file while reading " + what);
    return *t;
  }
  std::int64_t need_int(const std::string& what) {
    const auto t = need(what);
    auto v = parse_int(t);
    if (!v) throw InputError(file_, line_, "'" + printable(t) + "' is not an integer (" + what + ")");
    return *v;
  }
  std::int64_t need_count(const std::string& what) {
    const std::int64_t n = need_int(what);
    if (n < 0 || n > kMaxCount) throw InputError(file_, line_, what + " " + std::to_string(n) + " is out of range");
    return n;
  }
  double need_double(const std::string& what) {
    const auto t = need(what);
    auto v = parse_double(t);
    if (!v) {
      const std::string low = to_lower(t);
      if (low.find("nan") != std::string::npos || low.find("inf") != std::string::npos)
        throw InputError(file_, line_, "non-finite coordinate '" + printable(t) + "'");
      throw InputError(file_, line_, "'" + printable(t) + "' is not a number (" + what + ")");
    }
    return *v;
  }

  // Binary data starts after the end of the keyword's line.
  void to_next_line() {
    while (pos_ < b_.size() && (b_[pos_] == ' ' || b_[pos_] == '\t' || b_[pos_] == '\r')) ++pos_;
    if (pos_ >= b_.size() || b_[pos_] != '\n')
      throw InputError(file_, line_, "expected the end of the line before binary data");
    ++pos_;
    ++line_;
  }
  // Refuses `count` values that cannot fit in the rest of the file: binary values of
  // `bytes_each` bytes, or (bytes_each == 0) text numbers of at least one digit and a separator.
  void check_fits(std::int64_t count, std::size_t bytes_each, const std::string& what) {
    const double need = bytes_each ? double(count) * double(bytes_each) : 2.0 * double(count) - 1.0;
    if (need > static_cast<double>(remaining()))
      throw InputError(file_, line_, what + " " + std::to_string(count) + " cannot fit in the " +
                                         std::to_string(remaining()) + " bytes left in the file");
  }
  BinaryCursor cursor() const { return BinaryCursor(b_, pos_, file_, true); }
  std::size_t offset() const { return pos_; }
  void skip_bytes(std::size_t n) { pos_ += std::min(n, remaining()); }

  // Skips a METADATA block: the rest of the keyword's line, then lines up to the first empty one.
  void skip_metadata() {
    raw_line(kMaxToken);
    for (;;) {
      if (pos_ >= b_.size()) return;
      if (raw_line(std::size_t(1) << 20).find_first_not_of(" \t") == std::string_view::npos) return;
    }
  }

 private:
  std::string_view b_;
  const std::string& file_;
  std::size_t pos_ = 0;
  std::size_t line_ = 1;  // line of the current position
};

struct Grid {
  std::vector<double> xyz;
  bool have_points = false;
  // Cells: record r holds conn[offsets[r] .. offsets[r+1]); for classic files the record is
  // what follows the size count (so a polyhedron's record is its face stream).
  std::vector<std::int64_t> conn;
  std::vector<std::size_t> offsets{0};
  std::vector<std::size_t> cell_lines;
  bool have_cells = false;
  std::vector<std::int64_t> types;
  std::vector<std::size_t> type_lines;
  bool have_types = false;
  std::vector<VertexAttribute> point_attributes;            // POINT_DATA scalars, vectors, colours, fields
  std::vector<std::pair<std::string, std::size_t>> not_kept;  // what the data sections hold that is not kept, and its line
};

// Reads `n` numbers: ASCII tokens (doubles, or integers for an integer T, whatever `type` says),
// or big-endian binary of `type` read as double.
template <class T>
void read_values(Scanner& s, bool binary, const std::string& type, std::int64_t n, const std::string& what,
                 const std::string& file, std::vector<T>& out, std::vector<std::size_t>* lines = nullptr) {
  constexpr bool ints = std::is_integral_v<T>;
  const std::size_t size = type_size(type);
  if ((binary || !ints) && (size == 0 || type == "bit"))
    throw InputError(file, s.line(), "unsupported data type '" + printable(type) + "' for " + what);
  s.check_fits(n, binary ? size : 0, what);
  out.reserve(out.size() + static_cast<std::size_t>(n));
  if (!binary) {
    for (std::int64_t i = 0; i < n; ++i) {
      if constexpr (ints) out.push_back(s.need_int(what));
      else out.push_back(s.need_double(what));
      if (lines) lines->push_back(s.line());
    }
    return;
  }
  s.to_next_line();
  BinaryCursor c = s.cursor();
  for (std::int64_t i = 0; i < n; ++i) {
    double v = 0;
    if (type == "float") v = c.read<float>(what.c_str());
    else if (type == "double") v = c.read<double>(what.c_str());
    else if (type == "int" || type == "vtktypeint32") v = c.read<std::int32_t>(what.c_str());
    else if (type == "unsigned_int" || type == "vtktypeuint32") v = c.read<std::uint32_t>(what.c_str());
    else if (type == "short") v = c.read<std::int16_t>(what.c_str());
    else if (type == "unsigned_short") v = c.read<std::uint16_t>(what.c_str());
    else if (type == "char") v = c.read<std::int8_t>(what.c_str());
    else if (type == "unsigned_char") v = c.read<std::uint8_t>(what.c_str());
    else if (type == "vtktypeuint64") v = static_cast<double>(c.read<std::uint64_t>(what.c_str()));
    else v = static_cast<double>(c.read<std::int64_t>(what.c_str()));
    if (!std::isfinite(v)) throw InputError(file, s.line(), "non-finite value in " + what + " (value " + std::to_string(i) + ")");
    out.push_back(static_cast<T>(v));
    if (lines) lines->push_back(s.line());
  }
  s.skip_bytes(c.offset() - s.offset());
}

void skip_field(Scanner& s, bool binary, const std::string& file) {
  s.need("FIELD name");
  const std::int64_t arrays = s.need_count("FIELD array count");
  for (std::int64_t a = 0; a < arrays; ++a) {
    const std::string name(s.need("field array name"));
    const std::int64_t comps = s.need_count("field array components");
    const std::int64_t tuples = s.need_count("field array tuples");
    const std::string type = to_lower(s.need("field array type"));
    const std::int64_t n = comps * tuples;
    if (type == "string" || type == "utf8_string") throw InputError(file, s.line(), "string field arrays are not supported");
    if (binary) {
      const std::size_t size = type_size(type);
      if (size == 0) throw InputError(file, s.line(), "unsupported data type '" + printable(type) + "' in field data");
      s.to_next_line();
      s.check_fits(n, size, "field array " + name);
      s.skip_bytes(static_cast<std::size_t>(n) * size);
    } else {
      s.check_fits(n, 0, "field array " + name);
      for (std::int64_t i = 0; i < n; ++i) s.need("field value");
    }
  }
}

std::string to_upper(std::string s) {
  for (char& c : s) c = char(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

// The type a VTK data type is written back as (the attribute's `type`).
std::string attribute_type(const std::string& vtk_type) {
  if (vtk_type == "unsigned_char") return "uchar";
  if (vtk_type == "char") return "char";
  if (vtk_type == "unsigned_short") return "ushort";
  if (vtk_type == "short") return "short";
  if (vtk_type == "int" || vtk_type == "vtktypeint32") return "int";
  if (vtk_type == "unsigned_int" || vtk_type == "vtktypeuint32") return "uint";
  if (vtk_type == "float") return "float";
  return "double";
}

// Reads the sections of one POINT_DATA or CELL_DATA block (`n` tuples) up to the end of the file
// or the next block, whose keyword it returns ("" at the end). Point data (`into` not null) become
// attributes: SCALARS (a channel per component), VECTORS (name_x, _y, _z), COLOR_SCALARS (red,
// green, blue, alpha), FIELD arrays of n tuples; what is not kept (normals, texture coordinates,
// tensors, lookup tables, cell data) is read past and named in `not_kept` with its line.
std::string read_data_block(Scanner& s, bool binary, std::int64_t n, bool cells, const std::string& file,
                            std::vector<VertexAttribute>* into, std::vector<std::pair<std::string, std::size_t>>& not_kept) {
  const std::string where = cells ? "CELL_DATA" : "POINT_DATA";
  const auto add = [&](const std::string& name, const std::string& type, const std::vector<double>& v, std::int64_t comps,
                       const std::vector<std::string>& names) {
    for (double x : v)
      if (std::abs(x) > kMaxCoordinate)
        throw InputError(file, s.line(), where + " '" + printable(name) + "': a value exceeds the supported magnitude " + max_coordinate_text());
    for (std::int64_t k = 0; k < comps; ++k) {
      VertexAttribute a{names.empty() ? (comps == 1 ? name : name + "_" + std::to_string(k)) : names[std::size_t(k)], type, {}};
      a.values.resize(std::size_t(n));
      for (std::int64_t i = 0; i < n; ++i) a.values[std::size_t(i)] = v[std::size_t(i * comps + k)];
      into->push_back(std::move(a));
    }
  };
  const auto drop = [&](const std::string& what, std::size_t line) { not_kept.emplace_back(where + " " + what, line); };
  while (const auto t = s.token()) {
    const std::string key = to_lower(*t);
    const std::size_t ln = s.line();
    if (key == "point_data" || key == "cell_data") return key;
    std::vector<double> v;
    if (key == "scalars") {
      const std::string name(s.need("SCALARS name")), type = to_lower(s.need("SCALARS type"));
      std::string next(s.need("LOOKUP_TABLE"));
      std::int64_t comps = 1;
      if (const auto c = parse_int(next)) {
        comps = *c;
        if (comps < 1 || comps > 4) throw InputError(file, ln, "SCALARS " + printable(name) + ": " + std::to_string(comps) + " components (1..4)");
        next = std::string(s.need("LOOKUP_TABLE"));
      }
      if (to_lower(next) != "lookup_table") throw InputError(file, s.line(), "expected LOOKUP_TABLE after SCALARS " + printable(name));
      s.need("LOOKUP_TABLE name");
      read_values(s, binary, type, n * comps, "SCALARS " + name, file, v);
      if (into) add(name, attribute_type(type), v, comps, {});
      else drop("scalars '" + printable(name) + "'", ln);
    } else if (key == "vectors" || key == "normals") {
      const std::string name(s.need(key + " name")), type = to_lower(s.need(key + " type"));
      read_values(s, binary, type, 3 * n, to_upper(key) + " " + name, file, v);
      if (into && key == "vectors") add(name, attribute_type(type), v, 3, {name + "_x", name + "_y", name + "_z"});
      else drop(key + " '" + printable(name) + "'" + (key == "normals" ? " (they follow from the shape)" : ""), ln);
    } else if (key == "color_scalars") {
      const std::string name(s.need("COLOR_SCALARS name"));
      const std::int64_t comps = s.need_count("COLOR_SCALARS values");
      if (comps < 1 || comps > 4) throw InputError(file, ln, "COLOR_SCALARS " + printable(name) + ": " + std::to_string(comps) + " values (1..4)");
      read_values(s, binary, binary ? "unsigned_char" : "float", n * comps, "COLOR_SCALARS " + name, file, v);
      static const std::vector<std::string> rgba{"red", "green", "blue", "alpha"};
      if (into) add(name, binary ? "uchar" : "float", v, comps, std::vector<std::string>(rgba.begin(), rgba.begin() + comps));
      else drop("colours '" + printable(name) + "'", ln);
    } else if (key == "texture_coordinates" || key == "tensors") {
      const std::string name(s.need(key + " name"));
      std::int64_t comps = 9;
      if (key == "texture_coordinates") comps = s.need_count("TEXTURE_COORDINATES dimension");
      const std::string type = to_lower(s.need(key + " type"));
      read_values(s, binary, type, comps * n, to_upper(key) + " " + name, file, v);
      drop(key == "tensors" ? "tensors '" + printable(name) + "'" : "texture coordinates '" + printable(name) + "' (vertex UVs; Sublift's are per face corner)", ln);
    } else if (key == "lookup_table") {
      const std::string name(s.need("LOOKUP_TABLE name"));
      const std::int64_t size = s.need_count("LOOKUP_TABLE size");
      read_values(s, binary, binary ? "unsigned_char" : "float", 4 * size, "LOOKUP_TABLE " + name, file, v);
      drop("lookup table '" + printable(name) + "'", ln);
    } else if (key == "field") {
      s.need("FIELD name");
      const std::int64_t arrays = s.need_count("FIELD array count");
      for (std::int64_t a = 0; a < arrays; ++a) {
        const std::string name(s.need("field array name"));
        const std::size_t aline = s.line();
        const std::int64_t comps = s.need_count("field array components");
        const std::int64_t tuples = s.need_count("field array tuples");
        const std::string type = to_lower(s.need("field array type"));
        if (type == "string" || type == "utf8_string") throw InputError(file, s.line(), "string field arrays are not supported");
        v.clear();
        read_values(s, binary, type, comps * tuples, "field array " + name, file, v);
        if (into && tuples == n && comps >= 1 && comps <= 4) add(name, attribute_type(type), v, comps, {});
        else drop("field array '" + printable(name) + "'", aline);
      }
    } else {
      throw InputError(file, ln, "unknown keyword '" + printable(*t) + "' in " + where);
    }
  }
  return "";
}

Grid parse(std::string_view bytes, const std::string& file) {
  Scanner s(bytes, file);
  if (bytes.empty()) throw InputError(file, 0, "empty file");
  const std::string_view magic = s.raw_line(256);
  if (magic.substr(0, 22) != "# vtk DataFile Version")
    throw InputError(file, 1, "not a legacy VTK file (the first line must start with '# vtk DataFile Version')");
  const std::string version(magic.substr(std::min<std::size_t>(22, magic.size())));
  const int major = std::atoi(version.c_str());
  s.raw_line(256);  // title
  const std::string mode = to_lower(std::string(s.raw_line(256)));
  bool binary = false;
  if (mode.rfind("binary", 0) == 0) binary = true;
  else if (mode.rfind("ascii", 0) != 0)
    throw InputError(file, 3, "the third line must be ASCII or BINARY, not '" + printable(mode) + "'");
  if (to_lower(s.need("DATASET")) != "dataset") throw InputError(file, s.line(), "expected 'DATASET UNSTRUCTURED_GRID'");
  const std::string kind = to_lower(s.need("dataset type"));
  if (kind != "unstructured_grid")
    throw InputError(file, s.line(), "DATASET " + kind + " is not supported (only UNSTRUCTURED_GRID)");

  Grid g;
  while (auto t = s.token()) {
    const std::string key = to_lower(*t);
    const std::size_t ln = s.line();
    if (key == "field") {
      skip_field(s, binary, file);
    } else if (key == "metadata") {
      s.skip_metadata();
    } else if (key == "points") {
      if (g.have_points) throw InputError(file, ln, "a second POINTS section");
      const std::int64_t n = s.need_count("POINTS count");
      const std::string type = to_lower(s.need("POINTS type"));
      read_values(s, binary, type, 3 * n, "POINTS", file, g.xyz);
      for (double v : g.xyz)
        if (std::abs(v) > kMaxCoordinate)
          throw InputError(file, ln, "a coordinate exceeds the supported magnitude " + max_coordinate_text());
      g.have_points = true;
    } else if (key == "cells") {
      if (g.have_cells) throw InputError(file, ln, "a second CELLS section");
      const std::int64_t a = s.need_count("CELLS count");
      const std::int64_t b = s.need_count("CELLS size");
      if (major >= 5) {
        // OFFSETS type, a values; CONNECTIVITY type, b values.
        if (to_lower(s.need("OFFSETS")) != "offsets") throw InputError(file, s.line(), "expected OFFSETS (a version 5 file)");
        const std::string otype = to_lower(s.need("OFFSETS type"));
        std::vector<std::int64_t> off;
        read_values(s, binary, otype, a, "OFFSETS", file, off);
        if (a < 1 || off.front() != 0 || off.back() != b)
          throw InputError(file, ln, "OFFSETS must run from 0 to the CONNECTIVITY size " + std::to_string(b));
        for (std::size_t i = 1; i < off.size(); ++i)
          if (off[i] < off[i - 1]) throw InputError(file, ln, "OFFSETS decrease at cell " + std::to_string(i - 1));
        if (to_lower(s.need("CONNECTIVITY")) != "connectivity") throw InputError(file, s.line(), "expected CONNECTIVITY");
        const std::string ctype = to_lower(s.need("CONNECTIVITY type"));
        std::vector<std::size_t> lines;
        read_values(s, binary, ctype, b, "CONNECTIVITY", file, g.conn, &lines);
        g.offsets.assign(off.begin(), off.end());
        for (std::size_t c = 0; c + 1 < g.offsets.size(); ++c)
          g.cell_lines.push_back(g.offsets[c] < lines.size() ? lines[g.offsets[c]] : ln);
      } else {
        if (a > b) throw InputError(file, ln, "CELLS count " + std::to_string(a) + " exceeds its size " + std::to_string(b));
        std::vector<std::int64_t> raw;
        std::vector<std::size_t> lines;
        read_values(s, binary, "int", b, "CELLS", file, raw, &lines);
        std::size_t pos = 0;
        g.conn.reserve(raw.size());
        for (std::int64_t c = 0; c < a; ++c) {
          if (pos >= raw.size())
            throw InputError(file, ln, "CELLS holds fewer than the " + std::to_string(a) + " cells it announces");
          const std::int64_t k = raw[pos];
          if (k < 1 || static_cast<std::size_t>(k) > raw.size() - pos - 1)
            throw InputError(file, lines[pos], "cell " + std::to_string(c) + " has a vertex count of " + std::to_string(k) +
                                                   ", beyond the CELLS size");
          g.cell_lines.push_back(lines[pos]);
          g.conn.insert(g.conn.end(), raw.begin() + static_cast<std::ptrdiff_t>(pos + 1),
                        raw.begin() + static_cast<std::ptrdiff_t>(pos + 1 + static_cast<std::size_t>(k)));
          g.offsets.push_back(g.conn.size());
          pos += 1 + static_cast<std::size_t>(k);
        }
        if (pos != raw.size())
          throw InputError(file, ln, "CELLS size " + std::to_string(b) + " does not match its " + std::to_string(a) +
                                         " cells (" + std::to_string(pos) + " numbers used)");
      }
      g.have_cells = true;
    } else if (key == "cell_types") {
      if (g.have_types) throw InputError(file, ln, "a second CELL_TYPES section");
      const std::int64_t n = s.need_count("CELL_TYPES count");
      read_values(s, binary, "int", n, "CELL_TYPES", file, g.types, &g.type_lines);
      g.have_types = true;
    } else if (key == "cell_data" || key == "point_data") {
      // Data blocks run to the end of the file: point data become attributes, cell data named.
      std::string block = key;
      while (!block.empty()) {
        const std::size_t bline = s.line();
        const std::int64_t n = s.need_count(to_upper(block) + " count");
        const bool cells = block == "cell_data";
        if (!cells && (!g.have_points || std::size_t(n) != g.xyz.size() / 3))
          throw InputError(file, bline, "POINT_DATA " + std::to_string(n) + " does not match the " + std::to_string(g.xyz.size() / 3) + " points");
        if (!cells && !g.point_attributes.empty()) throw InputError(file, bline, "a second POINT_DATA block");
        if (!cells) {
          block = read_data_block(s, binary, n, cells, file, &g.point_attributes, g.not_kept);
          continue;
        }
        try {  // cell data are not kept: a fault in them costs them alone
          block = read_data_block(s, binary, n, cells, file, nullptr, g.not_kept);
        } catch (const InputError& e) {
          g.not_kept.emplace_back(std::string("CELL_DATA and what follows it (unreadable: ") + e.what() + ")", bline);
          block.clear();
        }
      }
      break;
    } else {
      throw InputError(file, ln, "unknown keyword '" + printable(*t) + "'");
    }
  }
  if (!g.have_points) throw InputError(file, 0, "no POINTS section");
  if (!g.have_cells) throw InputError(file, 0, "no CELLS section");
  if (!g.have_types) throw InputError(file, 0, "no CELL_TYPES section");
  if (g.types.size() != g.offsets.size() - 1)
    throw InputError(file, g.type_lines.empty() ? 0 : g.type_lines.front(),
                     "CELL_TYPES lists " + std::to_string(g.types.size()) + " types for " +
                         std::to_string(g.offsets.size() - 1) + " cells");
  if (major >= 5)
    for (std::size_t c = 0; c < g.types.size(); ++c)
      if (g.types[c] == kPolyhedron)
        throw InputError(file, g.type_lines[c], "cell " + std::to_string(c) +
                                                    ": VTK_POLYHEDRON in a version 5 file is not supported (save as legacy version 4.2)");
  return g;
}

}  // namespace

Shape read_vtk(std::string_view bytes, const std::string& file) {
  Grid g = parse(bytes, file);
  Shape shape;
  shape.positions = g.xyz;
  shape.attributes = std::move(g.point_attributes);
  for (const auto& [what, line] : g.not_kept) shape.report.note_not_kept(what, line);
  const auto nv = static_cast<std::uint32_t>(g.xyz.size() / 3);
  ShapeBuilder b;
  std::vector<std::int64_t> loop;
  for (std::size_t c = 0; c < g.types.size(); ++c) {
    const std::int64_t t = g.types[c];
    const std::span<const std::int64_t> ids(g.conn.data() + g.offsets[c], g.offsets[c + 1] - g.offsets[c]);
    const std::size_t line = g.cell_lines[c];
    const std::string label = "cell " + std::to_string(c) + " (" + type_name(t) + ")";
    auto need = [&](std::size_t n, bool at_least = false) {
      if (at_least ? ids.size() < n : ids.size() != n)
        throw InputError(file, line, label + " has " + std::to_string(ids.size()) + " vertices; " + type_name(t) +
                                         (at_least ? " needs at least " : " has ") + std::to_string(n));
    };
    auto standard = [&](CellShape s, const int* order) {
      need(static_cast<std::size_t>(cell_shape_vertex_count(s)));
      b.begin_cell(line, label);
      for (const auto& f : cell_shape_faces(s)) {
        loop.clear();
        for (int i : f) loop.push_back(ids[static_cast<std::size_t>(order ? order[i] : i)]);
        b.add_cell_face(loop, line);
      }
    };
    static constexpr int kVoxelToHex[8] = {0, 1, 3, 2, 4, 5, 7, 6};
    switch (t) {
      case kVertex: need(1); b.add_corner(ids[0], line); break;
      case kPolyVertex:
        need(1, true);
        for (std::int64_t v : ids) b.add_corner(v, line);
        break;
      case kLine: need(2); b.add_polyline(ids, line, label); break;
      case kPolyLine: need(2, true); b.add_polyline(ids, line, label); break;
      case kTriangle: need(3); b.add_polygon(ids, line, label); break;
      case kQuad: need(4); b.add_polygon(ids, line, label); break;
      case kPolygon: need(3, true); b.add_polygon(ids, line, label); break;
      case kPixel: {
        need(4);
        const std::int64_t q[4] = {ids[0], ids[1], ids[3], ids[2]};
        b.add_polygon(q, line, label);
        break;
      }
      case kTetra: standard(CellShape::Tetrahedron, nullptr); break;
      case kVoxel: standard(CellShape::Hexahedron, kVoxelToHex); break;
      case kHexahedron: standard(CellShape::Hexahedron, nullptr); break;
      case kWedge: standard(CellShape::Wedge, nullptr); break;
      case kPyramid: standard(CellShape::Pyramid, nullptr); break;
      case kPolyhedron: {
        // Face stream: nFaces, then per face nPts and its point ids.
        need(1, true);
        const std::int64_t nf = ids[0];
        if (nf < 1 || static_cast<std::size_t>(nf) > ids.size())
          throw InputError(file, line, label + " announces " + std::to_string(nf) + " faces, more than its record holds");
        b.begin_cell(line, label);
        std::size_t pos = 1;
        for (std::int64_t f = 0; f < nf; ++f) {
          if (pos >= ids.size())
            throw InputError(file, line, label + ": the face stream ends before face " + std::to_string(f));
          const std::int64_t k = ids[pos++];
          if (k < 1 || static_cast<std::size_t>(k) > ids.size() - pos)
            throw InputError(file, line, label + ": face " + std::to_string(f) + " has a vertex count of " +
                                             std::to_string(k) + ", beyond the cell's record");
          b.add_cell_face(ids.subspan(pos, static_cast<std::size_t>(k)), line);
          pos += static_cast<std::size_t>(k);
        }
        if (pos != ids.size())
          throw InputError(file, line, label + ": face stream length does not match its record (" +
                                           std::to_string(ids.size() - pos) + " numbers left over)");
        break;
      }
      default:
        throw InputError(file, c < g.type_lines.size() ? g.type_lines[c] : line,
                         "cell " + std::to_string(c) + " has VTK cell type " + std::to_string(t) + " (" + type_name(t) +
                             "), which Sublift does not read (supported: 1-5, 7-14 and 42)");
    }
  }
  b.build(file, nv, {}, TagPolicy::Warn, shape);
  return shape;
}

void write_vtk(const std::string& path, const Complex& c, std::span<const double> xyz, std::span<const VertexAttribute> attributes) {
  if (xyz.size() != 3 * static_cast<std::size_t>(c.num_vertices))
    throw InputError(path, 0, "positions do not match the vertex count");
  check_writable_positions(path, xyz);
  const FeatureTags tags = derive_feature_tags(c);
  // Records (count first) and types, built before writing so that the sizes are known.
  std::vector<std::int64_t> rec;
  std::vector<int> types;
  auto add = [&](int type, const std::vector<std::int64_t>& ids) {
    rec.push_back(static_cast<std::int64_t>(ids.size()));
    rec.insert(rec.end(), ids.begin(), ids.end());
    types.push_back(type);
  };
  std::vector<std::int64_t> ids;
  if (c.dim == 3) {
    const auto oriented = oriented_lattice_loops(c, xyz);
    for (std::uint32_t k = 0; k < c.num_cells(); ++k) {
      const auto& loops = oriented[k];
      ids.clear();
      if (const auto h = hexahedron_vertices(loops)) {
        ids.assign(h->begin(), h->end());
        add(kHexahedron, ids);
        continue;
      }
      ids.push_back(static_cast<std::int64_t>(loops.size()));
      for (const auto& l : loops) {
        ids.push_back(static_cast<std::int64_t>(l.size()));
        ids.insert(ids.end(), l.begin(), l.end());
      }
      add(kPolyhedron, ids);
    }
  }
  auto add_polygon = [&](std::span<const std::uint32_t> f) {
    ids.assign(f.begin(), f.end());
    add(f.size() == 3 ? kTriangle : f.size() == 4 ? kQuad : kPolygon, ids);
  };
  if (c.dim == 2)
    for (std::uint32_t f = 0; f < c.num_faces(); ++f) add_polygon(c.faces.row(f));
  if (c.dim == 1)
    for (std::uint32_t e = 0; e < c.num_edges(); ++e) add(kLine, {c.edge_verts[2 * e], c.edge_verts[2 * e + 1]});
  for (const auto& f : tags.feature_faces) add_polygon(f);
  for (auto [a, b] : tags.crease_edges) add(kLine, {a, b});
  for (std::uint32_t v : tags.corner_vertices) add(kVertex, {v});

  write_file_atomic(path, [&](std::ostream& out) {
    out << "# vtk DataFile Version 4.2\nSublift " << (c.dim == 3 ? "lattice" : c.dim == 2 ? "surface" : "curve") << ": "
        << c.num_vertices << " vertices\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS " << c.num_vertices << " double\n";
    for (std::uint32_t v = 0; v < c.num_vertices; ++v) write_xyz_line(out, "", &xyz[3 * v]);
    out << "CELLS " << types.size() << ' ' << rec.size() << '\n';
    for (std::size_t p = 0; p < rec.size();) {
      const auto n = static_cast<std::size_t>(rec[p]);
      for (std::size_t i = 0; i <= n; ++i) out << (i ? " " : "") << rec[p + i];
      out << '\n';
      p += n + 1;
    }
    out << "CELL_TYPES " << types.size() << '\n';
    for (int t : types) out << t << '\n';
    // Attributes as POINT_DATA scalars, in double (17 digits: a write/read round trip is exact).
    if (!attributes.empty()) out << "POINT_DATA " << c.num_vertices << '\n';
    for (const VertexAttribute& a : attributes) {
      std::string name = a.name.empty() ? "attribute" : a.name;
      for (char& ch : name)
        if (std::isspace(static_cast<unsigned char>(ch)) || ch < 0x21 || ch > 0x7e) ch = '_';
      out << "SCALARS " << name << " double 1\nLOOKUP_TABLE default\n";
      for (double x : a.values) out << format_double(x) << '\n';
    }
  });
}

}  // namespace sublift
