#pragma once
// Errors raised by the render layer. NoDisplayError is its own type so the GUI can tell "no
// window system here" (fall back to headless) from a real rendering failure.
#include "core/base/errors.h"

namespace sublift {

/// An OpenGL/EGL resource could not be created or a GL call failed.
class RenderError : public Error {
 public:
  using Error::Error;
};

/// No window system is reachable (no DISPLAY/WAYLAND_DISPLAY, or GLFW cannot open a window).
class NoDisplayError : public RenderError {
 public:
  using RenderError::RenderError;
};

/// A shader failed to compile or link; the message names the shader and carries the GLSL log.
class ShaderError : public RenderError {
 public:
  using RenderError::RenderError;
};

}  // namespace sublift
