// OBJ, PLY and OFF models for FFD: read through the validating import layer (mesh_import.h),
// written back by rewriting the original bytes so that everything but positions and normals
// stays as it was. The writers re-scan the file with the same line and token rules as the
// readers (text_lines.h), so vertex i here is vertex i there.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string_view>

#include "core/base/binary_cursor.h"
#include "core/base/errors.h"
#include "core/base/file_io.h"
#include "core/io/mesh/mesh_export.h"
#include "core/io/mesh/mesh_import.h"
#include "core/io/model/model_source.h"
#include "core/io/mesh/ply_types.h"
#include "core/complex/polygon_normal.h"
#include "core/base/text_lines.h"

namespace sublift {
namespace {

// One span of the original bytes replaced by new text.
struct Edit {
  std::size_t at = 0, len = 0;
  std::string text;
};

std::string apply_edits(const std::string& bytes, std::vector<Edit>& edits) {
  std::sort(edits.begin(), edits.end(), [](const Edit& a, const Edit& b) { return a.at < b.at; });
  std::string out;
  out.reserve(bytes.size() + edits.size() * 8);
  std::size_t pos = 0;
  for (const Edit& e : edits) {
    out.append(bytes, pos, e.at - pos);
    out += e.text;
    pos = e.at + e.len;
  }
  out.append(bytes, pos, std::string::npos);
  return out;
}

std::size_t offset_in(const std::string& bytes, std::string_view token) {
  return static_cast<std::size_t>(token.data() - bytes.data());
}

// A coordinate token: kept as written when it already holds `v`, else 17 significant digits.
void edit_number(std::vector<Edit>& edits, const std::string& bytes, std::string_view token, double v) {
  const auto old = parse_double(token);
  if (old && *old == v) return;
  edits.push_back({offset_in(bytes, token), token.size(), format_double(v)});
}

// Unit normal of `sum` or nothing when it is zero.
bool unit(const double sum[3], double n[3]) {
  const double len = std::sqrt(sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]);
  if (!(len > 0) || !std::isfinite(len)) return false;
  for (int k = 0; k < 3; ++k) n[k] = sum[k] / len;
  return true;
}

// Vertex normals that need rewriting: area-weighted over the new positions, for vertices on a
// face with a moved vertex. `want[v]` false keeps the file's normal.
struct VertexNormals {
  std::vector<double> n;
  std::vector<char> want;
};

VertexNormals moved_normals(const Model& model, std::span<const double> xyz) {
  const std::size_t nv = model.num_vertices();
  std::vector<char> moved(nv, 0);
  for (std::size_t v = 0; v < nv; ++v)
    for (int k = 0; k < 3; ++k) moved[v] |= xyz[3 * v + std::size_t(k)] != model.positions[3 * v + std::size_t(k)];
  VertexNormals out;
  out.n = area_weighted_normals(model.faces, xyz);
  out.want.assign(nv, 0);
  for (std::size_t f = 0; f < model.faces.rows(); ++f) {
    const auto c = model.faces.row(f);
    if (std::any_of(c.begin(), c.end(), [&](std::uint32_t v) { return moved[v]; }))
      for (std::uint32_t v : c) out.want[v] = 1;
  }
  for (std::size_t v = 0; v < nv; ++v) {
    const double* n = &out.n[3 * v];
    if (n[0] == 0 && n[1] == 0 && n[2] == 0) out.want[v] = 0;
  }
  return out;
}

// ---- OBJ: `v` coordinates replaced in order; `vn` recomputed from the faces whose corners name
// them: each referenced normal becomes the normalised sum of those faces' area vectors (a
// per-vertex normal gets the area-weighted vertex normal, a per-face one the face normal), when
// one of those faces moved. Everything else is copied byte for byte.
std::string rewrite_obj(const Model& model, const std::string& bytes, std::span<const double> xyz) {
  const std::string& file = model.path;
  const ImportLimits limits;
  LineReader lines(bytes, file, limits.max_line_length);
  std::vector<Edit> edits;
  std::vector<std::string_view> tok;
  struct Vn {  // a `vn` line: its tokens, and the area vectors of the faces naming it
    std::string_view t[3];
    bool ok = false, moved = false;
    double sum[3] = {0, 0, 0};
  };
  std::vector<Vn> vns;
  std::vector<std::uint32_t> corners;
  std::vector<std::int64_t> corner_vn;
  std::size_t nv = 0;
  while (next_tokens(lines, tok)) {
    if (tok[0] == "v") {
      const std::size_t v = nv++;
      if (v >= model.num_vertices()) throw InputError(file, lines.line_number(), "more 'v' lines than when the file was imported");
      bool readable = tok.size() >= 4;
      for (int k = 1; readable && k <= 3; ++k) readable = parse_double(tok[std::size_t(k)]).has_value();
      if (!readable) continue;  // the reader's unused placeholder: left as written
      for (int k = 0; k < 3; ++k) edit_number(edits, bytes, tok[std::size_t(k) + 1], xyz[3 * v + std::size_t(k)]);
    } else if (tok[0] == "vn") {
      Vn n;
      n.ok = tok.size() >= 4;
      for (int k = 0; n.ok && k < 3; ++k) {
        n.t[k] = tok[std::size_t(k) + 1];
        n.ok = parse_double(n.t[k]).has_value();
      }
      vns.push_back(n);
    } else if (tok[0] == "f") {
      corners.clear();
      corner_vn.clear();
      bool ok = true;
      for (std::size_t k = 1; ok && k < tok.size(); ++k) {
        const std::string_view t = tok[k];
        const std::size_t s1 = t.find('/');
        const auto vi = parse_int(t.substr(0, s1));
        std::int64_t v = vi ? (*vi > 0 ? *vi - 1 : std::int64_t(nv) + *vi) : -1;
        ok = vi && *vi != 0 && v >= 0 && v < std::int64_t(nv);
        if (!ok) break;
        corners.push_back(std::uint32_t(v));
        std::int64_t n = -1;
        if (s1 != std::string_view::npos) {
          const std::size_t s2 = t.find('/', s1 + 1);
          if (s2 != std::string_view::npos) {
            const auto ni = parse_int(t.substr(s2 + 1));
            if (ni && *ni != 0) n = *ni > 0 ? *ni - 1 : std::int64_t(vns.size()) + *ni;
            if (n >= std::int64_t(vns.size())) n = -1;
          }
        }
        corner_vn.push_back(n);
      }
      if (!ok || corners.size() < 3) continue;
      double a[3];
      polygon_area_vector(corners, xyz.data(), a);
      bool face_moved = false;
      for (std::uint32_t v : corners)
        for (int k = 0; k < 3; ++k) face_moved |= xyz[3 * v + std::size_t(k)] != model.positions[3 * v + std::size_t(k)];
      for (std::int64_t n : corner_vn) {
        if (n < 0) continue;
        for (int k = 0; k < 3; ++k) vns[std::size_t(n)].sum[k] += a[k];
        vns[std::size_t(n)].moved |= face_moved;
      }
    }
  }
  if (nv != model.num_vertices())
    throw InputError(file, 0, "the file has " + std::to_string(nv) + " 'v' lines, the model " + std::to_string(model.num_vertices()) + " vertices");
  for (std::size_t i = 0; i < vns.size(); ++i) {
    double n[3];
    if (!vns[i].ok || !vns[i].moved || !unit(vns[i].sum, n)) continue;
    for (int k = 0; k < 3; ++k) edit_number(edits, bytes, vns[i].t[k], n[k]);
  }
  return apply_edits(bytes, edits);
}

// ---- PLY: x y z (and nx ny nz, recomputed) overwritten in their declared type, in place for
// binary files, token by token for ASCII ones.
// The value as the property's type stores it; integers are rounded and must fit.
struct PlyValue {
  bool ok = true;
  double v = 0;
};

PlyValue ply_cast(PlyType t, double v) {
  if (t == PlyType::Float64) return {true, v};
  if (t == PlyType::Float32) return {std::isfinite(static_cast<float>(v)), double(static_cast<float>(v))};
  const double r = std::nearbyint(v);
  return with_ply_type(t, [&](auto x) {
    using T = decltype(x);
    return PlyValue{r >= double(std::numeric_limits<T>::lowest()) && r <= double(std::numeric_limits<T>::max()), r};
  });
}

std::string ply_text(PlyType t, double v) {
  if (t == PlyType::Float64) return format_double(v);
  char buf[64];
  std::to_chars_result res;
  if (t == PlyType::Float32) res = std::to_chars(buf, buf + sizeof buf, static_cast<float>(v));  // shortest exact float
  else res = std::to_chars(buf, buf + sizeof buf, static_cast<long long>(v));
  return std::string(buf, res.ptr);
}

std::string rewrite_ply(const Model& model, const std::string& bytes, std::span<const double> xyz) {
  const std::string& file = model.path;
  const ImportLimits limits;
  const PlyHeader header = read_ply_header(bytes, file, limits.max_line_length);
  const std::size_t body = header.body;
  const VertexNormals normals = moved_normals(model, xyz);
  // The value a slot of vertex v gets, or nullopt to keep the file's.
  auto value_of = [&](std::size_t v, int slot) -> std::optional<double> {
    if (slot < 3) return xyz[3 * v + std::size_t(slot)];
    if (!normals.want[v]) return std::nullopt;
    return normals.n[3 * v + std::size_t(slot - 3)];
  };
  auto fail_range = [&](std::size_t v, const PlyProperty& p, double x) {
    throw InputError(file, 0, "vertex " + std::to_string(v) + ": " + p.name + " = " + format_double(x) +
                                  " does not fit the file's property type");
  };
  // Walks the body up to the end of the vertex element: `next(type)` passes one value and says
  // where it is, `count(type)` reads a list count, `store(where, type, v)` writes a new value.
  auto rewrite = [&](auto next, auto count, auto store) {
    for (const PlyElement& e : header.elements) {
      const bool vertex = e.name == "vertex";
      std::vector<int> slots(e.props.size(), -1);  // 0..2 x y z, 3..5 nx ny nz of the vertex element
      static constexpr std::string_view kSlots[] = {"x", "y", "z", "nx", "ny", "nz"};
      for (std::size_t i = 0; vertex && i < e.props.size(); ++i)
        for (int s = 0; s < 6; ++s)
          if (!e.props[i].is_list && e.props[i].name == kSlots[s]) slots[i] = s;
      for (std::int64_t r = 0; r < e.count; ++r)
        for (std::size_t i = 0; i < e.props.size(); ++i) {
          const PlyProperty& p = e.props[i];
          const int slot = slots[i];
          if (p.is_list) {
            const std::int64_t n = count(p.count_type);
            for (std::int64_t k = 0; k < n; ++k) next(p.type);
            continue;
          }
          const auto at = next(p.type);
          if (!vertex || slot < 0) continue;
          const auto x = value_of(std::size_t(r), slot);
          if (!x) continue;
          const PlyValue pv = ply_cast(p.type, *x);
          if (!pv.ok) {
            if (slot < 3) fail_range(std::size_t(r), p, *x);
            continue;  // an integer normal is left as written
          }
          if (slot < 3 || ply_type_is_float(p.type)) store(at, p.type, pv.v);
        }
      if (vertex) break;
    }
  };
  if (header.format == PlyFormat::Ascii) {
    LineReader body_lines(std::string_view(bytes).substr(body), file, limits.max_line_length);
    std::vector<std::string_view> toks;
    std::size_t next = 0;
    auto token = [&](PlyType) -> std::string_view {
      while (next >= toks.size()) {
        std::string_view l;
        if (!body_lines.next(l)) throw InputError(file, 0, "PLY body ends early (the file changed since it was imported?)");
        split_tokens(l, toks);
        next = 0;
      }
      return toks[next++];
    };
    std::vector<Edit> edits;
    rewrite(token, [&](PlyType t) { return parse_int(token(t)).value_or(0); },
            [&](std::string_view t, PlyType type, double v) {
              const auto old = parse_double(t);
              if (!old || *old != v) edits.push_back({offset_in(bytes, t), t.size(), ply_text(type, v)});
            });
    return apply_edits(bytes, edits);
  }
  const bool big = header.format == PlyFormat::BinaryBE;
  BinaryCursor in(bytes, body, file, big);
  std::string out = bytes;
  rewrite(
      [&](PlyType t) {
        const std::size_t at = in.offset();
        read_ply_value(in, t, "PLY data");
        return at;
      },
      [&](PlyType t) { return std::int64_t(read_ply_value(in, t, "PLY data")); },
      [&](std::size_t at, PlyType t, double v) {
        with_ply_type(t, [&](auto x) { store_endian(out.data() + at, static_cast<decltype(x)>(v), big); });
      });
  return out;
}

// ---- OFF: [ST][C][N][4]OFF ASCII vertex lines get new coordinates (4OFF keeps w and writes
// x*w y*w z*w), NOFF normals are recomputed; `OFF BINARY` coordinates are overwritten in place.
std::string rewrite_off(const Model& model, const std::string& bytes, std::span<const double> xyz) {
  const std::string& file = model.path;
  const ImportLimits limits;
  LineReader lines(bytes, file, limits.max_line_length);
  std::vector<std::string_view> tok;
  if (!next_tokens(lines, tok)) throw InputError(file, 0, "empty file: no OFF header");
  const std::string magic(tok[0]);
  std::string_view kind = magic;
  bool has_normals = false;
  int dims = 3;
  if (kind.starts_with("ST")) kind.remove_prefix(2);
  if (kind.starts_with("C")) kind.remove_prefix(1);
  if (kind.starts_with("N")) {
    kind.remove_prefix(1);
    has_normals = true;
  }
  if (kind.starts_with("4")) dims = 4;
  const std::size_t nv = model.num_vertices();
  if (tok.size() >= 2 && tok[1] == "BINARY") {  // big-endian: 3 int32 counts, then float32 x y z
    std::string out = bytes;
    const std::size_t start = lines.offset() + 12;
    if (start + 12 * nv > out.size()) throw InputError(file, 0, "binary OFF shorter than its vertices");
    for (std::size_t i = 0; i < 3 * nv; ++i) {
      const float f = static_cast<float>(xyz[i]);
      if (!std::isfinite(f)) throw InputError(file, 0, "vertex " + std::to_string(i / 3) + ": position does not fit in float32");
      store_endian(out.data() + start + 4 * i, f, true);
    }
    return out;
  }
  if (tok.size() == 1 && !next_tokens(lines, tok)) throw InputError(file, lines.line_number(), "missing vertex/face counts");
  const VertexNormals normals = moved_normals(model, xyz);
  std::vector<Edit> edits;
  for (std::size_t v = 0; v < nv; ++v) {
    if (!next_tokens(lines, tok) || tok.size() < std::size_t(dims))
      throw InputError(file, lines.line_number(), "vertex line missing (the file changed since it was imported?)");
    const double w = dims == 4 ? parse_double(tok[3]).value_or(1.0) : 1.0;
    for (int k = 0; k < 3; ++k) {
      const double x = xyz[3 * v + std::size_t(k)];
      // Keep the token when dividing it by w gives the position back exactly (unchanged vertex).
      const auto old = parse_double(tok[std::size_t(k)]);
      if (old && *old / w == x) continue;
      edits.push_back({offset_in(bytes, tok[std::size_t(k)]), tok[std::size_t(k)].size(), format_double(x * w)});
    }
    if (has_normals && normals.want[v] && tok.size() >= std::size_t(dims) + 3)
      for (int k = 0; k < 3; ++k) edit_number(edits, bytes, tok[std::size_t(dims + k)], normals.n[3 * v + std::size_t(k)]);
  }
  return apply_edits(bytes, edits);
}

}  // namespace

