// sublift-cli render FILE -o PNG [--size WxH] [--json]
#include <iostream>

#include <nlohmann/json.hpp>

#include "app/cli/cli_args.h"
#include "app/cli/cli_commands.h"
#include "core/base/errors.h"
#include "core/base/file_io.h"
#include "core/io/mesh/mesh_import.h"
#ifdef SUBLIFT_HAVE_RENDER
#include "render/headless_render.h"
#include "render/offscreen_target.h"
#endif

namespace sublift::cli {

int run_render(int argc, char** argv) {
  const Args a = parse_args(argc, argv, 2, {"-o", "--size"}, {"--json", "--help"});
  if (a.has("--help")) {
    std::cout << "usage: sublift-cli render FILE -o PNG [--size WxH] [--json]\n"
                 "  Renders the mesh shaded with its wireframe from the default 3/4 view, without\n"
                 "  a display (EGL surfaceless), and writes a PNG. Default size 800x600.\n";
    return 0;
  }
  if (a.positional.size() != 1) throw UsageError("expected exactly one FILE");
  const auto out = a.value("-o");
  if (!out) throw UsageError("missing -o PNG");
  if (file_extension(*out) != "png") throw UsageError("output must be a .png file, got '" + *out + "'");
  int w = 800, h = 600;
  if (auto s = a.value("--size")) parse_size(*s, w, h);
  const LoadedMesh loaded = import_surface_mesh(a.positional[0]);
  std::cerr << loaded.report.format(a.positional[0]);
#ifdef SUBLIFT_HAVE_RENDER
  const Image img = render_mesh_headless(loaded.mesh, w, h);
  write_png(*out, img.width, img.height, img.rgba);
  if (a.has("--json"))
    std::cout << nlohmann::json{{"input", a.positional[0]}, {"output", *out}, {"width", w}, {"height", h}}.dump(2)
              << "\n";
  return 0;
#else
  throw Error("this build has no renderer (configured with SUBLIFT_WITH_GUI=OFF)");
#endif
}

}  // namespace sublift::cli
