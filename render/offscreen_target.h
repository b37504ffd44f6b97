#pragma once
// Framebuffer objects to render into without a window, pixel read-back and PNG output.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace sublift {

/// An RGBA8 colour + 24-bit depth framebuffer, optionally multisampled (resolved on read).
class OffscreenTarget {
 public:
  /// Creates the framebuffer in the current GL context; throws RenderError if incomplete.
  OffscreenTarget(int width, int height, int samples = 4);
  ~OffscreenTarget();
  OffscreenTarget(const OffscreenTarget&) = delete;
  OffscreenTarget& operator=(const OffscreenTarget&) = delete;

  /// Binds the framebuffer for drawing and sets the viewport to all of it.
  void bind() const;
  /// Resolves (if multisampled) and returns the pixels as top-down RGBA rows, alpha forced to 255.
  std::vector<std::uint8_t> read_rgba() const;

  int width() const { return width_; }
  int height() const { return height_; }
  int samples() const { return samples_; }

 private:
  int width_, height_, samples_;
  unsigned draw_fbo_ = 0, color_rb_ = 0, depth_rb_ = 0;  // what bind() draws into
  unsigned resolve_fbo_ = 0, resolve_rb_ = 0;            // single-sample copy when samples > 0
};

/// Reads the bound read framebuffer (e.g. the window's back buffer) as top-down RGBA rows.
std::vector<std::uint8_t> read_framebuffer_rgba(int width, int height);

/// Writes `rgba` (top-down rows, width*height*4 bytes) as a PNG through a temporary file and a
/// rename, so an existing file is replaced only by a complete one. Throws IoError.
void write_png(const std::string& path, int width, int height,
               std::span<const std::uint8_t> rgba);

}  // namespace sublift
