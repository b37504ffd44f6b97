// sublift-cli compress PROJECT (--keep F | --threshold T | --linf E) [--region SPEC] [--raw]
//             [--bits B] -o OUT [--json]
#include <algorithm>
#include <chrono>
#include <optional>
#include <cmath>
#include <cstdio>
#include <iostream>

#include "app/cli/cli_args.h"
#include "app/cli/cli_commands.h"
#include "app/cli/cli_json.h"
#include "app/cli/cli_hierarchy.h"
#include "core/analysis/compress.h"
#include "core/base/errors.h"
#include "core/io/project/project_io.h"
#include "core/io/lattice/shape_io.h"
#include "core/base/text_lines.h"

namespace sublift::cli {
namespace {

constexpr const char* kHelp =
    "usage: sublift-cli compress PROJECT (--keep F | --threshold T | --linf E) [--region SPEC] [--raw]\n"
    "                            [--group NAME] [--bits B] -o OUT [--json]\n"
    "  Drops the wavelet coefficients of a .sublift project that contribute least and writes the\n"
    "  result (docs/compression.md). Wavelets are ranked by normalised magnitude |w| x ||psi||_2\n"
    "  (the wavelet's L2 norm; the level's detail gain applied); exactly one mode:\n"
    "  --keep F       keep the largest fraction F (0..1) of the wavelets (the ranking and rounding\n"
    "                 of 'synthesize --keep')\n"
    "  --threshold T  keep wavelets whose normalised magnitude is >= T x the bounding-box diagonal\n"
    "                 of the finest shape (T is scale-free)\n"
    "  --linf E       remove as many of the smallest wavelets as found while the largest finest-\n"
    "                 vertex error stays <= E x the diagonal (bisection over the ranking: the\n"
    "                 largest prefix removal found, not a global optimum)\n"
    "  --region SPEC  only wavelets whose vertex lies inside may be removed: box:x0,y0,z0,x1,y1,z1\n"
    "                 or sphere:cx,cy,cz,r (position on the level the wavelet lives on); F then\n"
    "                 counts the wavelets inside\n"
    "  --raw          rank by the raw magnitude |w| instead (for experiments)\n"
    "  --group NAME   a project with attribute channels: compress one channel group alone (position,\n"
    "                 colour, or an attribute's name), every other channel kept exactly; without it\n"
    "                 each group is compressed by its own ranking\n"
    "  --bits B       a project OUT stores the kept wavelets quantized to B bits (8, 16 or 32; a\n"
    "                 step per level and channel): smaller, lossy; the error is reported.\n"
    "                 Without it the project is exact, the dropped wavelets a bit each\n"
    "  OUT            a .sublift project (the compressed coefficients, gains and level kept), or\n"
    "                 the finest level as a mesh by extension (.obj .off .ply .vtk .lattice .ovm)\n"
    "  --json         prints kept, total, l2_error, linf_error (relative to the diagonal), mode,\n"
    "                 value, timings and, for a project, its encoding and bytes (with --bits the\n"
    "                 largest coefficient change and finest-vertex move it adds)\n";

double mode_value(const std::string& option, const std::string& text) {
  const auto v = parse_double(text);
  if (!v) throw UsageError(option + " needs a number, got '" + text + "'");
  if (option == "--keep" && (*v < 0 || *v > 1)) throw UsageError("--keep must be a fraction in 0..1, got '" + text + "'");
  if (*v < 0) throw UsageError(option + " must not be negative, got '" + text + "'");
  return *v;
}

}  // namespace

int run_compress(int argc, char** argv) {
  const Args a = parse_args(argc, argv, 2, {"-o", "--keep", "--threshold", "--linf", "--region", "--bits", "--group"},
                            {"--json", "--help", "--raw"});
  if (a.has("--help")) {
    std::cout << kHelp;
    return 0;
  }
  if (a.positional.size() != 1) throw UsageError("expected exactly one PROJECT file");
  struct Choice {
    const char* option;
    CompressMode mode;
  };
  const Choice choices[] = {{"--keep", CompressMode::Keep}, {"--threshold", CompressMode::Threshold},
                            {"--linf", CompressMode::Linf}};
  std::optional<CompressMode> mode;
  double value = 0;
  for (const Choice& c : choices) {
    const auto v = a.value(c.option);
    if (!v) continue;
    if (mode) throw UsageError("give exactly one of --keep F, --threshold T, --linf E (got more than one)");
    mode = c.mode;
    value = mode_value(c.option, *v);
  }
  if (!mode) throw UsageError("give exactly one of --keep F, --threshold T, --linf E");
  if (!a.value("-o")) throw UsageError("missing -o OUT");
  CompressOptions options;
  options.normalise = !a.has("--raw");
  if (const auto r = a.value("--region")) {
    try {
      options.region = parse_region(*r);
    } catch (const Error& e) {
      throw UsageError(std::string("--region: ") + e.what());
    }
  }

  int bits = 0;
  if (const auto b = a.value("--bits")) {
    const auto n = parse_int(*b);
    if (!n || (*n != 8 && *n != 16 && *n != 32)) throw UsageError("--bits takes 8, 16 or 32, got '" + *b + "'");
    if (!is_project_path(*a.value("-o"))) throw UsageError("--bits quantizes a project: OUT must be a .sublift file");
    bits = static_cast<int>(*n);
  }

  const std::string& in = a.positional[0];
  ProjectExtras extras;
  const Hierarchy h = read_project(in, &extras);
  ImportReport topology;  // of the base whose wavelets are compressed
  add_topology_warnings(topology, h.levels.front());
  std::cerr << topology.format(in);
  const bool project_out = is_project_path(*a.value("-o"));
  const std::string out = output_option(a, project_out ? 0 : h.levels.front().dim);
  options.gains = extras.gains;

  // Attribute channels are compressed by groups of their own (x, y, z; the colour; each other
  // attribute), each ranked by its own magnitude and measured in its own range.
  const std::vector<ChannelGroup> groups = channel_groups(h.channels, extras.attributes);
  const std::optional<std::string> only = a.value("--group");  // one group alone, the rest exact
  std::size_t only_group = groups.size();
  if (only) {
    std::string names;
    for (std::size_t g = 0; g < groups.size(); ++g) {
      if (groups[g].name == *only) only_group = g;
      names += (g ? ", " : "") + groups[g].name;
    }
    if (groups.empty()) throw UsageError("--group: " + in + " has no attribute channels (its only group is x, y, z)");
    if (only_group == groups.size()) throw UsageError("--group " + *only + ": the project's groups are " + names);
  }
  if (!groups.empty()) options.channels = groups[only ? only_group : 0].range;
  const auto t0 = std::chrono::steady_clock::now();
  const Compressor compressor(h, options);
  const auto t1 = std::chrono::steady_clock::now();
  Compression c = compressor.run(*mode, value);
  nlohmann::json group_rows = nlohmann::json::array();
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const ChannelGroup& group = groups[g];
    if (only && g != only_group) {  // kept exactly: the run above zeroed only the chosen group
      group_rows.push_back({{"name", group.name}, {"channels", group.channels}, {"untouched", true}});
      continue;
    }
    CompressOptions o = options;
    o.channels = group.range;
    Compression gc;
    try {
      gc = g == 0 || only ? c : Compressor(h, o).run(*mode, value);
    } catch (const Error&) {  // a constant attribute: no range to measure against, nothing to drop
      group_rows.push_back({{"name", group.name}, {"channels", group.channels}, {"constant", true}});
      continue;
    }
    for (std::size_t v = 0; g > 0 && !only && v < gc.coeffs.size(); v += std::size_t(h.channels))
      std::copy_n(&gc.coeffs[v + std::size_t(group.range.first)], group.range.count, &c.coeffs[v + std::size_t(group.range.first)]);
    group_rows.push_back({{"name", group.name},
                          {"channels", group.channels},
                          {"kept", gc.kept},
                          {"total", gc.total},
                          {"l2_error", gc.l2_error},
                          {"linf_error", gc.linf_error}});
  }
  if (groups.size() > 1 && !only) c.finest = synthesize_coefficients(h, c.coeffs, options.gains, h.finest_level());
  const auto t2 = std::chrono::steady_clock::now();

