#include <cctype>
#include "app/cli/cli_hierarchy.h"

#include <charconv>
#include <cstdio>

#include "core/base/errors.h"
#include "core/complex/complex_build.h"
#include "core/edit/scheme_switch.h"
#include "core/complex/level_counts.h"
#include "core/io/project/project_io.h"
#include "core/io/lattice/shape_io.h"
#include "core/complex/face_varying.h"
#include "core/multires/level_uv.h"

namespace sublift::cli {

int levels_option(const Args& a, Scheme scheme) {
  const auto v = a.value("--levels");
  if (!v) throw UsageError("missing --levels N");
  int n = -1;
  const int most = max_levels(scheme);
  auto [p, ec] = std::from_chars(v->data(), v->data() + v->size(), n);
  if (ec != std::errc() || p != v->data() + v->size() || n < 0 || n > most)
    throw UsageError("--levels must be an integer in 0.." + std::to_string(most) + ", got '" + *v + "'");
  return n;
}

Scheme scheme_option(const Args& a) {
  const auto v = a.value("--scheme");
  if (!v) {
    std::string names;
    for (const SchemeInfo& s : all_schemes()) names.append(names.empty() ? "" : "|").append(s.name);
    throw UsageError("missing --scheme " + names);
  }
  try {
    return parse_scheme(*v);
  } catch (const std::invalid_argument&) {
    throw UsageError("--scheme must be " + scheme_names_list() + ", got '" + *v + "'");
  }
}

int disc_option(const Args& a, Scheme scheme) {
  const auto v = a.value("--disc");
  if (!v) return 2;
  if (!scheme_is_tri(scheme)) throw UsageError("--disc applies to the triangle schemes (linear-tri, butterfly, loop)");
  if (*v != "1" && *v != "2" && *v != "3") throw UsageError("--disc must be 1, 2 or 3, got '" + *v + "'");
  return *v == "1" ? 1 : *v == "2" ? 2 : 3;
}

void check_refined_size(const Complex& base, int levels, Scheme scheme) {
  try {  // the one rule of which scheme takes which base (core/edit/scheme_switch.h)
    check_scheme_takes(scheme, base);
  } catch (const sublift::Error& e) {
    throw UsageError(e.what());
  }
  const double n = predicted_level_counts(base, levels, scheme).back();
  if (n > kMaxOutputVertices) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "%d levels of this base make %.0f vertices, more than the limit of %.0f; use fewer levels",
                  levels, n, kMaxOutputVertices);
    throw UsageError(buf);
  }
}

std::string output_option(const Args& a, int dim) {
  const auto out = a.value("-o");
  if (!out) throw UsageError("missing -o OUT");
  if (dim > 0)
    if (const std::string why = shape_output_problem(*out, dim); !why.empty()) throw UsageError(why);
  return *out;
}

bool is_project_path(const std::string& path) {
  const std::string ext = ".sublift";
  if (path.size() < ext.size()) return false;
  for (std::size_t i = 0; i < ext.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(path[path.size() - ext.size() + i])) != ext[i]) return false;
  return true;
}

std::vector<std::string> write_level(const std::string& out, const Hierarchy& h, int L, std::span<const double> x,
                                     int channels, const InputOrder& order, std::span<const VertexAttribute> names,
                                     const FaceVaryingUV* base_uv) {
  const auto attributes = [&](std::span<const double> values) {
    return channels == 3 + static_cast<int>(names.size()) ? attributes_of(values, channels, names) : std::vector<VertexAttribute>{};
  };
  const Complex& level = h.levels[static_cast<std::size_t>(L)];
  std::vector<std::string> notes;
  FaceVaryingUV uv = base_uv ? uv_for_output(h, *base_uv, L, notes) : FaceVaryingUV{};
  const auto add = [&](std::vector<std::string> more) {
    notes.insert(notes.end(), more.begin(), more.end());
    return notes;
  };
  if (order.level != L) return add(write_shape(out, level, xyz_of(x, channels), attributes(x), &uv));
  const std::vector<double> ordered = in_input_order(order, x, channels);
  const Complex file_level = in_input_order(order, level);
  if (!uv.empty()) {  // the file's faces over the engine's vertices, corner for corner
    Csr engine_faces = order.faces;
    for (std::uint32_t& v : engine_faces.items) v = order.engine_vertex[v];
    uv = uv_for_faces(level.faces, uv, engine_faces);
  }
  return add(write_shape(out, file_level, xyz_of(ordered, channels), attributes(ordered), &uv));
}

FaceVaryingUV project_uv(const Hierarchy& h, const Shape& fine, const std::vector<std::uint32_t>* engine_vertex,
                         std::vector<std::string>& not_kept) {
  if (!fine.texture.empty())
    not_kept.push_back("the texture image '" + fine.texture.name + "' (a project keeps the UVs, not the image: give it to render --texture)");
  if (fine.uv.empty()) return {};
  std::string why;
  FaceVaryingUV base = coarsen_file_uv(h, fine.base.faces, fine.uv, engine_vertex ? std::span<const std::uint32_t>(*engine_vertex) : std::span<const std::uint32_t>(), &why);
  if (!base.empty()) return base;
  not_kept.push_back("texture coordinates (" + std::to_string(fine.uv.num_points()) + " UV points): " + why);
  return {};
}

nlohmann::json attribute_list_json(std::span<const VertexAttribute> attributes) {
  nlohmann::json j = nlohmann::json::array();
  for (const VertexAttribute& a : attributes) j.push_back({{"name", a.name}, {"type", a.type}});
  return j;
}


nlohmann::json complex_counts_json(const Complex& c) {
  return {{"dim", c.dim},
          {"vertices", c.num_vertices},
          {"edges", c.num_edges()},
          {"faces", c.num_faces()},
          {"cells", c.num_cells()}};
}

}  // namespace sublift::cli
