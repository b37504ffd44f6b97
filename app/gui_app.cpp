#include "app/gui_app.h"

#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/errors.h"
#include "core/mesh_import.h"
#include "core/mesh_stats.h"
#include "render/headless_context.h"
#include "render/offscreen_target.h"
#include "render/render_errors.h"
#include "render/viewport_renderer.h"
#include "render/window_context.h"
#include "ui/panels.h"
#include "ui/viewport_input.h"

#ifndef SUBLIFT_ASSETS_DIR
#define SUBLIFT_ASSETS_DIR "assets"
#endif

namespace sublift {
namespace {

constexpr const char* kGlslVersion = "#version 330 core";
constexpr const char* kDefaultScreenshot = "sublift-screenshot.png";
constexpr int kDefaultScreenshotFrames = 3;  // ImGui settles its layout within two frames
constexpr glm::vec3 kWindowClear{0.11f, 0.12f, 0.13f};
constexpr double kAwakeSeconds = 1.5;  // keep redrawing this long after the last input

struct LoadedModel {
  SurfaceMesh mesh;
  ModelInfo info;
};

/// Imports `path` and computes what the panel shows; throws sublift::Error.
LoadedModel load_model(const std::string& path) {
  LoadedMesh loaded = import_surface_mesh(path);
  LoadedModel model;
  model.info.file_path = path;
  model.info.file_name = std::filesystem::path(path).filename().string();
  model.info.stats = compute_mesh_stats(loaded.mesh);
  // Lines name the file's base name: the panel is narrow and shows the path in a tooltip.
  model.info.warnings = loaded.report.empty() ? "" : loaded.report.format(model.info.file_name);
  model.mesh = std::move(loaded.mesh);
  return model;
}

// Time spent producing a frame (drawing and presenting, which includes waiting for vsync; not
// the idle wait for input), smoothed so the status line is readable.
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

struct AppState {
  LoadedModel model;
  OrbitCamera camera;
  ViewToggles toggles;
  PanelLayout layout;
  FrameClock clock;
  bool framed = false;  // frame the model once the viewport size is known
};

// Applies one viewport or panel request to the camera and keeps it in step with the toggles.
void apply_camera_action(AppState& state, const CameraAction& action, const Bounds& bounds) {
  OrbitCamera& camera = state.camera;
  switch (action.type) {
    case CameraActionType::None: break;
    case CameraActionType::Orbit: camera.orbit(action.dx, action.dy); break;
    case CameraActionType::Pan: camera.pan(action.dx, action.dy); break;
    case CameraActionType::Zoom: camera.zoom(action.steps); break;
    case CameraActionType::Frame: frame_bounds(camera, bounds); break;
    case CameraActionType::ViewFront: camera.set_view(ViewPreset::Front); break;
    case CameraActionType::ViewBack: camera.set_view(ViewPreset::Back); break;
    case CameraActionType::ViewRight: camera.set_view(ViewPreset::Right); break;
    case CameraActionType::ViewLeft: camera.set_view(ViewPreset::Left); break;
    case CameraActionType::ViewTop: camera.set_view(ViewPreset::Top); break;
    case CameraActionType::ViewBottom: camera.set_view(ViewPreset::Bottom); break;
    case CameraActionType::ToggleOrthographic:
      state.toggles.orthographic = !state.toggles.orthographic;
      break;
  }
  camera.orthographic = state.toggles.orthographic;
  const UpAxis up_axis = state.toggles.z_up ? UpAxis::Z : UpAxis::Y;
  if (camera.up_axis != up_axis) {
    // The same angles now look at the model from elsewhere: frame it again.
    camera.up_axis = up_axis;
    frame_bounds(camera, bounds);
  }
}

// The one frame both the window and the headless path draw: panels, viewport, ImGui on top.
// The caller has started the ImGui backend frame(s) and bound the target framebuffer.
void draw_frame(AppState& state, ViewportRenderer& viewport, int fb_width, int fb_height) {
  const ImGuiIO& io = ImGui::GetIO();
  const float display_w = io.DisplaySize.x, display_h = io.DisplaySize.y;

  ImGui::NewFrame();
  const CameraAction panel_action =
      draw_side_panel(state.model.info, state.toggles, display_w, display_h, state.layout);
  const MeshStats& stats = state.model.info.stats;
  draw_status_line({state.model.info.file_name, stats.vertices, stats.faces, stats.polylines,
                    state.clock.average_ms(), state.toggles.orthographic},
                   display_w, display_h, state.layout);
  ImGui::Render();

  // ImGui works in window coordinates, top-left origin; GL in framebuffer pixels, bottom-left.
  const ScreenRect r = viewport_rect(display_w, display_h, state.layout);
  const float sx = display_w > 0.0f ? static_cast<float>(fb_width) / display_w : 1.0f;
  const float sy = display_h > 0.0f ? static_cast<float>(fb_height) / display_h : 1.0f;
  const ViewportRect rect{static_cast<int>(std::lround(r.x * sx)),
                         static_cast<int>(std::lround((display_h - r.y - r.height) * sy)),
                         static_cast<int>(std::lround(r.width * sx)),
                         static_cast<int>(std::lround(r.height * sy))};
  state.camera.set_viewport(rect.width, rect.height);
  if (!state.framed) {
    frame_bounds(state.camera, viewport.bounds());
    state.framed = true;
  }
  apply_camera_action(state, panel_action, viewport.bounds());

  clear_framebuffer(fb_width, fb_height, kWindowClear);
  if (rect.width > 0 && rect.height > 0) {
    viewport.draw(state.camera, rect, DisplayOptions{state.toggles.shaded, state.toggles.wireframe});
  }
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

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
    if (!ImGui_ImplOpenGL3_Init(kGlslVersion)) {
      throw RenderError("Dear ImGui's OpenGL 3 backend failed to start");
    }
  }
  ~OpenGl3BackendGuard() { ImGui_ImplOpenGL3_Shutdown(); }
  OpenGl3BackendGuard(const OpenGl3BackendGuard&) = delete;
  OpenGl3BackendGuard& operator=(const OpenGl3BackendGuard&) = delete;
};

struct GlfwBackendGuard {
  explicit GlfwBackendGuard(GLFWwindow* window) {
    // install_callbacks: ImGui chains to the callbacks the app installed before.
    if (!ImGui_ImplGlfw_InitForOpenGL(window, true)) {
      throw RenderError("Dear ImGui's GLFW backend failed to start");
    }
  }
  ~GlfwBackendGuard() { ImGui_ImplGlfw_Shutdown(); }
  GlfwBackendGuard(const GlfwBackendGuard&) = delete;
  GlfwBackendGuard& operator=(const GlfwBackendGuard&) = delete;
};

// ---- window path ----------------------------------------------------------------------------

// Input gathered by the GLFW callbacks between frames.
struct WindowInput {
  std::vector<InputEvent> events;
  bool dragging[3] = {false, false, false};  // left, right, middle: pressed over the viewport
  double last_x = 0.0, last_y = 0.0;
  std::optional<std::string> dropped_file;
  double last_activity = 0.0;  // glfwGetTime() of the last input, to decide how long to sleep
};

Modifiers current_modifiers(GLFWwindow* window) {
  auto down = [window](int key) { return glfwGetKey(window, key) == GLFW_PRESS; };
  return Modifiers{down(GLFW_KEY_LEFT_SHIFT) || down(GLFW_KEY_RIGHT_SHIFT),
                   down(GLFW_KEY_LEFT_CONTROL) || down(GLFW_KEY_RIGHT_CONTROL),
                   down(GLFW_KEY_LEFT_ALT) || down(GLFW_KEY_RIGHT_ALT)};
}

Key to_key(int glfw_key) {
  switch (glfw_key) {
    case GLFW_KEY_F: return Key::F;
    case GLFW_KEY_HOME: return Key::Home;
    case GLFW_KEY_KP_DECIMAL: return Key::NumpadPeriod;
    case GLFW_KEY_KP_1: return Key::Numpad1;
    case GLFW_KEY_KP_3: return Key::Numpad3;
    case GLFW_KEY_KP_5: return Key::Numpad5;
    case GLFW_KEY_KP_7: return Key::Numpad7;
    default: return Key::None;
  }
}

WindowInput& input_of(GLFWwindow* window) {
  return *static_cast<WindowInput*>(glfwGetWindowUserPointer(window));
}

void on_mouse_button(GLFWwindow* window, int button, int action, int /*mods*/) {
  WindowInput& input = input_of(window);
  input.last_activity = glfwGetTime();
  if (button < 0 || button > 2) return;
  if (action == GLFW_PRESS && !ImGui::GetIO().WantCaptureMouse) input.dragging[button] = true;
  if (action == GLFW_RELEASE) input.dragging[button] = false;
}

void on_scroll(GLFWwindow* window, double /*x*/, double y) {
  input_of(window).last_activity = glfwGetTime();
  if (ImGui::GetIO().WantCaptureMouse) return;
  InputEvent event;
  event.type = InputEvent::Type::Wheel;
  event.mods = current_modifiers(window);
  event.wheel = y;
  input_of(window).events.push_back(event);
}

void on_key(GLFWwindow* window, int key, int /*scancode*/, int action, int mods) {
  input_of(window).last_activity = glfwGetTime();
  if (action != GLFW_PRESS || ImGui::GetIO().WantCaptureKeyboard) return;
  InputEvent event;
  event.type = InputEvent::Type::KeyPress;
  event.key = to_key(key);
  event.mods = Modifiers{(mods & GLFW_MOD_SHIFT) != 0, (mods & GLFW_MOD_CONTROL) != 0,
                         (mods & GLFW_MOD_ALT) != 0};
  if (event.key != Key::None) input_of(window).events.push_back(event);
}

void on_drop(GLFWwindow* window, int count, const char** paths) {
  input_of(window).last_activity = glfwGetTime();
  if (count > 0) input_of(window).dropped_file = paths[0];
}

void on_cursor_pos(GLFWwindow* window, double /*x*/, double /*y*/) {
  input_of(window).last_activity = glfwGetTime();
}

// Turns this frame's cursor motion and queued events into camera changes.
void process_input(GLFWwindow* window, WindowInput& input, AppState& state,
                   const Bounds& bounds) {
  double x = 0.0, y = 0.0;
  glfwGetCursorPos(window, &x, &y);
  int window_w = 1, window_h = 1, fb_w = 1, fb_h = 1;
  glfwGetWindowSize(window, &window_w, &window_h);
  glfwGetFramebufferSize(window, &fb_w, &fb_h);
  const double scale = window_w > 0 ? static_cast<double>(fb_w) / window_w : 1.0;
  InputEvent move;
  move.type = InputEvent::Type::MouseMove;
  move.mods = current_modifiers(window);
  move.left = input.dragging[GLFW_MOUSE_BUTTON_LEFT];
  move.right = input.dragging[GLFW_MOUSE_BUTTON_RIGHT];
  move.middle = input.dragging[GLFW_MOUSE_BUTTON_MIDDLE];
  move.dx = (x - input.last_x) * scale;
  move.dy = (y - input.last_y) * scale;
  input.last_x = x;
  input.last_y = y;
  if (move.left || move.right || move.middle) {
    apply_camera_action(state, map_viewport_input(move), bounds);
  }
  for (const InputEvent& event : input.events) {
    apply_camera_action(state, map_viewport_input(event), bounds);
  }
  input.events.clear();
}

// Replaces the model with a dropped file; a failure leaves the current one and is shown.
void open_dropped_file(WindowInput& input, AppState& state, ViewportRenderer& viewport) {
  if (!input.dropped_file) return;
  const std::string path = *std::exchange(input.dropped_file, std::nullopt);
  try {
    LoadedModel model = load_model(path);
    viewport.set_mesh(model.mesh);
    state.model = std::move(model);
    state.framed = false;
  } catch (const std::exception& e) {
    state.model.info.error = std::string("Cannot open dropped file: ") + e.what();
  }
}

int run_window(WindowContext& window, AppState& state, const GuiOptions& options) {
  GLFWwindow* handle = window.handle();
  WindowInput input;
  glfwSetWindowUserPointer(handle, &input);
  glfwGetCursorPos(handle, &input.last_x, &input.last_y);
  glfwSetMouseButtonCallback(handle, on_mouse_button);
  glfwSetScrollCallback(handle, on_scroll);
  glfwSetKeyCallback(handle, on_key);
  glfwSetDropCallback(handle, on_drop);
  glfwSetCursorPosCallback(handle, on_cursor_pos);

  ImGuiContextGuard imgui;
  GlfwBackendGuard platform(handle);
  OpenGl3BackendGuard renderer;
  ViewportRenderer viewport;
  viewport.set_mesh(state.model.mesh);

  const bool screenshot = !options.screenshot.empty();
  const int frames = options.frames > 0 ? options.frames
                                        : (screenshot ? kDefaultScreenshotFrames : 0);
  for (int frame = 1; !window.should_close(); ++frame) {
    if (frames > 0) {
      glfwPollEvents();
    } else if (glfwGetTime() - input.last_activity < kAwakeSeconds) {
      // Shortly after input keep drawing a few frames a second: ImGui's hover effects and
      // delayed tooltips need frames without new events.
      glfwWaitEventsTimeout(0.1);
    } else {
      glfwWaitEvents();  // idle: draw nothing until something happens
    }
    state.clock.begin();
    open_dropped_file(input, state, viewport);
    process_input(handle, input, state, viewport.bounds());
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    int fb_w = 0, fb_h = 0;
    window.framebuffer_size(fb_w, fb_h);
    draw_frame(state, viewport, fb_w, fb_h);
    const bool last = frames > 0 && frame >= frames;
    if (last && screenshot) {
      int width = 0, height = 0;
      const std::vector<std::uint8_t> rgba = window.read_back_buffer(width, height);
      write_png(options.screenshot, width, height, rgba);
    }
    window.swap_buffers();
    state.clock.end();
    if (last) break;
  }
  return 0;
}

// ---- headless path --------------------------------------------------------------------------

int run_headless(AppState& state, const GuiOptions& options, const std::string& path) {
  HeadlessContext context;
  OffscreenTarget target(options.width, options.height);
  ImGuiContextGuard imgui;
  OpenGl3BackendGuard renderer;
  ViewportRenderer viewport;
  viewport.set_mesh(state.model.mesh);

  ImGuiIO& io = ImGui::GetIO();
  const int frames = options.frames > 0 ? options.frames : kDefaultScreenshotFrames;
  for (int frame = 0; frame < frames; ++frame) {
    // No platform backend: the app states the display size and clock itself.
    io.DisplaySize = ImVec2(static_cast<float>(options.width), static_cast<float>(options.height));
    io.DeltaTime = 1.0f / 60.0f;
    state.clock.begin();
    ImGui_ImplOpenGL3_NewFrame();
    target.bind();
    draw_frame(state, viewport, options.width, options.height);
    state.clock.end();
  }
  write_png(path, options.width, options.height, target.read_rgba());
  return 0;
}

}  // namespace

