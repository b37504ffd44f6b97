// Stanford PLY: ascii, binary_little_endian and binary_big_endian 1.0. Reads `vertex` (x, y, z),
// `face` (vertex_indices / vertex_index list) and Stanford `tristrips`; other elements and
// properties are skipped by their declared types. Counts are bounded by the file size first.
#include <cmath>
#include <string>
#include <vector>

#include "core/base/binary_cursor.h"
#include "core/base/errors.h"
#include "core/complex/face_builder.h"
#include "core/io/mesh/mesh_readers.h"
#include "core/io/mesh/ply_types.h"
#include "core/base/text_lines.h"

namespace sublift {
namespace {

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::Float32;
  bool is_list = false;
  PlyType count_type = PlyType::UInt8;
};

struct PlyElement {
  std::string name;
  std::int64_t count = 0;
  std::size_t line = 0;
  std::vector<PlyProperty> props;
};

enum class PlyFormat { Ascii, BinaryLE, BinaryBE };

// Reads values of the body one at a time, from text tokens or from binary.
class PlyValues {
 public:
  PlyValues(std::string_view bytes, std::size_t offset, const std::string& file, PlyFormat fmt,
            std::size_t max_line)
      : file_(file), fmt_(fmt), lines_(bytes.substr(offset), file, max_line),
        bin_(bytes, offset, file, fmt == PlyFormat::BinaryBE), header_lines_(0) {}
  void set_header_lines(std::size_t n) { header_lines_ = n; }

  /// One value as double; integers stay exact (|v| < 2^53).
  double read(PlyType t, const char* what) {
    if (fmt_ == PlyFormat::Ascii) {
      const std::string_view tok = next_token(what);
      if (ply_type_is_float(t)) {
        auto d = parse_double(tok);
        if (!d) throw InputError(file_, line(), std::string("bad or non-finite number '") +
                                                    std::string(tok.substr(0, 32)) + "' in " + what);
        return *d;
      }
      auto i = parse_int(tok);
      if (!i) throw InputError(file_, line(), std::string("bad integer '") +
                                                  std::string(tok.substr(0, 32)) + "' in " + what);
      return static_cast<double>(*i);
    }
    switch (t) {
      case PlyType::Int8: return bin_.read<std::int8_t>(what);
      case PlyType::UInt8: return bin_.read<std::uint8_t>(what);
      case PlyType::Int16: return bin_.read<std::int16_t>(what);
      case PlyType::UInt16: return bin_.read<std::uint16_t>(what);
      case PlyType::Int32: return bin_.read<std::int32_t>(what);
      case PlyType::UInt32: return bin_.read<std::uint32_t>(what);
      case PlyType::Float32: return bin_.read<float>(what);
      case PlyType::Float64: return bin_.read<double>(what);
    }
    return 0.0;
  }
  /// Source line (ascii) or 0 (binary, where messages give byte offsets instead).
  std::size_t line() const { return fmt_ == PlyFormat::Ascii ? header_lines_ + lines_.line_number() : 0; }
  std::size_t offset() const { return bin_.offset(); }
  std::size_t remaining_binary() const { return bin_.remaining(); }
  bool ascii() const { return fmt_ == PlyFormat::Ascii; }
  /// True when only blanks remain (ascii) or nothing (binary).
  bool at_end() {
    if (fmt_ != PlyFormat::Ascii) return bin_.remaining() == 0;
    if (next_ < tok_.size()) return false;
    std::string_view l;
    while (lines_.next(l)) {
      split_tokens(l, tok_);
      next_ = 0;
      if (!tok_.empty()) return false;
    }
    return true;
  }

 private:
  std::string_view next_token(const char* what) {
    while (next_ >= tok_.size()) {
      std::string_view l;
      if (!lines_.next(l))
        throw InputError(file_, line(), std::string("unexpected end of file while reading ") + what);
      split_tokens(l, tok_);
      next_ = 0;
    }
    return tok_[next_++];
  }

  std::string file_;
  PlyFormat fmt_;
  LineReader lines_;
  BinaryCursor bin_;
  std::size_t header_lines_;
  std::vector<std::string_view> tok_;
  std::size_t next_ = 0;
};

}  // namespace

