#include "app/modeler/script_runner.h"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <fstream>
#include <new>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <utility>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "core/base/errors.h"
#include "core/edit/selection.h"

namespace sublift {
namespace {

// A command's own mistake (bad arguments); reported like any other failure.
struct ScriptError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

double number(const std::string& word, const char* what) {
  double v = 0.0;
  const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), v);
  if (error != std::errc() || end != word.data() + word.size() || !std::isfinite(v)) {
    throw ScriptError(std::string(what) + " must be a number, got '" + word + "'");
  }
  return v;
}

long long integer(const std::string& word, const char* what) {
  long long v = 0;
  const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), v);
  if (error != std::errc() || end != word.data() + word.size()) {
    throw ScriptError(std::string(what) + " must be a whole number, got '" + word + "'");
  }
  return v;
}

// The rest of the line after the command word: paths may contain spaces.
std::string rest_of(const std::string& line, const std::string& command) {
  std::size_t at = line.find(command) + command.size();
  while (at < line.size() && (line[at] == ' ' || line[at] == '\t')) ++at;
  std::string out = line.substr(at);
  while (!out.empty() && (out.back() == ' ' || out.back() == '\t' || out.back() == '\r')) out.pop_back();
  return out;
}

// What a handler gets: the words (w[0] is the command), the raw rest of the line and what it may change.
struct Call {
  const std::vector<std::string>& w;
  const std::string& raw;
  ModelerState& state;
  ModelerDisplay& show;
  ScriptStep& step;
  const char* usage;
  [[noreturn]] void usage_error() const { throw ScriptError(std::string("usage: ") + usage); }
};

constexpr int kMany = 1 << 30;  // max: no upper limit on the argument words
constexpr int kPath = -1;       // min: the raw rest of the line must not be empty (max unused)
struct Command {
  const char* name;
  int min, max;       // argument words allowed, else "usage: " + usage
  const char* usage;
  void (*run)(const Call&);
  bool needs_model = true;
};

void ffd(const Call& c) {
  const std::vector<std::string>& w = c.w;
  ModelerState& state = c.state;
  if (w[1] == "unbind" && w.size() == 2) return state.unbind_model();
  if (w[1] == "remove" && w.size() == 2) return state.remove_model();
  if (w[1] == "export" && w.size() >= 3) return state.export_model(c.raw.substr(c.raw.find("export") + 7));
  if (w[1] == "bind" && w.size() <= 3) {
    if (w.size() == 3 && w[2] != "nearest") throw ScriptError("ffd bind takes 'nearest' or nothing, got '" + w[2] + "'");
    return state.bind_model(w.size() == 3 ? Outside::Nearest : Outside::Stay);
  }
  if (w[1] != "box" || (w.size() != 5 && w.size() != 6)) c.usage_error();
  int n[3];
  for (std::size_t k = 0; k < 3; ++k) {
    const long long v = integer(w[2 + k], "cell count");
    if (v < 1 || v > 64) throw ScriptError("cell counts must be 1..64, got " + w[2 + k]);
    n[k] = static_cast<int>(v);
  }
  const double margin = w.size() == 6 ? number(w[5], "MARGIN") : 0.05;
  if (margin < 0.0) throw ScriptError("MARGIN must not be negative");
  state.wrap_model_in_box(n[0], n[1], n[2], margin);
  c.step.reframe = true;
}

// animation open [cyclic] [levels J] [frames N] [clip A] [fps F] PATH... (paths without spaces;
// one glTF or two or more OBJ/PLY/OFF frames) | frame F | ghosts N | play | pause | export PATH
void animation(const Call& c) {
  const std::vector<std::string>& w = c.w;
  ModelerState& state = c.state;
  if (w[1] == "open") {
    AnimationOptions o;
    std::vector<std::string> paths;
    for (std::size_t i = 2; i < w.size(); ++i) {
      const std::string& k = w[i];
      const bool has_value = i + 1 < w.size();
      if (k == "cyclic") o.cyclic = true;
      else if (k == "levels" && has_value) o.levels = int(integer(w[++i], "J"));
      else if (k == "frames" && has_value) o.frames = int(integer(w[++i], "N"));
      else if (k == "clip" && has_value) o.animation = int(integer(w[++i], "A"));
      else if (k == "fps" && has_value) o.fps = number(w[++i], "F");
      else paths.push_back(k);
    }
    if (paths.empty()) c.usage_error();
    if (o.levels < 1 || o.levels > 6) throw ScriptError("levels must be 1..6");
    state.open_animation(paths, o);
    c.step.reframe = true;
    return;
  }
  if (!state.has_session()) throw ScriptError("no animation is open ('animation open PATH...')");
  if (w[1] == "frame" && w.size() == 3) return state.set_frame(number(w[2], "F"));
  if (w[1] == "ghosts" && w.size() == 3) return state.set_ghosts(int(integer(w[2], "N")));
  if (w[1] == "play" && w.size() == 2) return state.set_playing(true);
  if (w[1] == "pause" && w.size() == 2) return state.set_playing(false);
  if (w[1] == "export" && w.size() >= 3) {
    state.export_animation(c.raw.substr(c.raw.find("export") + 7));
    return;
  }
  c.usage_error();
}

