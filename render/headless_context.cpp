#include "render/headless_context.h"

// libEGL directly for the display and context; libepoxy resolves the GL calls against it.
#include <epoxy/gl.h>
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstring>
#include <string>

#include "render/render_errors.h"

namespace sublift {
namespace {

// The surfaceless display is shared by every context in the process; terminate it only when
// the last HeadlessContext goes, or a second live context would lose its display.
int g_live_contexts = 0;

std::string egl_error_name(EGLint code) {
  switch (code) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    default: return "EGL error 0x" + std::to_string(code);
  }
}

[[noreturn]] void fail(const std::string& step) {
  throw RenderError("headless OpenGL unavailable: " + step + " failed (" +
                    egl_error_name(eglGetError()) +
                    "); install libegl-mesa0 and libgl1-mesa-dri (Mesa's EGL surfaceless platform)");
}

bool has_extension(const char* list, const char* name) {
  if (list == nullptr) return false;
  const std::size_t n = std::strlen(name);
  for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += n) {
    const bool starts = p == list || p[-1] == ' ';
    const bool ends = p[n] == '\0' || p[n] == ' ';
    if (starts && ends) return true;
  }
  return false;
}

}  // namespace

HeadlessContext::HeadlessContext() {
  const char* client_extensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!has_extension(client_extensions, "EGL_MESA_platform_surfaceless")) {
    throw RenderError(
        "headless OpenGL unavailable: EGL lacks EGL_MESA_platform_surfaceless; install "
        "libegl-mesa0 and libgl1-mesa-dri");
  }
  EGLDisplay display =
      eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  if (display == EGL_NO_DISPLAY) fail("eglGetPlatformDisplay(surfaceless)");
  EGLint major = 0, minor = 0;
  if (!eglInitialize(display, &major, &minor)) fail("eglInitialize");
  ++g_live_contexts;
  display_ = display;

  try {
    // EGL_SURFACE_TYPE 0: the default asks for window surfaces, which surfaceless has none of.
    const EGLint config_attribs[] = {EGL_SURFACE_TYPE, 0,
                                     EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                                     EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8,
                                     EGL_NONE};
    EGLConfig config = nullptr;
    EGLint num_configs = 0;
    if (!eglChooseConfig(display, config_attribs, &config, 1, &num_configs) || num_configs < 1) {
      fail("eglChooseConfig(OpenGL, no surface)");
    }
    if (!eglBindAPI(EGL_OPENGL_API)) fail("eglBindAPI(EGL_OPENGL_API)");
    const EGLint context_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 3,
                                      EGL_CONTEXT_MINOR_VERSION, 3,
                                      EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                      EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                      EGL_NONE};
    EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, context_attribs);
    if (context == EGL_NO_CONTEXT) fail("eglCreateContext(OpenGL 3.3 core)");
    context_ = context;
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) fail("eglMakeCurrent");
  } catch (...) {
    release();
    throw;
  }
}

HeadlessContext::~HeadlessContext() { release(); }

void HeadlessContext::release() {
  if (display_ == nullptr) return;
  auto display = static_cast<EGLDisplay>(display_);
  if (context_ != nullptr) {
    if (eglGetCurrentContext() == static_cast<EGLContext>(context_)) {
      eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    }
    eglDestroyContext(display, static_cast<EGLContext>(context_));
    context_ = nullptr;
  }
  if (--g_live_contexts == 0) eglTerminate(display);
  display_ = nullptr;
}

std::string HeadlessContext::renderer() const {
  const auto* text = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  return text != nullptr ? text : "unknown";
}

}  // namespace sublift
