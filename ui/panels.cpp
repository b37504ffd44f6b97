#include "ui/panels.h"

#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>

namespace sublift {
namespace {

constexpr ImGuiWindowFlags kDockedFlags =
    ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
    ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoBringToFrontOnFocus;

const ImVec4 kAccent{0.93f, 0.72f, 0.45f, 1.0f};   // the clay of the viewport, for headings
const ImVec4 kMuted{0.62f, 0.64f, 0.68f, 1.0f};
const ImVec4 kWarning{0.98f, 0.78f, 0.30f, 1.0f};
const ImVec4 kError{1.00f, 0.45f, 0.42f, 1.0f};

// Font candidates on Debian; ImGui's built-in bitmap font is the fallback.
constexpr const char* kFontFiles[] = {
    "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/truetype/liberation/LiberationSans-Regular.ttf",
};

std::string with_thousands(std::size_t n) {
  const std::string digits = std::to_string(n);
  std::string out;
  out.reserve(digits.size() + digits.size() / 3);
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out.push_back(',');
    out.push_back(digits[i]);
  }
  return out;
}

std::string face_size_name(std::size_t corners) {
  switch (corners) {
    case 3: return "Triangles";
    case 4: return "Quads";
    case 5: return "Pentagons";
    case 6: return "Hexagons";
    default: return std::to_string(corners) + "-gons";
  }
}

void table_row(const char* label, const std::string& value, bool flag = false) {
  ImGui::TableNextRow();
  ImGui::TableSetColumnIndex(0);
  ImGui::TextColored(kMuted, "%s", label);
  ImGui::TableSetColumnIndex(1);
  if (flag) {
    ImGui::TextColored(kWarning, "%s", value.c_str());
  } else {
    ImGui::TextUnformatted(value.c_str());
  }
}

void count_row(const char* label, std::size_t value, bool problem_if_nonzero = false) {
  table_row(label, with_thousands(value), problem_if_nonzero && value > 0);
}

std::string format_vec(const glm::dvec3& v) {
  char text[96];
  std::snprintf(text, sizeof text, "%.4g, %.4g, %.4g", v.x, v.y, v.z);
  return text;
}

bool section(const char* title) {
  ImGui::Spacing();
  return ImGui::CollapsingHeader(title, ImGuiTreeNodeFlags_DefaultOpen);
}

void draw_file_section(const ModelInfo& model) {
  ImGui::TextColored(kMuted, "File");
  ImGui::SameLine();
  ImGui::TextUnformatted(model.file_name.c_str());
  if (ImGui::IsItemHovered() && !model.file_path.empty()) {
    ImGui::SetTooltip("%s", model.file_path.c_str());
  }
  if (!model.error.empty()) {
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextColored(kError, "%s", model.error.c_str());
    ImGui::PopTextWrapPos();
  }
}

void draw_mesh_section(const MeshStats& s) {
  if (!section("Mesh")) return;
  if (ImGui::BeginTable("counts", 2, ImGuiTableFlags_SizingStretchProp)) {
    ImGui::TableSetupColumn("label", ImGuiTableColumnFlags_WidthStretch, 1.3f);
    ImGui::TableSetupColumn("value", ImGuiTableColumnFlags_WidthStretch, 1.0f);
    count_row("Vertices", s.vertices);
    if (s.used_vertices != s.vertices) count_row("  used by faces", s.used_vertices);
    count_row("Edges", s.edges);
    count_row("Faces", s.faces);
    count_row("Components", s.components);
    table_row("Euler characteristic", std::to_string(s.euler_characteristic));
    table_row("Boundary", with_thousands(s.boundary_loops) + " loops, " +
                              with_thousands(s.boundary_edges) + " edges");
    table_row("Non-manifold",
              with_thousands(s.non_manifold_edges) + " edges, " +
                  with_thousands(s.non_manifold_vertices) + " verts",
              s.non_manifold_edges + s.non_manifold_vertices > 0);
    count_row("Misoriented edges", s.misoriented_edges, true);
    count_row("Isolated vertices", s.isolated_vertices, true);
    if (s.polylines > 0) {
      table_row("Polylines", with_thousands(s.polylines) + " (" +
                                 with_thousands(s.closed_polylines) + " closed)");
      count_row("  segments", s.polyline_segments);
    }
    ImGui::EndTable();
  }

  if (!s.face_sizes.empty()) {
    ImGui::Spacing();
    ImGui::TextColored(kMuted, "Face sizes");
    std::size_t largest = 1;
    for (const auto& [corners, count] : s.face_sizes) largest = std::max(largest, count);
    if (ImGui::BeginTable("face_sizes", 2, ImGuiTableFlags_SizingStretchProp)) {
      ImGui::TableSetupColumn("size", ImGuiTableColumnFlags_WidthStretch, 0.8f);
      ImGui::TableSetupColumn("bar", ImGuiTableColumnFlags_WidthStretch, 1.5f);
      for (const auto& [corners, count] : s.face_sizes) {
        ImGui::TableNextRow();
        ImGui::TableSetColumnIndex(0);
        ImGui::TextUnformatted(face_size_name(corners).c_str());
        ImGui::TableSetColumnIndex(1);
        const std::string label = with_thousands(count);
        ImGui::ProgressBar(static_cast<float>(count) / static_cast<float>(largest),
                           ImVec2(-1.0f, 0.0f), label.c_str());
      }
      ImGui::EndTable();
    }
  }

  ImGui::Spacing();
  ImGui::TextColored(kMuted, "Bounding box");
  if (ImGui::BeginTable("bbox", 2, ImGuiTableFlags_SizingStretchProp)) {
    ImGui::TableSetupColumn("label", ImGuiTableColumnFlags_WidthStretch, 0.5f);
    ImGui::TableSetupColumn("value", ImGuiTableColumnFlags_WidthStretch, 2.0f);
    table_row("min", format_vec(s.bbox_min));
    table_row("max", format_vec(s.bbox_max));
    table_row("size", format_vec(s.bbox_max - s.bbox_min));
    ImGui::EndTable();
  }
}

void draw_warnings_section(const std::string& warnings) {
  if (warnings.empty()) return;
  const auto lines = static_cast<int>(std::count(warnings.begin(), warnings.end(), '\n') +
                                      (warnings.back() != '\n' ? 1 : 0));
  const std::string title = "Import warnings (" + std::to_string(lines) + ")###warnings";
  ImGui::PushStyleColor(ImGuiCol_Text, kWarning);
  const bool open = section(title.c_str());
  ImGui::PopStyleColor();
  if (!open) return;
  std::istringstream in(warnings);
  for (std::string line; std::getline(in, line);) {
    if (line.empty()) continue;
    ImGui::Bullet();
    ImGui::TextWrapped("%s", line.c_str());  // BulletText would not wrap
  }
}

void draw_display_section(ViewToggles& toggles) {
  if (!section("Display")) return;
  // Two aligned columns of checkboxes.
  const float column = ImGui::GetContentRegionAvail().x * 0.5f;
  ImGui::Checkbox("Shaded", &toggles.shaded);
  ImGui::SameLine(column);
  ImGui::Checkbox("Wireframe", &toggles.wireframe);
  ImGui::Checkbox("Orthographic", &toggles.orthographic);
  ImGui::SameLine(column);
  ImGui::Checkbox("Z up", &toggles.z_up);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Z is up (Blender); off: Y is up (OBJ, glTF)");
}

CameraAction draw_view_section() {
  CameraAction action;
  if (!section("View")) return action;
  struct Button {
    const char* label;
    CameraActionType type;
  };
  constexpr Button kButtons[] = {
      {"Front", CameraActionType::ViewFront}, {"Right", CameraActionType::ViewRight},
      {"Top", CameraActionType::ViewTop},     {"Back", CameraActionType::ViewBack},
      {"Left", CameraActionType::ViewLeft},   {"Bottom", CameraActionType::ViewBottom},
  };
  const ImGuiStyle& style = ImGui::GetStyle();
  const float width = (ImGui::GetContentRegionAvail().x - 3.0f * style.ItemSpacing.x) / 4.0f;
  // Two rows: Frame + front/right/top, then the opposite views under their counterparts.
  if (ImGui::Button("Frame", ImVec2(width, 0.0f))) action.type = CameraActionType::Frame;
  for (int i = 0; i < 6; ++i) {
    if (i == 3) {
      ImGui::Dummy(ImVec2(width, 0.0f));
    }
    ImGui::SameLine();
    if (ImGui::Button(kButtons[i].label, ImVec2(width, 0.0f))) action.type = kButtons[i].type;
  }
  return action;
}

void draw_help_section() {
  if (!section("Mouse and keys")) return;
  if (ImGui::BeginTable("mouse", 3, ImGuiTableFlags_SizingStretchProp)) {
    ImGui::TableSetupColumn("Drag", ImGuiTableColumnFlags_WidthStretch, 0.55f);
    ImGui::TableSetupColumn("Blender", ImGuiTableColumnFlags_WidthStretch, 1.25f);
    ImGui::TableSetupColumn("Maya", ImGuiTableColumnFlags_WidthStretch, 0.9f);
    ImGui::TableNextRow();
    for (int column = 0; column < 3; ++column) {
      ImGui::TableSetColumnIndex(column);
      ImGui::TextColored(kAccent, "%s", ImGui::TableGetColumnName(column));
    }
    for (const MouseBinding& b : mouse_bindings()) {
      ImGui::TableNextRow();
      ImGui::TableSetColumnIndex(0);
      ImGui::Text("%.*s", static_cast<int>(b.action.size()), b.action.data());
      ImGui::TableSetColumnIndex(1);
      ImGui::TextColored(kMuted, "%.*s", static_cast<int>(b.blender.size()), b.blender.data());
      ImGui::TableSetColumnIndex(2);
      ImGui::TextColored(kMuted, "%.*s", static_cast<int>(b.maya.size()), b.maya.data());
    }
    ImGui::EndTable();
  }
  ImGui::Spacing();
  if (ImGui::BeginTable("keys", 2, ImGuiTableFlags_SizingStretchProp)) {
    ImGui::TableSetupColumn("keys", ImGuiTableColumnFlags_WidthStretch, 1.1f);
    ImGui::TableSetupColumn("action", ImGuiTableColumnFlags_WidthStretch, 1.0f);
    for (const KeyBinding& b : key_bindings()) {
      ImGui::TableNextRow();
      ImGui::TableSetColumnIndex(0);
      ImGui::TextColored(kMuted, "%.*s", static_cast<int>(b.keys.size()), b.keys.data());
      ImGui::TableSetColumnIndex(1);
      ImGui::Text("%.*s", static_cast<int>(b.action.size()), b.action.data());
    }
    ImGui::EndTable();
  }
  ImGui::TextColored(kMuted, "Drop a mesh file on the window to open it.");
}

}  // namespace

