// sublift-cli basis IN --scheme S --level J (--vertex I | --wavelet I) [--dual] [--levels K] -o OUT
//                 [--png PNG] [--json]
#include <algorithm>
#include <cmath>
#include <iostream>
#include <ostream>

#include <nlohmann/json.hpp>

#include "app/cli/cli_args.h"
#include "app/cli/cli_commands.h"
#include "app/cli/cli_json.h"
#include "app/cli/cli_hierarchy.h"
#include "core/multires/basis.h"
#include "core/analysis/boundary_surface.h"
#include "core/base/errors.h"
#include "core/base/file_io.h"
#include "core/base/magnitude.h"
#include "core/complex/level_counts.h"
#include "core/io/mesh/mesh_export.h"
#include "core/io/project/project_io.h"
#include "core/io/lattice/shape_io.h"
#include "core/base/text_lines.h"
#ifdef SUBLIFT_HAVE_RENDER
#include "app/cli/cli_basis_png.h"
#endif

namespace sublift::cli {
namespace {

constexpr const char* kHelp =
    "usage: sublift-cli basis IN [--scheme linear|cubic|sqrt2] --level J (--vertex I | --wavelet I) [--dual]\n"
    "                    [--levels K] -o OUT [--png PNG] [--json]\n"
    "  One basis function of the hierarchy on IN (a curve, surface or lattice file, or a .sublift\n"
    "  project, whose base and scheme are used; --scheme is then optional): one coefficient set to\n"
    "  one, all others zero, synthesised from level J (the base refined J times) to level J+K.\n"
    "  --vertex I   the scaling function of vertex I of level J (engine's order; level 0 = file order)\n"
    "  --wavelet I  the wavelet of vertex I of level J+1, which must be an e/f/c vertex (I >= the\n"
    "               vertex count of level J)\n"
    "  --dual       the dual function instead: the row of the analysis operator, i.e. the weights w\n"
    "               with coefficient = sum_k w_k x_k for level J+K values x\n"
    "  --levels K   extra levels (default 6 for curves, 4 for surfaces, 3 for lattices, 8 for sqrt2\n"
    "               surfaces, fewer when level J+K would pass 4 million vertices)\n"
    "  OUT          surfaces and lattices: .ply with the level J+K vertices at their limit positions,\n"
    "               a float64 vertex property 'value' (limit values of the primal function; the\n"
    "               weights of a dual one) and the faces (lattices: their boundary faces);\n"
    "               curves: .json {\"positions\": [[x,y,z],...], \"values\": [...]}\n"
    "  --png PNG    an 800x600 headless picture, coloured by value with the viewer's viridis map\n"
    "               (purple = low, yellow = high; wavelets and dual functions centred on 0: teal = 0,\n"
    "               scaling functions: purple = 0 or the minimum, yellow = the maximum):\n"
    "               surfaces: a height field (limit surface displaced along its normals, the largest\n"
    "               |value| 0.15 of the support's diagonal), turned so the support's mean normal\n"
    "               points up, cropped to the support plus a margin, seen from above-front;\n"
    "               curves: the curve displaced along z (largest |value| a fifth of the bounding box\n"
    "               diagonal) drawn as a coloured ribbon over the thin undisplaced curve;\n"
    "               lattices: the plane z = z(peak vertex) cuts the volume: the boundary surface\n"
    "               behind it and the slice of finest faces on it, both coloured, seen from +x+y+z\n"
    "  --json       level, kind, index, dual, levels, support (non-zero finest vertices),\n"
    "               support_per_level (non-zero control values of levels J..J+K), integral,\n"
    "               moments, min, max, output (conventions: core/multires/basis.h, docs/engine.md)\n";

int int_option(const Args& a, const std::string& key, int lo, int hi) {
  const std::string v = *a.value(key);
  const auto n = parse_int(v);
  if (!n || *n < lo || *n > hi)
    throw UsageError(key + " must be an integer in " + std::to_string(lo) + ".." + std::to_string(hi) + ", got '" + v +
                     "'");
  return static_cast<int>(*n);
}

std::uint32_t index_option(const Args& a, const std::string& key) {
  const std::string v = *a.value(key);
  const auto n = parse_int(v);
  if (!n || *n < 0 || *n > 0xFFFFFFFFll) throw UsageError(key + " needs a non-negative index, got '" + v + "'");
  return static_cast<std::uint32_t>(*n);
}

void write_ply(const std::string& path, std::span<const double> xyz, std::span<const double> values, const Csr& faces) {
  std::uint32_t widest = 0;
  for (std::size_t f = 0; f < faces.rows(); ++f) widest = std::max(widest, faces.size(f));
  check_writable_positions(path, xyz);
  if (faces.rows() == 0) throw InputError(path, 0, "the surface has no faces (a lattice without boundary faces?); nothing written");
  write_file_atomic(path, [&](std::ostream& o) {
    o << "ply\nformat ascii 1.0\ncomment sublift basis function\n"
      << "element vertex " << values.size() << "\nproperty double x\nproperty double y\nproperty double z\n"
      << "property double value\n"
      << "element face " << faces.rows() << "\nproperty list " << (widest > 255 ? "uint" : "uchar")
      << " int vertex_indices\nend_header\n";
    for (std::size_t v = 0; v < values.size(); ++v)
      o << format_double(xyz[3 * v]) << ' ' << format_double(xyz[3 * v + 1]) << ' ' << format_double(xyz[3 * v + 2])
        << ' ' << format_double(values[v]) << '\n';
    for (std::size_t f = 0; f < faces.rows(); ++f) {
      o << faces.size(f);
      for (std::uint32_t i : faces.row(f)) o << ' ' << i;
      o << '\n';
    }
  });
}

void write_curve_json(const std::string& path, std::span<const double> xyz, std::span<const double> values) {
  check_writable_positions(path, xyz);
  nlohmann::json j;
  j["positions"] = nlohmann::json::array();
  for (std::size_t v = 0; v < values.size(); ++v) j["positions"].push_back({xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]});
  j["values"] = std::vector<double>(values.begin(), values.end());
  write_file_atomic(path, [&](std::ostream& o) { o << j.dump() << "\n"; });
}


}  // namespace

