// Wavefront OBJ: `v`, `vt` (face-varying UVs), `f` (v, v/vt, v//vn, v/vt/vn; negative = relative), `l` polylines (v, v/vt),
// OpenSubdiv `t` tags.
// Everything else that OBJ allows is skipped; unknown statements are reported.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/base/errors.h"
#include "core/complex/face_builder.h"
#include "core/io/mesh/mesh_readers.h"
#include "core/base/text_lines.h"

namespace sublift {
namespace {

// Statements that are valid OBJ but carry nothing a surface mesh needs.
bool ignorable_statement(std::string_view k) {
  static constexpr std::string_view kIgnored[] = {
      "vn", "vt", "vp", "g", "o", "s", "usemtl", "mtllib", "mg", "lod", "bevel", "c_interp",
      "d_interp", "shadow_obj", "trace_obj", "cstype", "deg", "bmat", "step", "curv", "curv2",
      "surf", "parm", "trim", "hole", "scrv", "sp", "end", "con", "usemap", "maplib", "call",
      "csh", "ctech", "stech"};
  for (std::string_view s : kIgnored)
    if (k == s) return true;
  return false;
}

// Parses an OpenSubdiv tag: `t name ni/nf/ns ints... floats... strings...`.
bool parse_tag(const std::vector<std::string_view>& tok, std::size_t line, MeshTag& tag) {
  if (tok.size() < 3) return false;
  tag.name = std::string(tok[1]);
  tag.line = line;
  std::string_view counts = tok[2];
  std::int64_t n[3];
  for (int k = 0; k < 3; ++k) {
    const std::size_t slash = counts.find('/');
    const std::string_view part = k < 2 ? counts.substr(0, slash) : counts;
    if (k < 2 && slash == std::string_view::npos) return false;
    auto v = parse_int(part);
    if (!v || *v < 0 || *v > 1 << 20) return false;
    n[k] = *v;
    if (k < 2) counts.remove_prefix(slash + 1);
  }
  if (tok.size() != 3 + static_cast<std::size_t>(n[0] + n[1] + n[2])) return false;
  std::size_t i = 3;
  for (std::int64_t k = 0; k < n[0]; ++k, ++i) {
    auto v = parse_int(tok[i]);
    if (!v) return false;
    tag.ints.push_back(*v);
  }
  for (std::int64_t k = 0; k < n[1]; ++k, ++i) {
    auto v = parse_double(tok[i]);
    if (!v) return false;
    tag.floats.push_back(*v);
  }
  for (std::int64_t k = 0; k < n[2]; ++k, ++i) tag.strings.emplace_back(tok[i]);
  return true;
}

}  // namespace

LoadedMesh read_obj(std::string_view bytes, const std::string& file, const ImportLimits& limits) {
  LoadedMesh out;
  SurfaceMesh& mesh = out.mesh;
  ImportReport& report = out.report;
  FaceBuilder faces;
  PolylineBuilder polylines;
  std::vector<std::size_t> vertex_lines;
  std::vector<std::string_view> tok;
  std::vector<std::int64_t> corners, corner_uvs;  // vertex and vt index of each corner (-1: no vt)
  std::vector<double> colours;           // r g b per vertex (`v x y z r g b`, the common extension)
  std::size_t coloured = 0, first_colour_line = 0;
  std::size_t uv_broken_line = 0;        // first unreadable `vt` line (the UVs are then not kept)
  LineReader lines(bytes, file, limits.max_line_length);
  // The vertices of an `f` or `l` line into `corners` (v, v/vt, v//vn, v/vt/vn; negative:
  // relative to here); false when there are more than the size limit or one is unreadable or 0.
  auto read_corners = [&] {
    corners.clear();
    corner_uvs.clear();
    if (tok.size() > limits.max_face_size + 1) return false;
    const auto num_uv = static_cast<std::int64_t>(mesh.uv.num_points());
    bool any_uv = false;
    for (std::size_t k = 1; k < tok.size(); ++k) {
      const std::size_t slash = tok[k].find('/');
      const auto idx = parse_int(tok[k].substr(0, slash));
      if (!idx || *idx == 0) return false;
      corners.push_back(*idx > 0 ? *idx - 1 : static_cast<std::int64_t>(mesh.positions.size()) + *idx);
      std::int64_t uv = -1;  // v//vn and v have none; an unreadable one counts as none
      if (slash != std::string_view::npos) {
        const std::string_view rest = tok[k].substr(slash + 1);
        if (const auto t = parse_int(rest.substr(0, rest.find('/'))); t && *t != 0)
          uv = *t > 0 ? *t - 1 : num_uv + *t;
        if (uv < 0) uv = -1;
      }
      // Filled from the first corner with a UV on (the common face without any costs nothing).
      if (uv >= 0 && !any_uv) corner_uvs.assign(k - 1, -1), any_uv = true;
      if (any_uv) corner_uvs.push_back(uv);
    }
    return true;
  };
  while (next_tokens(lines, tok)) {
    const std::size_t ln = lines.line_number();
    const std::string_view key = tok[0];
    if (key == "v") {
      glm::dvec3 p(0.0);
      bool ok = tok.size() >= 4;
      for (int k = 0; ok && k < 3; ++k) {
        auto d = parse_double(tok[k + 1]);
        if (!d) {
          // A literal nan/inf is a number the file really states: refuse the file.
          const std::string t = to_lower(tok[k + 1]);
          if (t.find("nan") != std::string::npos || t.find("inf") != std::string::npos)
            throw InputError(file, ln, "non-finite coordinate '" + printable(tok[k + 1]) + "'");
          ok = false;
        } else if (std::abs(*d) > kMaxCoordinate) {
          throw InputError(file, ln, "coordinate " + printable(tok[k + 1]) +
                                         " exceeds the supported magnitude " + max_coordinate_text());
        } else {
          p[k] = *d;
        }
      }
      if (!ok) {
        // Keep a placeholder so later vertices keep their numbers; faces using it are dropped.
        report.add("unreadable vertex line: unused placeholder kept so numbering is unchanged", ln);
        faces.mark_unusable_vertex(mesh.positions.size());
      }
      double rgb[3] = {0.0, 0.0, 0.0};
      bool has_rgb = ok && tok.size() == 7;
      for (int k = 0; has_rgb && k < 3; ++k) {
        const auto d = parse_double(tok[4 + k]);
        has_rgb = d && std::abs(*d) <= kMaxCoordinate;
        if (has_rgb) rgb[k] = *d;
      }
      if (has_rgb && !coloured++) first_colour_line = ln;
      colours.insert(colours.end(), rgb, rgb + 3);
      mesh.positions.push_back(p);
      vertex_lines.push_back(ln);
    } else if (key == "f") {
      if (read_corners())
        faces.add(corners, ln, corner_uvs);
      else
        faces.add_unreadable(ln, report, tok.size() > limits.max_face_size + 1
                                             ? "more corners than the face-size limit"
                                             : "unreadable or zero vertex index");
    } else if (key == "t") {
      MeshTag tag;
      if (parse_tag(tok, ln, tag))
        mesh.tags.push_back(std::move(tag));
      else
        report.add("tag dropped: malformed 't name ni/nf/ns values' line", ln);
    } else if (key == "l") {
      if (read_corners())
        polylines.add(corners, ln);
      else
        report.add(tok.size() > limits.max_face_size + 1 ? "polyline dropped: more vertices than the size limit"
                                                         : "polyline dropped: unreadable or zero vertex index",
                   ln);
    } else if (key == "vt") {  // u [v [w]]: u and v kept (w, for 3D textures, is not)
      const auto u = tok.size() >= 2 ? parse_double(tok[1]) : std::nullopt;
      const auto v = tok.size() >= 3 ? parse_double(tok[2]) : std::optional<double>(0.0);
      const bool ok = u && v && std::isfinite(*u) && std::isfinite(*v) && std::abs(*u) <= kMaxCoordinate && std::abs(*v) <= kMaxCoordinate;
      if (!ok && !uv_broken_line) uv_broken_line = ln;
      mesh.uv.points.insert(mesh.uv.points.end(), {ok ? *u : 0.0, ok ? *v : 0.0});
    } else if (key == "vn" || key == "usemtl") {
      report.note_not_kept(key == "vn" ? "normals (vn)" : "materials (usemtl)", ln);
    } else if (key == "p") {
      report.add("point element ignored (not a face or polyline)", ln);
    } else if (!ignorable_statement(key)) {
      report.add("unknown statement ignored ('" + printable(key, 16) + "')", ln);
    }
  }
  // Colours on every vertex are kept (red, green, blue, as the file writes them, usually 0..1);
  // on some only, they cannot be channels and are named as not kept.
  if (coloured == mesh.num_vertices() && coloured > 0) {
    for (int k = 0; k < 3; ++k) {
      VertexAttribute a{k == 0 ? "red" : k == 1 ? "green" : "blue", "float", std::vector<double>(coloured)};
      for (std::size_t v = 0; v < coloured; ++v) a.values[v] = colours[3 * v + k];
      mesh.attributes.push_back(std::move(a));
    }
  } else if (coloured > 0) {
    report.not_kept.push_back({"vertex colours (on " + std::to_string(coloured) + " of " + std::to_string(mesh.num_vertices()) +
                                   " vertices: a colour channel needs all)",
                               coloured, {first_colour_line}});
  }
  if (uv_broken_line) {
    report.not_kept.push_back({"texture coordinates (vt): an unreadable 'vt u [v [w]]' line", 1, {uv_broken_line}});
    mesh.uv = {};
  }
  faces.finish(mesh, report);
  polylines.finish(mesh, faces.unusable(), report);
  // crease/corner tags name vertices (0-based, as OpenSubdiv writes them).
  std::erase_if(mesh.tags, [&](const MeshTag& t) {
    if (t.name != "crease" && t.name != "corner") return false;
    const bool bad = std::any_of(t.ints.begin(), t.ints.end(), [&](std::int64_t v) {
      return v < 0 || v >= static_cast<std::int64_t>(mesh.num_vertices());
    }) || (t.name == "crease" && t.ints.size() < 2);
    if (bad) report.add("tag dropped: " + t.name + " names a vertex out of range", t.line);
    return bad;
  });
  check_imported_mesh(file, mesh, vertex_lines, report);
  return out;
}

}  // namespace sublift