ScreenRect viewport_rect(float width, float height, const PanelLayout& layout) {
  const float side = std::min(layout.side_width, width);
  const float status = std::min(layout.status_height, height);
  return ScreenRect{side, 0.0f, std::max(width - side, 0.0f), std::max(height - status, 0.0f)};
}

void apply_ui_theme(float font_size) {
  ImGuiIO& io = ImGui::GetIO();
  for (const char* file : kFontFiles) {
    if (std::filesystem::exists(file) && io.Fonts->AddFontFromFileTTF(file, font_size) != nullptr) {
      break;
    }
  }
  if (io.Fonts->Fonts.empty()) io.Fonts->AddFontDefault();

  ImGui::StyleColorsDark();
  ImGuiStyle& style = ImGui::GetStyle();
  style.WindowRounding = 0.0f;
  style.WindowBorderSize = 0.0f;
  style.FrameRounding = 3.0f;
  style.GrabRounding = 3.0f;
  style.WindowPadding = ImVec2(12.0f, 10.0f);
  style.FramePadding = ImVec2(8.0f, 4.0f);
  style.ItemSpacing = ImVec2(8.0f, 4.0f);
  style.CellPadding = ImVec2(4.0f, 1.0f);
  style.ScrollbarSize = 12.0f;
  ImVec4* c = style.Colors;
  c[ImGuiCol_WindowBg] = ImVec4(0.16f, 0.17f, 0.19f, 1.0f);
  c[ImGuiCol_Text] = ImVec4(0.90f, 0.91f, 0.93f, 1.0f);
  c[ImGuiCol_Header] = ImVec4(0.24f, 0.26f, 0.30f, 1.0f);
  c[ImGuiCol_HeaderHovered] = ImVec4(0.30f, 0.33f, 0.38f, 1.0f);
  c[ImGuiCol_HeaderActive] = ImVec4(0.34f, 0.37f, 0.43f, 1.0f);
  c[ImGuiCol_Button] = ImVec4(0.26f, 0.28f, 0.32f, 1.0f);
  c[ImGuiCol_ButtonHovered] = ImVec4(0.36f, 0.39f, 0.45f, 1.0f);
  c[ImGuiCol_ButtonActive] = ImVec4(0.44f, 0.47f, 0.54f, 1.0f);
  c[ImGuiCol_FrameBg] = ImVec4(0.22f, 0.23f, 0.26f, 1.0f);
  c[ImGuiCol_FrameBgHovered] = ImVec4(0.28f, 0.30f, 0.34f, 1.0f);
  c[ImGuiCol_CheckMark] = kAccent;
  c[ImGuiCol_PlotHistogram] = ImVec4(0.72f, 0.55f, 0.36f, 1.0f);
  c[ImGuiCol_Separator] = ImVec4(0.30f, 0.32f, 0.36f, 1.0f);
}