void colour(const Call& c) {
  if (c.w[1] == "off") {
    c.state.set_colour_channel(-1);
    return c.state.set_colour_level(-1);
  }
  if (c.w[1] == "channel") {  // colour channel NAME: an attribute channel through viridis
    if (c.w.size() != 3) throw ScriptError("colour channel NAME needs the channel's name");
    const auto& names = c.state.attribute_names();
    std::string all;
    for (std::size_t k = 0; k < names.size(); ++k) {
      if (names[k].name == c.w[2]) return c.state.set_colour_channel(int(k));
      all += (k ? ", " : "") + names[k].name;
    }
    throw ScriptError("no attribute channel '" + c.w[2] + "'" + (all.empty() ? " (the model has none)" : " (the model's: " + all + ")"));
  }
  const long long l = integer(c.w[1], "LEVEL");
  const int top = c.state.session().finest_level() - 1;
  if (l < 0 || l > top) throw ScriptError("colour level " + c.w[1] + " is outside 0.." + std::to_string(top));
  c.state.set_colour_level(static_cast<int>(l));
}

void basis(const Call& c) {
  const std::vector<std::string>& w = c.w;
  ModelerState& state = c.state;
  if (w.size() == 2 && w[1] == "off") return state.set_basis(BasisSettings{});
  if (w.size() == 2 && w[1] == "pin") return state.pin_basis();
  if (w.size() == 2 && w[1] == "unpin") return state.clear_pin();
  auto current = [&](const char* what) {
    if (!state.basis_on()) throw ScriptError(std::string("basis ") + what + " needs the basis mode on (use 'basis scaling|wavelet INDEX')");
    return state.basis_settings();
  };
  auto fraction = [&](const std::string& word, const char* name) {
    const double f = number(word, name);
    if (f < 0.0 || f > 1.0) throw ScriptError(std::string(name) + " must be in 0..1, got " + word);
    return f;
  };
  if (w.size() >= 3 && w[1] == "slice") {
    BasisSettings b = current("slice");
    if (w.size() == 3 && w[2] == "off") {
      b.slice_axis = -1;
    } else if (w.size() == 4 && (w[2] == "x" || w[2] == "y" || w[2] == "z")) {
      b.slice_axis = w[2][0] - 'x';
      b.slice_pos = fraction(w[3], "FRACTION");
    } else {
      throw ScriptError("usage: basis slice x|y|z FRACTION | basis slice off");
    }
    if (state.dim() != 3) throw ScriptError("basis slice needs a lattice");
    return state.set_basis(b);
  }
  if (w.size() == 3 && w[1] == "iso") {
    BasisSettings b = current("iso");
    if (state.dim() != 3) throw ScriptError("basis iso needs a lattice");
    b.iso = w[2] != "off";
    if (b.iso) b.iso_level = fraction(w[2], "FRACTION");
    return state.set_basis(b);
  }
  if (w.size() == 3 && w[1] == "follow") {
    if (w[2] != "on" && w[2] != "off") throw ScriptError("basis follow takes 'on' or 'off', got '" + w[2] + "'");
    BasisSettings b = current("follow");
    b.follow = w[2] == "on";
    return state.set_basis(b);
  }
  if (w.size() == 3 && w[1] == "height") {
    BasisSettings b = current("height");
    if (w[2] == "off") {
      b.height = false;
    } else {
      const double scale = number(w[2], "SCALE");
      if (scale < 0.0) throw ScriptError("SCALE must not be negative");
      b.height = scale > 0.0;
      if (scale > 0.0) b.height_scale = scale;
    }
    return state.set_basis(b);
  }
  if (w.size() < 3 || w.size() > 4 || (w[1] != "scaling" && w[1] != "wavelet")) c.usage_error();
  if (w.size() == 4 && w[3] != "dual") throw ScriptError("basis takes 'dual' after the index, got '" + w[3] + "'");
  const long long index = integer(w[2], "INDEX");
  const Complex& cj = state.session().hierarchy().levels[static_cast<std::size_t>(state.level())];
  const long long nv = cj.num_vertices, nc = static_cast<long long>(predicted_level_counts(cj, 1, state.session().hierarchy().scheme, state.level()).back());
  BasisSettings b = state.basis_on() ? state.basis_settings() : BasisSettings{};
  b.on = true;
  b.request.kind = w[1] == "scaling" ? BasisKind::Scaling : BasisKind::Wavelet;
  b.request.dual = w.size() == 4;
  if (b.request.kind == BasisKind::Scaling && (index < 0 || index >= nv)) {
    throw ScriptError("scaling index " + w[2] + " is outside 0.." + std::to_string(nv - 1) + " of level " +
                      std::to_string(state.level()));
  }
  if (b.request.kind == BasisKind::Wavelet && (index < nv || index >= nc)) {
    throw ScriptError("wavelet index " + w[2] + " is outside " + std::to_string(nv) + ".." + std::to_string(nc - 1) +
                      " (e/f/c vertices of level " + std::to_string(state.level() + 1) + ")");
  }
  b.request.index = static_cast<std::uint32_t>(index);
  b.request.level = state.level();
  state.set_basis(b);
}

