// sublift-cli rebuild FINE [--scheme auto|S] [--levels N|max] [--integer] [--disc K] -o OUT.sublift [--json]
// (also `analyze FINE` without --base): the levels of a mesh another tool subdivided.
#include <chrono>
#include <iostream>

#include "app/cli/cli_args.h"
#include "app/cli/cli_commands.h"
#include "app/cli/cli_hierarchy.h"
#include "app/cli/cli_json.h"
#include "core/complex/feature_tags.h"
#include "core/base/errors.h"
#include "core/base/file_io.h"
#include "core/complex/complex_build.h"
#include "core/io/lattice/shape_io.h"
#include "core/io/project/project_io.h"
#include "core/multires/rebuild.h"

namespace sublift::cli {

namespace {

constexpr const char* kHelp =
    "usage: sublift-cli rebuild FINE [--scheme auto|linear|cubic|sqrt2|linear-tri|butterfly|loop]\n"
    "                           [--levels N|max] [--integer] [--disc K] -o PROJECT.sublift [--json]\n"
    "  Finds the levels of a mesh that another tool subdivided (Blender, ZBrush, OpenSubdiv...),\n"
    "  in any vertex and face order: the base mesh and every level between (docs/rebuild.md).\n"
    "  Then analyses the mesh's own positions into wavelets, so the finest level is the file\n"
    "  exactly and every coarser level an exact coarse approximation, ready for coarse edits.\n"
    "  --scheme auto (default): cubic for quad meshes, loop for triangle meshes (sqrt2 only when\n"
    "  asked: one level per sqrt(2) step). Volume lattices: the 1-to-8 split of simple cells. --levels max\n"
    "  (default): as many as every piece of the mesh holds; N: exactly N or an error saying\n"
    "  where the mesh stops. The project remembers the file's vertex and face order: synthesize,\n"
    "  edit and compress write the finest level in that order. 'analyze FINE' without --base\n"
    "  does the same.\n";

}  // namespace

namespace {

// Faces, edges and vertices of a lattice whose feature dim is below what its topology gives
// (tags), which rebuild does not carry.
std::size_t lattice_feature_count(const Complex& c) {
  std::size_t n = 0;
  for (std::uint32_t f = 0; f < c.num_faces(); ++f) n += c.face_dim[f] < untagged_face_dim(c, f);
  for (std::uint32_t e = 0; e < c.num_edges(); ++e) n += c.edge_dim[e] < untagged_edge_dim(c, e);
  for (std::uint32_t v = 0; v < c.num_vertices; ++v) n += c.vertex_dim[v] < untagged_vertex_dim(c, v);
  return n;
}

}  // namespace

int run_rebuild(int argc, char** argv) {
  const Args a = parse_args(argc, argv, 2, {"-o", "--scheme", "--levels", "--disc", "--base"}, {"--json", "--help", "--integer"});
  if (a.has("--help")) {
    std::cout << kHelp;
    return 0;
  }
  if (a.positional.size() != 1) throw UsageError("expected exactly one FINE file");
  if (a.value("--base")) throw UsageError("rebuild finds the base itself; use 'analyze FINE --base BASE' to give one");
  const std::string out = output_option(a, 0);
  if (file_extension(out) != "sublift") throw UsageError("the project OUT must have the extension .sublift");
  const std::string& fine_path = a.positional[0];

  const auto t0 = std::chrono::steady_clock::now();
  Shape fine = read_shape(fine_path);
  if (fine.base.dim == 3) fine.report.note_attributes_not_kept(fine.attributes);  // lattices: positions only
  add_topology_warnings(fine.report, fine.base);
  std::cerr << fine.report.format(fine_path);
  if (fine.base.dim == 1) throw UsageError("rebuild takes surface meshes and volume lattices; " + fine_path + " is a curve");
  const bool lattice = fine.base.dim == 3;
  const bool automatic = !a.value("--scheme") || *a.value("--scheme") == "auto";
  const Scheme scheme = automatic ? rebuild_auto_scheme(fine.base.faces) : scheme_option(a);
  int levels = -1;
  if (const auto v = a.value("--levels"); v && *v != "max") levels = levels_option(a, scheme);
  const int disc = disc_option(a, scheme);
  const bool integer = a.has("--integer");
  const double read_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();

  Rebuilt r = lattice ? rebuild_volume_hierarchy(fine.base, fine.positions, scheme, levels, integer)
                      : rebuild_hierarchy(fine.base.num_vertices, fine.base.faces, fine.positions, scheme, levels, integer, disc,
                                          derive_feature_tags(fine.base), {}, fine.attributes);
  for (const std::string& why : r.features.dropped) std::cerr << fine_path << ": warning: feature tag dropped: " << why << "\n";
  // What the project does not keep, so synthesize cannot write back.
  std::vector<std::string> not_kept;
  if (const std::string s = fine.report.not_kept_summary(); !s.empty()) not_kept.push_back(s);
  if (lattice)
    if (const std::size_t n = lattice_feature_count(fine.base); n > 0)
      not_kept.push_back(std::to_string(n) + " lattice feature tags (faces, edges or vertices marked as features)");
  ProjectExtras extras;
  if (!lattice) extras.uv = project_uv(r.hierarchy, fine, &r.engine_vertex, not_kept);
  for (const std::string& s : not_kept) std::cerr << fine_path << ": warning: not kept in the project (nor written back): " << s << "\n";
  const DetectedLevels& d = r.detected;
  extras.input_order.level = d.levels;
  if (!lattice) extras.attributes = attribute_names(fine.attributes);  // channels 3.. of the project
  extras.input_order.engine_vertex = std::move(r.engine_vertex);
  if (!lattice) extras.input_order.faces = fine.base.faces;
  write_project(out, r.hierarchy, extras);
  const Hierarchy& h = r.hierarchy;

  const char* split = d.split == SplitKind::Quads       ? "quad split"
                      : d.split == SplitKind::Triangles ? "triangle split"
                      : d.split == SplitKind::Sqrt2     ? "sqrt(2) step"
                                                        : "1-to-8 lattice split";
  if (a.has("--json")) {
    nlohmann::json per_level = nlohmann::json::array(), components = nlohmann::json::array();
    const std::vector<LevelStats> stats = level_stats(h);
    for (int l = 0; l <= h.finest_level(); ++l) {
      nlohmann::json row = {{"level", l}, {"vertices", h.num_vertices(l)}, {"faces", h.levels[static_cast<std::size_t>(l)].num_faces()}};
      if (l < h.finest_level()) {
        row["wavelet_max"] = stats[static_cast<std::size_t>(l)].wavelet_max;
        row["wavelet_rms"] = stats[static_cast<std::size_t>(l)].wavelet_rms;
      }
      per_level.push_back(row);
    }
    for (const ComponentLevels& c : d.components)
      components.push_back({{"first_vertex", c.first_vertex}, {"vertices", c.vertices}, {"faces", c.faces}, {"levels", c.levels}, {"stop", c.stop}});
    nlohmann::json j = {{"input", fine_path},
                        {"output", out},
                        {"scheme", scheme_name(scheme)},
                        {"attributes", attribute_list_json(extras.attributes)},
                        {"uv_points", extras.uv.num_points()},
                        {"scheme_picked", automatic},
                        {"split", split},
                        {"integer", integer},
                        {"levels", d.levels},
                        {"per_level", per_level},
                        {"components", components},
                        {"stop", d.stop},
                        {"not_kept", not_kept},
                        {"features", {{"creases", r.features.creases},
                                      {"corners", r.features.corners},
                                      {"base_creases", r.features.base.crease_edges.size()},
                                      {"base_corners", r.features.base.corner_vertices.size()},
                                      {"dropped", r.features.dropped}}},
                        {"time_ms", {{"read", read_ms}, {"detect", r.detect_ms}, {"build", r.build_ms}, {"analyse", r.analysis_ms}}},
                        {"warnings", report_json(fine.report)}};
    if (d.stop_vertex != UINT32_MAX) j["stop_vertex"] = d.stop_vertex;
    std::cout << j.dump(2) << "\n";
  } else {
    std::cout << fine_path << ": " << d.levels << " level" << (d.levels == 1 ? "" : "s") << " of a " << split << " rebuilt, "
              << scheme_name(scheme) << " scheme" << (automatic ? " (picked for its " + std::string(d.split == SplitKind::Triangles ? "triangles" : d.split == SplitKind::Hexes ? "hexahedra" : "quads") + ")" : "")
              << "; base " << h.num_vertices(0) << " vertices, " << h.levels[0].num_faces() << " faces\n";
    if (!d.stop.empty()) std::cout << "no more levels: " << d.stop << "\n";
    if (d.components.size() > 1)
      for (const ComponentLevels& c : d.components)
        std::cout << "  piece with vertex " << c.first_vertex << ": " << c.vertices << " vertices, " << c.levels << " level"
                  << (c.levels == 1 ? "" : "s") << " alone\n";
    std::cout << "wrote " << out << "\n";
  }
  return 0;
}

}  // namespace sublift::cli