int run_basis(int argc, char** argv) {
  const Args a = parse_args(argc, argv, 2, {"-o", "--scheme", "--level", "--vertex", "--wavelet", "--levels", "--png"},
                            {"--json", "--help", "--dual"});
  if (a.has("--help")) {
    std::cout << kHelp;
    return 0;
  }
  if (a.positional.size() != 1) throw UsageError("expected exactly one input file");
  if (!a.value("-o")) throw UsageError("missing -o OUT");
  if (!a.value("--level")) throw UsageError("missing --level J");
  const int J = int_option(a, "--level", 0, 2 * kMaxLevels);  // checked against the scheme below
  if (a.value("--vertex") && a.value("--wavelet")) throw UsageError("give either --vertex I or --wavelet I, not both");
  if (!a.value("--vertex") && !a.value("--wavelet")) throw UsageError("missing --vertex I or --wavelet I");
  BasisRequest r;
  r.level = J;
  r.kind = a.value("--vertex") ? BasisKind::Scaling : BasisKind::Wavelet;
  r.index = index_option(a, r.kind == BasisKind::Scaling ? "--vertex" : "--wavelet");
  r.dual = a.has("--dual");
  if (a.value("--levels")) r.extra_levels = int_option(a, "--levels", r.kind == BasisKind::Wavelet ? 1 : 0, 2 * kMaxLevels);
  const std::string out = *a.value("-o");
  const std::string png = a.value("--png").value_or("");
  if (!png.empty() && file_extension(png) != "png") throw UsageError("--png must name a .png file, got '" + png + "'");

  const std::string& in = a.positional[0];
  Complex base;
  std::vector<double> base_xyz;
  Scheme scheme = Scheme::Cubic;
  ImportReport report;
  if (is_project_path(in)) {
    Hierarchy p = read_project(in);
    scheme = a.value("--scheme") ? scheme_option(a) : p.scheme;
    base_xyz = xyz_of(std::span<const double>(p.coeffs).first(std::size_t(p.num_vertices(0)) * p.channels), p.channels);
    base = std::move(p.levels.front());
  } else {
    scheme = scheme_option(a);
    Shape s = read_shape(in);
    report = std::move(s.report);
    base = std::move(s.base);
    base_xyz = std::move(s.positions);
  }
  add_topology_warnings(report, base);
  std::cerr << report.format(in);
  const int dim = base.dim;
  const std::string ext = file_extension(out);
  if (dim == 1 && ext != "json") throw UsageError("a curve's basis function is written as .json, got '" + out + "'");
  if (dim != 1 && ext != "ply") throw UsageError("a surface's or lattice's basis function is written as .ply, got '" + out + "'");
#ifndef SUBLIFT_HAVE_RENDER
  if (!png.empty()) throw Error("this build has no renderer (configured with SUBLIFT_WITH_GUI=OFF); --png is unavailable");
#endif

  if (J > max_levels(scheme)) throw UsageError("--level must be in 0.." + std::to_string(max_levels(scheme)) + " for " + scheme_name(scheme));
  if (r.extra_levels > max_levels(scheme))
    throw UsageError("--levels must be at most " + std::to_string(max_levels(scheme)) + " for " + scheme_name(scheme));
  check_refined_size(base, J, scheme);
  if (r.extra_levels >= 0) {
    check_refined_size(base, J + r.extra_levels, scheme);
    r.max_vertices = kMaxOutputVertices;
  }
  Hierarchy h = make_hierarchy(base, J, scheme, 3);
  set_base(h, base_xyz);
  const std::vector<double> level_xyz = synthesize(h, J);
  const Complex& level = h.levels[std::size_t(J)];
  const std::uint32_t nv = level.num_vertices, nv1 = static_cast<std::uint32_t>(predicted_level_counts(level, 1, scheme, J).back());
  if (r.kind == BasisKind::Scaling && r.index >= nv)
    throw UsageError("--vertex " + std::to_string(r.index) + ": level " + std::to_string(J) + " has " +
                     std::to_string(nv) + " vertices");
  if (r.kind == BasisKind::Wavelet && r.index < nv)
    throw UsageError("--wavelet " + std::to_string(r.index) + ": vertex " + std::to_string(r.index) + " of level " +
                     std::to_string(J + 1) + " is a v vertex (an old vertex of level " + std::to_string(J) +
                     "); wavelets live on the e/f/c vertices " + std::to_string(nv) + ".." + std::to_string(nv1 - 1));
  if (r.kind == BasisKind::Wavelet && r.index >= nv1)
    throw UsageError("--wavelet " + std::to_string(r.index) + ": level " + std::to_string(J + 1) + " has " +
                     std::to_string(nv1) + " vertices");

  std::vector<double> xyz;
  const BasisFunction b = basis_function(level, scheme, r, level_xyz, &xyz);
  if (dim == 1) {
    write_curve_json(out, xyz, b.values);
  } else {
    const Csr faces = dim == 3 ? boundary_faces(b.finest, xyz) : b.finest.faces;
    write_ply(out, xyz, b.values, faces);
  }
  if (!png.empty()) {
#ifdef SUBLIFT_HAVE_RENDER
    write_basis_png(png, b, xyz, r.kind == BasisKind::Wavelet || r.dual, 800, 600);
#endif
  }
  if (a.has("--json")) {
    const nlohmann::json j = {{"input", in},
                              {"scheme", scheme_name(scheme)},
                              {"level", J},
                              {"kind", r.kind == BasisKind::Scaling ? "scaling" : "wavelet"},
                              {"index", r.index},
                              {"dual", r.dual},
                              {"levels", b.extra_levels},
                              {"vertices", b.finest.num_vertices},
                              {"limit", b.limit},
                              {"support", b.support.size()},
                              {"support_per_level", b.support_per_level},
                              {"integral", b.integral},
                              {"moments", {b.moment[0], b.moment[1], b.moment[2]}},
                              {"min", b.min},
                              {"max", b.max},
                              {"warnings", report_json(report)},
                              {"output", out}};
    std::cout << j.dump(2) << "\n";
  }
  return 0;
}

}  // namespace sublift::cli
