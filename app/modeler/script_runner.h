#pragma once
// `sublift --script FILE`: modeler commands one per line, run against a ModelerState through
// the same calls the mouse and keys use (a `move` is a drag: begin_drag / drag_to / end_drag on
// the selection with the current soft radius). Blank lines and `#` comments are skipped; paths
// are relative to the current directory. Commands:
//   open PATH | scheme linear|cubic | subdivide [N] | level L | select [INDEX...] | soft RADIUS
//   view-level L|finest (the level whose limit surface is drawn; edits and exports unaffected)
//   select all|none|invert|more|less|linked | select loop|ring A B [add] (through edge A-B)
//   move DX DY DZ | rotate x|y|z DEGREES | rotate AX AY AZ DEGREES | scale S | scale SX SY SZ
//   pivot median|active|cursor|origin | cursor X Y Z | active INDEX | gain LEVEL FACTOR
//   symmetry x|y|z on|off (mirror editing; fails, staying on, naming what has no mirror image)
//   brush draw|inflate|smooth|grab|flatten|pinch [RADIUS [STRENGTH]] | brush falloff NAME
//   brush front|invert on|off | stroke X Y Z [X Y Z ...] (dabs at world points, one undo step)
//   crease mark|clear|toggle (base edges between selected points) | corner mark|clear|toggle | frames world|local | undo | redo | save PATH
//   export PATH | export-net LEVEL PATH (that level's control net) | export-levels PATH (every level's net: PATH's name + _L0.._LJ) | screenshot PATH
//   delete higher|lower (the levels above the edit level / below it: it becomes the base)
//   apply-base (accepted for Blender users; nothing to do) | quit
//   colour LEVEL|off | display smooth|wireframe|net|xray|depth_cue|clip|ortho on|off
//   clip X|Y|Z OFFSET01 | view front|back|right|left|top|bottom  (display and camera only)
//   basis scaling|wavelet INDEX [dual] | basis height SCALE|off | basis off  (issue 5: the
//   basis-function mode on the edit level; height SCALE > 0 displaces, times the bbox diagonal)
//   basis slice x|y|z FRACTION | basis slice off | basis iso FRACTION|off  (lattices)
//   basis follow on|off (a selected point picks the function) | basis pin | basis unpin
//   model PATH (load a model for FFD; bound at once to an open lattice)
//   ffd box NX NY NZ [MARGIN] | ffd bind [nearest] | ffd unbind | ffd remove | ffd export PATH
//   compress keep F (show the largest fraction F in 0..1 of the wavelets; the shape is locked
//   until) compress apply (one undoable edit) | compress off (docs/compression.md)
// The runner executes commands until one needs a rendered frame (screenshot) or the script
// ends; the app draws and saves the frame, then calls next() again.
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "app/modeler/modeler_state.h"
#include "ui/modeler_panels.h"

namespace sublift {

struct ScriptStep {
  enum class Kind { Screenshot, Quit, End, Error };
  Kind kind = Kind::End;
  std::string path;     // Screenshot: the PNG to write
  std::string message;  // Error: "script:LINE: message"
  bool internal = false;  // Error: not a fault of the input (a defect; the fuzz target aborts on it)
  bool reframe = false; // an `open` ran since the last step: frame the new model
  std::string view;     // a `view` command ran: the preset name (front, right, ...)
};

class ScriptRunner {
 public:
  /// Reads the script; throws IoError when it cannot be read.
  explicit ScriptRunner(const std::string& path);
  /// From text (tests).
  ScriptRunner(const std::string& name, const std::string& text);

  /// `sublift --script FILE --json`: after each command, one line with a JSON object on `out`
  /// (null: none): {"line", "command", "ok", "ms", "level", "finest_level", "vertices",
  /// "message"} — the edit level, the finest level and the edit level's vertex count after the
  /// command; message the error of a failed command (the last line), else "".
  void set_json_output(std::ostream* out) { json_ = out; }

  /// Runs commands until a screenshot, quit, the end or the first failure.
  /// `display` receives the display commands (ignored when null).
  ScriptStep next(ModelerState& state, ModelerDisplay* display = nullptr);

 private:
  std::vector<std::string> lines_;
  std::size_t line_ = 0;  // next line to run (0-based)
  std::ostream* json_ = nullptr;
};

/// The command names, from the runner's table (for `sublift --help`).
std::vector<std::string_view> script_commands();

}  // namespace sublift
