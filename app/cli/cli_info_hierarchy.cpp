// sublift-cli info for .sublift projects and for lattices (.lattice, .ovm, .vtk).
#include <iostream>
#include <map>

#include <nlohmann/json.hpp>

#include "app/cli/cli_commands.h"
#include "app/cli/cli_hierarchy.h"
#include "app/cli/cli_json.h"
#include "core/multires/hierarchy.h"
#include "core/io/mesh/mesh_export.h"
#include "core/io/project/project_io.h"
#include "core/io/lattice/shape_io.h"

namespace sublift::cli {

namespace {

nlohmann::json dims_json(const std::vector<std::uint8_t>& dims) {
  std::map<int, std::size_t> h;
  for (std::uint8_t d : dims) ++h[d];
  nlohmann::json j = nlohmann::json::object();
  for (auto [d, n] : h) j[std::to_string(d)] = n;
  return j;
}

std::string dims_text(const nlohmann::json& j) {
  std::string s;
  for (auto it = j.begin(); it != j.end(); ++it)
    s += (s.empty() ? "" : ", ") + std::string("dim ") + it.key() + ": " + std::to_string(it.value().get<std::size_t>());
  return s.empty() ? "-" : s;
}

}  // namespace

int info_project(const std::string& file, bool json) {
  ProjectExtras extras;
  const Hierarchy h = read_project(file, &extras);
  std::vector<std::string> names;  // what each channel holds
  for (int k = 0; k < h.channels; ++k)
    names.push_back(k < 3 ? std::string(1, char('x' + k))
                          : k - 3 < static_cast<int>(extras.attributes.size()) ? extras.attributes[static_cast<std::size_t>(k - 3)].name
                                                                                : "channel " + std::to_string(k));
  const Complex& base = h.levels.front();
  const int J = h.finest_level();
  nlohmann::json per_level = nlohmann::json::array();
  for (const LevelStats& s : level_stats(h))
    per_level.push_back({{"level", s.level},
                         {"vertices", s.vertices},
                         {"wavelets", s.wavelets},
                         {"wavelet_max", s.wavelet_max},
                         {"wavelet_rms", s.wavelet_rms}});
  nlohmann::json j = {{"file", file},
                      {"format", "sublift-project"},
                      {"scheme", scheme_name(h.scheme)},
                      {"integer", h.integer},
                      {"channels", h.channels},
                      {"channel_names", names},
                      {"dim", base.dim},
                      {"levels", J},
                      {"vertices", base.num_vertices},
                      {"edges", base.num_edges()},
                      {"faces", base.num_faces()},
                      {"cells", base.num_cells()},
                      {"finest_vertices", h.num_vertices(J)},
                      {"uv_points", extras.uv.num_points()},
                      {"per_level", per_level},
                      {"feature_dims", {{"vertices", dims_json(base.vertex_dim)},
                                        {"edges", dims_json(base.edge_dim)},
                                        {"faces", dims_json(base.face_dim)}}}};
  if (json) {
    std::cout << j.dump(2) << "\n";
    return 0;
  }
  std::cout << "file:                  " << file << "\n"
            << "project:               " << scheme_name(h.scheme) << " scheme" << (h.integer ? ", integer" : "")
            << ", " << h.channels << " channel(s), dimension " << base.dim << "\n"
            << "channels:              " << [&] {
                 std::string t;
                 for (const std::string& n : names) t += (t.empty() ? "" : " ") + n;
                 return t;
               }() << "\n"
            << "base:                  " << base.num_vertices << " vertices, " << base.num_edges() << " edges, "
            << base.num_faces() << " faces, " << base.num_cells() << " cells\n"
            << "levels:                " << J << " (finest: " << h.num_vertices(J) << " vertices)\n";
  if (!extras.uv.empty()) std::cout << "texture coordinates:   " << extras.uv.num_points() << " UV points on the base's corners\n";
  for (const auto& s : per_level)
    std::cout << "  level " << s["level"].get<int>() << ": " << s["vertices"].get<std::uint64_t>() << " vertices, "
              << s["wavelets"].get<std::uint64_t>() << " wavelets, max " << format_double(s["wavelet_max"].get<double>())
              << ", rms " << format_double(s["wavelet_rms"].get<double>()) << "\n";
  return 0;
}

int info_shape(const std::string& file, bool json) {
  const Shape shape = read_shape(file);
  std::cerr << shape.report.format(file);
  const Complex& c = shape.base;
  std::size_t boundary_faces = 0;
  std::map<std::size_t, std::size_t> cell_sizes;  // faces per cell -> cells
  for (std::uint32_t f = 0; f < c.num_faces(); ++f) boundary_faces += c.dim == 3 && c.face_cells.size(f) == 1;
  for (std::uint32_t k = 0; k < c.num_cells(); ++k) ++cell_sizes[c.cell_faces.size(k)];
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  for (std::uint32_t v = 0; v < c.num_vertices; ++v)
    for (int t = 0; t < 3; ++t) {
      const double x = shape.positions[3 * v + t];
      lo[t] = v ? std::min(lo[t], x) : x;
      hi[t] = v ? std::max(hi[t], x) : x;
    }
  nlohmann::json sizes = nlohmann::json::object();
  for (auto [n, k] : cell_sizes) sizes[std::to_string(n)] = k;
  nlohmann::json j = complex_counts_json(c);
  j["file"] = file;
  j["boundary_faces"] = boundary_faces;
  j["cell_face_counts"] = sizes;
  j["feature_dims"] = {{"vertices", dims_json(c.vertex_dim)}, {"edges", dims_json(c.edge_dim)}, {"faces", dims_json(c.face_dim)}};
  j["bbox"] = {{"min", {lo[0], lo[1], lo[2]}}, {"max", {hi[0], hi[1], hi[2]}}};
  j["uv_points"] = shape.uv.num_points();
  j["texture"] = shape.texture.empty() ? nlohmann::json(nullptr) : nlohmann::json({{"name", shape.texture.name}, {"mime_type", shape.texture.mime_type}, {"bytes", shape.texture.bytes.size()}});
  j["warnings"] = report_json(shape.report);
  if (json) {
    std::cout << j.dump(2) << "\n";
    return 0;
  }
  std::string sz;
  for (auto [n, k] : cell_sizes) sz += (sz.empty() ? "" : ", ") + std::to_string(n) + ": " + std::to_string(k);
  std::cout << "file:                  " << file << "\n"
            << "dimension:             " << c.dim << "\n"
            << "vertices:              " << c.num_vertices << "\n"
            << "edges:                 " << c.num_edges() << "\n"
            << "faces:                 " << c.num_faces() << " (" << boundary_faces << " on the boundary)\n"
            << "cells:                 " << c.num_cells() << "\n"
            << "faces per cell:        " << (sz.empty() ? "-" : sz) << "\n"
            << "vertex feature dims:   " << dims_text(j["feature_dims"]["vertices"]) << "\n"
            << "edge feature dims:     " << dims_text(j["feature_dims"]["edges"]) << "\n"
            << "face feature dims:     " << dims_text(j["feature_dims"]["faces"]) << "\n"
            << "bounding box:          [" << format_double(lo[0]) << " " << format_double(lo[1]) << " "
            << format_double(lo[2]) << "] .. [" << format_double(hi[0]) << " " << format_double(hi[1]) << " "
            << format_double(hi[2]) << "]\n";
  if (!shape.uv.empty()) std::cout << "texture coordinates:   " << shape.uv.num_points() << " UV points\n";
  if (!shape.texture.empty()) std::cout << "texture:               " << shape.texture.name << " (" << shape.texture.mime_type << ", " << shape.texture.bytes.size() << " bytes)\n";
  return 0;
}

}  // namespace sublift::cli
