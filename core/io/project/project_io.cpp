#include "core/io/project/project_io.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <functional>
#include <ostream>

#include <nlohmann/json.hpp>

#include "core/base/binary_cursor.h"
#include "core/base/errors.h"
#include "core/base/text_lines.h"
#include "core/base/file_io.h"
#include "core/base/magnitude.h"
#include "core/complex/complex_build.h"
#include "core/complex/face_varying.h"
#include "core/complex/connectivity_match.h"
#include "core/complex/level_counts.h"
#include "core/io/project/coefficient_codec.h"

namespace sublift {
namespace {

constexpr std::string_view kMagic = "sublift-project";
constexpr std::size_t kMaxHeader = std::size_t(1) << 20;

// The header's "sharpness": {"edges": [[edge, s], ...], "vertices": [[vertex, s], ...]} onto the
// base (s > 0; 10 and above infinitely sharp), each entry checked.
void read_sharpness(const std::string& file, const nlohmann::json& j, Complex& c) {
  if (!j.is_object()) throw InputError(file, 2, "header 'sharpness' is not an object");
  if (c.dim != 2) throw InputError(file, 2, "header 'sharpness' on a base of dimension " + std::to_string(c.dim) + " (surfaces only)");
  c.edge_sharpness.assign(c.num_edges(), 0.0f);
  c.vertex_sharpness.assign(c.num_vertices, 0.0f);
  for (const char* key : {"edges", "vertices"}) {
    const bool edges = key[0] == 'e';
    const std::uint64_t bound = edges ? c.num_edges() : c.num_vertices;
    if (!j.contains(key) || !j.at(key).is_array()) throw InputError(file, 2, std::string("header 'sharpness' has no '") + key + "' list");
    for (const nlohmann::json& item : j.at(key)) {
      if (!item.is_array() || item.size() != 2 || !item[0].is_number_unsigned() || !item[1].is_number())
        throw InputError(file, 2, std::string("header 'sharpness' ") + key + ": entries are [index, sharpness]");
      const std::uint64_t i = item[0].get<std::uint64_t>();
      const double s = item[1].get<double>();
      if (i >= bound || !(s > 0) || !std::isfinite(s))
        throw InputError(file, 2, std::string("header 'sharpness' ") + key + ": [" + std::to_string(i) + ", " + format_shortest(s) +
                                      "] is no index below " + std::to_string(bound) + " with a sharpness > 0");
      (edges ? c.edge_sharpness : c.vertex_sharpness)[i] = s >= 10.0 ? INFINITY : float(s);
    }
  }
}
constexpr int kVersion = 2;  // 2: coefficients dense, sparse or quantized (coefficient_codec.h); 1: dense

template <class T>
void put(std::ostream& out, const std::vector<T>& v) {
  if constexpr (std::endian::native == std::endian::little || sizeof(T) == 1) {
    out.write(reinterpret_cast<const char*>(v.data()), static_cast<std::streamsize>(v.size() * sizeof(T)));
  } else {
    for (T x : v) {
      unsigned char b[sizeof(T)];
      store_endian(b, x, false);
      out.write(reinterpret_cast<const char*>(b), sizeof(T));
    }
  }
}

// Reads `n` little-endian values; the caller has checked that they fit.
template <class T>
std::vector<T> take(std::string_view bytes, std::size_t& pos, std::size_t n) {
  std::vector<T> v(n);
  if (n) std::memcpy(v.data(), bytes.data() + pos, n * sizeof(T));
  if constexpr (std::endian::native != std::endian::little && sizeof(T) > 1)
    for (T& x : v) x = load_endian<T>(&x, false);
  pos += n * sizeof(T);
  return v;
}

// A count computed in doubles, for a message: exact while it fits a long long, else "%g" (a
// lying header's count cannot be cast).
std::string whole_number(double v) { return v < 9e18 ? std::to_string(static_cast<long long>(v)) : format_shortest(v); }

// Header numbers read as what they must be: a count is a non-negative integer, a level or flag
// an integer (JSON's 1e20 or 2.5 would otherwise be cast, out of range, undefined).
std::uint64_t header_count(const std::string& file, const nlohmann::json& j, const char* key) {
  const nlohmann::json& v = j.at(key);
  if (!v.is_number_unsigned()) throw InputError(file, 2, std::string("header '") + key + "' is not a count (a non-negative integer)");
  return v.get<std::uint64_t>();
}
std::int64_t header_integer(const std::string& file, const nlohmann::json& j, const char* key) {
  const nlohmann::json& v = j.at(key);
  if (!v.is_number_integer()) throw InputError(file, 2, std::string("header '") + key + "' is not an integer");
  return v.get<std::int64_t>();
}
// An integer held to -1..2^20 (the range checks that follow name what it must be).
int header_small_integer(const std::string& file, const nlohmann::json& j, const char* key) {
  return static_cast<int>(std::clamp<std::int64_t>(header_integer(file, j, key), -1, 1 << 20));
}

// The optional session keys of the header, checked against the number of levels J.
void check_extras(const ProjectExtras& x, int levels, std::size_t base_vertices, const std::function<void(const std::string&)>& fail) {
  if (const FitSource& fs = x.fit_source; !fs.empty()) {
    if (fs.base_vertex.size() != base_vertices)
      fail("fit_source names " + std::to_string(fs.base_vertex.size()) + " base vertices, but the base has " + std::to_string(base_vertices));
    for (std::size_t v = 0; v < fs.base_vertex.size(); ++v)
      if (fs.base_vertex[v] >= fs.mesh_vertices)
        fail("fit_source: base vertex " + std::to_string(v) + " is mesh vertex " + std::to_string(fs.base_vertex[v]) + ", but the mesh has " +
             std::to_string(fs.mesh_vertices));
  }
  for (const VertexAttribute& a : x.attributes)
    if (a.name.empty() || a.name.size() > 64 || printable(a.name, 64) != a.name || a.type.empty() || printable(a.type, 16) != a.type ||
        a.name.find_first_of(" \t") != std::string::npos)
      fail("an attribute channel needs a name of 1 to 64 printable characters without blanks, and a type");
  if (x.current_level < 0 || x.current_level > levels)
    fail("current_level " + std::to_string(x.current_level) + " outside 0.." + std::to_string(levels));
  if (!x.gains.empty() && x.gains.size() != static_cast<std::size_t>(levels))
    fail(std::to_string(x.gains.size()) + " gains, but a project of " + std::to_string(levels) + " levels takes " +
         std::to_string(levels) + " (one per level below the finest) or none");
  for (std::size_t i = 0; i < x.gains.size(); ++i)
    if (!std::isfinite(x.gains[i])) fail("gain of level " + std::to_string(i) + " is not finite");
}

// The level a vertex is born at (its coefficient: a scaling one at level 0, else a wavelet of
// the level before), for messages.
int birth_level(const Hierarchy& h, std::size_t vertex) {
  int j = 0;
  while (j < h.finest_level() && vertex >= h.num_vertices(j)) ++j;
  return j;
}

// Empty when every coefficient is finite and within kMaxCoordinate; else which one is not.
std::string coefficient_problem(const Hierarchy& h, std::span<const double> coeffs) {
  const auto i = first_out_of_range(coeffs);
  if (!i) return "";
  const std::size_t v = *i / static_cast<std::size_t>(h.channels);
  return "coefficient at vertex " + std::to_string(v) + ", level " + std::to_string(birth_level(h, v)) + ", channel " +
         std::to_string(*i % static_cast<std::size_t>(h.channels)) + " " + out_of_range_text(coeffs[*i]);
}

}  // namespace

SavedProject write_project(const std::string& path, const Hierarchy& h, const ProjectExtras& extras, int quantize_bits) {
  const Complex& b = h.levels.at(0);
  if (quantize_bits && !valid_quantize_bits(quantize_bits))
    throw Error(path + ": cannot save project: quantization takes 8, 16 or 32 bits, not " + std::to_string(quantize_bits));
  if (quantize_bits && h.integer)
    throw Error(path + ": cannot save project: an integer-mode project is exact; it cannot be quantized");
  if (const std::string why = coefficient_problem(h, h.coeffs); !why.empty())
    throw Error(path + ": cannot save project: " + why + "; nothing written");
  check_extras(extras, h.finest_level(), b.num_vertices, [&](const std::string& why) { throw Error(path + ": cannot save project: " + why); });
  if (!extras.input_order.empty()) {
    if (extras.input_order.level > h.finest_level()) throw Error(path + ": cannot save project: input order of a level it lacks");
    if (const std::string why = input_order_problem(extras.input_order, h.levels[static_cast<std::size_t>(extras.input_order.level)]); !why.empty())
      throw Error(path + ": cannot save project: input order: " + why);
  }
  std::vector<std::uint32_t> level_vertices;
  for (const Complex& c : h.levels) level_vertices.push_back(c.num_vertices);
  const EncodedCoefficients enc = encode_coefficients(h.coeffs, level_vertices, h.channels, quantize_bits);
  nlohmann::json j;
  j["format"] = "sublift-project";
  j["version"] = kVersion;
  j["scheme"] = scheme_name(h.scheme);
  j["integer"] = h.integer;
  if (scheme_is_tri(h.scheme)) j["disc"] = h.disc;
  j["levels"] = h.finest_level();
  j["channels"] = h.channels;
  j["dim"] = b.dim;
  j["base"] = {{"vertices", b.num_vertices},           {"edges", b.num_edges()},
               {"faces", b.num_faces()},               {"cells", b.num_cells()},
               {"face_corners", b.faces.items.size()}, {"cell_faces", b.cell_faces.items.size()}};
  j["coefficients"] = h.coeffs.size();
  j["encoding"] = encoding_name(enc.encoding);
  if (enc.encoding != CoefficientEncoding::Dense) j["stored_vertices"] = enc.stored_vertices;
  if (enc.encoding == CoefficientEncoding::Quantized) j["bits"] = enc.bits;
  j["current_level"] = extras.current_level;
  j["gains"] = extras.gains.empty() ? std::vector<double>(static_cast<std::size_t>(h.finest_level()), 1.0) : extras.gains;
  j["local_frames"] = extras.local_frames;
  const InputOrder& io = extras.input_order;
  if (!io.empty())
    j["input_order"] = {{"level", io.level},
                        {"vertices", io.engine_vertex.size()},
                        {"faces", io.faces.rows()},
                        {"face_corners", io.faces.items.size()}};
  if (!extras.attributes.empty()) {
    if (extras.attributes.size() + 3 != static_cast<std::size_t>(h.channels))
      throw Error(path + ": cannot save project: " + std::to_string(extras.attributes.size()) + " attribute channels named for " +
                  std::to_string(h.channels) + " channels (x, y, z and one per attribute)");
    j["attributes"] = nlohmann::json::array();
    for (const VertexAttribute& a : extras.attributes) j["attributes"].push_back({{"name", a.name}, {"type", a.type}});
  }
  if (const FitSource& fs = extras.fit_source; !fs.empty())
    j["fit_source"] = {{"mesh", fs.mesh}, {"mesh_vertices", fs.mesh_vertices}, {"base_vertex", fs.base_vertex}};
  if (const AnimationExtras& an = extras.animation; !an.empty())
    j["animation"] = {{"base_steps", an.base_steps},           {"cyclic", an.cyclic},   {"surface_vertices", an.surface_vertices},
                      {"surface_faces", an.surface_faces},     {"times", an.times},     {"loop_end", an.loop_end}};
  if (!extras.uv.empty()) {
    if (const std::string why = uv_problem(b, extras.uv); !why.empty()) throw Error(path + ": cannot save project: texture coordinates: " + why);
    j["uv"] = {{"points", extras.uv.points}, {"corners", extras.uv.corners}};
  }
  if (!b.edge_sharpness.empty() || !b.vertex_sharpness.empty()) {
    // The base's semi-sharp features (OpenSubdiv sharpness; 10: infinitely sharp): the levels'
    // feature dims follow from them (Complex::edge_sharpness).
    nlohmann::json edges = nlohmann::json::array(), vertices = nlohmann::json::array();
    const auto value = [](float s) { return std::isfinite(s) ? double(s) : 10.0; };
    for (std::size_t e = 0; e < b.edge_sharpness.size(); ++e)
      if (b.edge_sharpness[e] > 0) edges.push_back({e, value(b.edge_sharpness[e])});
    for (std::size_t v = 0; v < b.vertex_sharpness.size(); ++v)
      if (b.vertex_sharpness[v] > 0) vertices.push_back({v, value(b.vertex_sharpness[v])});
    j["sharpness"] = {{"edges", edges}, {"vertices", vertices}};
  }
  j["payload"] =
      "little-endian u32 edge_verts[2*edges] face_offsets[faces+1] face_verts[face_corners] "
      "face_edges[face_corners] cell_offsets[cells+1] cell_faces[cell_faces]; u8 vertex_dim[vertices] "
      "edge_dim[edges] face_dim[faces]; the coefficients as 'encoding' says (docs/file_formats.md)";
  std::uint64_t bytes = 0;
  write_file_atomic(
      path,
      [&](std::ostream& out) {
        out << kMagic << ' ' << kVersion << '\n' << j.dump() << '\n';
        put(out, b.edge_verts);
        put(out, b.faces.offsets);
        put(out, b.faces.items);
        put(out, b.face_edges.items);
        put(out, b.cell_faces.offsets);
        put(out, b.cell_faces.items);
        put(out, b.vertex_dim);
        put(out, b.edge_dim);
        put(out, b.face_dim);
        out.write(enc.bytes.data(), static_cast<std::streamsize>(enc.bytes.size()));
        if (!io.empty()) {
          put(out, io.engine_vertex);
          put(out, io.faces.offsets);
          put(out, io.faces.items);
        }
        bytes = static_cast<std::uint64_t>(out.tellp());
      },
      true);
  return {encoding_name(enc.encoding), bytes, enc.max_error};
}

Hierarchy read_project_from_memory(const std::string& file, const std::string& bytes_in, ProjectExtras* extras_out) {
  const std::string_view bytes(bytes_in);
  // Line 1: magic and version.
  const std::size_t nl1 = bytes.find('\n');
  if (nl1 == std::string_view::npos || nl1 > 64 || bytes.substr(0, kMagic.size()) != kMagic)
    throw InputError(file, 1, "not a Sublift project (the first line must be 'sublift-project 1')");
  std::string_view first = bytes.substr(0, nl1);
  if (!first.empty() && first.back() == '\r') first.remove_suffix(1);
  const int version = first == "sublift-project 1" ? 1 : first == "sublift-project 2" ? 2 : 0;
  if (!version) {
    const std::string_view ver = first.substr(std::min(first.size(), kMagic.size() + 1));
    throw InputError(file, 1, "unsupported project version '" + printable(ver) + "' (this Sublift reads versions 1 and 2)");
  }
  // Line 2: JSON header.
  const std::size_t nl2 = bytes.find('\n', nl1 + 1);
  if (nl2 == std::string_view::npos || nl2 - nl1 - 1 > kMaxHeader)
    throw InputError(file, 2, "missing or over-long header line");
  nlohmann::json j;
  std::uint64_t V, E, F, C, SF, CF, N;
  int levels, channels, dim, disc = 2;
  bool integer;
  Scheme scheme;
  ProjectExtras extras;
  std::int64_t current_level = 0;
  std::int64_t io_level = -1;
  std::uint64_t IV = 0, IF = 0, IK = 0;  // input order: vertices, faces, face corners
  CoefficientEncoding encoding = CoefficientEncoding::Dense;
  std::uint64_t stored = 0;
  int bits = 0;
  try {
    j = nlohmann::json::parse(bytes.substr(nl1 + 1, nl2 - nl1 - 1));
    if (j.at("format").get<std::string>() != "sublift-project") throw InputError(file, 2, "header 'format' is not sublift-project");
    if (header_integer(file, j, "version") != version)
      throw InputError(file, 2, "header version is not " + std::to_string(version) + ", as line 1 says");
    try {
      scheme = parse_scheme(j.at("scheme").get<std::string>());
    } catch (const std::invalid_argument&) {
      throw InputError(file, 2, "unknown scheme '" + printable(j.at("scheme").get<std::string>()) + "'");
    }
    integer = j.at("integer").get<bool>();
    if (j.contains("disc")) disc = header_small_integer(file, j, "disc");
    if (disc < 1 || disc > 3) throw InputError(file, 2, "header 'disc' must be 1, 2 or 3, got " + std::to_string(disc));
    levels = header_small_integer(file, j, "levels");
    channels = header_small_integer(file, j, "channels");
    dim = header_small_integer(file, j, "dim");
    const auto& b = j.at("base");
    V = header_count(file, b, "vertices");
    E = header_count(file, b, "edges");
    F = header_count(file, b, "faces");
    C = header_count(file, b, "cells");
    SF = header_count(file, b, "face_corners");
    CF = header_count(file, b, "cell_faces");
    N = header_count(file, j, "coefficients");
    if (const auto it = j.find("encoding"); it != j.end()) {
      if (version < 2) throw InputError(file, 2, "header 'encoding' needs version 2");
      if (!it->is_string() || !parse_encoding(it->get<std::string>(), encoding))
        throw InputError(file, 2, "header 'encoding' must be dense, sparse or quantized");
    }
    if (encoding != CoefficientEncoding::Dense) stored = header_count(file, j, "stored_vertices");
    if (encoding == CoefficientEncoding::Quantized) {
      bits = header_small_integer(file, j, "bits");
      if (!valid_quantize_bits(bits)) throw InputError(file, 2, "header 'bits' must be 8, 16 or 32, got " + std::to_string(bits));
    }
    // Optional session keys (absent in older version-1 files).
    if (j.contains("current_level")) current_level = header_integer(file, j, "current_level");
    if (const auto it = j.find("gains"); it != j.end()) {
      if (!it->is_array()) throw InputError(file, 2, "header 'gains' is not an array");
      if (it->size() > static_cast<std::size_t>(max_levels(scheme)))
        throw InputError(file, 2, std::to_string(it->size()) + " gains, more than " + std::to_string(max_levels(scheme)) + " levels");
      for (std::size_t i = 0; i < it->size(); ++i) {
        if (!(*it)[i].is_number()) throw InputError(file, 2, "gain of level " + std::to_string(i) + " is not a number");
        extras.gains.push_back((*it)[i].get<double>());
      }
    }
    if (const auto it = j.find("input_order"); it != j.end()) {
      if (!it->is_object()) throw InputError(file, 2, "header 'input_order' is not an object");
      io_level = header_integer(file, *it, "level");
      IV = header_count(file, *it, "vertices");
      IF = header_count(file, *it, "faces");
      IK = header_count(file, *it, "face_corners");
      if (io_level < 0 || io_level > levels) throw InputError(file, 2, "input_order level " + std::to_string(io_level) + " outside 0.." + std::to_string(levels));
    }
    if (const auto it = j.find("fit_source"); it != j.end()) {
      if (!it->is_object()) throw InputError(file, 2, "header 'fit_source' is not an object");
      FitSource& fs = extras.fit_source;
      fs.mesh = it->at("mesh").get<std::string>();
      const std::uint64_t n = header_count(file, *it, "mesh_vertices");
      if (n > 0xfffffffeu) throw InputError(file, 2, "fit_source mesh_vertices exceeds 2^32 - 2");
      fs.mesh_vertices = static_cast<std::uint32_t>(n);
      const auto& bv = it->at("base_vertex");
      if (!bv.is_array() || bv.empty()) throw InputError(file, 2, "header 'fit_source' base_vertex is not a non-empty array");
      for (const auto& x : bv) {
        if (!x.is_number_unsigned()) throw InputError(file, 2, "fit_source base_vertex holds something other than a vertex number");
        fs.base_vertex.push_back(static_cast<std::uint32_t>(std::min<std::uint64_t>(x.get<std::uint64_t>(), 0xffffffffu)));
      }
    }
    if (const auto it = j.find("animation"); it != j.end()) {
      if (!it->is_object()) throw InputError(file, 2, "header 'animation' is not an object");
      AnimationExtras& an = extras.animation;
      const std::int64_t steps = header_integer(file, *it, "base_steps");
      if (steps < 1 || steps > (1 << 20)) throw InputError(file, 2, "animation base_steps " + std::to_string(steps) + " outside 1..2^20");
      an.base_steps = int(steps);
      an.cyclic = it->at("cyclic").get<bool>();
      const std::uint64_t sv = header_count(file, *it, "surface_vertices"), sf = header_count(file, *it, "surface_faces");
      if (sv == 0 || sf == 0 || sv > 0xfffffffeu || sf > 0xfffffffeu) throw InputError(file, 2, "animation surface counts out of range");
      an.surface_vertices = std::uint32_t(sv);
      an.surface_faces = std::uint32_t(sf);
      const auto& t = it->at("times");
      if (!t.is_array() || t.size() > (std::size_t(1) << 24)) throw InputError(file, 2, "animation 'times' is not an array of times");
      for (const auto& x : t) {
        if (!x.is_number() || !std::isfinite(x.get<double>()) || (!an.times.empty() && !(x.get<double>() > an.times.back())))
          throw InputError(file, 2, "animation 'times' must be finite and increasing");
        an.times.push_back(x.get<double>());
      }
      an.loop_end = it->at("loop_end").get<double>();
      if (!std::isfinite(an.loop_end)) throw InputError(file, 2, "animation 'loop_end' is not finite");
    }
    if (const auto it = j.find("attributes"); it != j.end()) {
      if (!it->is_array()) throw InputError(file, 2, "header 'attributes' is not an array");
      for (const auto& a : *it) {
        if (!a.is_object() || !a.at("name").is_string() || !a.at("type").is_string())
          throw InputError(file, 2, "header 'attributes' holds something other than {name, type} objects");
        extras.attributes.push_back({a.at("name").get<std::string>(), a.at("type").get<std::string>(), {}});
      }
    }
    if (const auto it = j.find("uv"); it != j.end()) {  // checked against the base below
      const auto& p = it->at("points");
      const auto& k = it->at("corners");
      if (!p.is_array() || !k.is_array() || p.size() > (std::size_t(1) << 27) || k.size() > (std::size_t(1) << 27))
        throw InputError(file, 2, "header 'uv' needs 'points' and 'corners' arrays");
      for (const auto& x : p) {
        if (!x.is_number() || !std::isfinite(x.get<double>())) throw InputError(file, 2, "header 'uv' points must be finite numbers");
        extras.uv.points.push_back(x.get<double>());
      }
      for (const auto& x : k) {
        if (!x.is_number_unsigned() || x.get<std::uint64_t>() > 0xffffffffu) throw InputError(file, 2, "header 'uv' corners must be UV point indices");
        extras.uv.corners.push_back(x.get<std::uint32_t>());
      }
    }
    if (const auto it = j.find("local_frames"); it != j.end()) {
      if (!it->is_boolean()) throw InputError(file, 2, "header 'local_frames' is not true or false");
      extras.local_frames = it->get<bool>();
    }
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file, 2, std::string("malformed header: ") + e.what());
  }
  if (levels < 0 || levels > max_levels(scheme))
    throw InputError(file, 2, "levels " + std::to_string(levels) + " outside 0.." + std::to_string(max_levels(scheme)));
  if (channels < 1 || channels > 64) throw InputError(file, 2, "channels " + std::to_string(channels) + " outside 1..64");
  if (dim < 1 || dim > 3) throw InputError(file, 2, "dim " + std::to_string(dim) + " outside 1..3");
  constexpr std::uint64_t kMax = 0xfffffffeu;
  for (std::uint64_t n : {V, E, F, C, SF, CF, IV, IF, IK})
    if (n > kMax) throw InputError(file, 2, "a base count exceeds 2^32 - 2");
  const double coeff_d = encoded_bytes(encoding, double(N), double(V), channels, levels, double(stored), bits);
  // Payload size, computed in doubles first so that lying counts cannot wrap.
  const std::size_t start = nl2 + 1;
  const std::size_t have = bytes.size() - start;
  const double io_d = io_level < 0 ? 0.0 : 4.0 * (double(IV) + double(IF) + 1.0 + double(IK));
  const double want_d = 4.0 * (2.0 * E + (F + 1) + 2.0 * SF + (C + 1) + CF) + double(V) + double(E) + double(F) + coeff_d + io_d;
  if (want_d > static_cast<double>(have) + 0.5)
    throw InputError(file, 0, "truncated payload: the header announces " + whole_number(want_d) +
                                  " bytes, the file holds " + std::to_string(have));
  if (N % static_cast<std::uint64_t>(channels) != 0 || N / static_cast<std::uint64_t>(channels) < V ||
      stored > N / static_cast<std::uint64_t>(channels) - V)
    throw InputError(file, 2, "coefficient counts do not fit: " + std::to_string(N) + " values of " + std::to_string(channels) +
                                  " channels on a base of " + std::to_string(V) + " vertices, " + std::to_string(stored) +
                                  " stored wavelet vertices");
  const auto coeff_bytes = static_cast<std::size_t>(coeff_d);
  const std::size_t want = 4 * (2 * E + (F + 1) + 2 * SF + (C + 1) + CF) + V + E + F + coeff_bytes +
                           (io_level < 0 ? 0 : 4 * (IV + IF + 1 + IK));
  if (want != have)
    throw InputError(file, 0, "payload of " + std::to_string(have) + " bytes, but the header announces " + std::to_string(want));

