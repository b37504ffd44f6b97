// sublift-cli analyze FINE --base BASE --scheme S --levels N [--integer] -o PROJECT.sublift [--json]
#include <iostream>

#include "app/cli/cli_args.h"
#include "app/cli/cli_commands.h"
#include "app/cli/cli_hierarchy.h"
#include "app/cli/cli_json.h"
#include "core/complex/connectivity_match.h"
#include "core/base/errors.h"
#include "core/base/file_io.h"
#include "core/multires/hierarchy.h"
#include "core/multires/level_uv.h"
#include "core/io/project/project_io.h"
#include "core/io/lattice/shape_io.h"

namespace sublift::cli {

namespace {

constexpr const char* kHelp =
    "usage: sublift-cli analyze FINE --base BASE --scheme S --levels N [--integer] [--disc K]\n"
    "                           -o PROJECT.sublift [--json]\n"
    "  S: linear | cubic | sqrt2 | linear-tri | butterfly | loop (the last three on triangle meshes;\n"
    "  their wavelets are fitted over K-ring discs, K = 1, 2, 3, default 2: docs/triangle_wavelets.md).\n"
    "  Analyses FINE, a shape with the connectivity of BASE refined N times and its vertices in\n"
    "  the order 'subdivide' writes, into scaling and wavelet coefficients, and saves base,\n"
    "  features, scheme and every coefficient as a .sublift project (docs/file_formats.md).\n"
    "  FINE must have exactly the vertex count and the faces (edges for curves, faces and cells\n"
    "  for lattices) of the refined BASE, else it is refused with the first difference.\n"
    "  --integer: lossless integer transform (use with integer coordinates).\n"
    "  Without --base: 'rebuild FINE' (the levels and base found from FINE itself, any order).\n";

}  // namespace

int run_analyze(int argc, char** argv) {
  const Args a = parse_args(argc, argv, 2, {"-o", "--base", "--scheme", "--levels", "--disc"},
                            {"--json", "--help", "--integer"});
  if (a.has("--help")) {
    std::cout << kHelp;
    return 0;
  }
  if (a.positional.size() != 1) throw UsageError("expected exactly one FINE file");
  const auto base_path = a.value("--base");
  if (!base_path) return run_rebuild(argc, argv);  // no base: find it (docs/rebuild.md)
  const Scheme scheme = scheme_option(a);
  const int levels = levels_option(a, scheme);
  const std::string out = output_option(a, 0);
  if (file_extension(out) != "sublift") throw UsageError("the project OUT must have the extension .sublift");
  const std::string& fine_path = a.positional[0];

  Shape base = read_shape(*base_path);
  add_topology_warnings(base.report, base.base);
  std::cerr << base.report.format(*base_path);
  check_refined_size(base.base, levels, scheme);
  Shape fine = read_shape(fine_path);
  std::cerr << fine.report.format(fine_path);
  // FINE's colours and scalars are analysed as channels of their own beside x, y, z.
  const int channels = 3 + static_cast<int>(fine.attributes.size());
  Hierarchy h = make_hierarchy(std::move(base.base), levels, scheme, channels, a.has("--integer"), 0, disc_option(a, scheme));
  if (const std::string why = connectivity_mismatch(h.levels.back(), fine.base); !why.empty())
    throw InputError(fine_path, 0, "is not " + *base_path + " refined " + std::to_string(levels) + " times: " + why);
  analyze(h, with_attributes(fine.positions, fine.attributes));
  ProjectExtras extras;
  extras.attributes = attribute_names(fine.attributes);
  // UVs: BASE's when it has them (FINE's are then not needed), else FINE's coarsened.
  std::vector<std::string> not_kept;
  if (!base.uv.empty() && !uv_refinement_problem(scheme).empty()) {
    not_kept.push_back("texture coordinates: " + uv_refinement_problem(scheme));
  } else if (!base.uv.empty()) {
    extras.uv = base.uv;
    if (!fine.uv.empty() || !fine.texture.empty()) not_kept.push_back("FINE's texture coordinates and texture (BASE's UVs are used)");
  } else {
    extras.uv = project_uv(h, fine, nullptr, not_kept);
  }
  for (const std::string& s : not_kept) std::cerr << fine_path << ": warning: not kept in the project: " << s << "\n";
  write_project(out, h, extras);
  if (a.has("--json")) {
    nlohmann::json stats = nlohmann::json::array();
    for (const LevelStats& s : level_stats(h))
      stats.push_back({{"level", s.level}, {"wavelet_max", s.wavelet_max}, {"wavelet_rms", s.wavelet_rms}});
    nlohmann::json j = {{"input", fine_path},   {"base", *base_path},     {"output", out},
                        {"scheme", scheme_name(scheme)}, {"integer", a.has("--integer")}, {"levels", levels},
                        {"disc", h.disc},
                        {"vertices", h.num_vertices(levels)}, {"per_level", stats},
                        {"attributes", attribute_list_json(extras.attributes)},
                        {"uv_points", extras.uv.num_points()}, {"not_kept", not_kept},
                        {"warnings", report_json(fine.report)}, {"base_warnings", report_json(base.report)}};
    std::cout << j.dump(2) << "\n";
  }
  return 0;
}

}  // namespace sublift::cli
