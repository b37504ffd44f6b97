// sublift-cli info FILE [--json]
#include <iostream>
#include <map>

#include <nlohmann/json.hpp>

#include "app/cli/cli_args.h"
#include "app/cli/cli_commands.h"
#include "app/cli/cli_json.h"
#include "core/base/errors.h"
#include "core/base/file_io.h"
#include "core/io/mesh/mesh_export.h"
#include "core/io/mesh/mesh_import.h"
#include "core/analysis/mesh_stats.h"

namespace sublift::cli {

namespace {

constexpr const char* kHelp =
    "usage: sublift-cli info FILE [--json]\n"
    "  Meshes (.obj/.off/.ply): vertex/edge/face counts, polylines, the face-size and valence\n"
    "  histograms, boundary loops, non-manifold edges and vertices, misoriented edges,\n"
    "  components, Euler characteristic, tags and the bounding box.\n"
    "  Lattices (.lattice/.ovm/.vtk): counts of vertices, edges, faces, cells, faces per cell,\n"
    "  feature dimensionalities and the bounding box.\n"
    "  Projects (.sublift): scheme, integer flag, channels, dimension, base counts, 'levels' and\n"
    "  'per_level' (level, vertices, wavelets, wavelet_max, wavelet_rms: Euclidean norms).\n"
    "  Repairs made on import are listed as warnings on stderr (and under \"warnings\").\n";

std::string histogram(const std::map<std::size_t, std::size_t>& h) {
  std::string s;
  for (auto [k, n] : h) s += (s.empty() ? "" : ", ") + std::to_string(k) + ": " + std::to_string(n);
  return s;
}

std::string point(const glm::dvec3& p) {
  return format_double(p.x) + " " + format_double(p.y) + " " + format_double(p.z);
}

}  // namespace

int run_info(int argc, char** argv) {
  const Args a = parse_args(argc, argv, 2, {}, {"--json", "--help"});
  if (a.has("--help")) {
    std::cout << kHelp;
    return 0;
  }
  if (a.positional.size() != 1) throw UsageError("expected exactly one FILE");
  const std::string& file = a.positional[0];
  const std::string ext = file_extension(file);
  if (ext == "sublift") return info_project(file, a.has("--json"));
  if (ext == "lattice" || ext == "ovm" || ext == "vtk" || ext == "gltf" || ext == "glb") return info_shape(file, a.has("--json"));
  // Everything info reads, so an unknown extension is answered with the whole list.
  if (ext != "obj" && ext != "off" && ext != "ply")
    throw InputError(file, 0, "unsupported format '." + ext + "' (info reads .obj, .off, .ply, .gltf, .glb, .lattice, .ovm, .vtk and .sublift)");
  const LoadedMesh loaded = import_surface_mesh(file);
  std::cerr << loaded.report.format(file);
  const MeshStats s = compute_mesh_stats(loaded.mesh);
  std::map<std::string, std::size_t> tags;
  for (const MeshTag& t : loaded.mesh.tags) ++tags[t.name];

  if (a.has("--json")) {
    nlohmann::json j = mesh_stats_json(s);
    j["file"] = file;
    j["tags"] = tags;
    j["uv_points"] = loaded.mesh.uv.num_points();
    j["warnings"] = report_json(loaded.report);
    std::cout << j.dump(2) << "\n";
    return 0;
  }
  std::cout << "file:                  " << file << "\n"
            << "vertices:              " << s.vertices << " (" << s.used_vertices << " used, "
            << s.isolated_vertices << " isolated)\n"
            << "edges:                 " << s.edges << "\n"
            << "faces:                 " << s.faces << "\n";
  if (s.polylines)
    std::cout << "polylines:             " << s.polylines << " (" << s.closed_polylines << " closed, "
              << s.polyline_segments << " segments)\n";
  std::cout
            << "face sizes:            " << histogram(s.face_sizes) << "\n"
            << "valences:              " << histogram(s.valences) << "\n"
            << "boundary:              " << s.boundary_edges << " edges in " << s.boundary_loops
            << " loop(s)\n"
            << "non-manifold:          " << s.non_manifold_edges << " edges, "
            << s.non_manifold_vertices << " vertices\n"
            << "misoriented edges:     " << s.misoriented_edges << "\n"
            << "components:            " << s.components << "\n"
            << "Euler characteristic:  " << s.euler_characteristic << "\n";
  if (auto g = genus(s)) std::cout << "genus:                 " << *g << "\n";
  if (!loaded.mesh.uv.empty()) std::cout << "texture coordinates:   " << loaded.mesh.uv.num_points() << " UV points\n";
  std::cout << "bounding box:          [" << point(s.bbox_min) << "] .. [" << point(s.bbox_max) << "]\n";
  if (!tags.empty()) {
    std::cout << "tags:                  ";
    bool first = true;
    for (auto& [name, n] : tags) std::cout << (first ? "" : ", ") << name << " x" << n, first = false;
    std::cout << "\n";
  }
  return 0;
}

}  // namespace sublift::cli
