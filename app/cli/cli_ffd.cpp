// sublift-cli ffd (--lattice L | --box NX NY NZ [--margin M]) --model M [--edits EDITS] [--scheme S]
//               [--extra-levels N] [--outside stay|nearest] [--lattice-out FILE] -o OUT [--json]
#include <chrono>
#include <iostream>

#include <nlohmann/json.hpp>

#include "app/cli/cli_args.h"
#include "app/cli/cli_commands.h"
#include "app/cli/cli_json.h"
#include "core/base/errors.h"
#include "core/ffd/ffd_edits.h"
#include "core/ffd/ffd_scene.h"
#include "core/io/lattice/shape_io.h"
#include "core/base/text_lines.h"

namespace sublift::cli {
namespace {

constexpr const char* kHelp =
    "usage: sublift-cli ffd (--lattice L | --box NX NY NZ [--margin M]) --model M [--edits EDITS]\n"
    "                  [--scheme linear|cubic] [--extra-levels N] [--outside stay|nearest]\n"
    "                  [--lattice-out FILE] -o OUT [--json]\n"
    "  Free-form deformation: binds the model's vertices into the finest level of the lattice's\n"
    "  wavelet hierarchy, applies the edits to the lattice as the modeler's drags do (any level;\n"
    "  coarse edits keep finer detail) and moves every bound vertex to the same parametric\n"
    "  coordinates in the deformed finest lattice.\n"
    "  --lattice L     a volume lattice (.lattice, .ovm or .vtk) of any polyhedral cells and features\n"
    "  --box NX NY NZ  instead: NX x NY x NZ hexahedra around the model, --margin M times its\n"
    "                  bounding-box diagonal on every side (default 0.05)\n"
    "  --model M       .gltf/.glb (nodes, materials, UVs, skins kept), .obj/.ply/.off\n"
    "  --edits EDITS   a text file of 'level index dx dy dz' lines: move control point `index`\n"
    "                  (the engine's order of that level; level 0 = the lattice file's vertex\n"
    "                  order) by (dx, dy, dz); applied in order; blank lines and # comments\n"
    "                  allowed; an empty file (or no --edits) means no edit\n"
    "  --scheme S      lattice wavelets, cubic (default) or linear\n"
    "  --extra-levels N  lattice levels above the file's, 0..6 (default 2): a smoother map\n"
    "  --outside stay|nearest  vertices outside the lattice stay put (default) or follow the\n"
    "                  nearest cell\n"
    "  --lattice-out FILE  also writes the deformed finest lattice (.lattice, .ovm or .vtk)\n"
    "  OUT             the deformed model in the model's format (.gltf and .glb interchangeable):\n"
    "                  positions and normals new, everything else as it was\n"
    "  --json          prints vertices, bound, outside, nearest, lattice sizes, edits and the\n"
    "                  times of binding, the edits (lattice resynthesis) and the deformation\n";

double ms_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
}

int positive_int(const std::string& s, const char* what) {
  const auto v = parse_int(s);
  if (!v || *v < 1 || *v > 1000) throw UsageError(std::string(what) + " must be an integer 1..1000, got '" + s + "'");
  return static_cast<int>(*v);
}

}  // namespace

