// sublift-cli convert IN -o OUT [--json]
#include <iostream>

#include "app/cli/cli_args.h"
#include "app/cli/cli_commands.h"
#include "app/cli/cli_json.h"
#include "core/base/file_io.h"
#include "core/io/mesh/mesh_export.h"
#include "core/io/mesh/mesh_import.h"
#include "core/io/lattice/shape_io.h"

namespace sublift::cli {

int run_convert(int argc, char** argv) {
  const Args a = parse_args(argc, argv, 2, {"-o"}, {"--json", "--help"});
  if (a.has("--help")) {
    std::cout << "usage: sublift-cli convert IN -o OUT [--json]\n"
                 "  Reads IN through the safe import layer and writes OUT in the format of its\n"
                 "  extension (.obj keeps 't' tags and 'l' polylines; .off; ascii .ply), vertices in\n"
                 "  the same order, coordinates with 17 significant digits. OUT is replaced\n"
                 "  atomically. Lattices convert between .lattice, .vtk (features kept) and .ovm.\n";
    return 0;
  }
  if (a.positional.size() != 1) throw UsageError("expected exactly one input file");
  const auto out = a.value("-o");
  if (!out) throw UsageError("missing -o OUT");
  const std::string in_ext = file_extension(a.positional[0]), out_ext = file_extension(*out);
  if (in_ext == "lattice" || in_ext == "vtk" || out_ext == "lattice" || out_ext == "vtk") {
    // Shapes of any dimension: through the complex (features carried by tags).
    const Shape shape = read_shape(a.positional[0]);
    std::cerr << shape.report.format(a.positional[0]);
    if (const std::string why = shape_output_problem(*out, shape.base.dim); !why.empty()) throw UsageError(why);
    const auto notes = write_shape(*out, shape.base, shape.positions, shape.attributes, &shape.uv, &shape.texture);
    for (const std::string& n : notes) std::cerr << *out << ": warning: " << n << "\n";
    if (a.has("--json")) {
      nlohmann::json j = {{"input", a.positional[0]}, {"output", *out}, {"dim", shape.base.dim},
                          {"vertices", shape.base.num_vertices}, {"faces", shape.base.num_faces()},
                          {"cells", shape.base.num_cells()}, {"warnings", report_json(shape.report)}};
      std::cout << j.dump(2) << "\n";
    }
    return 0;
  }
  const LoadedMesh loaded = import_surface_mesh(a.positional[0]);
  std::cerr << loaded.report.format(a.positional[0]);
  if (file_extension(*out) != "obj" && loaded.mesh.num_polylines() > 0 && loaded.mesh.num_faces() > 0)
    std::cerr << *out << ": warning: " << loaded.mesh.num_polylines() << " polylines not written (." << file_extension(*out)
              << " holds faces only)\n";
  if (const std::string dropped = attributes_not_written(file_extension(*out), loaded.mesh.attributes); !dropped.empty())
    std::cerr << *out << ": warning: ." << file_extension(*out) << " cannot hold the vertex attributes " << dropped
              << ": not written (use .ply)\n";
  write_surface_mesh(*out, loaded.mesh);
  if (a.has("--json")) {
    nlohmann::json j = {{"input", a.positional[0]}, {"output", *out},
                        {"vertices", loaded.mesh.num_vertices()}, {"faces", loaded.mesh.num_faces()},
                        {"warnings", report_json(loaded.report)}};
    std::cout << j.dump(2) << "\n";
  }
  return 0;
}

}  // namespace sublift::cli
