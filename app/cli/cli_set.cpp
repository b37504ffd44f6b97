// sublift-cli set PROJECT [--scheme S] [--subdivide N] [--delete-higher L] [--delete-lower L]
//                 [--crease A B]... [--uncrease A B]... [--corner V]... [--uncorner V]... [--gain L F]... [--frames world|local] [--level L] -o OUT [--json]
// The session state the modeler's panel sets, on a project: what the Scheme menu, Subdivide
// (Ctrl+D), the level gains, World/Local and the edit level do, in that order.
#include <iostream>
#include <optional>

#include "app/cli/cli_args.h"
#include "app/cli/cli_commands.h"
#include "app/cli/cli_hierarchy.h"
#include "core/edit/attribute_channels.h"
#include "core/multires/level_uv.h"
#include "app/cli/cli_json.h"
#include "core/base/errors.h"
#include "core/base/text_lines.h"
#include "core/complex/feature_tags.h"
#include "core/edit/features.h"
#include "core/edit/level_ops.h"
#include "core/edit/selection.h"
#include "core/edit/scheme_switch.h"
#include "core/edit/session.h"
#include "core/io/project/project_io.h"

namespace sublift::cli {

namespace {

constexpr const char* kHelp =
    "usage: sublift-cli set PROJECT [--scheme S] [--subdivide N] [--delete-higher L] [--delete-lower L]\n"
    "                   [--crease A B]... [--uncrease A B]... [--corner V]... [--uncorner V]... [--gain L F]... [--frames world|local] [--level L] -o OUT [--json]\n"
    "  Changes a project's session as the modeler's panel does, in this order:\n"
    "  --scheme S        linear, cubic, sqrt2, linear-tri, butterfly or loop. Between schemes of\n"
    "                    the same refinement (linear/cubic; the three triangle schemes) the shape\n"
    "                    is kept: the finest level, gains applied, is analysed by the new scheme\n"
    "                    (gains become 1). To or from sqrt2 the levels start from the base\n"
    "                    without the detail (a note says so). The same finest resolution.\n"
    "  --subdivide N     adds N levels with zero detail (the shape kept, one level finer)\n"
    "  --delete-higher L keeps levels 0..L (level L becomes the finest, unchanged)\n"
    "  --delete-lower L  makes level L the base: the coarser levels go, every finer level stays as\n"
    "                    it was (levels renumbered from 0; gains of the levels below L go)\n"
    "  --crease A B      crease the base edge A-B (repeatable; --uncrease A B clears one);\n"
    "  --corner V        make base vertex V a corner (repeatable; --uncorner V clears one): the\n"
    "                    hierarchy is rebuilt on the base's new features and the finest level as\n"
    "                    shown is analysed by the new rules (shape and detail kept, gains 1)\n"
    "  --gain L F        the detail gain of level L's wavelets (repeatable; 0 mutes, 1 as analysed)\n"
    "  --frames F        world or local detail frames (local: surfaces only)\n"
    "  --level L         the edit level the modeler opens at\n"
    "  OUT               a .sublift project, or the finest level (as shown, gains applied) as a\n"
    "                    mesh or lattice by extension\n"
    "  --json            the resulting levels, gains, frames, level and notes\n";

int count(const std::string& s, const char* what, long lo, long hi) {
  const auto v = parse_int(s);
  if (!v || *v < lo || *v > hi)
    throw UsageError(std::string(what) + " must be a whole number in " + std::to_string(lo) + ".." + std::to_string(hi) +
                     ", got '" + s + "'");
  return static_cast<int>(*v);
}

}  // namespace

int run_set(int argc, char** argv) {
  const Args a = parse_args(argc, argv, 2,
                            {"-o", "--scheme", "--subdivide", "--frames", "--level", "--delete-higher", "--delete-lower"},
                            {"--json", "--help"},
                            {{"--gain", 2}, {"--crease", 2}, {"--uncrease", 2}, {"--corner", 1}, {"--uncorner", 1}});
  if (a.has("--help")) {
    std::cout << kHelp;
    return 0;
  }
  if (a.positional.size() != 1) throw UsageError("expected exactly one PROJECT file");
  if (!a.value("-o")) throw UsageError("missing -o OUT");
  std::optional<Scheme> scheme;
  if (const auto s = a.value("--scheme")) {
    try {
      scheme = parse_scheme(*s);
    } catch (const std::invalid_argument&) {
      throw UsageError("--scheme must be " + scheme_names_list() + ", got '" + *s + "'");
    }
  }
  const int subdivide = a.value("--subdivide") ? count(*a.value("--subdivide"), "--subdivide", 1, 2 * kMaxLevels) : 0;
  std::optional<bool> local;
  if (const auto f = a.value("--frames")) {
    if (*f != "world" && *f != "local") throw UsageError("--frames must be world or local, got '" + *f + "'");
    local = *f == "local";
  }
  const std::string& in = a.positional[0];
  ProjectExtras extras;
  Hierarchy h = read_project(in, &extras);
  const std::string out = output_option(a, is_project_path(*a.value("-o")) ? 0 : h.levels.front().dim);
  if (h.integer) throw Error(in + ": an integer project has no session to set (gains, frames and edits need real coefficients)");

  std::vector<std::string> notes;
  // Attribute channels stay beside the session (attribute_channels.h), fitted to it at the end.
  std::optional<Hierarchy> attributes;
  if (h.channels > 3) {
    attributes = channel_range(h, 3, h.channels - 3);
    h = channel_range(h, 0, 3);
  }
  auto session = std::make_unique<Session>(std::move(h), extras.gains);
  if (extras.local_frames) session->set_detail_frames(DetailFrames::Local);
  int level = extras.current_level;
  if (scheme && *scheme != session->hierarchy().scheme) {
    const Scheme from = session->hierarchy().scheme;
    SchemeSwitch next = switch_scheme(*session, *scheme);
    if (!next.kept_detail) {
      notes.push_back("the " + scheme_name(*scheme) + " scheme refines differently from " + scheme_name(from) +
                      ": its levels start from the base, without the detail");
      if (!extras.input_order.empty())  // the file's vertex order belongs to the old levels
        notes.push_back("the vertex order of the file the project was rebuilt from is not kept (its levels are gone)");
      extras.input_order = {};
    }
    const bool was_local = session->detail_frames() == DetailFrames::Local;
    session = std::make_unique<Session>(std::move(next.hierarchy));
    if (was_local) session->set_detail_frames(DetailFrames::Local);
    level = level_under_scheme(level, from, *scheme);
    if (!extras.uv.empty() && !uv_refinement_problem(*scheme).empty()) {
      notes.push_back("texture coordinates not kept: " + uv_refinement_problem(*scheme));
      extras.uv = {};
    }
  }
  for (int i = 0; i < subdivide; ++i) session->subdivide();
  // Level deletions (core/edit/level_ops.h), as the modeler's Delete higher / Delete lower.
  auto replace = [&](Hierarchy next, std::vector<double> gains) {
    const bool was_local = session->detail_frames() == DetailFrames::Local;
    session = std::make_unique<Session>(std::move(next), std::move(gains));
    if (was_local) session->set_detail_frames(DetailFrames::Local);
  };
  if (const auto v = a.value("--delete-higher")) {
    const int L = count(*v, "--delete-higher", 0, session->finest_level());
    if (extras.input_order.level > L && !extras.input_order.empty()) {
      notes.push_back("the vertex order of the file the project was rebuilt from belonged to a deleted level and is not kept");
      extras.input_order = {};
    }
    replace(delete_higher(session->hierarchy(), L), std::vector<double>(session->gains().begin(), session->gains().begin() + L));
    level = std::min(level, L);
  }
  if (const auto v = a.value("--delete-lower")) {
    const int L = count(*v, "--delete-lower", 0, session->finest_level());
    if (!extras.input_order.empty()) {
      if (extras.input_order.level >= L) {
        extras.input_order.level -= L;
      } else {
        notes.push_back("the vertex order of the file the project was rebuilt from belonged to a deleted level and is not kept");
        extras.input_order = {};
      }
    }
    if (L > 0 && !extras.fit_source.empty()) {
      notes.push_back("the fit's map from the old base to the mesh it was fitted to is not kept");
      extras.fit_source = {};
    }
    if (!extras.uv.empty()) extras.uv = uv_at_level(session->hierarchy(), extras.uv, L);  // level L's are the new base's
    if (attributes) {  // level L's attribute net becomes their base too
      std::string why;
      if (std::optional<Hierarchy> fitted = attributes_for(*attributes, session->hierarchy(), &why)) {
        Hierarchy shown = *fitted;
        apply_gains(shown, session->gains());
        attributes = delete_lower(*fitted, L, synthesize(shown, L));
      } else {
        notes.push_back("vertex attributes not kept: " + why);
        attributes.reset();
        extras.attributes.clear();
      }
    }
    replace(delete_lower(session->hierarchy(), L, session->positions(L)),
            std::vector<double>(session->gains().begin() + L, session->gains().end()));
    level = std::max(level - L, 0);
  }
  // Features of the base (core/edit/features.h), as the modeler's Shift+E / Ctrl+Shift+E.
  {
    const Complex& base = session->hierarchy().levels.front();
    auto vertex = [&](const std::string& s, const char* what) {
      return static_cast<std::uint32_t>(count(s, what, 0, static_cast<long>(base.num_vertices) - 1));
    };
    auto edges_of = [&](const char* option) {
      std::vector<std::uint32_t> edges;
      if (const auto it = a.lists.find(option); it != a.lists.end())
        for (std::size_t k = 0; k + 1 < it->second.size(); k += 2) {
          const std::uint32_t u = vertex(it->second[k], option), v = vertex(it->second[k + 1], option);
          const std::int64_t e = find_edge(base, u, v);
          if (e < 0) throw UsageError(std::string(option) + " " + it->second[k] + " " + it->second[k + 1] + ": no base edge joins them");
          edges.push_back(static_cast<std::uint32_t>(e));
        }
      return edges;
    };
    auto vertices_of = [&](const char* option) {
      std::vector<unsigned> vs;
      if (const auto it = a.lists.find(option); it != a.lists.end())
        for (const std::string& s : it->second) vs.push_back(vertex(s, option));
      return vs;
    };
    const auto crease = edges_of("--crease"), uncrease = edges_of("--uncrease");
    const auto corner = vertices_of("--corner"), uncorner = vertices_of("--uncorner");
    if (!crease.empty() || !uncrease.empty() || !corner.empty() || !uncorner.empty()) {
      if (base.dim != 2 && (!crease.empty() || !uncrease.empty()))
        throw UsageError("--crease and --uncrease are for surfaces (a lattice's features come from its file's tags)");
      FeatureTags tags = derive_feature_tags(base);
      tags = with_creases(base, std::move(tags), uncrease, false);
      tags = with_creases(base, std::move(tags), crease, true);
      tags = with_corners(std::move(tags), uncorner, false);
      tags = with_corners(std::move(tags), corner, true);
      replace(with_base_features(*session, tags), {});
      notes.push_back("features changed: the finest level as shown is analysed on the new base (gains are now 1)");
    }
  }
  if (const auto it = a.lists.find("--gain"); it != a.lists.end()) {
    for (std::size_t k = 0; k + 1 < it->second.size(); k += 2) {
      const int l = count(it->second[k], "--gain L", 0, session->finest_level() - 1);
      const auto f = parse_double(it->second[k + 1]);
      if (!f) throw UsageError("--gain F must be a number, got '" + it->second[k + 1] + "'");
      session->set_gain(l, *f);
    }
  }
  if (local) session->set_detail_frames(*local ? DetailFrames::Local : DetailFrames::World);
  if (const auto l = a.value("--level")) level = count(*l, "--level", 0, session->finest_level());
  level = std::min(level, session->finest_level());

  const int J = session->finest_level();
  std::optional<Hierarchy> merged;  // the session with the attribute channels fitted to it
  if (attributes) {
    std::string why;
    if (const std::optional<Hierarchy> fitted = attributes_for(*attributes, session->hierarchy(), &why)) {
      merged = merge_channels(session->hierarchy(), *fitted);
    } else {
      notes.push_back("vertex attributes not kept: " + why);
      extras.attributes.clear();
    }
  }
  if (is_project_path(out)) {
    extras.current_level = level;
    extras.gains.assign(session->gains().begin(), session->gains().end());
    extras.local_frames = session->detail_frames() == DetailFrames::Local;
    write_project(out, merged ? *merged : session->hierarchy(), extras);
  } else if (merged) {
    Hierarchy shown = *merged;
    apply_gains(shown, session->gains());
    for (const std::string& n : write_level(out, *merged, J, synthesize(shown, J), merged->channels, extras.input_order, extras.attributes, &extras.uv))
      notes.push_back(n);
  } else {
    for (const std::string& n : write_level(out, session->hierarchy(), J, session->positions(J), 3, extras.input_order, {}, &extras.uv))
      notes.push_back(n);
  }
  for (const std::string& n : notes) std::cerr << out << ": note: " << n << "\n";
  if (a.has("--json")) {
    const nlohmann::json j = {{"input", in},
                              {"output", out},
                              {"scheme", scheme_name(session->hierarchy().scheme)},
                              {"levels", J},
                              {"finest_vertices", session->num_vertices(J)},
                              {"gains", std::vector<double>(session->gains().begin(), session->gains().end())},
                              {"detail_frames", session->detail_frames() == DetailFrames::Local ? "local" : "world"},
                              {"level", level},
                              {"notes", notes}};
    std::cout << j.dump(2) << "\n";
  }
  return 0;
}

}  // namespace sublift::cli