  std::size_t pos = start;
  Complex c;
  c.dim = dim;
  c.num_vertices = static_cast<std::uint32_t>(V);
  c.edge_verts = take<std::uint32_t>(bytes, pos, 2 * E);
  c.faces.offsets = take<std::uint32_t>(bytes, pos, F + 1);
  c.faces.items = take<std::uint32_t>(bytes, pos, SF);
  c.face_edges.offsets = c.faces.offsets;
  c.face_edges.items = take<std::uint32_t>(bytes, pos, SF);
  c.cell_faces.offsets = take<std::uint32_t>(bytes, pos, C + 1);
  c.cell_faces.items = take<std::uint32_t>(bytes, pos, CF);
  c.vertex_dim = take<std::uint8_t>(bytes, pos, V);
  c.edge_dim = take<std::uint8_t>(bytes, pos, E);
  c.face_dim = take<std::uint8_t>(bytes, pos, F);
  // Offsets and indices before anything walks them.
  auto check_csr = [&](const Csr& r, std::uint64_t items, std::uint64_t bound, const char* what) {
    if (r.offsets.front() != 0 || r.offsets.back() != items)
      throw InputError(file, 0, std::string(what) + " offsets do not run from 0 to " + std::to_string(items));
    for (std::size_t i = 1; i < r.offsets.size(); ++i)
      if (r.offsets[i] < r.offsets[i - 1]) throw InputError(file, 0, std::string(what) + " offsets decrease at row " + std::to_string(i - 1));
    for (std::uint32_t x : r.items)
      if (x >= bound) throw InputError(file, 0, std::string(what) + " names " + std::to_string(x) + ", beyond " + std::to_string(bound));
  };
  for (std::uint32_t v : c.edge_verts)
    if (v >= V) throw InputError(file, 0, "an edge names vertex " + std::to_string(v) + ", beyond " + std::to_string(V));
  check_csr(c.faces, SF, V, "face");
  check_csr(c.face_edges, SF, E, "face-edge");
  check_csr(c.cell_faces, CF, F, "cell");
  if ((dim < 3 && C) || (dim < 2 && F) || (dim >= 2 && F == 0))
    throw InputError(file, 2, "counts do not fit a complex of dimension " + std::to_string(dim));
  if (scheme_info(scheme).surfaces_only && dim != 2)
    throw InputError(file, 2, "the " + scheme_name(scheme) + " scheme needs a surface (dim 2), the header says dim " +
                                  std::to_string(dim));
  try {
    build_adjacency(c);
    validate(c);
  } catch (const TopologyError& e) {
    throw InputError(file, 0, std::string("base complex: ") + e.what());
  }
  const std::vector<double> counts = predicted_level_counts(c, levels, scheme);
  if (static_cast<double>(N) != counts.back() * channels)
    throw InputError(file, 2, std::to_string(N) + " coefficients, but " + std::to_string(levels) + " levels of this base with " +
                                  std::to_string(channels) + " channels need " +
                                  whole_number(counts.back() * channels));
  // The session keys, once the levels are known to fit the payload.
  if (current_level < 0 || current_level > levels)
    throw InputError(file, 2, "current_level " + std::to_string(current_level) + " outside 0.." + std::to_string(levels));
  extras.current_level = static_cast<int>(current_level);
  if (!extras.attributes.empty() && extras.attributes.size() + 3 != static_cast<std::size_t>(channels))
    throw InputError(file, 2, std::to_string(extras.attributes.size()) + " attribute channels named for " + std::to_string(channels) +
                                  " channels (x, y, z and one per attribute)");
  check_extras(extras, levels, static_cast<std::size_t>(V), [&](const std::string& why) { throw InputError(file, 2, why); });
  const std::string_view coeff_payload = bytes.substr(pos, coeff_bytes);
  pos += coeff_bytes;
  if (j.contains("sharpness")) read_sharpness(file, j.at("sharpness"), c);
  if (!extras.uv.empty())
    if (const std::string why = uv_problem(c, extras.uv); !why.empty()) throw InputError(file, 2, "header 'uv': " + why);
  Hierarchy h;
  try {
    h = make_hierarchy(std::move(c), levels, scheme, channels, integer, 0, disc);
  } catch (const TopologyError& e) {  // sqrt2 needs consistently oriented faces
    throw InputError(file, 0, std::string("base complex: ") + e.what());
  }
  if (h.coeffs.size() != N) throw InputError(file, 2, "coefficient count does not match the refined base");
  std::vector<std::uint32_t> level_vertices;
  for (const Complex& l : h.levels) level_vertices.push_back(l.num_vertices);
  std::vector<double> coeffs =
      decode_coefficients(coeff_payload, encoding, N, level_vertices, channels, stored, bits, file);
  if (const std::string why = coefficient_problem(h, coeffs); !why.empty()) throw InputError(file, 0, why);
  h.coeffs = std::move(coeffs);
  if (io_level >= 0) {
    InputOrder& io = extras.input_order;
    io.level = static_cast<int>(io_level);
    io.engine_vertex = take<std::uint32_t>(bytes, pos, IV);
    io.faces.offsets = take<std::uint32_t>(bytes, pos, IF + 1);
    io.faces.items = take<std::uint32_t>(bytes, pos, IK);
    check_csr(io.faces, IK, IV, "input-order face");
    if (const std::string why = input_order_problem(io, h.levels[static_cast<std::size_t>(io.level)]); !why.empty())
      throw InputError(file, 0, "input order: " + why);
  }
  if (extras_out) {
    if (extras.gains.empty()) extras.gains.assign(static_cast<std::size_t>(levels), 1.0);
    *extras_out = std::move(extras);
  }
  return h;
}

