// sublift-cli synthesize PROJECT [--level L | --limit | --every-level] [--keep FRACTION] -o OUT [--json]
#include <charconv>
#include <chrono>
#include <filesystem>
#include <iostream>

#include "app/cli/cli_args.h"
#include "app/cli/cli_commands.h"
#include "app/cli/cli_hierarchy.h"
#include "core/analysis/compress.h"
#include "core/analysis/limit_surface.h"
#include "core/io/model/surface_export.h"
#include "core/multires/hierarchy.h"
#include "core/multires/level_uv.h"
#include "core/io/project/project_io.h"
#include "core/io/lattice/shape_io.h"
#include "core/base/errors.h"
#include "core/base/text_lines.h"

namespace sublift::cli {

namespace {

constexpr const char* kHelp =
    "usage: sublift-cli synthesize PROJECT [--level L | --limit | --every-level] [--keep FRACTION] -o OUT\n"
    "                   [--json]\n"
    "  Writes the control net of level L (default: the finest) of a .sublift project, vertices\n"
    "  in the order 'subdivide' writes (a project made by 'rebuild': the finest level in the\n"
    "  order of the file it came from), with the project's detail gains applied, as the modeler\n"
    "  shows it. --keep F (0..1) first keeps only the largest fraction F of the wavelet\n"
    "  coefficients, ranked by L2-normalised magnitude times the gain (as 'compress' ranks);\n"
    "  --keep 0 gives the pure subdivision of the base, --keep 1 the shape. OUT by extension as\n"
    "  in 'subdivide'. --limit writes the finest level's limit surface instead of its net, as the\n"
    "  modeler draws and exports it: .obj .ply .gltf .glb with unit normals from the limit\n"
    "  tangents (a lattice: its boundary), other formats the limit positions. --every-level\n"
    "  writes the net of every level at once, OUT's name + _L0 .. _LJ (name_L0.obj ...).\n";

}  // namespace

int run_synthesize(int argc, char** argv) {
  const Args a = parse_args(argc, argv, 2, {"-o", "--level", "--keep"}, {"--json", "--help", "--limit", "--every-level"});
  if (a.has("--help")) {
    std::cout << kHelp;
    return 0;
  }
  if (a.positional.size() != 1) throw UsageError("expected exactly one PROJECT file");
  if (!a.value("-o")) throw UsageError("missing -o OUT");
  std::optional<double> keep;
  if (const auto k = a.value("--keep")) {
    keep = parse_double(*k);
    if (!keep || *keep < 0 || *keep > 1) throw UsageError("--keep must be a fraction in 0..1, got '" + *k + "'");
  }
  std::optional<int> level;
  if (const auto l = a.value("--level")) {
    int n = -1;
    auto [p, ec] = std::from_chars(l->data(), l->data() + l->size(), n);
    if (ec != std::errc() || p != l->data() + l->size() || n < 0)
      throw UsageError("--level must be a non-negative integer, got '" + *l + "'");
    level = n;
  }
  const std::string& in = a.positional[0];
  ProjectExtras extras;
  Hierarchy h = read_project(in, &extras);
  // --limit writes surfaces with normals (glTF too); otherwise, or for a curve, the shape formats.
  const bool surface_out = a.has("--limit") && h.levels.front().dim >= 2 && surface_export_supported(*a.value("-o"));
  const std::string out = surface_out ? *a.value("-o") : output_option(a, h.levels.front().dim);
  const int L = level.value_or(h.finest_level());
  const bool limit = a.has("--limit");
  const bool every = a.has("--every-level");
  if (every && (limit || level)) throw UsageError("--every-level writes every level's net; leave out --level and --limit");
  if (limit && L != h.finest_level())
    throw UsageError("--limit evaluates the finest level (" + std::to_string(h.finest_level()) + "); leave out --level");
  if (L > h.finest_level())
    throw UsageError("--level " + std::to_string(L) + " is beyond the project's finest level " +
                     std::to_string(h.finest_level()));
  // The shape the modeler showed: the saved detail gains applied (compress ranks the same way).
  try {
    apply_gains(h, extras.gains);
  } catch (const Error& e) {
    throw Error(in + ": " + e.what());
  }
  std::size_t kept = 0;
  if (keep) kept = keep_largest(h, *keep);
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<double> x;
  try {  // values no reader would read back are not written (core/base/magnitude.h)
    x = synthesize_in_range(h, L);
  } catch (const Error& e) {
    throw Error(in + ": " + e.what() + "; nothing written");
  }
  const double synthesis_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  std::vector<std::string> notes, written;
  if (limit) {
    if (h.channels != 3) throw Error(in + ": --limit needs a project of positions (3 channels), this one has " + std::to_string(h.channels));
    const LimitSurface surface = finest_limit_surface(h, x);  // core/analysis/limit_surface.h
    if (surface_out && surface.faces.rows() > 0) {
      // The limit surface has level L's faces: its UVs are the level's.
      FaceVaryingUV uv = uv_for_output(h, extras.uv, L, notes);
      if (!uv.empty() && surface.faces.items != h.levels[std::size_t(L)].faces.items) {
        notes.push_back("texture coordinates not written with the limit surface: its faces are not the level's");
        uv = {};
      }
      for (std::string& n : write_surface_with_normals(out, surface.faces, surface.positions, surface.normals, {}, &uv)) notes.push_back(std::move(n));
    } else {
      notes = write_level(out, h, L, surface.positions, 3, extras.input_order, {}, &extras.uv);
    }
  } else if (every) {
    // Each level's net: the finest one is synthesised already, the coarser ones are its prefix
    // levels' syntheses (the same gains and kept wavelets).
    const std::filesystem::path p(out);
    for (int l = 0; l <= h.finest_level(); ++l) {
      const std::string file = (p.parent_path() / (p.stem().string() + "_L" + std::to_string(l) + p.extension().string())).string();
      const std::vector<double> xl = l == L ? x : synthesize_in_range(h, l);
      for (const std::string& n : write_level(file, h, l, xl, h.channels, extras.input_order, extras.attributes, &extras.uv))
        notes.push_back(file + ": " + n);
      written.push_back(file);
    }
  } else {
    notes = write_level(out, h, L, x, h.channels, extras.input_order, extras.attributes, &extras.uv);
  }
  for (const std::string& n : notes) std::cerr << out << ": warning: " << n << "\n";
  if (a.has("--json")) {
    nlohmann::json j = {{"input", in}, {"output", out}, {"level", L}, {"vertices", h.num_vertices(L)}, {"limit", limit},
                      {"gains", extras.gains}, {"synthesis_ms", synthesis_ms}, {"notes", notes}};
    if (every) j["files"] = written;
    if (keep) {
      j["keep"] = *keep;
      j["kept_wavelets"] = kept;
    }
    std::cout << j.dump(2) << "\n";
  }
  return 0;
}

}  // namespace sublift::cli
