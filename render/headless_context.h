#pragma once
// An OpenGL 3.3 core context without any window system: EGL on Mesa's surfaceless platform.
// There is no default framebuffer; draw into an OffscreenTarget.
#include <string>

namespace sublift {

/// RAII owner of a surfaceless EGL display + context, current on the constructing thread.
class HeadlessContext {
 public:
  /// Creates the context and makes it current; throws RenderError saying what is missing.
  HeadlessContext();
  ~HeadlessContext();
  HeadlessContext(const HeadlessContext&) = delete;
  HeadlessContext& operator=(const HeadlessContext&) = delete;

  /// GL_RENDERER of the context (e.g. "llvmpipe (LLVM 15.0.6, 256 bits)").
  std::string renderer() const;

 private:
  void release();

  void* display_ = nullptr;  // EGLDisplay
  void* context_ = nullptr;  // EGLContext
};

}  // namespace sublift