std::vector<double> in_input_order(const InputOrder& order, std::span<const double> level_values, int channels) {
  const auto ch = static_cast<std::size_t>(channels);
  std::vector<double> out(order.engine_vertex.size() * ch);
  for (std::size_t i = 0; i < order.engine_vertex.size(); ++i)
    for (std::size_t k = 0; k < ch; ++k) out[i * ch + k] = level_values[order.engine_vertex[i] * ch + k];
  return out;
}

Complex in_input_order(const InputOrder& order, const Complex& level) {
  const auto n = static_cast<std::uint32_t>(order.engine_vertex.size());
  if (order.faces.rows() > 0) return complex_from_polygons(n, order.faces);
  std::vector<std::uint32_t> file_of(n);
  for (std::uint32_t i = 0; i < n; ++i) file_of[order.engine_vertex[i]] = i;
  Complex c = level;
  for (std::uint32_t& v : c.edge_verts) v = file_of[v];
  for (std::uint32_t& v : c.faces.items) v = file_of[v];
  std::vector<std::uint8_t> dims(c.vertex_dim.size());
  for (std::uint32_t v = 0; v < dims.size(); ++v) dims[file_of[v]] = c.vertex_dim[v];
  c.vertex_dim = std::move(dims);
  build_adjacency(c);
  return c;
}

