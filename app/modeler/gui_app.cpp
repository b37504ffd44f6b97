#include "app/modeler/gui_app.h"

#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <cfloat>
#include <chrono>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "app/modeler/modeler_controller.h"
#include "app/modeler/modeler_view.h"
#include "app/modeler/script_runner.h"
#include "render/headless_context.h"
#include "render/offscreen_target.h"
#include "render/render_errors.h"
#include "render/window_context.h"
#include "ui/panels.h"

#ifndef SUBLIFT_ASSETS_DIR
#define SUBLIFT_ASSETS_DIR "assets"
#endif

namespace sublift {
namespace {

constexpr const char* kGlslVersion = "#version 330 core";
constexpr const char* kDefaultScreenshot = "sublift-screenshot.png";
constexpr int kDefaultScreenshotFrames = 3;  // ImGui settles its layout within two frames
constexpr int kSettleFrames = 2;             // frames drawn before a scripted screenshot
constexpr double kAwakeSeconds = 1.5;        // keep redrawing this long after the last input

// Time spent producing a frame, smoothed so the status line is readable.
class FrameClock {
 public:
  void begin() { start_ = std::chrono::steady_clock::now(); }
  void end() {
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
    average_ms_ = average_ms_ == 0.0 ? ms : 0.9 * average_ms_ + 0.1 * ms;
  }
  double average_ms() const { return average_ms_; }

 private:
  std::chrono::steady_clock::time_point start_;
  double average_ms_ = 0.0;
};

// ImGui context for one run; IniFilename off: the panels are docked, nothing to remember.
struct ImGuiContextGuard {
  ImGuiContextGuard() {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;
    apply_ui_theme();
  }
  ~ImGuiContextGuard() { ImGui::DestroyContext(); }
  ImGuiContextGuard(const ImGuiContextGuard&) = delete;
  ImGuiContextGuard& operator=(const ImGuiContextGuard&) = delete;
};

struct OpenGl3BackendGuard {
  OpenGl3BackendGuard() {
    if (!ImGui_ImplOpenGL3_Init(kGlslVersion)) throw RenderError("Dear ImGui's OpenGL 3 backend failed to start");
  }
  ~OpenGl3BackendGuard() { ImGui_ImplOpenGL3_Shutdown(); }
  OpenGl3BackendGuard(const OpenGl3BackendGuard&) = delete;
  OpenGl3BackendGuard& operator=(const OpenGl3BackendGuard&) = delete;
};

struct GlfwBackendGuard {
  explicit GlfwBackendGuard(GLFWwindow* window) {
    // install_callbacks: ImGui chains to the callbacks the app installed before.
    if (!ImGui_ImplGlfw_InitForOpenGL(window, true)) throw RenderError("Dear ImGui's GLFW backend failed to start");
  }
  ~GlfwBackendGuard() { ImGui_ImplGlfw_Shutdown(); }
  GlfwBackendGuard(const GlfwBackendGuard&) = delete;
  GlfwBackendGuard& operator=(const GlfwBackendGuard&) = delete;
};

// What the frame loop does after drawing a frame: nothing, save it, or stop.
struct FramePlan {
  std::string screenshot;  // write this frame to this PNG
  bool last = false;       // stop after this frame
  int exit_code = 0;
};

// Decides, frame by frame, what a --script, --screenshot or interactive run does.
class RunPlan {
 public:
  RunPlan(const GuiOptions& options, std::unique_ptr<ScriptRunner> script, bool headless)
      : script_(std::move(script)) {
    if (!script_) {
      frames_ = options.frames > 0 ? options.frames
                                   : (!options.screenshot.empty() || headless ? kDefaultScreenshotFrames : 0);
      screenshot_ = options.screenshot.empty() && headless ? kDefaultScreenshot : options.screenshot;
    }
  }
  bool scripted() const { return script_ != nullptr; }
  bool bounded() const { return script_ != nullptr || frames_ > 0; }

