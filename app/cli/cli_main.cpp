// sublift-cli: every job of the modeler without a display. Exit codes: 0 success, 1 bad input
// (file missing or malformed; one message on stderr naming file and problem), 2 bad usage.
#include <cstring>
#include <exception>
#include <iostream>
#include <new>
#include <string>

#include "app/cli/cli_args.h"
#include "app/cli/cli_commands.h"
#include "core/base/errors.h"

namespace {

constexpr const char* kUsage =
    "usage: sublift-cli COMMAND [ARGS] [--json]\n"
    "\n"
    "commands:\n"
    "  info FILE [--json]                    counts, face sizes, boundary loops, non-manifold\n"
    "                                        elements, valences and bounding box of a mesh;\n"
    "                                        counts and features of a lattice; levels and\n"
    "                                        wavelet statistics of a .sublift project\n"
    "  render FILE -o PNG [--size WxH] [--level L] [--colour L]\n"
    "                                        render a mesh, lattice or project headless (shaded +\n"
    "                                        wireframe; --colour L: by |w| of level L)\n"
    "  convert IN -o OUT [--json]            rewrite a mesh as .obj/.off/.ply (17 digits)\n"
    "  subdivide IN --scheme S --levels N [--integer] -o OUT\n"
    "                                        subdivide a curve, surface or lattice N times\n"
    "  analyze FINE --base BASE --scheme S --levels N [--integer] -o PROJECT.sublift\n"
    "                                        wavelet coefficients of a finest-level shape\n"
    "  rebuild FINE [--scheme auto|S] [--levels N|max] -o PROJECT.sublift\n"
    "                                        find the levels of a mesh another tool subdivided\n"
    "                                        (any vertex order) and analyse it into wavelets\n"
    "  fit MESH [--scheme S] [--base-vertices N] [--levels J] -o OUT\n"
    "                                        a coarse base and fitted levels for any triangle\n"
    "                                        mesh (a first version: docs/fit.md)\n"
    "  synthesize PROJECT [--level L | --limit | --every-level] [--keep F] -o OUT\n"
    "                                        control net of level L, optionally keeping only\n"
    "                                        the largest fraction F of the wavelets\n"
    "  compress PROJECT (--keep F | --threshold T | --linf E) [--region SPEC] [--raw] -o OUT\n"
    "                                        drop the smallest wavelets: a fraction, a threshold\n"
    "                                        or an L-infinity error bound (docs/compression.md)\n"
    "  edit PROJECT --level L --vertex I|--loop A B|... [--falloff R] (--delta DX DY DZ | --rotate AXIS DEG |\n"
    "        --scale S) [--pivot P] [--local-frames] -o OUT\n"
    "                                        move, rotate or scale control points of level L,\n"
    "                                        fine detail kept\n"
    "  set PROJECT [--scheme S] [--subdivide N] [--delete-higher L] [--delete-lower L]\n"
    "        [--gain L F]... [--frames world|local] [--level L]\n"
    "        -o OUT                          the modeler panel's session settings on a project:\n"
    "                                        scheme (shape kept where it can be), more levels,\n"
    "                                        level deletion,\n"
    "                                        gains, detail frames, edit level\n"
    "  basis IN [--scheme S] --level J (--vertex I | --wavelet I) [--dual] [--levels K] -o OUT\n"
    "        [--png PNG]                     one scaling function or wavelet (or its dual) as\n"
    "                                        values at the level J+K vertices (.ply or curve .json)\n"
    "  coefficients --scheme sqrt2 (--valences N0 N1 N2 N3 | --boundary a|b) [--json]\n"
    "                                        lifting coefficient tables (sqrt(2): omega of a\n"
    "                                        face wavelet, eta of a boundary wavelet)\n"
    "  experiment noise|fit|compress --scheme S --model BASE --levels J [--sigma X] [--json]\n"
    "                                        the papers' noise-filtering, fitting and\n"
    "                                        compression errors per level (docs/experiments.md)\n"
    "  animation IN... [--frames N] [--levels J] [--cyclic] [--edits E] [--keep F | --linf E]\n"
    "        [-o OUT] [--json]               a glTF animation or OBJ/PLY frames as a swept\n"
    "                                        space-time lattice: edit and compress it in space\n"
    "                                        and time (docs/animation.md)\n"
    "  resample-sphere MESH --levels J -o OUT [--base-out BASE] [--json]\n"
    "                                        sample a star-shaped closed mesh onto the octahedron\n"
    "                                        split 1-to-4 J times, by rays from its centroid\n"
    "\n"
    "Meshes: .obj (with OpenSubdiv 't' tags; 'l' polylines are curves), .off, .ply (ascii and\n"
    "binary), .gltf/.glb (read: triangles welded by position). Lattices: .lattice (Sublift's text format), .vtk (legacy unstructured grid),\n"
    ".ovm (OpenVolumeMesh ASCII).\n"
    "Projects: .sublift. Formats: docs/file_formats.md.\n"
    "Run 'sublift-cli COMMAND --help' for a command's options.\n";

}  // namespace

int main(int argc, char** argv) {
  using namespace sublift;
  if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h") ||
      !std::strcmp(argv[1], "help")) {
    (argc < 2 ? std::cerr : std::cout) << kUsage;
    return argc < 2 ? 2 : 0;
  }
  const std::string cmd = argv[1];
  try {
    if (cmd == "info") return cli::run_info(argc, argv);
    if (cmd == "render") return cli::run_render(argc, argv);
    if (cmd == "convert") return cli::run_convert(argc, argv);
    if (cmd == "subdivide") return cli::run_subdivide(argc, argv);
    if (cmd == "analyze") return cli::run_analyze(argc, argv);
    if (cmd == "rebuild") return cli::run_rebuild(argc, argv);
    if (cmd == "fit") return cli::run_fit(argc, argv);
    if (cmd == "synthesize") return cli::run_synthesize(argc, argv);
    if (cmd == "edit") return cli::run_edit(argc, argv);
    if (cmd == "set") return cli::run_set(argc, argv);
    if (cmd == "basis") return cli::run_basis(argc, argv);
    if (cmd == "ffd") return cli::run_ffd(argc, argv);
    if (cmd == "animation") return cli::run_animation(argc, argv);
    if (cmd == "coefficients") return cli::run_coefficients(argc, argv);
    if (cmd == "experiment") return cli::run_experiment(argc, argv);
    if (cmd == "resample-sphere") return cli::run_resample_sphere(argc, argv);
    if (cmd == "compress") return cli::run_compress(argc, argv);
    std::cerr << "sublift-cli: unknown command '" << cmd << "'\n\n" << kUsage;
    return 2;
  } catch (const cli::UsageError& e) {
    std::cerr << "sublift-cli " << cmd << ": " << e.what() << "\n(see 'sublift-cli " << cmd
              << " --help')\n";
    return 2;
  } catch (const Error& e) {
    std::cerr << "sublift-cli " << cmd << ": error: " << e.what() << "\n";
    return 1;
  } catch (const std::bad_alloc&) {
    std::cerr << "sublift-cli " << cmd << ": error: out of memory\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "sublift-cli " << cmd << ": internal error: " << e.what() << "\n";
    return 3;
  }
}