CameraAction draw_side_panel(const ModelInfo& model, ViewToggles& toggles, float display_width,
                             float display_height, const PanelLayout& layout) {
  const ScreenRect view = viewport_rect(display_width, display_height, layout);
  ImGui::SetNextWindowPos(ImVec2(0.0f, 0.0f));
  ImGui::SetNextWindowSize(ImVec2(view.x, view.height));
  CameraAction action;
  if (ImGui::Begin("Sublift##side_panel", nullptr, kDockedFlags | ImGuiWindowFlags_NoTitleBar)) {
    ImGui::TextColored(kAccent, "SUBLIFT");
    ImGui::SameLine();
    ImGui::TextColored(kMuted, "multiresolution modeler");
    ImGui::Separator();
    draw_file_section(model);
    draw_mesh_section(model.stats);
    draw_warnings_section(model.warnings);
    draw_display_section(toggles);
    action = draw_view_section();
    draw_help_section();
  }
  ImGui::End();
  return action;
}

void draw_status_line(const StatusInfo& status, float display_width, float display_height,
                      const PanelLayout& layout) {
  const float height = std::min(layout.status_height, display_height);
  ImGui::SetNextWindowPos(ImVec2(0.0f, display_height - height));
  ImGui::SetNextWindowSize(ImVec2(display_width, height));
  ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(12.0f, 5.0f));
  ImGui::PushStyleColor(ImGuiCol_WindowBg, ImVec4(0.11f, 0.12f, 0.13f, 1.0f));
  const ImGuiWindowFlags flags = kDockedFlags | ImGuiWindowFlags_NoTitleBar |
                                 ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoInputs;
  if (ImGui::Begin("##status_line", nullptr, flags)) {
    ImGui::TextUnformatted(status.file_name.c_str());
    ImGui::SameLine(0.0f, 24.0f);
    ImGui::TextColored(kMuted, "%s vertices   %s faces", with_thousands(status.vertices).c_str(),
                       with_thousands(status.faces).c_str());
    if (status.polylines > 0) {
      ImGui::SameLine();
      ImGui::TextColored(kMuted, "  %s %s", with_thousands(status.polylines).c_str(),
                         status.polylines == 1 ? "polyline" : "polylines");
    }
    ImGui::SameLine(0.0f, 24.0f);
    ImGui::TextColored(kMuted, "%s", status.orthographic ? "Orthographic" : "Perspective");
    char timing[48];
    std::snprintf(timing, sizeof timing, "frame %.2f ms", status.frame_ms);
    const float right = ImGui::GetWindowContentRegionMax().x - ImGui::CalcTextSize(timing).x;
    ImGui::SameLine(std::max(right, ImGui::GetCursorPosX() + 24.0f));
    ImGui::TextColored(kMuted, "%s", timing);
  }
  ImGui::End();
  ImGui::PopStyleColor();
  ImGui::PopStyleVar();
}

}  // namespace sublift
