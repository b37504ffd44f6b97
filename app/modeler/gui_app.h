#pragma once
// The interactive GUI: a GLFW window with the 3-D viewport, the ImGui side panel and status
// line; or, when no display is reachable, the same frame rendered headless to a PNG.
#include <string>

namespace sublift {

struct GuiOptions {
  std::string file;        // mesh to open; empty opens the bundled sample
  std::string screenshot;  // PNG to save after `frames` frames; empty = interactive
  int frames = 0;          // frames to run before exiting; 0 = until closed (3 with a screenshot)
  int width = 1280;        // window (or headless image) size in pixels
  int height = 800;
  std::string script;      // `--script FILE`: run modeler commands, then exit (script_runner.h)
  bool headless = false;   // `--headless`: render through EGL even when a display exists
  bool json = false;       // `--json` with --script: one JSON line per command on stdout
};

/// The mesh opened when no file is given (assets/sample.obj of the source tree).
std::string default_model_path();

/// Runs the GUI and returns the process exit code (0 ok, 1 load or render failure); messages
/// go to stderr.
int run_gui(const GuiOptions& options);

}  // namespace sublift
