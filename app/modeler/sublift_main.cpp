// sublift: the interactive modeler. Argument parsing only; the GUI lives in gui_app.cpp.
#include <charconv>
#include <cstdio>
#include <iostream>
#include <optional>
#include <string>
#include <string_view>

#include "app/modeler/gui_app.h"
#include "app/modeler/script_runner.h"

namespace {

constexpr int kExitUsage = 2;

void print_usage(std::ostream& out) {
  out << "usage: sublift [FILE] [--script FILE [--json]] [--headless] [--screenshot PATH] [--frames N]\n"
         "               [--size WxH] [--help]\n"
         "\n"
         "Opens FILE (OBJ, OFF, PLY, glTF/GLB, curve OBJ, .lattice, .ovm, .vtk or a .sublift project) in the\n"
         "Sublift modeler; without FILE opens the bundled sample\n"
         "(" << sublift::default_model_path() << ").\n"
         "\n"
         "  --script FILE      run modeler commands from FILE (one per line, see docs/modeler.md)\n"
         "                     and exit: 0, or 1 with 'script:LINE: message' on the first failure;\n";
  // The command names come from the runner's table, wrapped under the option's text.
  std::string names = "                     commands:";
  for (const std::string_view name : sublift::script_commands()) {
    if (names.size() + 1 + name.size() > 88) {
      out << names << '\n';
      names.assign(30, ' ');  // under the first name
    }
    names.append(" ").append(name);
  }
  out << names << "\n"
         "  --json             with --script: one JSON object per command on stdout (line,\n"
         "                     command, ok, ms, level, finest_level, vertices, message)\n"
         "  --headless         render through EGL without a window even if a display exists\n"
         "  --screenshot PATH  render the GUI, save it as a PNG and exit (default 3 frames)\n"
         "  --frames N         run N frames, then exit\n"
         "  --size WxH         window size in pixels (default 1280x800)\n"
         "  --help             show this help\n"
         "\n"
         "Without a display (no DISPLAY or WAYLAND_DISPLAY) the same view is rendered headless\n"
         "to the --screenshot path, or sublift-screenshot.png in the current directory.\n";
}

std::optional<int> parse_int(std::string_view text, int min, int max) {
  int value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || value < min || value > max) {
    return std::nullopt;
  }
  return value;
}

int usage_error(const std::string& message) {
  std::cerr << "sublift: " << message << "\n";
  print_usage(std::cerr);
  return kExitUsage;
}

}  // namespace

int main(int argc, char** argv) {
  sublift::GuiOptions options;
  bool have_file = false;
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    // The argument after a flag, consumed; nullopt when the flag ends the command line.
    auto value = [&]() -> std::optional<std::string_view> {
      if (i + 1 >= argc) return std::nullopt;
      return std::string_view(argv[++i]);
    };
    if (arg == "--help" || arg == "-h") {
      print_usage(std::cout);
      return 0;
    } else if (arg == "--script") {
      const auto path = value();
      if (!path || path->empty()) return usage_error("--script needs a script file");
      options.script = std::string(*path);
    } else if (arg == "--json") {
      options.json = true;
    } else if (arg == "--headless") {
      options.headless = true;
    } else if (arg == "--screenshot") {
      const auto path = value();
      if (!path || path->empty()) return usage_error("--screenshot needs a PNG path");
      options.screenshot = std::string(*path);
    } else if (arg == "--frames") {
      const auto text = value();
      const auto frames = text ? parse_int(*text, 1, 1000000) : std::nullopt;
      if (!frames) return usage_error("--frames needs a whole number from 1 to 1000000");
      options.frames = *frames;
    } else if (arg == "--size") {
      const auto text = value();
      const std::size_t x = text ? text->find('x') : std::string_view::npos;
      const auto w = x != std::string_view::npos ? parse_int(text->substr(0, x), 64, 16384)
                                                 : std::nullopt;
      const auto h = x != std::string_view::npos ? parse_int(text->substr(x + 1), 64, 16384)
                                                 : std::nullopt;
      if (!w || !h) return usage_error("--size needs WIDTHxHEIGHT, each from 64 to 16384");
      options.width = *w;
      options.height = *h;
    } else if (arg.size() > 1 && arg[0] == '-') {
      return usage_error("unknown option '" + std::string(arg) + "'");
    } else if (have_file) {
      return usage_error("only one FILE can be opened, got '" + options.file + "' and '" +
                         std::string(arg) + "'");
    } else {
      options.file = std::string(arg);
      have_file = true;
    }
  }
  if (options.json && options.script.empty()) return usage_error("--json goes with --script");
  return sublift::run_gui(options);
}
