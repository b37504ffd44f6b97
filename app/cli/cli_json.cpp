#include "app/cli/cli_json.h"

namespace sublift::cli {

std::optional<long long> genus(const MeshStats& s) {
  if (s.faces == 0 || s.non_manifold_edges || s.non_manifold_vertices || s.misoriented_edges) return std::nullopt;
  const long long twice = 2 * static_cast<long long>(s.components) - s.euler_characteristic -
                          static_cast<long long>(s.boundary_loops);
  if (twice < 0 || twice % 2) return std::nullopt;
  return twice / 2;
}

static nlohmann::json histogram_json(const std::map<std::size_t, std::size_t>& h) {
  nlohmann::json j = nlohmann::json::object();
  for (auto [k, n] : h) j[std::to_string(k)] = n;
  return j;
}

nlohmann::json mesh_stats_json(const MeshStats& s) {
  nlohmann::json j;
  j["vertices"] = s.vertices;
  j["edges"] = s.edges;
  j["faces"] = s.faces;
  j["used_vertices"] = s.used_vertices;
  j["isolated_vertices"] = s.isolated_vertices;
  j["polylines"] = s.polylines;
  j["closed_polylines"] = s.closed_polylines;
  j["polyline_segments"] = s.polyline_segments;
  j["face_sizes"] = histogram_json(s.face_sizes);
  j["valences"] = histogram_json(s.valences);
  j["boundary_edges"] = s.boundary_edges;
  j["boundary_loops"] = s.boundary_loops;
  j["non_manifold_edges"] = s.non_manifold_edges;
  j["non_manifold_vertices"] = s.non_manifold_vertices;
  j["misoriented_edges"] = s.misoriented_edges;
  j["components"] = s.components;
  j["euler_characteristic"] = s.euler_characteristic;
  if (auto g = genus(s)) j["genus"] = *g;
  else j["genus"] = nullptr;
  j["bbox"] = {{"min", {s.bbox_min.x, s.bbox_min.y, s.bbox_min.z}},
               {"max", {s.bbox_max.x, s.bbox_max.y, s.bbox_max.z}}};
  return j;
}

nlohmann::json report_json(const ImportReport& r) {
  nlohmann::json j = nlohmann::json::array();
  for (const ImportWarning& w : r.warnings)
    j.push_back({{"what", w.what}, {"count", w.count}, {"first_lines", w.first_lines}});
  return j;
}

}  // namespace sublift::cli
