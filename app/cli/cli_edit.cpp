// sublift-cli edit PROJECT --level L --vertex I [--vertex I ...] [--falloff R]
//             --delta DX DY DZ | --rotate AXIS DEGREES | --scale S  [--pivot P]
//             | --brush KIND --at X Y Z [--radius R] [--strength S] [--falloff-curve F]
//             [--mirror x|y|z]... [--local-frames] -o OUT [--json]
#include <algorithm>
#include <charconv>
#include <chrono>
#include <iostream>
#include <optional>
#include <numbers>

#include "app/cli/cli_args.h"
#include "app/cli/cli_commands.h"
#include "app/cli/cli_json.h"
#include "app/cli/cli_hierarchy.h"
#include "core/io/project/project_io.h"
#include "core/edit/attribute_channels.h"
#include "core/edit/session.h"
#include "core/base/errors.h"
#include "core/edit/brush.h"
#include "core/edit/selection.h"
#include "core/edit/symmetry.h"
#include "core/edit/transform.h"
#include "core/complex/complex.h"
#include "core/io/lattice/shape_io.h"
#include "core/base/text_lines.h"

namespace sublift::cli {
namespace {

constexpr const char* kHelp =
    "usage: sublift-cli edit PROJECT --level L --vertex I [--vertex I ...] [--falloff R]\n"
    "                   --delta DX DY DZ | --rotate AXIS DEGREES | --scale S [--pivot P]\n"
    "                   [--mirror x|y|z]... [--local-frames] -o OUT [--json]\n"
    "       sublift-cli edit PROJECT --level L --brush KIND --at X Y Z [--radius R] [--strength S]\n"
    "                   [--falloff-curve F] [--mirror x|y|z]... [--local-frames] -o OUT [--json]\n"
    "  Moves control points I of level L (indices in the engine's order of that level; level 0 is\n"
    "  the base file's order) by (DX, DY, DZ), or rotates or scales them about a pivot, as the\n"
    "  modeler's G, R and S do: finer levels are resynthesised locally from the stored wavelets,\n"
    "  coarser ones take the change by analysis.\n"
    "  --rotate AXIS DEGREES  AXIS x, y, z or AX,AY,AZ (right-handed about it)\n"
    "  --scale S    a factor, or SX,SY,SZ per axis (a negative one mirrors)\n"
    "  --pivot P    median (of the --vertex points; the default), active (the last --vertex),\n"
    "               origin, or a point X,Y,Z\n"
    "  --brush KIND one sculpt dab (draw, inflate, smooth, grab, flatten, pinch; docs/modeler.md)\n"
    "               centred at --at X Y Z on level L's net: --radius R (world units, default 0.1),\n"
    "               --strength S (0..1, default 0.5), --falloff-curve smooth|linear|sharp|constant;\n"
    "               grab moves by --delta DX DY DZ times the falloff\n"
    "  --loop A B, --ring A B, --linked V, --grow N  select as the modeler's Alt+click, Ctrl+Alt+click,\n"
    "               L and Ctrl+numpad + do (repeatable; added to the --vertex points): the edge loop\n"
    "               or ring through the edge A-B, everything joined to V, N more rings of neighbours\n"
    "  --mirror A   mirror editing across the world plane A = 0 (repeatable): the mirror images of\n"
    "               what moves move the mirrored way (found by position, then topology)\n"
    "  --falloff R  soft selection: points within distance R of a selected one move by\n"
    "               1 - smoothstep(d / R) of the delta (rotate by that part of the angle, scale\n"
    "               by that part of the factor)\n"
    "  --local-frames  keep detail in local frames of the coarser surface (surfaces only), so it\n"
    "               turns with the surface; default: world coordinates\n"
    "  OUT          a .sublift project (the edited session: coefficients, gains, level L), or the\n"
    "               finest level as a mesh by extension (.obj .off .ply .vtk .lattice .ovm)\n"
    "  --json       prints resynthesis_ms (the local resynthesis alone, no file I/O),\n"
    "               setup_ms (what opening pays once: the sparse indices, every level's\n"
    "               positions, the edit buffers) and vertices_updated; compare with\n"
    "               'synthesize --json' synthesis_ms\n";

std::uint32_t index_value(const std::string& s) {
  std::uint32_t v = 0;
  auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || p != s.data() + s.size()) throw UsageError("--vertex needs a non-negative index, got '" + s + "'");
  return v;
}

// "a,b,c" as three numbers (or one, repeated, when `one_is_all`).
glm::dvec3 triple(const std::string& s, const char* option, bool one_is_all) {
  std::vector<double> v = number_list(s, option);
  if (v.size() == 1 && one_is_all) v = {v[0], v[0], v[0]};
  if (v.size() != 3) throw UsageError(std::string(option) + " needs " + (one_is_all ? "one number or " : "") + "three numbers A,B,C, got '" + s + "'");
  return {v[0], v[1], v[2]};
}

}  // namespace

