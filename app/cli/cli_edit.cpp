// sublift-cli edit PROJECT --level L --vertex I [--vertex I ...] [--falloff R]
//             --delta DX DY DZ | --rotate AXIS DEGREES | --scale S  [--pivot P]
//             [--local-frames] -o OUT [--json]
#include <charconv>
#include <chrono>
#include <iostream>
#include <numbers>

#include "app/cli/cli_args.h"
#include "app/cli/cli_commands.h"
#include "app/cli/cli_json.h"
#include "app/cli/cli_hierarchy.h"
#include "core/io/project/project_io.h"
#include "core/edit/session.h"
#include "core/edit/transform.h"
#include "core/io/lattice/shape_io.h"
#include "core/base/text_lines.h"

namespace sublift::cli {
namespace {

constexpr const char* kHelp =
    "usage: sublift-cli edit PROJECT --level L --vertex I [--vertex I ...] [--falloff R]\n"
    "                   --delta DX DY DZ | --rotate AXIS DEGREES | --scale S [--pivot P]\n"
    "                   [--local-frames] -o OUT [--json]\n"
    "  Moves control points I of level L (indices in the engine's order of that level; level 0 is\n"
    "  the base file's order) by (DX, DY, DZ), or rotates or scales them about a pivot, as the\n"
    "  modeler's G, R and S do: finer levels are resynthesised locally from the stored wavelets,\n"
    "  coarser ones take the change by analysis.\n"
    "  --rotate AXIS DEGREES  AXIS x, y, z or AX,AY,AZ (right-handed about it)\n"
    "  --scale S    a factor, or SX,SY,SZ per axis (a negative one mirrors)\n"
    "  --pivot P    median (of the --vertex points; the default), active (the last --vertex),\n"
    "               origin, or a point X,Y,Z\n"
    "  --falloff R  soft selection: points within distance R of a selected one move by\n"
    "               1 - smoothstep(d / R) of the delta (rotate by that part of the angle, scale\n"
    "               by that part of the factor)\n"
    "  --local-frames  keep detail in local frames of the coarser surface (surfaces only), so it\n"
    "               turns with the surface; default: world coordinates\n"
    "  OUT          a .sublift project (the edited session: coefficients, gains, level L), or the\n"
    "               finest level as a mesh by extension (.obj .off .ply .vtk .lattice)\n"
    "  --json       prints resynthesis_ms (the local resynthesis alone, no file I/O) and\n"
    "               vertices_updated; compare with 'synthesize --json' synthesis_ms\n";

std::uint32_t index_value(const std::string& s) {
  std::uint32_t v = 0;
  auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || p != s.data() + s.size()) throw UsageError("--vertex needs a non-negative index, got '" + s + "'");
  return v;
}

// "a,b,c" as three finite numbers (or one, repeated, when `one_is_all`).
glm::dvec3 triple(const std::string& s, const char* option, bool one_is_all) {
  std::vector<std::string> parts(1);
  for (const char ch : s) {
    if (ch == ',') parts.emplace_back();
    else parts.back().push_back(ch);
  }
  if (parts.size() == 1 && one_is_all) parts = {parts[0], parts[0], parts[0]};
  if (parts.size() != 3) throw UsageError(std::string(option) + " needs " + (one_is_all ? "one number or " : "") + "three numbers A,B,C, got '" + s + "'");
  glm::dvec3 out;
  for (int c = 0; c < 3; ++c) {
    const auto d = parse_double(parts[static_cast<std::size_t>(c)]);
    if (!d) throw UsageError(std::string(option) + " needs finite numbers, got '" + s + "'");
    out[c] = *d;
  }
  return out;
}

}  // namespace