LoadedMesh read_ply(std::string_view bytes, const std::string& file, const ImportLimits& limits) {
  LineReader header(bytes, file, limits.max_line_length);
  std::vector<std::string_view> tok;
  std::string_view line;
  if (!header.next(line) || line != "ply") throw InputError(file, 1, "not a PLY file (first line is not 'ply')");
  PlyFormat fmt = PlyFormat::Ascii;
  bool have_format = false, ended = false;
  std::vector<PlyElement> elements;
  constexpr std::size_t kMaxHeaderLines = 100000;
  while (!ended) {
    bool got = false;
    try {
      got = header.next(line);
    } catch (const InputError&) {
      got = false;  // binary bytes before end_header: the header is broken
    }
    if (!got || header.line_number() > kMaxHeaderLines)
      throw InputError(file, header.line_number(), "PLY header never ends (no 'end_header' line)");
    const std::size_t ln = header.line_number();
    split_tokens(line, tok);
    if (tok.empty()) continue;
    const std::string_view key = tok[0];
    if (key == "comment" || key == "obj_info") continue;
    if (key == "format") {
      if (tok.size() != 3 || tok[2] != "1.0") throw InputError(file, ln, "unsupported PLY format line");
      if (tok[1] == "ascii") fmt = PlyFormat::Ascii;
      else if (tok[1] == "binary_little_endian") fmt = PlyFormat::BinaryLE;
      else if (tok[1] == "binary_big_endian") fmt = PlyFormat::BinaryBE;
      else throw InputError(file, ln, "unknown PLY format '" + std::string(tok[1].substr(0, 32)) + "'");
      have_format = true;
    } else if (key == "element") {
      if (tok.size() != 3) throw InputError(file, ln, "expected 'element NAME COUNT'");
      auto n = parse_int(tok[2]);
      if (!n || *n < 0) throw InputError(file, ln, "element count is not a non-negative integer");
      elements.push_back({std::string(tok[1]), *n, ln, {}});
    } else if (key == "property") {
      if (elements.empty()) throw InputError(file, ln, "property before any element");
      PlyProperty p;
      if (tok.size() == 5 && tok[1] == "list") {
        p.is_list = true;
        if (!parse_ply_type(tok[2], p.count_type) || ply_type_is_float(p.count_type))
          throw InputError(file, ln, "unknown or non-integer list count type '" + std::string(tok[2].substr(0, 32)) + "'");
        if (!parse_ply_type(tok[3], p.type))
          throw InputError(file, ln, "unknown property type '" + std::string(tok[3].substr(0, 32)) + "'");
        p.name = tok[4];
      } else if (tok.size() == 3) {
        if (!parse_ply_type(tok[1], p.type))
          throw InputError(file, ln, "unknown property type '" + std::string(tok[1].substr(0, 32)) + "'");
        p.name = tok[2];
      } else {
        throw InputError(file, ln, "expected 'property TYPE NAME' or 'property list CTYPE TYPE NAME'");
      }
      elements.back().props.push_back(p);
    } else if (key == "end_header") {
      ended = true;
    } else {
      throw InputError(file, ln, "unknown PLY header keyword '" + std::string(key.substr(0, 32)) +
                                    "' (is the 'end_header' line missing?)");
    }
  }
  if (!have_format) throw InputError(file, header.line_number(), "PLY header has no 'format' line");

  // Bound every element count by the bytes left before reserving anything.
  const std::size_t body = header.offset();
  double min_bytes = 0;
  for (const PlyElement& e : elements) {
    double row = 0;
    for (const PlyProperty& p : e.props)
      row += fmt == PlyFormat::Ascii ? 2.0 : double(ply_type_size(p.is_list ? p.count_type : p.type));
    min_bytes += row * double(e.count);
    if (min_bytes > double(bytes.size() - body))
      throw InputError(file, e.line, "element '" + e.name + "' claims " + std::to_string(e.count) +
                                         " rows but only " + std::to_string(bytes.size() - body) +
                                         " bytes of data follow the header");
  }

  LoadedMesh out;
  SurfaceMesh& mesh = out.mesh;
  // Per-vertex and per-face data beyond positions and corners (colours, normals, texture
  // coordinates...), and other elements: skipped, and named for commands that give files back.
  for (const PlyElement& e : elements) {
    const bool is_vertex = e.name == "vertex", is_face = e.name == "face" || e.name == "tristrips";
    if (!is_vertex && !is_face) {
      out.report.not_kept.push_back({"'" + e.name + "' elements (PLY)", std::size_t(e.count), {e.line}});
      continue;
    }
    for (const PlyProperty& p : e.props) {
      const bool used = is_vertex ? (p.name == "x" || p.name == "y" || p.name == "z")
                                  : (p.is_list && (p.name == "vertex_indices" || p.name == "vertex_index"));
      if (!used) out.report.not_kept.push_back({e.name + " property '" + p.name + "' (PLY)", std::size_t(e.count), {e.line}});
    }
  }
  FaceBuilder faces;
  std::vector<std::size_t> vertex_lines;
  PlyValues in(bytes, body, file, fmt, limits.max_line_length);
  in.set_header_lines(header.line_number());
  std::vector<std::int64_t> list;
  bool have_vertices = false;
  for (const PlyElement& e : elements) {
    const bool is_vertex = e.name == "vertex";
    const bool is_face = e.name == "face" || e.name == "tristrips";
    if (is_vertex) {
      have_vertices = true;
      int found = 0;
      for (const PlyProperty& p : e.props)
        if (!p.is_list && (p.name == "x" || p.name == "y" || p.name == "z")) ++found;
      if (found != 3) throw InputError(file, e.line, "vertex element lacks scalar x, y and z properties");
      mesh.positions.reserve(static_cast<std::size_t>(e.count));
    }
    for (std::int64_t r = 0; r < e.count; ++r) {
      glm::dvec3 pos(0.0);
      std::size_t row_line = 0;
      for (const PlyProperty& p : e.props) {
        if (!p.is_list) {
          const double v = in.read(p.type, is_vertex ? "vertex data" : "element data");
          row_line = row_line ? row_line : in.line();
          if (is_vertex && (p.name == "x" || p.name == "y" || p.name == "z")) {
            if (!std::isfinite(v))
              throw InputError(file, in.line(), "non-finite coordinate" + (in.ascii() ? std::string() : " at byte offset " + std::to_string(in.offset())));
            if (std::abs(v) > kMaxCoordinate)
              throw InputError(file, in.line(), "coordinate exceeds the supported magnitude 1e30");
            pos[p.name[0] - 'x'] = v;
          }
          continue;
        }
        const double nd = in.read(p.count_type, "a list count");
        row_line = row_line ? row_line : in.line();
        const auto n = static_cast<std::int64_t>(nd);
        const bool too_many = n < 0 || static_cast<std::size_t>(n) > limits.max_face_size ||
                              (!in.ascii() && double(n) * double(ply_type_size(p.type)) > double(in.remaining_binary()));
        if (too_many)
          throw InputError(file, in.line(), "list of " + std::to_string(n) + " entries in element '" + e.name +
                                                "' row " + std::to_string(r) +
                                                (in.ascii() ? std::string() : " at byte offset " + std::to_string(in.offset())) +
                                                " exceeds the face-size limit or the file");
        list.clear();
        for (std::int64_t k = 0; k < n; ++k) {
          const double v = in.read(p.type, "list entries");
          if (ply_type_is_float(p.type) && v != std::floor(v)) list.push_back(-1);
          else list.push_back(static_cast<std::int64_t>(v));
        }
        if (is_face && (p.name == "vertex_indices" || p.name == "vertex_index")) {
          if (e.name == "face") {
            faces.add(list, row_line);
          } else {  // tristrips: -1 restarts a strip; every other triangle flips orientation
            std::size_t start = 0;
            for (std::size_t k = 0; k <= list.size(); ++k) {
              if (k < list.size() && list[k] != -1) continue;
              for (std::size_t t = start; t + 2 < k; ++t) {
                const std::int64_t a = list[t], b = list[t + 1], c = list[t + 2];
                const std::int64_t tri[3] = {a, ((t - start) & 1) ? c : b, ((t - start) & 1) ? b : c};
                if (a != b && b != c && a != c) faces.add(tri, row_line);
              }
              start = k + 1;
            }
          }
        }
      }
      if (is_vertex) {
        mesh.positions.push_back(pos);
        vertex_lines.push_back(row_line);
      }
    }
  }
  if (!have_vertices) throw InputError(file, 0, "PLY file has no 'vertex' element");
  if (!in.at_end()) out.report.add("trailing data after the last element ignored", in.line());
  faces.finish(mesh, out.report);
  check_imported_mesh(file, mesh, vertex_lines, out.report);
  return out;
}

}  // namespace sublift
