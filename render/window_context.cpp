#include "render/window_context.h"

#include <epoxy/gl.h>
#ifndef GLFW_INCLUDE_NONE
#define GLFW_INCLUDE_NONE  // libepoxy provides the GL declarations
#endif
#include <GLFW/glfw3.h>

#include <cstdlib>
#include <string>

#include "render/offscreen_target.h"
#include "render/render_errors.h"

namespace sublift {
namespace {

// GLFW reports failures through a callback only; keep the last one for the exception text.
std::string g_last_glfw_error;

void record_glfw_error(int /*code*/, const char* description) {
  g_last_glfw_error = description != nullptr ? description : "unknown GLFW error";
}

bool env_set(const char* name) {
  const char* value = std::getenv(name);
  return value != nullptr && value[0] != '\0';
}

GLFWwindow* create_window(const WindowSettings& settings, int samples) {
  glfwDefaultWindowHints();
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_SAMPLES, samples);
  glfwWindowHint(GLFW_DEPTH_BITS, 24);
  return glfwCreateWindow(settings.width, settings.height, settings.title.c_str(), nullptr,
                          nullptr);
}

}  // namespace

WindowContext::WindowContext(const WindowSettings& settings) {
  if (!env_set("DISPLAY") && !env_set("WAYLAND_DISPLAY")) {
    throw NoDisplayError("no display: neither DISPLAY nor WAYLAND_DISPLAY is set");
  }
  glfwSetErrorCallback(record_glfw_error);
  if (!glfwInit()) throw NoDisplayError("no display: GLFW cannot start: " + g_last_glfw_error);
  window_ = create_window(settings, settings.samples);
  if (window_ == nullptr && settings.samples > 0) window_ = create_window(settings, 0);
  if (window_ == nullptr) {
    const std::string why = g_last_glfw_error;
    glfwTerminate();
    throw NoDisplayError("no display: cannot open an OpenGL 3.3 core window: " + why);
  }
  glfwMakeContextCurrent(window_);
  glfwSwapInterval(settings.vsync ? 1 : 0);
  if (settings.samples > 0) glEnable(GL_MULTISAMPLE);
}

WindowContext::~WindowContext() {
  if (window_ != nullptr) glfwDestroyWindow(window_);
  glfwTerminate();
}

bool WindowContext::should_close() const { return glfwWindowShouldClose(window_) != 0; }

void WindowContext::swap_buffers() { glfwSwapBuffers(window_); }

void WindowContext::framebuffer_size(int& width, int& height) const {
  glfwGetFramebufferSize(window_, &width, &height);
}

void WindowContext::window_size(int& width, int& height) const {
  glfwGetWindowSize(window_, &width, &height);
}

std::vector<std::uint8_t> WindowContext::read_back_buffer(int& width, int& height) const {
  framebuffer_size(width, height);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  return read_framebuffer_rgba(width, height);
}

}  // namespace sublift