// The work of a begun drag (move, transform, stroke) as one history entry: cancelled when it
// fails, so no half-applied edit stays in the history.
template <class Work>
void as_one_drag(ModelerState& state, Work work) {
  try {
    work();
  } catch (...) {
    state.cancel_drag();
    throw;
  }
  state.end_drag();
}

// rotate and scale: one transform of the selection.
void transform(const Call& c, TransformMode mode, const glm::dvec3& axis, double angle, const glm::dvec3& factors) {
  if (c.state.selection().empty())
    throw ScriptError(std::string(mode == TransformMode::Rotate ? "rotate" : "scale") + " needs a selection (use 'select INDEX...')");
  c.state.begin_transform(mode);
  as_one_drag(c.state, [&] { c.state.transform_to(axis, angle, factors); });
}

Scheme script_scheme(const std::string& name) {
  try {
    return parse_scheme(name);
  } catch (const std::exception&) {
    throw ScriptError("unknown scheme '" + name + "' (" + scheme_names_list() + ")");
  }
}

// One entry per command, in the order `sublift --help` lists them. Handlers run after the
// argument count passed, so they index w[1..min] freely.
constexpr Command kCommands[] = {
    {"open", kPath, 0, "open PATH", [](const Call& c) { c.state.open(c.raw); c.step.reframe = true; }, false},
    {"model", kPath, 0, "model PATH", [](const Call& c) { c.state.load_model(c.raw); c.step.reframe = true; }, false},
    {"ffd", 1, kMany, "ffd box NX NY NZ [MARGIN] | ffd bind [nearest] | ffd unbind | ffd remove | ffd export PATH", ffd},
    {"animation", 1, kMany,
     "animation open [cyclic] [levels J] [frames N] [clip A] [fps F] PATH... | animation frame F | animation ghosts N | "
     "animation play|pause | animation export PATH",
     animation, false},
    {"scheme", 1, 1, "scheme linear|cubic|sqrt2|linear-tri|butterfly|loop", [](const Call& c) {
      c.state.set_scheme(script_scheme(c.w[1]));
    }},
    {"subdivide", 0, 1, "subdivide [N]", [](const Call& c) {
      const long long n = c.w.size() == 2 ? integer(c.w[1], "N") : 1;
      if (n < 1 || n > 12) throw ScriptError("subdivide N needs N from 1 to 12");
      for (long long i = 0; i < n; ++i) c.state.subdivide();
    }},
    {"rebuild", 0, 1, "rebuild [N|max]", [](const Call& c) {
      long long n = -1;
      if (c.w.size() == 2 && c.w[1] != "max") {
        n = integer(c.w[1], "N");
        if (n < 1 || n > 24) throw ScriptError("rebuild N needs N from 1 to 24, or max");
      }
      c.state.rebuild_levels(static_cast<int>(n));
    }},
    {"fit", 0, 3, "fit [BASE_VERTICES [LEVELS [SCHEME]]]", [](const Call& c) {
      ModelerState::FitSettings s;
      if (c.w.size() == 4) s.scheme = script_scheme(c.w[3]);
      const long long n = c.w.size() >= 2 ? integer(c.w[1], "BASE_VERTICES") : 0;
      const long long l = c.w.size() >= 3 ? integer(c.w[2], "LEVELS") : 0;
      const int most = 6 * scheme_levels_per_split(s.scheme);
      if (n < 0 || n > 10000000) throw ScriptError("fit BASE_VERTICES needs 0 (the default size) to 10000000");
      if (l < 0 || l > most) throw ScriptError("fit LEVELS needs 0 (to about the mesh's vertex count) to " + std::to_string(most));
      s.base_vertices = static_cast<std::uint32_t>(n);
      s.levels = static_cast<int>(l);
      c.state.fit_base(s);
    }},
    {"fit-preview", 0, 3, "fit-preview [BASE_VERTICES [FEATURE_ANGLE [SCHEME]]] | fit-preview off", [](const Call& c) {
      if (c.w.size() == 2 && c.w[1] == "off") return c.state.clear_fit_preview();
      ModelerState::FitSettings s;
      const long long n = c.w.size() >= 2 ? integer(c.w[1], "BASE_VERTICES") : 0;
      if (n < 0 || n > 10000000) throw ScriptError("fit-preview BASE_VERTICES needs 0 (the default size) to 10000000");
      s.base_vertices = static_cast<std::uint32_t>(n);
      if (c.w.size() >= 3) {
        const double a = number(c.w[2], "FEATURE_ANGLE");
        if (!(a > 0 && a < 180)) throw ScriptError("fit-preview FEATURE_ANGLE needs degrees in (0, 180)");
        s.feature_angle_deg = a;
      }
      if (c.w.size() == 4) s.scheme = script_scheme(c.w[3]);
      c.state.preview_fit(s);
    }},
    {"level", 1, 1, "level L", [](const Call& c) {
      const long long l = integer(c.w[1], "L");
      const int finest = c.state.session().finest_level();
      if (l < 0 || l > finest) throw ScriptError("level " + c.w[1] + " is outside 0.." + std::to_string(finest));
      c.state.set_level(static_cast<int>(l));
    }},
    {"view-level", 1, 1, "view-level L|finest", [](const Call& c) {
      if (c.w[1] == "finest") return c.state.set_view_level(-1);
      const long long l = integer(c.w[1], "L");
      const int finest = c.state.session().finest_level();
      if (l < 0 || l > finest) throw ScriptError("view-level " + c.w[1] + " is outside 0.." + std::to_string(finest) + " (or finest)");
      c.state.set_view_level(static_cast<int>(l));
    }},
    {"select", 0, kMany, "select [INDEX...] (an animation: points of the layer shown) | select all|none|invert|more|less|linked | select loop|ring A B [add]", [](const Call& c) {
      using Op = ModelerState::SelectOp;
      static constexpr std::pair<const char*, Op> kOps[] = {
          {"invert", Op::Invert}, {"more", Op::More}, {"less", Op::Less}, {"linked", Op::Linked}};
      if (c.w.size() == 2) {
        if (c.w[1] == "all") return c.state.select_all();
        if (c.w[1] == "none") return c.state.set_selection({});
        for (const auto& [name, op] : kOps)
          if (c.w[1] == name) return c.state.select_op(op);
      }
      if (c.w.size() >= 2 && (c.w[1] == "loop" || c.w[1] == "ring")) {
        if (c.w.size() != 4 && !(c.w.size() == 5 && c.w[4] == "add")) c.usage_error();
        const long long n = c.state.session().num_vertices(c.state.level());
        const long long a = integer(c.w[2], "A"), b = integer(c.w[3], "B");
        if (a < 0 || a >= n || b < 0 || b >= n)
          throw ScriptError("select " + c.w[1] + ": vertices must be in 0.." + std::to_string(n - 1) + " of level " +
                            std::to_string(c.state.level()));
        const std::int64_t e = find_edge(c.state.level_complex(), static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(b));
        if (e < 0) throw ScriptError("select " + c.w[1] + ": vertices " + c.w[2] + " and " + c.w[3] + " share no edge");
        return c.state.select_loop(static_cast<std::uint32_t>(e), c.w[1] == "ring", c.w.size() == 5);
      }
      std::vector<unsigned> sel;
      // An animation numbers the points of the layer shown (the surface's vertices of the level).
      const AnimationViewState* anim = c.state.animation();
      const long long n = anim ? anim->anim.st.surface_vertices(c.state.level()) : c.state.session().num_vertices(c.state.level());
      for (std::size_t i = 1; i < c.w.size(); ++i) {
        const long long v = integer(c.w[i], "INDEX");
        if (v < 0 || v >= n) {
          throw ScriptError("vertex " + c.w[i] + " is outside 0.." + std::to_string(n - 1) + " of level " +
                            std::to_string(c.state.level()) + (anim ? "'s layer shown" : ""));
        }
        sel.push_back(anim ? anim->anim.st.layer_vertices[std::size_t(c.state.level())][std::size_t(anim->layer) * std::size_t(n) + std::size_t(v)]
                           : static_cast<unsigned>(v));
      }
      c.state.set_selection(std::move(sel));
    }},
    {"soft", 1, 1, "soft RADIUS", [](const Call& c) {
      const double r = number(c.w[1], "RADIUS");
      if (r < 0.0) throw ScriptError("RADIUS must not be negative");
      c.state.set_soft_radius(r);
    }},
    {"move", 3, 3, "move DX DY DZ", [](const Call& c) {
      if (c.state.selection().empty()) throw ScriptError("move needs a selection (use 'select INDEX...')");
      const double d[3] = {number(c.w[1], "DX"), number(c.w[2], "DY"), number(c.w[3], "DZ")};
      c.state.begin_drag("Move");
      as_one_drag(c.state, [&] { c.state.drag_to(d); });
    }},
    {"rotate", 2, 4, "rotate x|y|z DEGREES | rotate AX AY AZ DEGREES", [](const Call& c) {
      glm::dvec3 axis(0.0);
      if (c.w.size() == 3) {
        if (c.w[1] != "x" && c.w[1] != "y" && c.w[1] != "z") throw ScriptError("rotate axis must be x, y, z or three numbers");
        axis[c.w[1][0] - 'x'] = 1.0;
      } else if (c.w.size() == 5) {
        axis = {number(c.w[1], "AX"), number(c.w[2], "AY"), number(c.w[3], "AZ")};
        if (glm::length(axis) == 0.0) throw ScriptError("the rotation axis must not be zero");
      } else {
        c.usage_error();
      }
      const double deg = number(c.w.back(), "DEGREES");
      transform(c, TransformMode::Rotate, axis, deg * std::numbers::pi / 180.0, glm::dvec3(1.0));
    }},
    {"scale", 1, 3, "scale S | scale SX SY SZ", [](const Call& c) {
      if (c.w.size() == 3) c.usage_error();
      const glm::dvec3 f = c.w.size() == 2 ? glm::dvec3(number(c.w[1], "S"))
                                            : glm::dvec3(number(c.w[1], "SX"), number(c.w[2], "SY"), number(c.w[3], "SZ"));
      transform(c, TransformMode::Scale, glm::dvec3(0.0, 0.0, 1.0), 0.0, f);
    }},
    {"brush", 1, 3, "brush draw|inflate|smooth|grab|flatten|pinch [RADIUS [STRENGTH]] | brush falloff smooth|linear|sharp|constant | brush front|invert on|off", [](const Call& c) {
      BrushSettings b = c.state.brush();
      try {
        if (c.w[1] == "falloff" && c.w.size() == 3) {
          b.falloff = parse_falloff(c.w[2]);
        } else if ((c.w[1] == "front" || c.w[1] == "invert") && c.w.size() == 3) {
          if (c.w[2] != "on" && c.w[2] != "off") throw ScriptError("brush " + c.w[1] + " takes 'on' or 'off'");
          (c.w[1] == "front" ? b.front_faces_only : b.invert) = c.w[2] == "on";
        } else {
          b.kind = parse_brush(c.w[1]);
          if (c.w.size() >= 3) b.radius = number(c.w[2], "RADIUS");
          if (c.w.size() == 4) b.strength = number(c.w[3], "STRENGTH");
        }
        c.state.set_brush(b);
      } catch (const Error& e) {
        throw ScriptError(e.what());
      }
    }},
    {"stroke", 3, kMany, "stroke X Y Z [X Y Z ...]", [](const Call& c) {
      // Dabs at the given world points, one history entry; the grab brush moves by the motion
      // from each point to the next. No view: every point in reach counts as front-facing.
      if ((c.w.size() - 1) % 3 != 0) c.usage_error();
      std::vector<glm::dvec3> points;
      for (std::size_t i = 1; i + 2 < c.w.size(); i += 3)
        points.emplace_back(number(c.w[i], "X"), number(c.w[i + 1], "Y"), number(c.w[i + 2], "Z"));
      c.state.begin_stroke();
      as_one_drag(c.state, [&] {
        for (std::size_t i = 0; i < points.size(); ++i) {
          Dab d;
          d.center = points[i];
          d.view_dir = glm::dvec3(0.0);
          if (c.state.brush().kind == BrushKind::Grab) {
            if (i + 1 == points.size()) break;
            d.motion = points[i + 1] - points[i];
          }
          c.state.dab(d);
        }
      });
    }},
    {"crease", 1, 1, "crease mark|clear|toggle", [](const Call& c) {
      if (c.w[1] != "mark" && c.w[1] != "clear" && c.w[1] != "toggle") c.usage_error();
      c.state.toggle_creases(c.w[1] == "toggle" ? std::nullopt : std::optional<bool>(c.w[1] == "mark"));
    }},
    {"corner", 1, 1, "corner mark|clear|toggle", [](const Call& c) {
      if (c.w[1] != "mark" && c.w[1] != "clear" && c.w[1] != "toggle") c.usage_error();
      c.state.toggle_corners(c.w[1] == "toggle" ? std::nullopt : std::optional<bool>(c.w[1] == "mark"));
    }},
    {"symmetry", 2, 2, "symmetry x|y|z on|off", [](const Call& c) {
      if (c.w[1] != "x" && c.w[1] != "y" && c.w[1] != "z") throw ScriptError("symmetry axis must be x, y or z");
      if (c.w[2] != "on" && c.w[2] != "off") throw ScriptError("symmetry takes 'on' or 'off', got '" + c.w[2] + "'");
      const std::string problem = c.state.set_symmetry(c.w[1][0] - 'x', c.w[2] == "on");
      if (!problem.empty()) throw ScriptError(problem + " (the mesh is not symmetric there; symmetry stays on for the rest)");
    }},
    {"pivot", 1, 1, "pivot median|active|cursor|origin", [](const Call& c) {
      try {
        c.state.set_pivot(parse_pivot(c.w[1]));
      } catch (const Error& e) {
        throw ScriptError(e.what());
      }
    }},
    {"cursor", 3, 3, "cursor X Y Z", [](const Call& c) {
      c.state.set_cursor({number(c.w[1], "X"), number(c.w[2], "Y"), number(c.w[3], "Z")});
    }},
    {"active", 1, 1, "active INDEX", [](const Call& c) {
      const long long v = integer(c.w[1], "INDEX");
      if (v < 0 || !std::binary_search(c.state.selection().begin(), c.state.selection().end(), static_cast<unsigned>(v)))
        throw ScriptError("active " + c.w[1] + ": the active point must be selected");
      c.state.set_active(v);
    }},
    {"gain", 2, 2, "gain LEVEL FACTOR", [](const Call& c) {
      const long long l = integer(c.w[1], "LEVEL");
      const double f = number(c.w[2], "FACTOR");
      const int top = c.state.session().finest_level() - 1;
      if (l < 0 || l > top) throw ScriptError("gain level " + c.w[1] + " is outside 0.." + std::to_string(top));
      c.state.begin_gain(static_cast<int>(l));
      c.state.set_gain(static_cast<int>(l), f);
      c.state.end_gain();
    }},
    {"frames", 1, 1, "frames world|local", [](const Call& c) {
      if (c.w[1] != "world" && c.w[1] != "local") throw ScriptError("frames must be 'world' or 'local'");
      c.state.set_local_frames(c.w[1] == "local");
    }},
    {"undo", 0, 0, "undo", [](const Call& c) { if (!c.state.undo()) throw ScriptError("nothing to undo"); }},
    {"redo", 0, 0, "redo", [](const Call& c) { if (!c.state.redo()) throw ScriptError("nothing to redo"); }},
    {"save", kPath, 0, "save PATH", [](const Call& c) {
      if (!is_project_file(c.raw)) throw ScriptError("save writes a .sublift project; use export for '" + c.raw + "'");
      c.state.save_project(c.raw);
    }},
    {"export", kPath, 0, "export PATH", [](const Call& c) { c.state.export_shape(c.raw, true); }},
    {"export-levels", kPath, 0, "export-levels PATH", [](const Call& c) { c.state.export_levels(c.raw); }},
    {"export-net", 2, kMany, "export-net LEVEL PATH", [](const Call& c) {
      const long long l = integer(c.w[1], "LEVEL");
      const int finest = c.state.session().finest_level();
      if (l < 0 || l > finest) throw ScriptError("export-net level " + c.w[1] + " is outside 0.." + std::to_string(finest));
      const std::string path = rest_of(c.raw, c.w[1]);
      if (path.empty()) c.usage_error();
      c.state.export_level(path, static_cast<int>(l));
    }},

    {"delete", 1, 1, "delete higher|lower", [](const Call& c) {
      if (c.w[1] == "higher") return void(c.state.delete_higher_levels());
      if (c.w[1] == "lower") return void(c.state.delete_lower_levels());
      c.usage_error();
    }},
    {"apply-base", 0, 0, "apply-base", [](const Call&) {}},  // nothing to do in Sublift (ModelerState::apply_base_note)
    {"screenshot", kPath, 0, "screenshot PATH",
     [](const Call& c) { c.step.kind = ScriptStep::Kind::Screenshot; c.step.path = c.raw; }},
    {"colour", 1, 2, "colour LEVEL|off|channel NAME", colour},
    {"channel-keep", 2, 2, "channel-keep NAME FRACTION",
     [](const Call& c) { c.state.set_channel_keep(c.w[1], number(c.w[2], "FRACTION")); }},
    {"color", 1, 2, "colour LEVEL|off|channel NAME", colour},
    {"basis", 1, kMany,
     "basis scaling|wavelet INDEX [dual] | basis height SCALE|off | basis slice x|y|z FRACTION | basis slice off | "
     "basis iso FRACTION|off | basis follow on|off | basis pin | basis unpin | basis off",
     basis},
    {"compress", 1, 2, "compress keep F | compress apply | compress off", [](const Call& c) {
      if (c.w.size() == 2 && c.w[1] == "apply") return c.state.apply_compression();
      if (c.w.size() == 2 && c.w[1] == "off") return c.state.compression_off();
      if (c.w.size() != 3 || c.w[1] != "keep") c.usage_error();
      const double f = number(c.w[2], "F");
      if (f < 0.0 || f > 1.0) throw ScriptError("compress keep F needs F in 0..1, got " + c.w[2]);
      c.state.set_compression(f);
    }},
    {"display", 2, 2, "display smooth|wireframe|net|xray|depth_cue|clip|ortho|texture on|off", [](const Call& c) {
      using D = ModelerDisplay;
      using Switch = std::pair<const char*, bool D::*>;
      static constexpr Switch kSwitches[] = {{"smooth", &D::smooth}, {"wireframe", &D::wireframe}, {"net", &D::net},
                                             {"xray", &D::xray},     {"depth_cue", &D::depth_cue}, {"clip", &D::clip},
                                             {"ortho", &D::orthographic}, {"texture", &D::texture}};
      if (c.w[2] != "on" && c.w[2] != "off") throw ScriptError("display takes 'on' or 'off', got '" + c.w[2] + "'");
      const Switch* s = std::ranges::find(kSwitches, c.w[1], &Switch::first);
      if (s == std::end(kSwitches)) throw ScriptError("unknown display switch '" + c.w[1] + "'");
      c.show.*s->second = c.w[2] == "on";
    }},
    {"clip", 2, 2, "clip X|Y|Z OFFSET01", [](const Call& c) {
      const std::string& axis = c.w[1];
      if (axis != "X" && axis != "Y" && axis != "Z" && axis != "x" && axis != "y" && axis != "z") {
        throw ScriptError("clip axis must be X, Y or Z");
      }
      const double at = number(c.w[2], "OFFSET01");
      if (at < 0.0 || at > 1.0) throw ScriptError("OFFSET01 must be between 0 and 1");
      c.show.clip = true;
      c.show.clip_axis = (axis[0] | 0x20) - 'x';
      c.show.clip_offset = static_cast<float>(at);
    }},
    {"view", 1, 1, "view front|back|right|left|top|bottom", [](const Call& c) {
      static const char* kViews[] = {"front", "back", "right", "left", "top", "bottom"};
      if (std::ranges::find(kViews, c.w[1]) == std::end(kViews)) throw ScriptError("unknown view '" + c.w[1] + "'");
      c.step.view = c.w[1];
    }},
    {"quit", 0, 0, "quit", [](const Call& c) { c.step.kind = ScriptStep::Kind::Quit; }},
};