std::string input_order_problem(const InputOrder& order, const Complex& level) {
  if (order.engine_vertex.size() != level.num_vertices)
    return std::to_string(order.engine_vertex.size()) + " vertices, the level has " + std::to_string(level.num_vertices);
  std::vector<std::uint8_t> hit(level.num_vertices, 0);
  for (std::uint32_t v : order.engine_vertex) {
    if (v >= level.num_vertices || hit[v]) return "the vertex map is not a permutation";
    hit[v] = 1;
  }
  if (order.faces.rows() == 0) return "";  // lattices keep the vertex order only
  for (std::size_t f = 0; f < order.faces.rows(); ++f)
    if (order.faces.size(f) < 3) return "face " + std::to_string(f) + " has fewer than 3 corners";
  Complex mapped;
  mapped.dim = level.dim;
  mapped.num_vertices = level.num_vertices;
  mapped.faces = order.faces;
  for (std::uint32_t& v : mapped.faces.items) {
    if (v >= order.engine_vertex.size()) return "a face names a vertex beyond the map";
    v = order.engine_vertex[v];
  }
  return connectivity_mismatch(level, mapped);
}

Hierarchy read_project(const std::string& path, ProjectExtras* extras) {
  return read_project_from_memory(path, read_file_bytes(path), extras);
}

}  // namespace sublift