  /// Runs script commands before a frame is drawn; returns what to do after drawing it.
  FramePlan before_frame(ModelerController& app) {
    ++frame_;
    FramePlan plan;
    if (!script_) {
      if (frames_ > 0 && frame_ >= frames_) {
        plan.last = true;
        plan.screenshot = screenshot_;
      }
      return plan;
    }
    if (settle_ > 0) {  // a screenshot is pending: let ImGui settle first
      if (--settle_ == 0) plan.screenshot = std::exchange(pending_, {});
      return plan;
    }
    const ScriptStep step = script_->next(app.model, &app.display);
    if (step.reframe) app.framed = false;
    if (!step.view.empty()) {
      const ViewPreset preset = step.view == "front"   ? ViewPreset::Front
                                : step.view == "back"  ? ViewPreset::Back
                                : step.view == "right" ? ViewPreset::Right
                                : step.view == "left"  ? ViewPreset::Left
                                : step.view == "top"   ? ViewPreset::Top
                                                       : ViewPreset::Bottom;
      app.camera.set_view(preset);
      app.framed = false;
    }
    switch (step.kind) {
      case ScriptStep::Kind::Screenshot:
        pending_ = step.path;
        settle_ = kSettleFrames;  // this frame and kSettleFrames - 1 more, then capture
        break;
      case ScriptStep::Kind::Quit:
      case ScriptStep::Kind::End:
        plan.last = true;
        break;
      case ScriptStep::Kind::Error:
        std::cerr << step.message << '\n';
        plan.last = true;
        plan.exit_code = 1;
        break;
    }
    return plan;
  }