void run_line(ModelerState& state, ModelerDisplay* display, const std::vector<std::string>& w, const std::string& raw,
              ScriptStep& step) {
  const Command* cmd = std::ranges::find(kCommands, w[0], &Command::name);
  const bool known = cmd != std::end(kCommands);
  // Without a model only open and model run; an unknown word gets this message too.
  if ((!known || cmd->needs_model) && !state.has_session()) {
    throw ScriptError("no model is open (use 'open PATH' or 'model PATH')");
  }
  if (!known) throw ScriptError("unknown command '" + w[0] + "'");
  ModelerDisplay ignored;
  const Call call{w, raw, state, display != nullptr ? *display : ignored, step, cmd->usage};
  const int n = static_cast<int>(w.size()) - 1;
  if (cmd->min == kPath ? raw.empty() : n < cmd->min || n > cmd->max) call.usage_error();
  cmd->run(call);
}

}  // namespace

std::vector<std::string_view> script_commands() {
  std::vector<std::string_view> names;
  for (const Command& k : kCommands) names.emplace_back(k.name);
  return names;
}

ScriptRunner::ScriptRunner(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path + ": cannot read the script");
  for (std::string line; std::getline(in, line);) lines_.push_back(line);
}

ScriptRunner::ScriptRunner(const std::string& /*name*/, const std::string& text) {
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines_.push_back(line);
}

