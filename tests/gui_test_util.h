#pragma once
// Shared by the GUI tests that run the `sublift` executable: shell quoting, running a command
// with stderr captured, and reading the PNGs it writes (stb_image).
#include <sys/wait.h>

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

}  // namespace sublift::testing
