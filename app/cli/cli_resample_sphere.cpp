// sublift-cli resample-sphere MESH --levels J -o OUT [--base-out BASE] [--json]
#include <charconv>
#include <chrono>
#include <iostream>

#include "app/cli/cli_args.h"
#include "app/cli/cli_commands.h"
#include "app/cli/cli_hierarchy.h"
#include "app/cli/cli_json.h"
#include "core/base/errors.h"
#include "core/io/mesh/mesh_import.h"
#include "core/io/lattice/shape_io.h"
#include "core/analysis/mesh_stats.h"
#include "core/analysis/sphere_resample.h"

namespace sublift::cli {

namespace {

constexpr const char* kHelp =
    "usage: sublift-cli resample-sphere MESH --levels J -o OUT [--base-out BASE] [--json]\n"
    "  Samples MESH, a closed and roughly star-shaped surface (.obj/.off/.ply), onto the octahedron\n"
    "  split 1-to-4 J times (0..10), as paper 004 prepared its examples: a ray from MESH's centroid\n"
    "  towards every vertex of the geodesic sphere, the vertex placed at the farthest hit. The\n"
    "  centroid is the volume centroid of a closed mesh, else the area-weighted one; rays that\n"
    "  miss (holes, open meshes) take the mean radius of their neighbours. OUT (.obj/.off/.ply/\n"
    "  .vtk) is the finest mesh, vertices in the engine's order, so that 'analyze OUT --base BASE\n"
    "  --levels J' accepts it; BASE is the octahedron with its 6 sampled vertices (the first 6 of\n"
    "  OUT). --json reports counts, the centroid, missed and multiple-hit rays and the seconds\n"
    "  the resampling took (file reading and writing excluded). docs/resample_sphere.md.\n"
    "  A MESH that is not one closed genus-0 surface, or on which a ray hits more than once (not\n"
    "  star-shaped from its centroid), is refused: the sphere cannot represent it. The reasons are\n"
    "  printed (and in --json's 'problems'), nothing is written, and the exit code is 1; --force\n"
    "  writes the resampled mesh anyway (use 'rebuild' or a fit for such meshes).\n";

int sphere_levels_option(const Args& a) {
  const auto v = a.value("--levels");
  if (!v) throw UsageError("missing --levels J");
  int n = -1;
  auto [p, ec] = std::from_chars(v->data(), v->data() + v->size(), n);
  if (ec != std::errc() || p != v->data() + v->size() || n < 0)
    throw UsageError("--levels must be an integer in 0.." + std::to_string(kMaxSphereLevels) + ", got '" + *v + "'");
  if (n > kMaxSphereLevels)
    throw UsageError("--levels " + std::to_string(n) + " would make " + std::to_string(sphere_vertex_count(n)) +
                     " vertices; at most " + std::to_string(kMaxSphereLevels) + " (" +
                     std::to_string(sphere_vertex_count(kMaxSphereLevels)) + " vertices)");
  return n;
}

}  // namespace

int run_resample_sphere(int argc, char** argv) {
  const Args a = parse_args(argc, argv, 2, {"-o", "--levels", "--base-out"}, {"--json", "--help", "--force"});
  if (a.has("--help")) {
    std::cout << kHelp;
    return 0;
  }
  if (a.positional.size() != 1) throw UsageError("expected exactly one input MESH");
  const int levels = sphere_levels_option(a);
  const std::string out = output_option(a, 2);
  const auto base_out = a.value("--base-out");
  if (base_out)
    if (const std::string why = shape_output_problem(*base_out, 2); !why.empty()) throw UsageError("--base-out: " + why);
  const std::string& in = a.positional[0];

  const LoadedMesh loaded = import_surface_mesh(in);
  std::cerr << loaded.report.format(in);
  if (loaded.mesh.num_faces() == 0) throw InputError(in, 0, "has no faces to sample (expected a closed surface)");
  const auto start = std::chrono::steady_clock::now();
  SphereResample r;
  try {
    r = resample_sphere(loaded.mesh, levels);
  } catch (const TopologyError& e) {
    throw InputError(in, 0, e.what());
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  // What the sphere cannot represent: other topology, or a surface a ray crosses twice.
  std::vector<std::string> problems;
  const MeshStats stats = compute_mesh_stats(loaded.mesh);
  if (stats.components != 1) problems.push_back(std::to_string(stats.components) + " pieces, not one");
  if (stats.boundary_loops > 0) problems.push_back(std::to_string(stats.boundary_loops) + " boundary loop(s): not closed");
  if (stats.components == 1 && stats.boundary_loops == 0 && stats.euler_characteristic != 2)
    problems.push_back("genus " + std::to_string((2 - stats.euler_characteristic) / 2) + ", not 0 (Euler characteristic " +
                       std::to_string(stats.euler_characteristic) + ")");
  if (r.multiple_hits > 0)
    problems.push_back(std::to_string(r.multiple_hits) + " of " + std::to_string(r.rays) +
                       " rays hit the surface more than once (not star-shaped from the centroid)");
  const bool refused = !problems.empty() && !a.has("--force");
  for (const std::string& p : problems) std::cerr << in << ": " << (refused ? "error: " : "warning: ") << p << "\n";
  if (refused) std::cerr << in << ": nothing written; --force resamples it anyway\n";
  if (!refused) {
    for (const std::string& n : write_shape(out, r.fine, r.positions)) std::cerr << out << ": warning: " << n << "\n";
    if (base_out)
      for (const std::string& n : write_shape(*base_out, r.base, r.base_positions))
        std::cerr << *base_out << ": warning: " << n << "\n";
  }
  if (a.has("--json")) {
    const glm::dvec3& c = r.centroid.point;
    nlohmann::json j = {{"input", in},
                        {"output", out},
                        {"base", base_out ? nlohmann::json(*base_out) : nlohmann::json(nullptr)},
                        {"levels", levels},
                        {"vertices", r.fine.num_vertices},
                        {"faces", r.fine.num_faces()},
                        {"centroid", {c.x, c.y, c.z}},
                        {"centroid_kind", centroid_kind_name(r.centroid.kind)},
                        {"rays", r.rays},
                        {"missed", r.missed},
                        {"multiple_hits", r.multiple_hits},
                        {"fill_rounds", r.fill_rounds},
                        {"seconds", seconds},
                        {"problems", problems},
                        {"written", !refused},
                        {"warnings", report_json(loaded.report)}};
    std::cout << j.dump(2) << "\n";
  }
  return refused ? 1 : 0;
}

}  // namespace sublift::cli