int run_ffd(int argc, char** argv) {
  const Args a = parse_args(argc, argv, 2,
                            {"-o", "--lattice", "--model", "--edits", "--scheme", "--extra-levels", "--outside",
                             "--margin", "--lattice-out"},
                            {"--json", "--help"}, {{"--box", 3}});
  if (a.has("--help")) {
    std::cout << kHelp;
    return 0;
  }
  if (!a.positional.empty()) throw UsageError("unexpected argument '" + a.positional[0] + "' (see --help)");
  const auto box = a.lists.find("--box");
  const bool has_box = box != a.lists.end();
  if (has_box == a.value("--lattice").has_value()) throw UsageError("give exactly one of --lattice L and --box NX NY NZ");
  if (has_box && box->second.size() != 3) throw UsageError("--box is given once, with three cell counts");
  if (!has_box && a.value("--margin")) throw UsageError("--margin goes with --box");
  if (!a.value("--model")) throw UsageError("missing --model M");
  if (!a.value("-o")) throw UsageError("missing -o OUT");
  FfdSceneOptions options;
  if (const auto s = a.value("--scheme")) {
    const std::string name = to_lower(*s);
    if (name != "linear" && name != "cubic")  // sqrt2 refines surfaces; FFD lattices are volumes
      throw UsageError("--scheme must be linear or cubic (FFD lattices are volumes), got '" + *s + "'");
    options.scheme = parse_scheme(name);
  }
  if (const auto e = a.value("--extra-levels")) {
    const auto v = parse_int(*e);
    if (!v || *v < 0 || *v > 6) throw UsageError("--extra-levels must be 0..6, got '" + *e + "'");
    options.extra_levels = static_cast<int>(*v);
  }
  if (const auto o = a.value("--outside")) {
    if (*o != "stay" && *o != "nearest") throw UsageError("--outside must be stay or nearest, got '" + *o + "'");
    options.outside = *o == "stay" ? Outside::Stay : Outside::Nearest;
  }
  double margin = 0.05;
  if (const auto m = a.value("--margin")) {
    const auto v = parse_double(*m);
    if (!v || *v < 0.0 || *v > 10.0) throw UsageError("--margin must be a number 0..10, got '" + *m + "'");
    margin = *v;
  }
  const std::string model_path = *a.value("--model"), out = *a.value("-o");
  if (!model_format_supported(model_path)) throw UsageError("--model must be .gltf, .glb, .obj, .ply or .off: " + model_path);
  if (!model_format_supported(out)) throw UsageError("OUT must be .gltf, .glb, .obj, .ply or .off: " + out);
  if (const auto lo = a.value("--lattice-out")) {
    const std::string problem = shape_output_problem(*lo, 3);
    if (!problem.empty()) throw UsageError("--lattice-out: " + problem);
  }
  std::vector<FfdEdit> edits;
  if (const auto e = a.value("--edits")) edits = read_ffd_edits(*e);

  Model model = import_model(model_path);
  ImportReport topology;  // of a mesh model (glTF triangles split at seams say nothing of the surface)
  if (model.format == ModelFormat::Obj || model.format == ModelFormat::Ply || model.format == ModelFormat::Off) {
    SurfaceMesh m;
    m.positions.assign(model.num_vertices(), glm::dvec3(0.0));
    m.face_offsets = model.faces.offsets;
    m.face_indices = model.faces.items;
    add_topology_warnings(topology, m);
    std::cerr << topology.format(model_path);
  }
  const Shape lattice = has_box ? box_lattice_around(model, positive_int(box->second[0], "--box NX"),
                                                     positive_int(box->second[1], "--box NY"),
                                                     positive_int(box->second[2], "--box NZ"), margin)
                                : read_ffd_lattice(*a.value("--lattice"));
  FfdScene scene = make_ffd_scene(std::move(model), lattice, options);
  if (const auto e = a.value("--edits")) check_ffd_edits(edits, scene.lattice->hierarchy(), *e);

  double edit_ms = 0.0, deform_ms = 0.0;
  std::vector<std::uint8_t> moved(scene.model.num_vertices(), 0);
  for (const FfdEdit& e : edits) {
    auto t = std::chrono::steady_clock::now();
    const std::uint32_t v[1] = {e.index};
    scene.lattice->move(e.level, v, {}, e.delta);
    edit_ms += ms_since(t);
    t = std::chrono::steady_clock::now();
    for (const std::uint32_t m : update_deformation(scene)) moved[m] = 1;
    deform_ms += ms_since(t);
  }
  export_model(scene.model, scene.deformed, out);
  const int J = scene.finest();
  if (const auto lo = a.value("--lattice-out")) {
    for (const std::string& n : write_shape(*lo, scene.lattice->hierarchy().levels[static_cast<std::size_t>(J)],
                                            scene.lattice->positions(J))) {
      std::cerr << *lo << ": warning: " << n << "\n";
    }
  }
  for (const std::string& n : scene.model.notes) std::cerr << model_path << ": note: " << n << "\n";
  if (a.has("--json")) {
    std::size_t moved_count = 0;
    for (const std::uint8_t m : moved) moved_count += m;
    const FfdReport& r = scene.binding.report;
    const nlohmann::json j = {{"model", model_path},
                              {"lattice", has_box ? std::string("box") : *a.value("--lattice")},
                              {"output", out},
                              {"scheme", scheme_name(options.scheme)},
                              {"lattice_levels", J},
                              {"lattice_vertices", scene.lattice->num_vertices(0)},
                              {"finest_lattice_vertices", scene.lattice->num_vertices(J)},
                              {"finest_lattice_cells", scene.lattice->hierarchy().levels.back().num_cells()},
                              {"vertices", scene.model.num_vertices()},
                              {"bound", r.bound},
                              {"outside", r.outside},
                              {"nearest", r.nearest},
                              {"edits", edits.size()},
                              {"moved", moved_count},
                              {"bind_ms", r.ms},
                              {"edit_ms", edit_ms},
                              {"deform_ms", deform_ms},
                              {"warnings", report_json(topology)},
                              {"notes", scene.model.notes}};
    std::cout << j.dump(2) << "\n";
  }
  return 0;
}

}  // namespace sublift::cli
