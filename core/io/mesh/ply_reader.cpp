// Stanford PLY: ascii, binary_little_endian and binary_big_endian 1.0. Reads `vertex` (x, y, z),
// `face` (vertex_indices / vertex_index list) and Stanford `tristrips`; other elements and
// properties are skipped by their declared types. Counts are bounded by the file size first.
#include <algorithm>
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

// The value of type t whose bytes end at `end`, read in the byte order the header does not
// say: what a file mislabelled little- for big-endian (or back) really holds.
double swapped_value(std::string_view bytes, std::size_t end, PlyType t, PlyFormat fmt) {
  BinaryCursor in(bytes, end - ply_type_size(t), {}, /*big_endian=*/fmt == PlyFormat::BinaryLE);
  return read_ply_value(in, t, "");
}

// "the file may be big-endian (its header says binary_little_endian)", or the reverse.
std::string byte_order_hint(PlyFormat fmt) {
  return fmt == PlyFormat::BinaryLE ? "the file may be big-endian (its header says binary_little_endian)"
                                    : "the file may be little-endian (its header says binary_big_endian)";
}

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
                                                    printable(tok) + "' in " + what);
        return *d;
      }
      auto i = parse_int(tok);
      if (!i) throw InputError(file_, line(), std::string("bad integer '") +
                                                  printable(tok) + "' in " + what);
      return static_cast<double>(*i);
    }
    return read_ply_value(bin_, t, what);
  }
  /// Source line (ascii) or 0 (binary, where messages give byte offsets instead).
  std::size_t line() const { return fmt_ == PlyFormat::Ascii ? header_lines_ + lines_.line_number() : 0; }
  std::size_t offset() const { return bin_.offset(); }
  std::size_t remaining_binary() const { return bin_.remaining(); }
  bool ascii() const { return fmt_ == PlyFormat::Ascii; }
  /// True when only blanks remain (ascii) or nothing (binary).
  bool at_end() { return fmt_ != PlyFormat::Ascii ? bin_.remaining() == 0 : !have_token(); }

 private:
  // True when a token is left (ascii), reading lines as needed.
  bool have_token() {
    std::string_view l;
    while (next_ >= tok_.size()) {
      if (!lines_.next(l)) return false;
      split_tokens(l, tok_);
      next_ = 0;
    }
    return true;
  }
  std::string_view next_token(const char* what) {
    if (!have_token()) throw InputError(file_, line(), std::string("unexpected end of file while reading ") + what);
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

PlyHeader read_ply_header(std::string_view bytes, const std::string& file, std::size_t max_line_length) {
  LineReader header(bytes, file, max_line_length);
  std::vector<std::string_view> tok;
  std::string_view line;
  if (!header.next(line) || line != "ply") throw InputError(file, 1, "not a PLY file (first line is not 'ply')");
  PlyHeader h;
  bool have_format = false, ended = false;
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
      if (tok[1] == "ascii") h.format = PlyFormat::Ascii;
      else if (tok[1] == "binary_little_endian") h.format = PlyFormat::BinaryLE;
      else if (tok[1] == "binary_big_endian") h.format = PlyFormat::BinaryBE;
      else throw InputError(file, ln, "unknown PLY format '" + printable(tok[1]) + "'");
      have_format = true;
    } else if (key == "element") {
      if (tok.size() != 3) throw InputError(file, ln, "expected 'element NAME COUNT'");
      auto n = parse_int(tok[2]);
      if (!n || *n < 0) throw InputError(file, ln, "element count is not a non-negative integer");
      h.elements.push_back({std::string(tok[1]), *n, ln, {}});
    } else if (key == "property") {
      if (h.elements.empty()) throw InputError(file, ln, "property before any element");
      PlyProperty p;
      if (tok.size() == 5 && tok[1] == "list") {
        p.is_list = true;
        if (!parse_ply_type(tok[2], p.count_type) || ply_type_is_float(p.count_type))
          throw InputError(file, ln, "unknown or non-integer list count type '" + printable(tok[2]) + "'");
        if (!parse_ply_type(tok[3], p.type))
          throw InputError(file, ln, "unknown property type '" + printable(tok[3]) + "'");
        p.name = tok[4];
      } else if (tok.size() == 3) {
        if (!parse_ply_type(tok[1], p.type))
          throw InputError(file, ln, "unknown property type '" + printable(tok[1]) + "'");
        p.name = tok[2];
      } else {
        throw InputError(file, ln, "expected 'property TYPE NAME' or 'property list CTYPE TYPE NAME'");
      }
      h.elements.back().props.push_back(p);
    } else if (key == "end_header") {
      ended = true;
    } else {
      throw InputError(file, ln, "unknown PLY header keyword '" + printable(key) +
                                    "' (is the 'end_header' line missing?)");
    }
  }
  if (!have_format) throw InputError(file, header.line_number(), "PLY header has no 'format' line");
  h.body = header.offset();
  h.lines = header.line_number();
  return h;
}