Model import_mesh_model(const std::string& path, ModelFormat format) {
  auto source = std::make_shared<ModelSource>();
  source->bytes = read_file_bytes(path);
  LoadedMesh loaded = import_surface_mesh_from_memory(path, source->bytes);
  Model model;
  model.path = path;
  model.format = format;
  model.positions.reserve(3 * loaded.mesh.num_vertices());
  for (const glm::dvec3& p : loaded.mesh.positions) model.positions.insert(model.positions.end(), {p.x, p.y, p.z});
  model.faces.offsets = std::move(loaded.mesh.face_offsets);
  model.faces.items = std::move(loaded.mesh.face_indices);
  model.normals = area_weighted_normals(model.faces, model.positions);
  model.notes = nonempty_lines(loaded.report.format(path));
  model.source = std::move(source);
  return model;
}

void export_mesh_model(const Model& model, std::span<const double> world_positions, const std::string& path) {
  const std::string& bytes = model.source->bytes;
  std::string out;
  switch (model.format) {
    case ModelFormat::Obj: out = rewrite_obj(model, bytes, world_positions); break;
    case ModelFormat::Ply: out = rewrite_ply(model, bytes, world_positions); break;
    case ModelFormat::Off: out = rewrite_off(model, bytes, world_positions); break;
    default: throw InputError(path, 0, "not an OBJ, PLY or OFF model");
  }
  write_file_atomic(path, [&](std::ostream& o) { o.write(out.data(), static_cast<std::streamsize>(out.size())); }, true);
}

}  // namespace sublift