 private:
  std::unique_ptr<ScriptRunner> script_;
  int frames_ = 0, frame_ = 0, settle_ = 0;
  std::string screenshot_, pending_;
};

// ---- window path ----------------------------------------------------------------------------

struct WindowInput {
  std::vector<WindowEvent> events;
  std::vector<std::string> dropped;
  double last_activity = 0.0;
};

WindowInput& input_of(GLFWwindow* window) { return *static_cast<WindowInput*>(glfwGetWindowUserPointer(window)); }

Modifiers modifiers_of(int mods) {
  return Modifiers{(mods & GLFW_MOD_SHIFT) != 0, (mods & GLFW_MOD_CONTROL) != 0, (mods & GLFW_MOD_ALT) != 0};
}

Modifiers current_modifiers(GLFWwindow* window) {
  auto down = [window](int key) { return glfwGetKey(window, key) == GLFW_PRESS; };
  return Modifiers{down(GLFW_KEY_LEFT_SHIFT) || down(GLFW_KEY_RIGHT_SHIFT),
                   down(GLFW_KEY_LEFT_CONTROL) || down(GLFW_KEY_RIGHT_CONTROL),
                   down(GLFW_KEY_LEFT_ALT) || down(GLFW_KEY_RIGHT_ALT)};
}

Key to_key(int k) {
  if (k >= GLFW_KEY_0 && k <= GLFW_KEY_9) return static_cast<Key>(static_cast<int>(Key::Digit0) + (k - GLFW_KEY_0));
  if (k >= GLFW_KEY_KP_0 && k <= GLFW_KEY_KP_9) {
    // Numpad 1/3/5/7 are views; the other numpad digits type distances.
    switch (k) {
      case GLFW_KEY_KP_1: return Key::Numpad1;
      case GLFW_KEY_KP_3: return Key::Numpad3;
      case GLFW_KEY_KP_5: return Key::Numpad5;
      case GLFW_KEY_KP_7: return Key::Numpad7;
      default: return static_cast<Key>(static_cast<int>(Key::Digit0) + (k - GLFW_KEY_KP_0));
    }
  }
  switch (k) {
    case GLFW_KEY_F: return Key::F;
    case GLFW_KEY_HOME: return Key::Home;
    case GLFW_KEY_KP_DECIMAL: return Key::NumpadPeriod;
    case GLFW_KEY_A: return Key::A;
    case GLFW_KEY_D: return Key::D;
    case GLFW_KEY_G: return Key::G;
    case GLFW_KEY_R: return Key::R;
    case GLFW_KEY_L: return Key::L;
    case GLFW_KEY_C: return Key::C;
    case GLFW_KEY_I: return Key::I;
    case GLFW_KEY_K: return Key::K;
    case GLFW_KEY_T: return Key::T;
    case GLFW_KEY_P: return Key::P;
    case GLFW_KEY_TAB: return Key::Tab;
    case GLFW_KEY_KP_ADD:
    case GLFW_KEY_EQUAL: return Key::NumpadPlus;
    case GLFW_KEY_X: return Key::X;
    case GLFW_KEY_Y: return Key::Y;
    case GLFW_KEY_Z: return Key::Z;
    case GLFW_KEY_S: return Key::S;
    case GLFW_KEY_O: return Key::O;
    case GLFW_KEY_E: return Key::E;
    case GLFW_KEY_PAGE_UP: return Key::PageUp;
    case GLFW_KEY_PAGE_DOWN: return Key::PageDown;
    case GLFW_KEY_ESCAPE: return Key::Escape;
    case GLFW_KEY_ENTER:
    case GLFW_KEY_KP_ENTER: return Key::Enter;
    case GLFW_KEY_BACKSPACE: return Key::Backspace;
    case GLFW_KEY_MINUS: return Key::Minus;
    case GLFW_KEY_KP_SUBTRACT: return Key::NumpadMinus;
    case GLFW_KEY_PERIOD: return Key::Period;
    case GLFW_KEY_SPACE: return Key::Space;
    case GLFW_KEY_LEFT: return Key::Left;
    case GLFW_KEY_RIGHT: return Key::Right;
    default: return Key::None;
  }
}

WindowEvent mouse_event(GLFWwindow* window, WindowEvent::Type type) {
  WindowEvent e;
  e.type = type;
  glfwGetCursorPos(window, &e.x, &e.y);
  e.mods = current_modifiers(window);
  e.over_ui = ImGui::GetIO().WantCaptureMouse;
  return e;
}

void on_mouse_button(GLFWwindow* window, int button, int action, int mods) {
  WindowInput& input = input_of(window);
  input.last_activity = glfwGetTime();
  if (button < 0 || button > 2) return;
  WindowEvent e = mouse_event(window, action == GLFW_PRESS ? WindowEvent::Type::Press : WindowEvent::Type::Release);
  // GLFW numbers left 0, right 1, middle 2, as WindowEvent does.
  e.button = button;
  e.mods = modifiers_of(mods);
  input.events.push_back(e);
}

void on_scroll(GLFWwindow* window, double /*x*/, double y) {
  input_of(window).last_activity = glfwGetTime();
  WindowEvent e = mouse_event(window, WindowEvent::Type::Wheel);
  e.wheel = y;
  input_of(window).events.push_back(e);
}

void on_key(GLFWwindow* window, int key, int /*scancode*/, int action, int mods) {
  input_of(window).last_activity = glfwGetTime();
  if (action != GLFW_PRESS && action != GLFW_REPEAT) return;
  WindowEvent e;
  e.type = WindowEvent::Type::Key;
  e.key = to_key(key);
  e.mods = modifiers_of(mods);
  e.over_ui = ImGui::GetIO().WantCaptureKeyboard;
  if (e.key != Key::None) input_of(window).events.push_back(e);
}

void on_drop(GLFWwindow* window, int count, const char** paths) {
  input_of(window).last_activity = glfwGetTime();
  if (count > 0) input_of(window).dropped.emplace_back(paths[0]);
}

void on_cursor_pos(GLFWwindow* window, double /*x*/, double /*y*/) {
  input_of(window).last_activity = glfwGetTime();
  input_of(window).events.push_back(mouse_event(window, WindowEvent::Type::Move));
}

int run_window(WindowContext& window, ModelerController& app, RunPlan& plan) {
  GLFWwindow* handle = window.handle();
  WindowInput input;
  glfwSetWindowUserPointer(handle, &input);
  glfwSetMouseButtonCallback(handle, on_mouse_button);
  glfwSetScrollCallback(handle, on_scroll);
  glfwSetKeyCallback(handle, on_key);
  glfwSetDropCallback(handle, on_drop);
  glfwSetCursorPosCallback(handle, on_cursor_pos);

  ImGuiContextGuard imgui;
  GlfwBackendGuard platform(handle);
  OpenGl3BackendGuard renderer;
  ModelerView view;
  // Clicks skip control points behind the surface: picking reads the surface's depth.
  app.set_depth_source([&view](const OrbitCamera& c, int w, int h, const ModelerDisplay& d) {
    return view.surface_depth(c, w, h, d);
  });
  struct ForgetView {
    ModelerController& app;
    ~ForgetView() { app.set_depth_source({}); }
  } forget_view{app};
  FrameClock clock;
  int exit_code = 0;
  std::string shown_title;
  while (true) {
    if (plan.bounded()) {
      glfwPollEvents();
    } else if (app.playing()) {
      glfwPollEvents();  // playback: a frame each swap
    } else if (glfwGetTime() - input.last_activity < kAwakeSeconds || app.model.dragging()) {
      glfwWaitEventsTimeout(0.1);
    } else {
      glfwWaitEventsTimeout(5.0);  // idle; wake now and then for the autosave
    }
    if (window.should_close()) {
      if (app.request_quit()) break;
      glfwSetWindowShouldClose(handle, GLFW_FALSE);
    }
    if (app.quit_confirmed()) break;
    clock.begin();
    for (const std::string& path : std::exchange(input.dropped, {})) app.open(path);
    for (const WindowEvent& e : std::exchange(input.events, {})) app.handle(e);
    const FramePlan frame = plan.before_frame(app);
    app.frame_ms = clock.average_ms();
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    int fb_w = 0, fb_h = 0;
    window.framebuffer_size(fb_w, fb_h);
    app.draw_frame(view, fb_w, fb_h);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    if (!frame.screenshot.empty()) {
      int width = 0, height = 0;
      const std::vector<std::uint8_t> rgba = window.read_back_buffer(width, height);
      write_png(frame.screenshot, width, height, rgba);
    }
    window.swap_buffers();
    clock.end();
    app.tick(glfwGetTime());
    if (app.model.has_session()) {
      std::string title = "Sublift - " + std::filesystem::path(app.model.file_path()).filename().string();
      if (app.model.session().dirty()) title += " *";
      if (title != shown_title) glfwSetWindowTitle(handle, (shown_title = title).c_str());
    }
    if (frame.last) {
      exit_code = frame.exit_code;
      break;
    }
  }
  app.clean_exit();
  return exit_code;
}

// ---- headless path --------------------------------------------------------------------------

int run_headless(ModelerController& app, RunPlan& plan, const GuiOptions& options) {
  HeadlessContext context;
  OffscreenTarget target(options.width, options.height);
  ImGuiContextGuard imgui;
  OpenGl3BackendGuard renderer;
  ModelerView view;
  FrameClock clock;
  ImGuiIO& io = ImGui::GetIO();
  // Keep the mouse off the viewport so hover effects match a window nobody touches.
  io.MousePos = ImVec2(-FLT_MAX, -FLT_MAX);
  for (;;) {
    io.DisplaySize = ImVec2(static_cast<float>(options.width), static_cast<float>(options.height));
    io.DeltaTime = 1.0f / 60.0f;
    clock.begin();
    const FramePlan frame = plan.before_frame(app);
    app.frame_ms = clock.average_ms();
    ImGui_ImplOpenGL3_NewFrame();
    target.bind();
    app.draw_frame(view, options.width, options.height);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    if (!frame.screenshot.empty()) write_png(frame.screenshot, options.width, options.height, target.read_rgba());
    clock.end();
    if (frame.last) return frame.exit_code;
  }
}

}  // namespace

std::string default_model_path() { return std::string(SUBLIFT_ASSETS_DIR) + "/sample.obj"; }

int run_gui(const GuiOptions& options) {
  const bool interactive = options.script.empty() && options.screenshot.empty() && options.frames == 0;
  ModelerController app(interactive);
  std::unique_ptr<ScriptRunner> script;
  try {
    if (!options.script.empty()) script = std::make_unique<ScriptRunner>(options.script);
    if (script && options.json) script->set_json_output(&std::cout);
  } catch (const std::exception& e) {
    std::cerr << "sublift: " << e.what() << '\n';
    return 1;
  }
  // A script opens its own model; without one, open FILE or the sample.
  if (!script || !options.file.empty()) {
    const std::string file = options.file.empty() ? default_model_path() : options.file;
    try {
      app.model.open(file);
    } catch (const std::exception& e) {  // sublift::Error, or bad_alloc on a huge file
      std::string what = e.what();
      while (!what.empty() && (what.back() == '\n' || what.back() == ' ')) what.pop_back();
      // core's messages usually start with the file name; add it when they do not.
      std::cerr << "sublift: " << (what.find(file) == std::string::npos ? file + ": " : "") << what << '\n';
      return 1;
    }
  }
  try {
    std::optional<WindowContext> window;
    bool headless = options.headless;
    if (!headless) {
      try {
        WindowSettings settings;
        settings.width = options.width;
        settings.height = options.height;
        settings.title = "Sublift";
        settings.vsync = interactive;
        window.emplace(settings);
      } catch (const NoDisplayError&) {
        headless = true;
        if (!script) {
          const std::string path = options.screenshot.empty() ? kDefaultScreenshot : options.screenshot;
          std::cerr << "sublift: no display available; rendering the same view headless to " << path << '\n';
        }
      }
    }
    app.set_interactive(interactive && !headless);
    app.check_recovery();
    RunPlan plan(options, std::move(script), headless);
    if (headless) return run_headless(app, plan, options);
    return run_window(*window, app, plan);
  } catch (const std::exception& e) {
    std::cerr << "sublift: " << e.what() << '\n';
    return 1;
  }
}

}  // namespace sublift