ScriptStep ScriptRunner::next(ModelerState& state, ModelerDisplay* display) {
  ScriptStep step;
  while (line_ < lines_.size()) {
    const std::size_t number = ++line_;
    std::string line = lines_[number - 1];
    if (const std::size_t hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    std::istringstream words_in(line);
    std::vector<std::string> words;
    for (std::string w; words_in >> w;) words.push_back(w);
    if (words.empty()) continue;
    const auto t0 = std::chrono::steady_clock::now();
    auto report = [&](bool ok, const std::string& message) {
      if (!json_) return;
      nlohmann::json j = {{"line", number}, {"command", words[0]}, {"ok", ok},
                          {"ms", std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count()},
                          {"message", message}};
      if (state.has_session()) {
        j["level"] = state.level();
        j["finest_level"] = state.session().finest_level();
        j["vertices"] = state.session().num_vertices(state.level());
      }
      *json_ << j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) << '\n' << std::flush;
    };
    try {
      ScriptStep::Kind before = step.kind;
      run_line(state, display, words, rest_of(line, words[0]), step);
      report(true, "");
      if (step.kind != before) return step;  // screenshot or quit
    } catch (const std::exception& e) {
      // Errors of the input (sublift::Error, a command's ScriptError) and running out of
      // memory are the script's; anything else is a defect of Sublift and says so.
      const bool expected = dynamic_cast<const Error*>(&e) || dynamic_cast<const ScriptError*>(&e) ||
                            dynamic_cast<const std::bad_alloc*>(&e);
      std::string what = e.what();
      while (!what.empty() && (what.back() == '\n' || what.back() == ' ')) what.pop_back();
      step.kind = ScriptStep::Kind::Error;
      step.internal = !expected;
      step.message = "script:" + std::to_string(number) + ": " + (expected ? "" : "internal error (please report): ") + what;
      report(false, step.message);
      return step;
    }
  }
  step.kind = ScriptStep::Kind::End;
  return step;
}

}  // namespace sublift
