// sublift-cli convert IN -o OUT [--json]
#include <iostream>

#include "app/cli_args.h"
#include "app/cli_commands.h"
#include "app/cli_json.h"
#include "core/mesh_export.h"
#include "core/mesh_import.h"

namespace sublift::cli {

int run_convert(int argc, char** argv) {
  const Args a = parse_args(argc, argv, 2, {"-o"}, {"--json", "--help"});
  if (a.has("--help")) {
    std::cout << "usage: sublift-cli convert IN -o OUT [--json]\n"
                 "  Reads IN through the safe import layer and writes OUT in the format of its\n"
                 "  extension (.obj keeps 't' tags; .off; ascii .ply), vertices in the same order,\n"
                 "  coordinates with 17 significant digits. OUT is replaced atomically.\n";
    return 0;
  }
  if (a.positional.size() != 1) throw UsageError("expected exactly one input file");
  const auto out = a.value("-o");
  if (!out) throw UsageError("missing -o OUT");
  const LoadedMesh loaded = import_surface_mesh(a.positional[0]);
  std::cerr << loaded.report.format(a.positional[0]);
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
