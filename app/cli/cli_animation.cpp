// sublift-cli animation IN... [--animation A] [--frames N] [--fps F] [--levels J] [--scheme S]
//               [--cyclic] [--edits E] [--keep F | --linf E] [-o OUT] [--json]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <optional>

#include <nlohmann/json.hpp>

#include "app/cli/cli_args.h"
#include "app/cli/cli_commands.h"
#include "core/analysis/compress.h"
#include "core/anim/animation_compress.h"
#include "core/anim/animation_edits.h"
#include "core/anim/animation_open.h"
#include "core/base/errors.h"
#include "core/base/file_io.h"
#include "core/base/text_lines.h"
#include "core/edit/session.h"
#include "core/io/model/animation_export.h"
#include "core/io/project/project_io.h"
#include "core/schemes/registry.h"

namespace sublift::cli {
namespace {

constexpr const char* kHelp =
    "usage: sublift-cli animation IN... [--animation A] [--frames N] [--fps F] [--levels J]\n"
    "                  [--scheme linear|cubic] [--cyclic] [--edits E] [--keep F | --linf E]\n"
    "                  [-o OUT] [--json]\n"
    "  A time-varying surface as a swept space-time lattice (paper 000 sec. 7; docs/animation.md):\n"
    "  the animated mesh's base swept over K base time steps into prisms, hexahedra or n-gon\n"
    "  prisms, refined J levels (layer t of the finest level is frame t), filled from the frames\n"
    "  and analysed, so the animation's detail in space and in time becomes wavelets. Edits move\n"
    "  a control point of any level at one frame; the change spreads over the frames its time\n"
    "  support covers, with the finer motion kept.\n"
    "  IN              an animation's .sublift project, or one .gltf/.glb (an animation of\n"
    "                  morph-target weights, a skin or node\n"
    "                  transforms, sampled at --frames uniform times), or two or more OBJ/PLY/OFF\n"
    "                  files of the same connectivity, one frame each, in the order given\n"
    "  --animation A   the glTF animation's index (default: the first)\n"
    "  --frames N      glTF samples: an open animation takes 2^J K + 1 frames (K >= 1), a cyclic\n"
    "                  one 2^J K (K >= 3); default K = 4\n"
    "  --fps F         a sequence's frame rate (default 24); a glTF without --frames is sampled at\n"
    "                  least this often (the count rounded up to one the levels take)\n"
    "  --levels J      space-time levels, 1..6 (default 2)\n"
    "  --scheme S      lattice wavelets, cubic (default) or linear\n"
    "  --cyclic        a periodic time axis: the last frame runs into the first (a loop);\n"
    "                  otherwise the first and last frames are the lattice's boundary\n"
    "  --edits E       a text file of 'level frame point dx dy dz' lines: move control point\n"
    "                  `point` of level `level` (the base mesh's vertices at level 0) on the layer\n"
    "                  at finest frame `frame` (a multiple of 2^(J - level)) by (dx, dy, dz)\n"
    "  --keep F        keep the largest fraction F (0..1) of the space-time wavelets\n"
    "  --linf E        keep as few as hold every frame's largest error <= E x diagonal\n"
    "  -o OUT          .gltf/.glb: the frames as morph targets keyed in time (LINEAR); .obj,\n"
    "                  .ply: one file per frame, '#...#' in the name replaced by the frame number\n"
    "                  (otherwise _0000 before the extension). The finest level's frames.\n"
    "                  .sublift: the animation's project (the lattice's coefficients and the\n"
    "                  frames' times), which IN, the modeler and its recovery open again\n"
    "  --json          prints frames, counts, the fit's errors, time and space wavelets, the\n"
    "                  edits, compression with the error per frame and the sizes against the raw\n"
    "                  frames and against per-frame compression with the surface wavelets, and\n"
    "                  the time of each stage\n";

double ms_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
}

double fraction_option(const Args& a, const char* name) {
  const std::string s = *a.value(name);
  const auto v = parse_double(s);
  if (!v || *v < 0 || (std::string(name) == "--keep" && *v > 1))
    throw UsageError(std::string(name) + " must be a number " + (std::string(name) == "--keep" ? "0..1" : ">= 0") + ", got '" + s + "'");
  return *v;
}

nlohmann::json errors_json(const std::vector<FrameError>& errors) {
  nlohmann::json out = nlohmann::json::array();
  for (std::size_t t = 0; t < errors.size(); ++t) out.push_back({{"frame", t}, {"max", errors[t].max}, {"rms", errors[t].rms}});
  return out;
}

double worst(const std::vector<FrameError>& errors) {
  double w = 0;
  for (const FrameError& e : errors) w = std::max(w, e.max);
  return w;
}

}  // namespace