int run_edit(int argc, char** argv) {
  const Args a = parse_args(argc, argv, 2,
                            {"-o", "--level", "--falloff", "--scale", "--pivot", "--brush", "--radius", "--strength", "--falloff-curve", "--grow"},
                            {"--json", "--help", "--local-frames"},
                            {{"--vertex", 1}, {"--delta", 3}, {"--rotate", 2}, {"--at", 3}, {"--mirror", 1},
                             {"--loop", 2}, {"--ring", 2}, {"--linked", 1}});
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
  const auto brush_kind = a.value("--brush");
  // The selection: --vertex points, plus the modeler's selection tools (core/edit/selection.h).
  const bool selects = vit != a.lists.end() || a.lists.count("--loop") || a.lists.count("--ring") || a.lists.count("--linked");
  if (!selects && !brush_kind) throw UsageError("missing --vertex I (or --loop A B, --ring A B, --linked V, or --brush KIND --at X Y Z)");
  if (selects && brush_kind) throw UsageError("--brush dabs where --at says; leave out the selection");
  const auto dit = a.lists.find("--delta");
  const auto rit = a.lists.find("--rotate");
  const int kinds = (dit != a.lists.end()) + (rit != a.lists.end()) + (a.value("--scale").has_value());
  BrushSettings brush;
  Dab dab;
  dab.view_dir = glm::dvec3(0.0);  // no view: nothing is culled as back-facing
  if (brush_kind) {
    try {
      brush.kind = parse_brush(*brush_kind);
      if (const auto f = a.value("--falloff-curve")) brush.falloff = parse_falloff(*f);
    } catch (const Error& e) {
      throw UsageError(std::string("--brush: ") + e.what());
    }
    const auto at = a.lists.find("--at");
    if (at == a.lists.end() || at->second.size() != 3) throw UsageError("--brush needs --at X Y Z once");
    for (int c = 0; c < 3; ++c) {
      const auto d = parse_double(at->second[static_cast<std::size_t>(c)]);
      if (!d) throw UsageError("--at needs three finite numbers");
      dab.center[c] = *d;
    }
    if (const auto r = a.value("--radius")) {
      const auto v = parse_double(*r);
      if (!v || *v <= 0) throw UsageError("--radius must be a positive distance, got '" + *r + "'");
      brush.radius = *v;
    }
    if (const auto st = a.value("--strength")) {
      const auto v = parse_double(*st);
      if (!v || *v < 0 || *v > 1) throw UsageError("--strength must be in 0..1, got '" + *st + "'");
      brush.strength = *v;
    }
    if (rit != a.lists.end() || a.value("--scale")) throw UsageError("--brush takes no --rotate or --scale");
    if (brush.kind != BrushKind::Grab && dit != a.lists.end()) throw UsageError("--delta goes with --brush grab only");
    if (brush.kind == BrushKind::Grab && dit == a.lists.end()) throw UsageError("--brush grab needs --delta DX DY DZ");
  } else {
    if (kinds == 0) throw UsageError("missing --delta DX DY DZ, --rotate AXIS DEGREES or --scale S");
    if (kinds > 1) throw UsageError("give one of --delta, --rotate and --scale");
  }
  std::vector<int> mirror_axes;
  if (const auto it = a.lists.find("--mirror"); it != a.lists.end())
    for (const std::string& m : it->second) {
      if (m != "x" && m != "y" && m != "z") throw UsageError("--mirror takes x, y or z, got '" + m + "'");
      mirror_axes.push_back(m[0] - 'x');
    }
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
  if (vit != a.lists.end())
    for (const std::string& s : vit->second) selected.push_back(index_value(s));
  const long long active = selected.empty() ? -1 : static_cast<long long>(selected.back());  // the last --vertex

  const std::string& in = a.positional[0];
  ProjectExtras extras;
  Hierarchy h = read_project(in, &extras);
  // Attribute channels (colours, scalars) stay as they are: the session moves x, y, z.
  std::optional<Hierarchy> attributes;
  if (h.channels > 3) {
    attributes = channel_range(h, 3, h.channels - 3);
    h = channel_range(h, 0, 3);
  }
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
  {
    const Complex& c = h.levels[static_cast<std::size_t>(level)];
    Complex adj;  // the finest level is stored without its upward rows
    const Complex& cc = c.vertex_edges.rows() == c.num_vertices ? c : (adj = c, build_adjacency(adj), adj);
    auto vertex = [&](const std::string& s, const char* option) {
      const std::uint32_t v = index_value(s);
      if (v >= cc.num_vertices)
        throw UsageError(std::string(option) + " " + s + ": level " + std::to_string(level) + " has " + std::to_string(cc.num_vertices) + " vertices");
      return v;
    };
    for (const char* option : {"--loop", "--ring"})
      if (const auto it = a.lists.find(option); it != a.lists.end())
        for (std::size_t k = 0; k + 1 < it->second.size(); k += 2) {
          const std::int64_t e = find_edge(cc, vertex(it->second[k], option), vertex(it->second[k + 1], option));
          if (e < 0) throw UsageError(std::string(option) + " " + it->second[k] + " " + it->second[k + 1] + ": they share no edge");
          if (option[2] == 'r' && cc.dim != 2) throw UsageError("--ring is for surfaces");
          const auto edges = option[2] == 'l' ? edge_loop(cc, static_cast<std::uint32_t>(e)) : edge_ring(cc, static_cast<std::uint32_t>(e));
          for (const unsigned v : edge_vertices(cc, edges)) selected.push_back(v);
        }
    if (const auto it = a.lists.find("--linked"); it != a.lists.end())
      for (const std::string& s : it->second) {
        const unsigned one[1] = {vertex(s, "--linked")};
        for (const unsigned v : select_linked(cc, one)) selected.push_back(v);
      }
    if (const auto g = a.value("--grow")) {
      const auto n = parse_int(*g);
      if (!n || *n < 0 || *n > 1000) throw UsageError("--grow must be a number of rings 0..1000, got '" + *g + "'");
      std::vector<unsigned> sel(selected.begin(), selected.end());
      for (long i = 0; i < *n; ++i) sel = grow_selection(cc, sel);
      selected.assign(sel.begin(), sel.end());
    }
    std::sort(selected.begin(), selected.end());
    selected.erase(std::unique(selected.begin(), selected.end()), selected.end());
  }
  const auto open_t0 = std::chrono::steady_clock::now();
  Session session(std::move(h), extras.gains);  // builds the sparse indices and every level's positions
  const double open_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - open_t0).count();
  if (a.has("--local-frames") || extras.local_frames) session.set_detail_frames(DetailFrames::Local);
  const SoftWeights w = soft_selection(session.positions(level), selected, falloff);
  glm::dvec3 pivot(0.0);
  // Every kind of edit as per-point moves, mirrored when asked, then one move_each.
  std::vector<std::uint32_t> moved;
  std::vector<double> deltas;
  const auto pos = session.positions(level);
  if (brush_kind) {
    Complex c = session.hierarchy().levels[static_cast<std::size_t>(level)];
    build_adjacency(c);  // the finest level is stored without its upward rows
    dab.motion = glm::dvec3(delta[0], delta[1], delta[2]);
    brush_dab(brush, dab, c, pos, moved, deltas);
  } else if (dit != a.lists.end()) {
    moved = w.vertices;
    for (std::size_t k = 0; k < w.vertices.size(); ++k)
      for (int c = 0; c < 3; ++c) deltas.push_back(w.weights[k] * delta[c]);
  } else {
    const std::string p = a.value("--pivot").value_or("median");
    const std::vector<unsigned> sel(selected.begin(), selected.end());
    if (p == "median" || p == "active" || p == "origin") {
      pivot = pivot_point(parse_pivot(p), pos, sel, active, glm::dvec3(0.0));
    } else {
      pivot = triple(p, "--pivot", false);
    }
    std::vector<double> start;
    for (const std::uint32_t v : w.vertices) start.insert(start.end(), pos.begin() + 3 * v, pos.begin() + 3 * v + 3);
    moved = w.vertices;
    transform_deltas(start, pos, w.vertices, w.weights, pivot, axis, angle, factors, deltas);
  }
  std::vector<MirrorMap> maps;
  std::vector<std::string> mirror_problems;
  nlohmann::json mirror_maps = nlohmann::json::array();  // how each axis's images were found
  for (const int axis_index : mirror_axes) {
    maps.push_back(find_mirror(session.hierarchy().levels[static_cast<std::size_t>(level)], pos, axis_index));
    const MirrorMap& m = maps.back();
    if (!m.problem().empty()) mirror_problems.push_back(m.problem());
    mirror_maps.push_back({{"axis", std::string(1, "xyz"[axis_index])},
                           {"by_position", m.by_position},
                           {"by_topology", m.by_topology},
                           {"unmatched", m.unmatched}});
  }
  for (const std::string& p : mirror_problems) std::cerr << in << ": warning: " << p << "\n";
  std::vector<const MirrorMap*> map_ptrs;
  for (const MirrorMap& m : maps) map_ptrs.push_back(&m);
  const std::size_t own = moved.size();
  if (!map_ptrs.empty()) mirror_deltas(map_ptrs, moved, deltas);
  const OpReport r = session.move_each(level, moved, deltas);

  std::vector<std::string> notes;
  if (is_project_path(out)) {
    extras.current_level = level;
    extras.gains.assign(session.gains().begin(), session.gains().end());
    extras.local_frames = session.detail_frames() == DetailFrames::Local;
    write_project(out, attributes ? merge_channels(session.hierarchy(), *attributes) : session.hierarchy(), extras);
  } else if (attributes) {  // the level with its attributes, the project's gains on every channel
    const int J = session.finest_level();
    Hierarchy shown = *attributes;
    apply_gains(shown, session.gains());
    const std::vector<VertexAttribute> at = attributes_of(synthesize(shown, J), attributes->channels, extras.attributes, 0);
    notes = write_level(out, merge_channels(session.hierarchy(), *attributes), J, with_attributes(session.positions(J), at),
                        3 + attributes->channels, extras.input_order, extras.attributes, &extras.uv);
  } else {
    const int J = session.finest_level();
    notes = write_level(out, session.hierarchy(), J, session.positions(J), 3, extras.input_order, {}, &extras.uv);
  }
  for (const std::string& n : notes) std::cerr << out << ": warning: " << n << "\n";
  if (a.has("--json")) {
    const nlohmann::json j = {{"input", in},
                              {"output", out},
                              {"level", level},
                              {"selected", selected.size()},
                              {"moved", own},
                              {"mirrored", moved.size() - own},
                              {"mirror_problems", mirror_problems},
                              {"mirror_maps", mirror_maps},
                              {"transform", brush_kind ? std::string("brush ") + brush_name(brush.kind)
                                            : dit != a.lists.end() ? std::string("move")
                                            : rit != a.lists.end() ? std::string("rotate") : std::string("scale")},
                              {"pivot", {pivot.x, pivot.y, pivot.z}},
                              {"detail_frames", session.detail_frames() == DetailFrames::Local ? "local" : "world"},
                              {"resynthesis_ms", r.resynthesis_ms},
                              {"setup_ms", open_ms + r.setup_ms},
                              {"vertices_updated", r.vertices_updated},
                              {"finest_vertices", session.num_vertices(session.finest_level())},
                              {"warnings", report_json(topology)},
                              {"notes", notes}};
    std::cout << j.dump(2) << "\n";
  }
  return 0;
}

}  // namespace sublift::cli