std::string default_model_path() { return std::string(SUBLIFT_ASSETS_DIR) + "/sample.obj"; }

int run_gui(const GuiOptions& options) {
  const std::string file = options.file.empty() ? default_model_path() : options.file;
  AppState state;
  try {
    state.model = load_model(file);
  } catch (const std::exception& e) {  // sublift::Error, or bad_alloc on a huge file
    std::string what = e.what();
    while (!what.empty() && (what.back() == '\n' || what.back() == ' ')) what.pop_back();
    // core's messages usually start with the file name; add it when they do not.
    if (what.find(file) == std::string::npos) {
      std::cerr << "sublift: " << file << ": " << what << '\n';
    } else {
      std::cerr << "sublift: " << what << '\n';
    }
    return 1;
  }

  try {
    std::optional<WindowContext> window;
    try {
      WindowSettings settings;
      settings.width = options.width;
      settings.height = options.height;
      settings.title = "Sublift - " + state.model.info.file_name;
      settings.vsync = options.screenshot.empty();
      window.emplace(settings);
    } catch (const NoDisplayError&) {
      const std::string path = options.screenshot.empty() ? kDefaultScreenshot : options.screenshot;
      std::cerr << "sublift: no display available; rendering the same view headless to " << path
                << '\n';
      return run_headless(state, options, path);
    }
    return run_window(*window, state, options);
  } catch (const std::exception& e) {
    std::cerr << "sublift: " << e.what() << '\n';
    return 1;
  }
}

}  // namespace sublift
