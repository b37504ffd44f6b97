// Object File Format: [ST][C][N][4]OFF, ASCII (one vertex or face per line, `#` comments) or
// `OFF BINARY` (big-endian int32/float32). Header counts are checked against the file size
// before anything is reserved.
#include <cmath>
#include <string>
#include <vector>

#include "core/base/binary_cursor.h"
#include "core/base/errors.h"
#include "core/complex/face_builder.h"
#include "core/io/mesh/mesh_readers.h"
#include "core/base/text_lines.h"

namespace sublift {
namespace {

struct OffCounts {
  std::int64_t vertices = 0, faces = 0;
};

// Throws unless the counts could fit in `bytes_left` bytes at `min_v`/`min_f` bytes each.
void check_counts(const std::string& file, std::size_t line, const OffCounts& c,
                  std::size_t bytes_left, std::size_t min_v, std::size_t min_f) {
  if (c.vertices < 0 || c.faces < 0)
    throw InputError(file, line, "negative vertex or face count in the header");
  const double need = double(c.vertices) * double(min_v) + double(c.faces) * double(min_f);
  if (need > double(bytes_left))
    throw InputError(file, line,
                     "header claims " + std::to_string(c.vertices) + " vertices and " +
                         std::to_string(c.faces) + " faces, but only " +
                         std::to_string(bytes_left) + " bytes follow (at least " +
                         (need < 9e18 ? std::to_string(static_cast<long long>(need)) : format_shortest(need)) + " needed)");
}

void check_coordinate(const std::string& file, std::size_t line, double v) {
  if (!std::isfinite(v)) throw InputError(file, line, "non-finite coordinate");
  if (std::abs(v) > kMaxCoordinate)
    throw InputError(file, line, "coordinate exceeds the supported magnitude " + max_coordinate_text());
}

LoadedMesh read_off_binary(std::string_view bytes, std::size_t offset, const std::string& file,
                           const ImportLimits& limits) {
  LoadedMesh out;
  BinaryCursor in(bytes, offset, file, /*big_endian=*/true);
  OffCounts c;
  c.vertices = in.read<std::int32_t>("the vertex count");
  c.faces = in.read<std::int32_t>("the face count");
  in.read<std::int32_t>("the edge count");
  check_counts(file, 1, c, in.remaining(), 12, 8);
  out.mesh.positions.reserve(static_cast<std::size_t>(c.vertices));
  for (std::int64_t v = 0; v < c.vertices; ++v) {
    glm::dvec3 p;
    for (int k = 0; k < 3; ++k) {
      p[k] = in.read<float>("vertex coordinates");
      check_coordinate(file, 0, p[k]);
    }
    out.mesh.positions.push_back(p);
  }
  FaceBuilder faces;
  std::vector<std::int64_t> corners;
  for (std::int64_t f = 0; f < c.faces; ++f) {
    const std::int32_t n = in.read<std::int32_t>("a face's corner count");
    if (n < 0 || static_cast<std::size_t>(n) > limits.max_face_size ||
        static_cast<std::size_t>(n) * 4 > in.remaining())
      throw InputError(file, 0, "face " + std::to_string(f) + " at byte offset " +
                                    std::to_string(in.offset() - 4) + " claims " +
                                    std::to_string(n) + " corners");
    corners.clear();
    for (std::int32_t k = 0; k < n; ++k) corners.push_back(in.read<std::int32_t>("face indices"));
    const std::int32_t ncol = in.read<std::int32_t>("a face's colour count");
    if (ncol < 0 || ncol > 4) throw InputError(file, 0, "face " + std::to_string(f) + " has a bad colour count");
    for (std::int32_t k = 0; k < ncol; ++k) in.read<float>("face colour");
    if (ncol > 0) out.report.note_not_kept("face colours (OFF)", 0);
    faces.add(corners, 0);
  }
  faces.finish(out.mesh, out.report);
  check_imported_mesh(file, out.mesh, {}, out.report);
  return out;
}

}  // namespace

LoadedMesh read_off(std::string_view bytes, const std::string& file, const ImportLimits& limits) {
  LineReader lines(bytes, file, limits.max_line_length);
  std::vector<std::string_view> tok;
  // Next non-empty line with comments removed, split into `tok`; false at EOF.
  auto next_line = [&]() { return next_tokens(lines, tok); };
  if (!next_line()) throw InputError(file, 0, "empty file: no OFF header");
  std::string magic(tok[0]);
  std::string_view kind = magic;
  int dims = 3;
  if (kind.starts_with("ST")) kind.remove_prefix(2);
  if (kind.starts_with("C")) kind.remove_prefix(1);
  if (kind.starts_with("N")) kind.remove_prefix(1);
  if (kind.starts_with("4")) {
    kind.remove_prefix(1);
    dims = 4;
  }
  if (kind != "OFF")
    throw InputError(file, lines.line_number(), "not an OFF file (header '" + printable(magic, 16) + "')");
  std::size_t first = 1;
  if (tok.size() >= 2 && tok[1] == "BINARY") {
    if (magic != "OFF") throw InputError(file, lines.line_number(), "only plain 'OFF BINARY' is supported");
    return read_off_binary(bytes, lines.offset(), file, limits);
  }
  if (tok.size() > first) {
    tok.erase(tok.begin(), tok.begin() + first);  // counts on the header line: "OFF 8 6 0"
  } else if (!next_line()) {
    throw InputError(file, lines.line_number(), "missing vertex/face counts");
  }
  if (tok.size() < 2) throw InputError(file, lines.line_number(), "expected 'vertices faces [edges]' counts");
  auto nv = parse_int(tok[0]);
  auto nf = parse_int(tok[1]);
  if (!nv || !nf) throw InputError(file, lines.line_number(), "vertex/face counts are not integers");
  const OffCounts c{*nv, *nf};
  check_counts(file, lines.line_number(), c, bytes.size() - lines.offset(), 6, 2);

  LoadedMesh out;
  std::vector<std::size_t> vertex_lines;
  out.mesh.positions.reserve(static_cast<std::size_t>(c.vertices));
  for (std::int64_t v = 0; v < c.vertices; ++v) {
    if (!next_line())
      throw InputError(file, lines.line_number(),
                       "file ends after " + std::to_string(v) + " of " + std::to_string(c.vertices) + " vertices");
    if (tok.size() < static_cast<std::size_t>(dims))
      throw InputError(file, lines.line_number(), "vertex line has fewer than " + std::to_string(dims) + " numbers");
    double x[4] = {0, 0, 0, 1};
    for (int k = 0; k < dims; ++k) {
      auto d = parse_double(tok[k]);
      if (!d) throw InputError(file, lines.line_number(), "bad or non-finite number '" + printable(tok[k]) + "'");
      x[k] = *d;
    }
    if (dims == 4) {
      if (x[3] == 0.0) throw InputError(file, lines.line_number(), "homogeneous coordinate w = 0");
      for (int k = 0; k < 3; ++k) x[k] /= x[3];
    }
    for (int k = 0; k < 3; ++k) check_coordinate(file, lines.line_number(), x[k]);
    if (tok.size() > static_cast<std::size_t>(dims)) out.report.note_not_kept("vertex colours or normals (OFF)", lines.line_number());
    out.mesh.positions.emplace_back(x[0], x[1], x[2]);
    vertex_lines.push_back(lines.line_number());
  }
  FaceBuilder faces;
  std::vector<std::int64_t> corners;
  for (std::int64_t f = 0; f < c.faces; ++f) {
    if (!next_line())
      throw InputError(file, lines.line_number(),
                       "file ends after " + std::to_string(f) + " of " + std::to_string(c.faces) + " faces");
    const std::size_t ln = lines.line_number();
    auto n = parse_int(tok[0]);
    if (!n || *n < 0 || static_cast<std::size_t>(*n) + 1 > tok.size() ||
        static_cast<std::size_t>(*n) > limits.max_face_size) {
      faces.add_unreadable(ln, out.report, "corner count missing, negative or larger than the indices given");
      continue;
    }
    corners.clear();
    bool ok = true;
    for (std::int64_t k = 0; k < *n && ok; ++k) {
      auto i = parse_int(tok[static_cast<std::size_t>(k) + 1]);
      ok = i.has_value();
      if (ok) corners.push_back(*i);
    }
    if (!ok)
      faces.add_unreadable(ln, out.report, "unreadable vertex index");
    else
      faces.add(corners, ln);
    if (ok && tok.size() > static_cast<std::size_t>(*n) + 1) out.report.note_not_kept("face colours (OFF)", ln);
  }
  if (next_line())
    out.report.add("trailing data after the last face ignored", lines.line_number());
  faces.finish(out.mesh, out.report);
  check_imported_mesh(file, out.mesh, vertex_lines, out.report);
  return out;
}

}  // namespace sublift