int run_animation(int argc, char** argv) {
  const Args a = parse_args(argc, argv, 2, {"-o", "--animation", "--frames", "--fps", "--levels", "--scheme", "--edits", "--keep", "--linf"},
                            {"--json", "--help", "--cyclic"});
  if (a.has("--help")) {
    std::cout << kHelp;
    return 0;
  }
  if (a.positional.empty()) throw UsageError("missing IN (a glTF, or two or more OBJ/PLY/OFF frames; see --help)");
  if (a.value("--keep") && a.value("--linf")) throw UsageError("give at most one of --keep and --linf");
  AnimationOptions options;
  options.cyclic = a.has("--cyclic");
  options.levels = int(integer_option(a, "--levels", 2, 1, 6));
  options.frames = int(integer_option(a, "--frames", 0, 2, 100000));
  options.animation = int(integer_option(a, "--animation", -1, 0, 1 << 20));
  if (const auto s = a.value("--scheme")) {
    const std::string name = to_lower(*s);
    if (name != "linear" && name != "cubic") throw UsageError("--scheme must be linear or cubic (space-time lattices are volumes), got '" + *s + "'");
    options.scheme = parse_scheme(name);
  }
  if (const auto f = a.value("--fps")) {
    const auto v = parse_double(*f);
    if (!v || !(*v > 0) || *v > 1e6) throw UsageError("--fps must be a positive number, got '" + *f + "'");
    options.fps = *v;
    options.sample_fps = *v;
  }
  if (const auto o = a.value("-o")) {
    const std::string ext = file_extension(*o);
    if (ext != "gltf" && ext != "glb" && ext != "obj" && ext != "ply" && ext != "sublift")
      throw UsageError("OUT must be .gltf, .glb (morph targets), .obj, .ply (one file per frame) or .sublift (the animation's project): " + *o);
  }
  // At most one of the two (checked above): which, and its value.
  const bool compress = a.value("--keep") || a.value("--linf"), keep = a.value("--keep").has_value();
  const double compress_value = compress ? fraction_option(a, keep ? "--keep" : "--linf") : 0.0;
  std::vector<AnimationEdit> edits;
  if (const auto e = a.value("--edits")) edits = read_animation_edits(*e);

  // A project of an animation (written by -o OUT.sublift or the modeler) opens as it was saved.
  const bool project_in = a.positional.size() == 1 && file_extension(a.positional[0]) == "sublift";
  OpenedAnimation anim = [&] {
    if (!project_in) return open_animation(a.positional, options);
    ProjectExtras x;
    const Hierarchy h = read_project(a.positional[0], &x);
    if (x.animation.empty()) throw InputError(a.positional[0], 0, "is not an animation's project (no 'animation' in its header)");
    return reopen_animation(a.positional[0], h, x.animation);
  }();
  SpaceTime& st = anim.st;
  const int J = st.levels(), n = st.layers(J);
  std::vector<std::uint32_t> edit_vertices;
  if (const auto e = a.value("--edits"))
    for (const AnimationEdit& ed : edits) edit_vertices.push_back(edit_vertex(st, ed, *e));
  for (const std::string& note : anim.notes) std::cerr << anim.source << ": note: " << note << "\n";

  // Edits, as the modeler's drags: a session on the lattice hierarchy.
  auto t = std::chrono::steady_clock::now();
  const std::vector<double> unedited = synthesize(st.lattice, J);
  if (!edits.empty()) {
    Session session(st.lattice);
    for (std::size_t i = 0; i < edits.size(); ++i) {
      const std::uint32_t v[1] = {edit_vertices[i]};
      session.move(edits[i].level, v, {}, edits[i].delta);
    }
    st.lattice.coeffs = session.hierarchy().coeffs;
  }
  const double edit_ms = ms_since(t);
  std::vector<double> finest = edits.empty() ? unedited : synthesize(st.lattice, J);

  // Time and space wavelets (of the edited animation).
  const std::vector<std::uint8_t> time_flags = time_wavelet_flags(st);
  const std::uint32_t nl0 = st.lattice.num_vertices(0);
  std::size_t time_count = 0;
  double time_energy = 0, space_energy = 0;
  for (std::size_t i = 0; i < time_flags.size(); ++i) {
    const double* w = &st.lattice.coeffs[3 * (nl0 + i)];
    const double e = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
    (time_flags[i] ? time_energy : space_energy) += e;
    time_count += time_flags[i];
  }

  nlohmann::json compression = nullptr;
  if (compress) {
    t = std::chrono::steady_clock::now();
    const Compressor c(st.lattice);
    const Compression r = c.run(keep ? CompressMode::Keep : CompressMode::Linf, compress_value);
    const double compress_ms = ms_since(t);
    const std::vector<FrameError> errors = frame_errors(st, r.finest, finest, c.diagonal());
    const std::size_t stored = nl0 + r.kept;
    t = std::chrono::steady_clock::now();
    const PerFrameCompression pf = per_frame_compression(st, finest, stored, c.diagonal());
    const double per_frame_ms = ms_since(t);
    const std::size_t raw = std::size_t(n) * st.surface_vertices(J), raw_input = std::size_t(n) * st.surface_vertices(0);
    compression = {{"mode", keep ? "keep" : "linf"},
                   {"kept", r.kept},
                   {"wavelets", r.total},
                   {"stored", stored},
                   {"raw_frames", raw},
                   {"raw_input_frames", raw_input},
                   {"ratio_to_raw", double(stored) / double(raw)},
                   {"max_error", worst(errors)},
                   {"l2_error", r.l2_error},
                   {"errors", errors_json(errors)},
                   {"per_frame", {{"stored", pf.stored},
                                  {"kept", pf.kept},
                                  {"wavelets", pf.wavelets},
                                  {"max_error", worst(pf.errors)},
                                  {"errors", errors_json(pf.errors)}}},
                   {"compress_ms", compress_ms},
                   {"per_frame_ms", per_frame_ms}};
    finest = r.finest;
    st.lattice.coeffs = r.coeffs;  // what a project output keeps
  }

  // Output: the finest level's layers, each on the surface's finest level.
  std::vector<std::string> written;
  t = std::chrono::steady_clock::now();
  if (const auto o = a.value("-o")) {
    std::vector<double> frames;
    frames.reserve(std::size_t(n) * 3 * st.surface_vertices(J));
    for (int l = 0; l < n; ++l) {
      const std::vector<double> x = layer_positions(st, finest, J, l);
      frames.insert(frames.end(), x.begin(), x.end());
    }
    const Csr& faces = st.surface_levels.levels[std::size_t(J)].faces;
    const std::string ext = file_extension(*o);
    if (ext == "sublift") {
      ProjectExtras x;
      x.animation = animation_extras(anim);
      write_project(*o, st.lattice, x);
      written.push_back(*o);
    } else if (ext == "gltf" || ext == "glb") {
      write_animation_gltf(*o, faces, frames, anim.times, st.cyclic, anim.loop_end);
      written.push_back(*o);
    } else {
      written = write_frame_sequence(*o, faces, frames, std::size_t(n));
    }
  }
  const double write_ms = ms_since(t);

  if (a.has("--json")) {
    const nlohmann::json j = {
        {"input", a.positional},
        {"frames", n},
        {"times", anim.times},
        {"cyclic", st.cyclic},
        {"scheme", scheme_name(st.lattice.scheme)},
        {"levels", J},
        {"base_steps", st.base_steps},
        {"base_vertices", st.surface_vertices(0)},
        {"finest_surface_vertices", st.surface_vertices(J)},
        {"lattice_vertices", nl0},
        {"lattice_cells", st.lattice.levels[0].num_cells()},
        {"finest_lattice_vertices", st.lattice.num_vertices(J)},
        {"diagonal", anim.diagonal},
        {"fit", {{"max_error", anim.fit.max_error / anim.diagonal}, {"max_surface_gap", anim.fit.max_surface_gap / anim.diagonal}}},
        {"wavelets", {{"time", time_count},
                      {"space", time_flags.size() - time_count},
                      {"time_energy", time_energy},
                      {"space_energy", space_energy}}},
        {"edits", edits.size()},
        {"compression", compression},
        {"output", written},
        {"notes", anim.notes},
        {"ms", {{"load", anim.load_ms}, {"build", anim.build_ms}, {"fit", anim.fit_ms}, {"edits", edit_ms}, {"write", write_ms}}}};
    std::cout << j.dump(2) << "\n";
  }
  return 0;
}

}  // namespace sublift::cli