LoadedMesh read_ply(std::string_view bytes, const std::string& file, const ImportLimits& limits) {
  const PlyHeader header = read_ply_header(bytes, file, limits.max_line_length);
  const PlyFormat fmt = header.format;
  const std::vector<PlyElement>& elements = header.elements;

  // Bound every element count by the bytes left before reserving anything.
  const std::size_t body = header.body;
  double min_bytes = 0;
  for (const PlyElement& e : elements) {
    double row = 0;
    for (const PlyProperty& p : e.props)
      row += fmt == PlyFormat::Ascii ? 2.0 : double(ply_type_size(p.is_list ? p.count_type : p.type));
    min_bytes += row * double(e.count);
    if (min_bytes > double(bytes.size() - body))
      throw InputError(file, e.line, "element '" + printable(e.name) + "' claims " + std::to_string(e.count) +
                                         " rows but only " + std::to_string(bytes.size() - body) +
                                         " bytes of data follow the header");
  }

  LoadedMesh out;
  SurfaceMesh& mesh = out.mesh;
  // Scalar vertex properties beyond x, y, z (colours, quality, ...) are kept as attributes, in
  // header order. Normals (derived from the surface), per-face data, lists and other elements
  // are skipped, and named for commands that give files back.
  const auto is_position = [](const PlyProperty& p) { return p.name == "x" || p.name == "y" || p.name == "z"; };
  const auto is_normal = [](const PlyProperty& p) { return p.name == "nx" || p.name == "ny" || p.name == "nz"; };
  for (const PlyElement& e : elements) {
    const bool is_vertex = e.name == "vertex", is_face = e.name == "face" || e.name == "tristrips";
    if (!is_vertex && !is_face) {
      out.report.not_kept.push_back({"'" + printable(e.name) + "' elements (PLY)", std::size_t(e.count), {e.line}});
      continue;
    }
    for (const PlyProperty& p : e.props) {
      if (is_vertex && !p.is_list && !is_position(p) && !is_normal(p)) {
        mesh.attributes.push_back({p.name, std::string(ply_type_name(p.type)), {}});
        mesh.attributes.back().values.reserve(static_cast<std::size_t>(e.count));
        continue;
      }
      const bool used = is_vertex ? is_position(p) : (p.is_list && (p.name == "vertex_indices" || p.name == "vertex_index"));
      if (!used) out.report.not_kept.push_back({printable(e.name) + " property '" + printable(p.name) + "' (PLY)", std::size_t(e.count), {e.line}});
    }
  }
  FaceBuilder faces;
  std::vector<std::size_t> vertex_lines;
  PlyValues in(bytes, body, file, fmt, limits.max_line_length);
  in.set_header_lines(header.lines);
  std::vector<std::int64_t> list;
  bool have_vertices = false;
  bool vertices_read = false;  // the vertex element is behind us: indices can be checked
  bool hinted = false;         // binary indices out of range reported once, with their offset
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
      std::size_t attribute = 0;  // the next of mesh.attributes, in header order
      for (const PlyProperty& p : e.props) {
        if (!p.is_list) {
          const double v = in.read(p.type, is_vertex ? "vertex data" : "element data");
          row_line = row_line ? row_line : in.line();
          if (is_vertex && !is_position(p) && !is_normal(p)) {
            if (!in_supported_range(v))
              throw InputError(file, in.line(), "vertex property '" + printable(p.name) + "' of vertex " + std::to_string(r) +
                                                    (std::isfinite(v) ? " exceeds the supported magnitude " + max_coordinate_text()
                                                                      : std::string(" is not finite")));
            mesh.attributes[attribute++].values.push_back(v);
          }
          if (is_vertex && is_position(p)) {
            if (!in_supported_range(v)) {
              std::string where;
              if (!in.ascii()) {
                const std::size_t at = in.offset() - ply_type_size(p.type);
                where = " at byte offset " + std::to_string(at);
                if (in_supported_range(swapped_value(bytes, in.offset(), p.type, fmt)))
                  where += "; " + byte_order_hint(fmt) + ": with its bytes swapped the value is " +
                           format_shortest(swapped_value(bytes, in.offset(), p.type, fmt));
              }
              throw InputError(file, in.line(), (std::isfinite(v) ? "coordinate exceeds the supported magnitude " + max_coordinate_text()
                                                                  : std::string("non-finite coordinate")) + where);
            }
            pos[p.name[0] - 'x'] = v;
          }
          continue;
        }
        const std::size_t record_at = in.ascii() ? 0 : in.offset();
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
        const std::size_t list_start = in.ascii() ? 0 : in.offset();
        for (std::int64_t k = 0; k < n; ++k) {
          const double v = in.read(p.type, "list entries");
          if (ply_type_is_float(p.type) && v != std::floor(v)) list.push_back(-1);
          else list.push_back(static_cast<std::int64_t>(v));
        }
        if (is_face && (p.name == "vertex_indices" || p.name == "vertex_index")) {
          // Binary indices out of range: name the byte offset, and say when the other byte
          // order would put them all in range (a mislabelled file, not a damaged one).
          const auto nv = static_cast<std::int64_t>(mesh.positions.size());
          const auto out_of_range = [&](double v) { return v < 0 || v >= static_cast<double>(nv); };
          if (!in.ascii() && !hinted && vertices_read &&
              std::any_of(list.begin(), list.end(), [&](std::int64_t v) { return out_of_range(double(v)); })) {
            hinted = true;
            const std::size_t size = ply_type_size(p.type);
            bool swapped_fit = !ply_type_is_float(p.type);
            for (std::size_t k = 0; swapped_fit && k < list.size(); ++k)
              swapped_fit = !out_of_range(swapped_value(bytes, list_start + (k + 1) * size, p.type, fmt));
            const std::string face = "face " + std::to_string(r) + " at byte offset " + std::to_string(record_at);
            out.report.add(swapped_fit ? byte_order_hint(fmt) + ": " + face +
                                             " has vertex indices out of range that are all in range with their bytes swapped"
                                       : face + " is the first with a vertex index out of range",
                           0);
          }
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
    if (is_vertex) vertices_read = true;
  }
  if (!have_vertices) throw InputError(file, 0, "PLY file has no 'vertex' element");
  if (!in.at_end()) out.report.add("trailing data after the last element ignored", in.line());
  faces.finish(mesh, out.report);
  check_imported_mesh(file, mesh, vertex_lines, out.report);
  return out;
}

}  // namespace sublift