int run_edit(int argc, char** argv) {
  const Args a = parse_args(argc, argv, 2, {"-o", "--level", "--falloff", "--scale", "--pivot"},
                            {"--json", "--help", "--local-frames"}, {{"--vertex", 1}, {"--delta", 3}, {"--rotate", 2}});
  if (a.has("--help")) {
    std::cout << kHelp;
    return 0;
  }
  if (a.positional.size() != 1) throw UsageError("expected exactly one PROJECT file");
  if (!a.value("-o")) throw UsageError("missing -o OUT");
  if (!a.value("--level")) throw UsageError("missing --level L");
  const auto lv = parse_int(*a.value("--level"));
  if (!lv || *lv < 0) throw UsageError("--level must be a non-negative integer, got '" + *a.value("--level") + "'");
  const auto vit = a.lists.find("--vertex");
  if (vit == a.lists.end()) throw UsageError("missing --vertex I");
  const auto dit = a.lists.find("--delta");
  const auto rit = a.lists.find("--rotate");
  const int kinds = (dit != a.lists.end()) + (rit != a.lists.end()) + (a.value("--scale").has_value());
  if (kinds == 0) throw UsageError("missing --delta DX DY DZ, --rotate AXIS DEGREES or --scale S");
  if (kinds > 1) throw UsageError("give one of --delta, --rotate and --scale");
  double delta[3] = {0, 0, 0};
  if (dit != a.lists.end()) {
    if (dit->second.size() != 3) throw UsageError("--delta is given once, with three numbers");
    for (int c = 0; c < 3; ++c) {
      const auto d = parse_double(dit->second[static_cast<std::size_t>(c)]);
      if (!d) throw UsageError("--delta needs three finite numbers, got '" + dit->second[static_cast<std::size_t>(c)] + "'");
      delta[c] = *d;
    }
  }
  glm::dvec3 axis(0.0, 0.0, 1.0), factors(1.0);
  double angle = 0.0;
  if (rit != a.lists.end()) {
    if (rit->second.size() != 2) throw UsageError("--rotate is given once, with an axis and degrees");
    const std::string& ax = rit->second[0];
    if (ax == "x" || ax == "y" || ax == "z") {
      axis = glm::dvec3(0.0);
      axis[ax[0] - 'x'] = 1.0;
    } else {
      axis = triple(ax, "--rotate AXIS", false);
      if (axis == glm::dvec3(0.0)) throw UsageError("--rotate AXIS must not be zero");
    }
    const auto deg = parse_double(rit->second[1]);
    if (!deg) throw UsageError("--rotate needs DEGREES as a finite number, got '" + rit->second[1] + "'");
    angle = *deg * std::numbers::pi / 180.0;
  }
  if (const auto sv = a.value("--scale")) factors = triple(*sv, "--scale", true);
  if (a.value("--pivot") && dit != a.lists.end()) throw UsageError("--pivot goes with --rotate or --scale");
  double falloff = 0.0;
  if (const auto f = a.value("--falloff")) {
    const auto r = parse_double(*f);
    if (!r || *r < 0) throw UsageError("--falloff must be a non-negative distance, got '" + *f + "'");
    falloff = *r;
  }
  std::vector<std::uint32_t> selected;
  for (const std::string& s : vit->second) selected.push_back(index_value(s));

  const std::string& in = a.positional[0];
  ProjectExtras extras;
  Hierarchy h = read_project(in, &extras);
  ImportReport topology;  // of the base the edit moves
  add_topology_warnings(topology, h.levels.front());
  std::cerr << topology.format(in);
  const int level = static_cast<int>(*lv);
  if (level > h.finest_level())
    throw UsageError("--level " + std::to_string(level) + " is beyond the project's finest level " +
                     std::to_string(h.finest_level()));
  const std::string out = output_option(a, is_project_path(*a.value("-o")) ? 0 : h.levels.front().dim);
  for (const std::uint32_t v : selected)
    if (v >= h.num_vertices(level))
      throw UsageError("--vertex " + std::to_string(v) + ": level " + std::to_string(level) + " has " +
                       std::to_string(h.num_vertices(level)) + " vertices");
  Session session(std::move(h), extras.gains);
  if (a.has("--local-frames") || extras.local_frames) session.set_detail_frames(DetailFrames::Local);
  const SoftWeights w = soft_selection(session.positions(level), selected, falloff);
  OpReport r;
  glm::dvec3 pivot(0.0);
  if (dit != a.lists.end()) {
    r = session.move(level, w.vertices, w.weights, delta);
  } else {
    const std::string p = a.value("--pivot").value_or("median");
    const std::vector<unsigned> sel(selected.begin(), selected.end());
    if (p == "median" || p == "active" || p == "origin") {
      pivot = pivot_point(parse_pivot(p), session.positions(level), sel, selected.back(), glm::dvec3(0.0));
    } else {
      pivot = triple(p, "--pivot", false);
    }
    const auto pos = session.positions(level);
    std::vector<double> start, deltas;
    for (const std::uint32_t v : w.vertices) start.insert(start.end(), pos.begin() + 3 * v, pos.begin() + 3 * v + 3);
    transform_deltas(start, pos, w.vertices, w.weights, pivot, axis, angle, factors, deltas);
    r = session.move_each(level, w.vertices, deltas);
  }

  std::vector<std::string> notes;
  if (is_project_path(out)) {
    extras.current_level = level;
    extras.gains.assign(session.gains().begin(), session.gains().end());
    extras.local_frames = session.detail_frames() == DetailFrames::Local;
    write_project(out, session.hierarchy(), extras);
  } else {
    const int J = session.finest_level();
    notes = write_level(out, session.hierarchy(), J, session.positions(J), 3, extras.input_order);
  }
  for (const std::string& n : notes) std::cerr << out << ": warning: " << n << "\n";
  if (a.has("--json")) {
    const nlohmann::json j = {{"input", in},
                              {"output", out},
                              {"level", level},
                              {"selected", selected.size()},
                              {"moved", w.vertices.size()},
                              {"transform", dit != a.lists.end() ? "move" : rit != a.lists.end() ? "rotate" : "scale"},
                              {"pivot", {pivot.x, pivot.y, pivot.z}},
                              {"detail_frames", session.detail_frames() == DetailFrames::Local ? "local" : "world"},
                              {"resynthesis_ms", r.resynthesis_ms},
                              {"vertices_updated", r.vertices_updated},
                              {"finest_vertices", session.num_vertices(session.finest_level())},
                              {"warnings", report_json(topology)},
                              {"notes", notes}};
    std::cout << j.dump(2) << "\n";
  }
  return 0;
}

}  // namespace sublift::cli
