#pragma once
// Shared by the GUI tests that run the `sublift` executable: shell quoting, running a command
// with stderr captured, and reading the PNGs it writes (stb_image).
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <stb_image.h>

namespace sublift::testing {

struct ShellResult {
  int exit_code = -1;
  std::string err;
};

/// `s` in single quotes for /bin/sh.
inline std::string quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

/// Runs `command` through the shell with stderr sent to `err_file` (one per concurrent test);
/// a hang is cut off by a `timeout` inside the command.
inline ShellResult run_shell(const std::string& command, const std::filesystem::path& err_file) {
  const int status = std::system((command + " 2>" + quote(err_file.string())).c_str());
  ShellResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(err_file);
  std::stringstream ss;
  ss << in.rdbuf();
  r.err = ss.str();
  return r;
}

struct Png {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;
  int channel(int x, int y, int c) const { return rgba[(static_cast<std::size_t>(y) * width + x) * 4 + c]; }
};

/// The image as RGBA; width 0 when it cannot be read.
inline Png load_png(const std::filesystem::path& path) {
  Png png;
  int channels = 0;
  stbi_uc* data = stbi_load(path.c_str(), &png.width, &png.height, &channels, 4);
  if (data == nullptr) return png;
  png.rgba.assign(data, data + static_cast<std::size_t>(png.width) * png.height * 4);
  stbi_image_free(data);
  return png;
}

/// The window the GUI tests script, and the side panel and status bar around its viewport
/// (ui/panels.h PanelLayout).
inline constexpr int kGuiWidth = 960, kGuiHeight = 640, kGuiPanelWidth = 330, kGuiStatusHeight = 28;

/// Viewport pixels (right of the panel, above the status bar) whose colour differs by more than
/// `threshold` in some channel.
inline long changed_viewport_pixels(const Png& a, const Png& b, int threshold) {
  long n = 0;
  for (int y = 0; y < kGuiHeight - kGuiStatusHeight; ++y)
    for (int x = kGuiPanelWidth; x < kGuiWidth; ++x) {
      int d = 0;
      for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(a.channel(x, y, c) - b.channel(x, y, c)));
      n += d > threshold;
    }
  return n;
}

/// `dir`, emptied (a test's screenshots from an earlier run must not pass for this one's).
inline std::filesystem::path fresh_dir(const std::filesystem::path& dir) {
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

/// Runs `exe --script SCRIPT` under xvfb-run at kGuiWidth x kGuiHeight in folder `dir` (recovery
/// files there too; a display number of the process's own), stderr to dir/stderr.txt.
inline ShellResult run_gui_script(const std::string& exe, const std::filesystem::path& dir, const std::string& script) {
  const int server = 500 + static_cast<int>(::getpid() % 400);
  const std::string command = "cd " + quote(dir.string()) + " && env SUBLIFT_RECOVERY_DIR=" + quote(dir.string()) +
                              " timeout 90 xvfb-run -a -n " + std::to_string(server) + " -s '-screen 0 1280x800x24' " +
                              quote(exe) + " --size " + std::to_string(kGuiWidth) + "x" + std::to_string(kGuiHeight) +
                              " --script " + quote(script);
  return run_shell(command, dir / "stderr.txt");
}

}  // namespace sublift::testing
