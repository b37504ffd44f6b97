// sublift-cli fit MESH [--scheme S] [--base-faces N | --base-vertices N] [--levels J | --tolerance E]
//                 [--feature-angle DEG] -o OUT [--json]
// A coarse base and fitted levels for any triangle mesh (issue 17, docs/fit.md).
#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>

#include "app/cli/cli_args.h"
#include "app/cli/cli_commands.h"
#include "app/cli/cli_hierarchy.h"
#include "app/cli/cli_json.h"
#include "core/base/errors.h"
#include "core/base/file_io.h"
#include "core/base/text_lines.h"
#include "core/fit/fit_levels.h"
#include "core/io/lattice/shape_io.h"
#include "core/io/mesh/mesh_import.h"
#include "core/io/project/project_io.h"

namespace sublift::cli {

namespace {

constexpr const char* kHelp =
    "usage: sublift-cli fit MESH [--scheme S] [--base-faces N | --base-vertices N]\n"
    "                       [--levels J | --tolerance E] [--feature-angle DEG] -o OUT.sublift|OUT.obj [--json]\n"
    "  Fits any triangle mesh (docs/fit.md) with scheme S (default sqrt2, which fits the shared\n"
    "  scans best): a coarse base from OpenMesh's decimater (N faces or\n"
    "  vertices, default 1/64 of the mesh's vertices; genus, boundaries, and edges sharper than DEG,\n"
    "  default 60, kept as creases and corners), then levels fitted to the mesh coarse to fine both\n"
    "  ways and analysed, so the mesh's detail becomes wavelets. Levels: J, or the first whose net\n"
    "  lies within E of the mesh both ways (E a fraction of the bounding-box diagonal, or a\n"
    "  percentage like 0.5%), or by default those that bring the finest level to about the mesh's\n"
    "  vertex count. OUT: a project, or the finest fitted net. --json reports the base, the\n"
    "  topology before and after, per level the distances both ways (fractions of the diagonal),\n"
    "  folded faces and time, the same for the finest level's limit surface, and the stage times.\n";


}  // namespace

int run_fit(int argc, char** argv) {
  const Args a = parse_args(argc, argv, 2, {"-o", "--scheme", "--base-vertices", "--base-faces", "--levels", "--tolerance", "--feature-angle"},
                            {"--json", "--help"});
  if (a.has("--help")) {
    std::cout << kHelp;
    return 0;
  }
  if (a.positional.size() != 1) throw UsageError("expected exactly one MESH");
  const auto o = a.value("-o");
  const bool project = o && file_extension(*o) == "sublift";
  const std::string out = output_option(a, project ? 0 : 2);
  FitOptions fo;
  fo.scheme = a.value("--scheme") ? scheme_option(a) : kDefaultFitScheme;
  if (a.value("--levels") && a.value("--tolerance")) throw UsageError("give --levels or --tolerance, not both");
  if (a.value("--base-vertices") && a.value("--base-faces")) throw UsageError("give --base-faces or --base-vertices, not both");
  const int most_levels = 6 * scheme_levels_per_split(fo.scheme);  // six 1-to-4 splits
  fo.levels = static_cast<int>(integer_option(a, "--levels", 3, 0, most_levels));
  if (const auto t = a.value("--tolerance")) {
    const bool percent = !t->empty() && t->back() == '%';
    const auto d = parse_double(percent ? t->substr(0, t->size() - 1) : *t);
    if (!d || *d <= 0 || (percent ? *d / 100 : *d) >= 1)
      throw UsageError("--tolerance must be a fraction of the diagonal in (0, 1) or a percentage, got '" + *t + "'");
    fo.tolerance = percent ? *d / 100 : *d;
    fo.levels = most_levels;  // fit_levels also stops at four times the mesh's vertices
  }
  BaseMeshOptions bo;
  bo.quads = fit_base_quads(fo.scheme);
  bo.target_vertices = static_cast<std::uint32_t>(integer_option(a, "--base-vertices", 0, 4, 10000000));
  bo.target_faces = static_cast<std::uint32_t>(integer_option(a, "--base-faces", 0, 4, 20000000));
  if (const auto v = a.value("--feature-angle")) {
    const auto d = parse_double(*v);
    if (!d || *d <= 0 || *d >= 180) throw UsageError("--feature-angle must be in (0, 180) degrees, got '" + *v + "'");
    bo.feature_angle_deg = *d;
  }
  const std::string& in = a.positional[0];
  LoadedMesh lm = import_surface_mesh(in);
  lm.report.note_attributes_not_kept(lm.mesh.attributes);
  add_topology_warnings(lm.report, lm.mesh);
  std::cerr << lm.report.format(in);
  if (const std::string s = lm.report.not_kept_summary(); !s.empty())
    std::cerr << in << ": warning: not kept by the fit: " << s << "\n";
  if (!lm.mesh.tags.empty())
    std::cerr << in << ": warning: not kept by the fit: " << lm.mesh.tags.size() << " tags (its features come from --feature-angle)\n";
  std::vector<double> xyz;
  for (const auto& p : lm.mesh.positions) xyz.insert(xyz.end(), {p.x, p.y, p.z});
  Csr faces;
  faces.offsets = lm.mesh.face_offsets;
  faces.items = lm.mesh.face_indices;
  const auto n = static_cast<std::uint32_t>(lm.mesh.num_vertices());
  const auto t0 = std::chrono::steady_clock::now();
  // By default, the levels that bring the finest level to about the mesh's vertex count.
  if (!a.value("--levels") && !a.value("--tolerance")) fo.levels = -1;
  MeshFit fitted;
  try {
    fitted = fit_mesh(n, faces, xyz, bo, fo);
  } catch (const TopologyError& e) {
    throw InputError(in, 0, e.what());
  }
  const BaseMesh& base = fitted.base;
  const Fitted& f = fitted.fitted;
  const double base_ms = fitted.base_ms;
  const double fit_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  const double back = f.levels.empty() ? f.limit_back_max : f.levels.back().back_max;
  if (project) {
    ProjectExtras extras;  // the base-to-mesh map, for comparing and fitting again
    extras.fit_source = {std::filesystem::absolute(in).lexically_normal().string(), n, base.input_vertex};
    write_project(out, f.hierarchy, extras);
  } else {
    for (const std::string& note : write_shape(out, f.hierarchy.levels.back(), f.finest)) std::cerr << out << ": warning: " << note << "\n";
  }
  nlohmann::json stages = {{"base", base_ms}};
  for (const auto& [name, ms] : f.stage_ms) stages[name] = ms;
  std::size_t quads = 0;
  for (std::size_t q = 0; q < base.faces.rows(); ++q) quads += base.faces.size(q) == 4;
  if (a.has("--json")) {
    nlohmann::json levels = nlohmann::json::array();
    for (const FitLevelReport& r : f.levels)
      levels.push_back({{"level", r.level},
                        {"vertices", r.vertices},
                        {"net_to_input_rms", r.rms},
                        {"net_to_input_max", r.max},
                        {"input_to_net_rms", r.back_rms},
                        {"input_to_net_max", r.back_max},
                        {"folded_faces", r.folded},
                        {"ms", r.ms}});
    const nlohmann::json j = {{"input", in},
                              {"output", out},
                              {"scheme", scheme_name(fo.scheme)},
                              {"base", {{"vertices", base.num_vertices}, {"faces", base.faces.rows()}, {"quads", quads}, {"creases", base.tags.crease_edges.size()},
                                        {"input_vertex", base.input_vertex}}},  // the mesh vertex each base vertex is
                              {"euler", {{"input", base.euler_before}, {"base", base.euler_after}}},
                              {"boundary_loops", {{"input", base.boundary_loops_before}, {"base", base.boundary_loops_after}}},
                              {"levels", levels},
                              {"input_to_fit_max", back},
                              {"tolerance", fo.tolerance > 0 ? nlohmann::json(fo.tolerance) : nlohmann::json()},
                              {"reached_tolerance", f.reached_tolerance},
                              {"limit", {{"to_input_rms", f.limit_rms},
                                         {"to_input_max", f.limit_max},
                                         {"input_to_limit_rms", f.limit_back_rms},
                                         {"input_to_limit_max", f.limit_back_max},
                                         {"folded_faces", f.limit_folded}}},
                              {"feature_lines", {{"input", f.feature_lines}, {"max_distance", f.feature_lines ? nlohmann::json(f.feature_max) : nlohmann::json()}}},
                              {"ms", fit_ms},
                              {"stage_ms", stages},
                              {"warnings", report_json(lm.report)}};
    std::cout << j.dump(2) << "\n";
  } else {
    std::cout << in << ": base of " << base.num_vertices << " vertices and " << base.faces.rows() << " faces (" << quads
              << " quads; Euler characteristic " << base.euler_after << ", as the mesh's " << base.euler_before << "), "
              << f.levels.size() << " " << scheme_name(fo.scheme) << " levels fitted\n";
    if (fo.tolerance > 0 && !f.reached_tolerance)
      std::cout << "  the tolerance " << 100 * fo.tolerance << " % was not reached (the finest level tried is reported below)\n";
    for (const FitLevelReport& r : f.levels)
      std::cout << "  level " << r.level << ": " << r.vertices << " vertices; net to mesh " << 100 * r.rms << " % rms, " << 100 * r.max
                << " % max; mesh to net " << 100 * r.back_rms << " % rms, " << 100 * r.back_max << " % max; " << r.folded
                << " folded faces; " << std::lround(r.ms) << " ms\n";
    std::cout << "  limit surface: to mesh " << 100 * f.limit_rms << " % rms, " << 100 * f.limit_max << " % max; mesh to it "
              << 100 * f.limit_back_rms << " % rms, " << 100 * f.limit_back_max << " % max (of the bounding-box diagonal); "
              << f.limit_folded << " folded faces\n";
    if (f.feature_lines)
      std::cout << "  feature lines: " << f.feature_lines << " in the mesh, within " << 100 * f.feature_max
                << " % of the fitted creases and boundaries\n";
    std::cout << "wrote " << out << "\n";
  }
  return 0;
}

}  // namespace sublift::cli
