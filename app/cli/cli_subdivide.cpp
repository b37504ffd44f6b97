// sublift-cli subdivide IN --scheme S --levels N [--integer] -o OUT [--json]
#include <iostream>

#include "app/cli/cli_args.h"
#include "app/cli/cli_commands.h"
#include "app/cli/cli_hierarchy.h"
#include "app/cli/cli_json.h"
#include "core/multires/hierarchy.h"
#include "core/multires/level_uv.h"
#include "core/io/lattice/shape_io.h"

namespace sublift::cli {

namespace {

constexpr const char* kHelp =
    "usage: sublift-cli subdivide IN --scheme S --levels N [--integer] -o OUT [--json]\n"
    "  Subdivides the curve, surface or lattice IN N times (0..12; sqrt2: 0..24) with Bertram's lifted B-spline\n"
    "  scheme (zero wavelet coefficients) and writes the finest level to OUT, vertices in the\n"
    "  engine's order (old vertices, then one per edge, face and cell of each level), which is\n"
    "  the order 'analyze' expects. sqrt2 (Wang & Ma's interpolatory sqrt(2) wavelets) takes\n"
    "  surfaces only, N in 0..24 (two of its levels make one 1-to-4 split); its new vertices\n"
    "  are one per boundary or crease edge (even levels) and one per face. linear-tri, butterfly\n"
    "  and loop (Lounsbery, DeRose & Warren) split triangle meshes 1-to-4 (0..12; old vertices,\n"
    "  then one per edge). IN: .obj/.off/.ply surfaces, .obj with only 'l' polylines\n"
    "  (curves), .lattice, .ovm and .vtk lattices. OUT by extension: .obj/.off/.ply for surfaces,\n"
    "  .obj for curves, .lattice for lattices, .vtk for any. Texture coordinates (OBJ vt, glTF\n"
    "  TEXCOORD_0) are refined linearly inside each face, seams kept, and written to .obj/.gltf/.glb\n"
    "  with the texture they map (not by sqrt2). --integer rounds every lifting\n"
    "  term (lossless integer transform). Requests beyond 50 million vertices are refused.\n";

}  // namespace

int run_subdivide(int argc, char** argv) {
  const Args a = parse_args(argc, argv, 2, {"-o", "--scheme", "--levels"}, {"--json", "--help", "--integer"});
  if (a.has("--help")) {
    std::cout << kHelp;
    return 0;
  }
  if (a.positional.size() != 1) throw UsageError("expected exactly one input file");
  const Scheme scheme = scheme_option(a);
  const int levels = levels_option(a, scheme);
  if (!a.value("-o")) throw UsageError("missing -o OUT");
  const std::string& in = a.positional[0];
  Shape shape = read_shape(in);
  add_topology_warnings(shape.report, shape.base);
  std::cerr << shape.report.format(in);
  const std::string out = output_option(a, shape.base.dim);
  check_refined_size(shape.base, levels, scheme);
  const nlohmann::json base_counts = complex_counts_json(shape.base);
  // A file's colours and scalars are channels of their own, subdivided with the positions.
  const int channels = 3 + static_cast<int>(shape.attributes.size());
  Hierarchy h = make_hierarchy(std::move(shape.base), levels, scheme, channels, a.has("--integer"));
  set_base(h, with_attributes(shape.positions, shape.attributes));
  const std::vector<double> x = synthesize(h, levels);
  const Complex& fine = h.levels.back();
  // Face-varying UVs by the linear rule (face_varying.h), with the texture they map.
  std::vector<std::string> notes;
  const FaceVaryingUV uv = uv_for_output(h, shape.uv, levels, notes);
  for (std::string& n : write_shape(out, fine, xyz_of(x, channels), attributes_of(x, channels, shape.attributes), &uv, &shape.texture))
    notes.push_back(std::move(n));
  for (const std::string& n : notes) std::cerr << out << ": warning: " << n << "\n";
  if (a.has("--json")) {
    nlohmann::json j = {{"input", in},       {"output", out},
                        {"scheme", scheme_name(scheme)}, {"integer", a.has("--integer")},
                        {"levels", levels},  {"base", base_counts},
                        {"finest", complex_counts_json(fine)}, {"vertices", fine.num_vertices},
                        {"attributes", attribute_list_json(shape.attributes)},
                        {"uv_points", uv.num_points()}, {"texture", shape.texture.empty() || uv.empty() ? "" : shape.texture.name},
                        {"warnings", report_json(shape.report)}, {"notes", notes}};
    std::cout << j.dump(2) << "\n";
  }
  return 0;
}

}  // namespace sublift::cli
