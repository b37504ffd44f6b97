#include "app/script_runner.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "core/errors.h"

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

void expect_args(const std::vector<std::string>& w, std::size_t n, const char* usage) {
  if (w.size() != n + 1) throw ScriptError(std::string("usage: ") + usage);
}

// The rest of the line after the command word: paths may contain spaces.
std::string rest_of(const std::string& line, const std::string& command) {
  std::size_t at = line.find(command) + command.size();
  while (at < line.size() && (line[at] == ' ' || line[at] == '\t')) ++at;
  std::string out = line.substr(at);
  while (!out.empty() && (out.back() == ' ' || out.back() == '\t' || out.back() == '\r')) out.pop_back();
  return out;
}

}  // namespace

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
    words.push_back(rest_of(line, words[0]));  // last entry: the raw argument text
    try {
      const std::string& command = words[0];
      if (command != "open" && command != "model" && !state.has_session()) {
        throw ScriptError("no model is open (use 'open PATH' or 'model PATH')");
      }
      ScriptStep::Kind before = step.kind;
      run_line(state, display, words, step);
      if (step.kind != before) return step;  // screenshot or quit
    } catch (const std::exception& e) {
      std::string what = e.what();
      while (!what.empty() && (what.back() == '\n' || what.back() == ' ')) what.pop_back();
      step.kind = ScriptStep::Kind::Error;
      step.message = "script:" + std::to_string(number) + ": " + what;
      return step;
    }
  }
  step.kind = ScriptStep::Kind::End;
  return step;
}

