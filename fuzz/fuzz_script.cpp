// libFuzzer target: modeler scripts (`sublift --script`), run by ScriptRunner against a
// ModelerState, the GL-free document the window drives. Paths in a script are relative to the
// working folder; the target works in a private folder holding five small samples (names
// below), refuses inputs naming any other folder ('/', '\\' or ".."), and empties the folder of
// everything a script wrote after each input, so every input runs from the same state.
// Work: scripts asking for more than 3 subdivisions in all (`open` makes 2 levels) or an
// FFD box of more than 64 cells are not run (bounded_work); SUBLIFT_MEMORY_BUDGET is 256 MB.
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "app/modeler/script_runner.h"
#include "fuzz/fuzz_input.h"

namespace {

// name in the private folder -> bundled asset
const std::pair<const char*, const char*> kSamples[] = {
    {"c.obj", "cube.obj"},  {"t.obj", "octahedron.obj"}, {"k.obj", "curves/curve.obj"},
    {"l.lattice", "cube_cell.lattice"}, {"m.obj", "pyramid.obj"}};
std::set<std::string> g_samples;

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  if (!in) {
    std::fprintf(stderr, "fuzz_script: cannot read %s\n", path.c_str());
    std::abort();
  }
  return s.str();
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  setenv("SUBLIFT_MEMORY_BUDGET", "256M", 1);
  std::string folder;
  for (auto [name, asset] : kSamples) {
    const std::string path = sublift::fuzz::write_private_file(name, slurp(std::string(SUBLIFT_ASSETS_DIR) + "/" + asset));
    folder = std::filesystem::path(path).parent_path().string();
    g_samples.insert(name);
  }
  if (chdir(folder.c_str()) != 0) {
    std::perror("fuzz_script: chdir");
    std::abort();
  }
  return 0;
}

// Legal scripts can ask for minutes of work (`subdivide 12`, `ffd box 64 64 64`), which is no
// finding: the harness refuses scripts asking for more than a few levels or lattice cells in
// all, so the 10 s per input libFuzzer allows stays a hang detector.
bool bounded_work(const std::string& text) {
  std::istringstream lines(text);
  double levels = 0;  // doubles: no overflow on huge numbers
  for (std::string line; std::getline(lines, line);) {
    std::istringstream words(line);
    std::string command, a, b, c, d;
    words >> command >> a >> b >> c >> d;
    if (command == "subdivide") levels += a.empty() ? 1 : std::abs(std::atof(a.c_str()));
    if (command == "ffd" && a == "box" && std::abs(std::atof(b.c_str()) * std::atof(c.c_str()) * std::atof(d.c_str())) > 64)
      return false;
    if (levels > 3) return false;
  }
  return true;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text = sublift::fuzz::bytes_of(data, size);
  if (text.find('/') != std::string::npos || text.find('\\') != std::string::npos || text.find("..") != std::string::npos)
    return -1;  // would leave the private folder: not run, not kept
  if (!bounded_work(text)) return -1;
  {
    sublift::ModelerState state;
    sublift::ModelerDisplay display;
    sublift::ScriptRunner runner("fuzz.script", text);
    // A failing command ends the script with Kind::Error; one that failed with anything but an
    // input error (step.internal: std::out_of_range, say) is a crasher, as is an escaping
    // exception. Screenshots need a frame: skipped here.
    for (int frames = 0; frames < 64; ++frames) {
      const sublift::ScriptStep step = runner.next(state, &display);
      if (step.internal) {
        std::fprintf(stderr, "fuzz_script: %s\n", step.message.c_str());
        std::abort();
      }
      if (step.kind != sublift::ScriptStep::Kind::Screenshot) break;
    }
  }
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(".", ec))
    if (!g_samples.count(e.path().filename().string())) std::filesystem::remove_all(e.path(), ec);
  return 0;
}