  std::vector<std::string> notes;
  SavedProject saved;
  double quantized_linf = 0.0;  // the finest level's largest move by quantization, / diagonal
  if (project_out) {
    Hierarchy compressed = h;
    compressed.coeffs = c.coeffs;
    saved = write_project(out, compressed, extras, bits);
    if (bits) {
      const std::vector<double> back = synthesize(read_project(out), h.finest_level());
      const std::vector<double> exact = synthesize(compressed, h.finest_level());
      for (std::size_t i = 0; i < exact.size(); ++i) quantized_linf = std::max(quantized_linf, std::abs(back[i] - exact[i]));
      quantized_linf /= compressor.diagonal();
    }
  } else {
    notes = write_level(out, h, h.finest_level(), c.finest, h.channels, extras.input_order, extras.attributes, &extras.uv);
  }
  for (const std::string& n : notes) std::cerr << out << ": warning: " << n << "\n";
  const auto ms = [](auto from, auto to) { return std::chrono::duration<double, std::milli>(to - from).count(); };
  if (a.has("--json")) {
    nlohmann::json j = {{"input", in},
                        {"output", out},
                        {"mode", compress_mode_name(*mode)},
                        {"value", value},
                        {"kept", c.kept},
                        {"total", c.total},
                        {"candidates", compressor.candidates()},
                        {"candidates_kept", c.keep},
                        {"l2_error", c.l2_error},
                        {"linf_error", c.linf_error},
                        {"diagonal", compressor.diagonal()},
                        {"normalise", options.normalise},
                        {"region", a.value("--region").value_or("")},
                        {"ranking_ms", ms(t0, t1)},
                        {"compress_ms", ms(t1, t2)},
                        {"warnings", report_json(topology)},
                        {"notes", notes}};
    if (!groups.empty()) j["groups"] = group_rows;  // kept, l2_error, linf_error above: the first (x, y, z), or --group's
    if (only) j["group"] = *only;
    if (project_out) {
      j["encoding"] = saved.encoding;
      j["bytes"] = saved.bytes;
      if (bits) {
        j["bits"] = bits;
        j["quantization_max_error"] = saved.max_quantization_error;
        j["quantization_linf_error"] = quantized_linf;
      }
    }
    std::cout << j.dump(2) << "\n";
  } else {
    char line[200];
    std::snprintf(line, sizeof line, "kept %zu of %zu wavelets; error relative to the diagonal: L2 %.3g, L-infinity %.3g\n",
                  c.kept, c.total, c.l2_error, c.linf_error);
    std::cout << line;
    if (project_out) {
      std::snprintf(line, sizeof line, "wrote %llu bytes (%s coefficients", static_cast<unsigned long long>(saved.bytes),
                    saved.encoding.c_str());
      std::cout << line;
      if (bits) {
        std::snprintf(line, sizeof line, ", %d bits: finest vertices moved by up to %.3g of the diagonal", bits, quantized_linf);
        std::cout << line;
      }
      std::cout << ")\n";
    }
  }
  return 0;
}

}  // namespace sublift::cli
