#pragma once
// A GLFW window with an OpenGL 3.3 core context. Construction throws NoDisplayError when no
// window system is reachable, so the app can fall back to HeadlessContext.
#include <cstdint>
#include <string>
#include <vector>

struct GLFWwindow;

namespace sublift {

struct WindowSettings {
  int width = 1280;
  int height = 800;
  std::string title = "Sublift";
  int samples = 4;        // MSAA samples of the default framebuffer; retried with 0 if refused
  bool vsync = true;
};

/// RAII owner of glfwInit/glfwTerminate and one window whose context is current.
class WindowContext {
 public:
  /// Opens the window; throws NoDisplayError (no display) or RenderError (no GL 3.3 context).
  explicit WindowContext(const WindowSettings& settings);
  ~WindowContext();
  WindowContext(const WindowContext&) = delete;
  WindowContext& operator=(const WindowContext&) = delete;

  /// The GLFW handle, for input polling and the ImGui backend.
  GLFWwindow* handle() const { return window_; }
  /// True once the user asked to close the window.
  bool should_close() const;
  /// Presents the back buffer.
  void swap_buffers();
  /// Size of the default framebuffer in pixels (may differ from the window size on HiDPI).
  void framebuffer_size(int& width, int& height) const;
  /// Size of the window in screen coordinates.
  void window_size(int& width, int& height) const;
  /// Reads the back buffer (call before swap_buffers) as top-down RGBA rows of the
  /// framebuffer size, which it stores in `width` and `height`.
  std::vector<std::uint8_t> read_back_buffer(int& width, int& height) const;

 private:
  GLFWwindow* window_ = nullptr;
};

}  // namespace sublift