void ScriptRunner::run_line(ModelerState& state, ModelerDisplay* display, const std::vector<std::string>& all,
                            ScriptStep& step) {
  ModelerDisplay ignored;
  ModelerDisplay& show = display != nullptr ? *display : ignored;
  const std::string raw = all.back();
  const std::vector<std::string> w(all.begin(), all.end() - 1);
  const std::string& c = w[0];
  if (c == "open") {
    if (raw.empty()) throw ScriptError("usage: open PATH");
    state.open(raw);
    step.reframe = true;
  } else if (c == "model") {
    if (raw.empty()) throw ScriptError("usage: model PATH");
    state.load_model(raw);
    step.reframe = true;
  } else if (c == "ffd") {
    const char* usage = "ffd box NX NY NZ [MARGIN] | ffd bind [nearest] | ffd unbind | ffd remove | ffd export PATH";
    if (w.size() < 2) throw ScriptError(std::string("usage: ") + usage);
    if (w[1] == "box" && (w.size() == 5 || w.size() == 6)) {
      int n[3];
      for (int k = 0; k < 3; ++k) {
        const long long v = integer(w[static_cast<std::size_t>(2 + k)], "cell count");
        if (v < 1 || v > 64) throw ScriptError("cell counts must be 1..64, got " + w[static_cast<std::size_t>(2 + k)]);
        n[k] = static_cast<int>(v);
      }
      const double margin = w.size() == 6 ? number(w[5], "MARGIN") : 0.05;
      if (margin < 0.0) throw ScriptError("MARGIN must not be negative");
      state.wrap_model_in_box(n[0], n[1], n[2], margin);
      step.reframe = true;
    } else if (w[1] == "bind" && w.size() <= 3) {
      if (w.size() == 3 && w[2] != "nearest") throw ScriptError("ffd bind takes 'nearest' or nothing, got '" + w[2] + "'");
      state.bind_model(w.size() == 3 ? Outside::Nearest : Outside::Stay);
    } else if (w[1] == "unbind" && w.size() == 2) {
      state.unbind_model();
    } else if (w[1] == "remove" && w.size() == 2) {
      state.remove_model();
    } else if (w[1] == "export" && w.size() >= 3) {
      state.export_model(raw.substr(raw.find("export") + 7));
    } else {
      throw ScriptError(std::string("usage: ") + usage);
    }
  } else if (c == "scheme") {
    expect_args(w, 1, "scheme linear|cubic|sqrt2|linear-tri|butterfly|loop");
    Scheme s;
    try {
      s = parse_scheme(w[1]);
    } catch (const std::exception&) {
      throw ScriptError("unknown scheme '" + w[1] + "' (linear, cubic, sqrt2, linear-tri, butterfly or loop)");
    }
    state.set_scheme(s);
  } else if (c == "subdivide") {
    if (w.size() > 2) throw ScriptError("usage: subdivide [N]");
    const long long n = w.size() == 2 ? integer(w[1], "N") : 1;
    if (n < 1 || n > 12) throw ScriptError("subdivide N needs N from 1 to 12");
    for (long long i = 0; i < n; ++i) state.subdivide();
  } else if (c == "level") {
    expect_args(w, 1, "level L");
    const long long l = integer(w[1], "L");
    if (l < 0 || l > state.session().finest_level()) {
      throw ScriptError("level " + w[1] + " is outside 0.." + std::to_string(state.session().finest_level()));
    }
    state.set_level(static_cast<int>(l));
  } else if (c == "select") {
    std::vector<unsigned> sel;
    const long long n = state.session().num_vertices(state.level());
    for (std::size_t i = 1; i < w.size(); ++i) {
      const long long v = integer(w[i], "INDEX");
      if (v < 0 || v >= n) {
        throw ScriptError("vertex " + w[i] + " is outside 0.." + std::to_string(n - 1) + " of level " +
                          std::to_string(state.level()));
      }
      sel.push_back(static_cast<unsigned>(v));
    }
    state.set_selection(std::move(sel));
  } else if (c == "soft") {
    expect_args(w, 1, "soft RADIUS");
    const double r = number(w[1], "RADIUS");
    if (r < 0.0) throw ScriptError("RADIUS must not be negative");
    state.set_soft_radius(r);
  } else if (c == "move") {
    expect_args(w, 3, "move DX DY DZ");
    if (state.selection().empty()) throw ScriptError("move needs a selection (use 'select INDEX...')");
    const double d[3] = {number(w[1], "DX"), number(w[2], "DY"), number(w[3], "DZ")};
    state.begin_drag("Move");
    try {
      state.drag_to(d);
    } catch (...) {
      state.cancel_drag();
      throw;
    }
    state.end_drag();
  } else if (c == "gain") {
    expect_args(w, 2, "gain LEVEL FACTOR");
    const long long l = integer(w[1], "LEVEL");
    const double f = number(w[2], "FACTOR");
    if (l < 0 || l >= state.session().finest_level()) {
      throw ScriptError("gain level " + w[1] + " is outside 0.." + std::to_string(state.session().finest_level() - 1));
    }
    state.begin_gain(static_cast<int>(l));
    state.set_gain(static_cast<int>(l), f);
    state.end_gain();
  } else if (c == "frames") {
    expect_args(w, 1, "frames world|local");
    if (w[1] != "world" && w[1] != "local") throw ScriptError("frames must be 'world' or 'local'");
    state.set_local_frames(w[1] == "local");
  } else if (c == "undo") {
    expect_args(w, 0, "undo");
    if (!state.undo()) throw ScriptError("nothing to undo");
  } else if (c == "redo") {
    expect_args(w, 0, "redo");
    if (!state.redo()) throw ScriptError("nothing to redo");
  } else if (c == "save") {
    if (raw.empty()) throw ScriptError("usage: save PATH");
    if (!is_project_file(raw)) throw ScriptError("save writes a .sublift project; use export for '" + raw + "'");
    state.save_project(raw);
  } else if (c == "export") {
    if (raw.empty()) throw ScriptError("usage: export PATH");
    state.export_shape(raw, true);
  } else if (c == "screenshot") {
    if (raw.empty()) throw ScriptError("usage: screenshot PATH");
    step.kind = ScriptStep::Kind::Screenshot;
    step.path = raw;
  } else if (c == "colour" || c == "color") {
    expect_args(w, 1, "colour LEVEL|off");
    if (w[1] == "off") {
      state.set_colour_level(-1);
    } else {
      const long long l = integer(w[1], "LEVEL");
      if (l < 0 || l >= state.session().finest_level()) {
        throw ScriptError("colour level " + w[1] + " is outside 0.." + std::to_string(state.session().finest_level() - 1));
      }
      state.set_colour_level(static_cast<int>(l));
    }
  } else if (c == "basis") {
    const char* usage =
        "basis scaling|wavelet INDEX [dual] | basis height SCALE|off | basis slice x|y|z FRACTION | basis slice off | "
        "basis iso FRACTION|off | basis follow on|off | basis pin | basis unpin | basis off";
    if (w.size() == 2 && w[1] == "off") {
      state.set_basis(BasisSettings{});
      return;
    }
    if (w.size() == 2 && (w[1] == "pin" || w[1] == "unpin")) {
      if (w[1] == "pin") state.pin_basis();
      else state.clear_pin();
      return;
    }
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
      state.set_basis(b);
      return;
    }
    if (w.size() == 3 && w[1] == "iso") {
      BasisSettings b = current("iso");
      if (state.dim() != 3) throw ScriptError("basis iso needs a lattice");
      b.iso = w[2] != "off";
      if (b.iso) b.iso_level = fraction(w[2], "FRACTION");
      state.set_basis(b);
      return;
    }
    if (w.size() == 3 && w[1] == "follow") {
      if (w[2] != "on" && w[2] != "off") throw ScriptError("basis follow takes 'on' or 'off', got '" + w[2] + "'");
      BasisSettings b = current("follow");
      b.follow = w[2] == "on";
      state.set_basis(b);
      return;
    }
    if (w.size() == 3 && w[1] == "height") {
      if (!state.basis_on()) throw ScriptError("basis height needs the basis mode on (use 'basis scaling|wavelet INDEX')");
      BasisSettings b = state.basis_settings();
      if (w[2] == "off") {
        b.height = false;
      } else {
        const double scale = number(w[2], "SCALE");
        if (scale < 0.0) throw ScriptError("SCALE must not be negative");
        b.height = scale > 0.0;
        if (scale > 0.0) b.height_scale = scale;
      }
      state.set_basis(b);
      return;
    }
    if (w.size() < 3 || w.size() > 4 || (w[1] != "scaling" && w[1] != "wavelet")) throw ScriptError(std::string("usage: ") + usage);
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
  } else if (c == "compress") {
    const char* usage = "compress keep F | compress apply | compress off";
    if (w.size() == 3 && w[1] == "keep") {
      const double f = number(w[2], "F");
      if (f < 0.0 || f > 1.0) throw ScriptError("compress keep F needs F in 0..1, got " + w[2]);
      state.set_compression(f);
    } else if (w.size() == 2 && w[1] == "apply") {
      state.apply_compression();
    } else if (w.size() == 2 && w[1] == "off") {
      state.compression_off();
    } else {
      throw ScriptError(std::string("usage: ") + usage);
    }
  } else if (c == "display") {
    expect_args(w, 2, "display smooth|wireframe|net|xray|depth_cue|clip|ortho on|off");
    if (w[2] != "on" && w[2] != "off") throw ScriptError("display takes 'on' or 'off', got '" + w[2] + "'");
    const bool on = w[2] == "on";
    if (w[1] == "smooth") show.smooth = on;
    else if (w[1] == "wireframe") show.wireframe = on;
    else if (w[1] == "net") show.net = on;
    else if (w[1] == "xray") show.xray = on;
    else if (w[1] == "depth_cue") show.depth_cue = on;
    else if (w[1] == "clip") show.clip = on;
    else if (w[1] == "ortho") show.orthographic = on;
    else throw ScriptError("unknown display switch '" + w[1] + "'");
  } else if (c == "clip") {
    expect_args(w, 2, "clip X|Y|Z OFFSET01");
    if (w[1] != "X" && w[1] != "Y" && w[1] != "Z" && w[1] != "x" && w[1] != "y" && w[1] != "z") {
      throw ScriptError("clip axis must be X, Y or Z");
    }
    const double at = number(w[2], "OFFSET01");
    if (at < 0.0 || at > 1.0) throw ScriptError("OFFSET01 must be between 0 and 1");
    show.clip = true;
    show.clip_axis = (w[1][0] | 0x20) - 'x';
    show.clip_offset = static_cast<float>(at);
  } else if (c == "view") {
    expect_args(w, 1, "view front|back|right|left|top|bottom");
    static const char* kViews[] = {"front", "back", "right", "left", "top", "bottom"};
    bool known = false;
    for (const char* v : kViews) known |= w[1] == v;
    if (!known) throw ScriptError("unknown view '" + w[1] + "'");
    step.view = w[1];
  } else if (c == "quit") {
    expect_args(w, 0, "quit");
    step.kind = ScriptStep::Kind::Quit;
  } else {
    throw ScriptError("unknown command '" + c + "'");
  }
}

}  // namespace sublift
