#include "ui/modeler_panels.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string_view>
#include <cstdio>
#include <vector>

#include "core/schemes/registry.h"
#include "ui/modeler_keys.h"

namespace sublift {
namespace {

constexpr ImGuiWindowFlags kDockedFlags = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize |
                                          ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoSavedSettings |
                                          ImGuiWindowFlags_NoBringToFrontOnFocus | ImGuiWindowFlags_NoTitleBar;
const ImVec4 kAccent{0.93f, 0.72f, 0.45f, 1.0f};
const ImVec4 kMuted{0.62f, 0.64f, 0.68f, 1.0f};
const ImVec4 kWarning{0.98f, 0.78f, 0.30f, 1.0f};
const ImVec4 kError{1.00f, 0.45f, 0.42f, 1.0f};
const ImVec4 kGood{0.55f, 0.85f, 0.55f, 1.0f};

bool section(const char* title, bool open_by_default = true) {
  ImGui::Spacing();
  return ImGui::CollapsingHeader(title, open_by_default ? ImGuiTreeNodeFlags_DefaultOpen : 0);
}

void draw_file_section(const ModelerPanelData& d, FileFields& f, ModelerPanelRequests& r) {
  ImGui::TextColored(kMuted, "File");
  ImGui::SameLine();
  ImGui::TextUnformatted(d.file_name.c_str());
  if (d.dirty) {
    ImGui::SameLine();
    ImGui::TextColored(kWarning, "(modified)");
  }
  if (ImGui::IsItemHovered() && !d.file_path.empty()) ImGui::SetTooltip("%s", d.file_path.c_str());
  if (!d.error.empty()) {
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextColored(kError, "%s", d.error.c_str());
    ImGui::PopTextWrapPos();
  } else if (!d.message.empty()) {
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextColored(kGood, "%s", d.message.c_str());
    ImGui::PopTextWrapPos();
  }
  if (!section("Files", false)) return;
  const float button = 70.0f;
  ImGui::SetNextItemWidth(-button - ImGui::GetStyle().ItemSpacing.x);
  const bool enter = ImGui::InputTextWithHint("##open", "path to open", &f.open_path,
                                              ImGuiInputTextFlags_EnterReturnsTrue);
  ImGui::SameLine();
  if ((ImGui::Button("Open", ImVec2(button, 0)) || enter) && !f.open_path.empty()) r.open = f.open_path;
  if (!d.recent.empty()) {
    ImGui::SetNextItemWidth(-1.0f);
    if (ImGui::BeginCombo("##recent", "Recent files")) {
      for (const std::string& path : d.recent) {
        if (ImGui::Selectable(path.c_str())) r.open = path;
      }
      ImGui::EndCombo();
    }
  }
  ImGui::SetNextItemWidth(-button - ImGui::GetStyle().ItemSpacing.x);
  ImGui::InputTextWithHint("##save", "project.sublift", &f.save_path);
  ImGui::SameLine();
  if (ImGui::Button("Save", ImVec2(button, 0)) && !f.save_path.empty()) r.save = f.save_path;
  ImGui::SetNextItemWidth(-button - ImGui::GetStyle().ItemSpacing.x);
  ImGui::InputTextWithHint("##export", "out.obj/.ply/.gltf/.glb/.lattice/.ovm/.vtk", &f.export_path);
  ImGui::SameLine();
  if (ImGui::Button("Export", ImVec2(button, 0)) && !f.export_path.empty()) {
    r.export_path = f.export_path;
    r.export_finest = f.export_finest;
  }
  ImGui::Checkbox("Export the finest limit (off: current level's net)", &f.export_finest);
  if (ImGui::Button("Export every level") && !f.export_path.empty()) r.export_levels = true;
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Each level's control net: name_L0.obj .. name_LJ.obj beside the export path");
}

// Fit base mesh... (docs/fit.md): a coarse base and fitted levels for an opened dense mesh.
void draw_fit_section(const ModelerPanelData& d, FileFields& f, ModelerPanelRequests& r) {
  if (!d.can_fit || !section("Fit base mesh...", d.file_vertices >= 1000)) return;
  FitRequest& q = f.fit;
  ImGui::PushTextWrapPos(0.0f);
  ImGui::TextColored(kMuted, "A coarse cage for any mesh: its detail comes along as wavelets, so a level-0 edit bends the "
                             "whole mesh with its detail.");
  ImGui::PopTextWrapPos();
  ImGui::SetNextItemWidth(120.0f);
  ImGui::InputInt("Base vertices", &q.base_vertices, 10, 100);
  q.base_vertices = std::max(0, q.base_vertices);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("0: 1/64 of the mesh's %u vertices (at least 24)", d.file_vertices);
  ImGui::SetNextItemWidth(120.0f);
  ImGui::SliderFloat("Feature angle", &q.feature_angle_deg, 5.0f, 175.0f, "%.0f deg");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Edges whose faces meet more sharply stay creases; where they meet or turn, corners");
  ImGui::SetNextItemWidth(120.0f);
  // Every scheme fits: the triangle schemes from a triangle base, the others from quads.
  std::vector<const char*> schemes;
  for (const SchemeInfo& i : all_schemes()) schemes.push_back(i.name);
  int pick = std::clamp(q.scheme, 0, static_cast<int>(schemes.size()) - 1);
  ImGui::SetNextItemWidth(120.0f);
  if (ImGui::Combo("Fit scheme", &pick, schemes.data(), static_cast<int>(schemes.size()))) q.scheme = pick;
  const int most_levels = 6 * scheme_levels_per_split(static_cast<Scheme>(q.scheme));
  q.levels = std::min(q.levels, most_levels);
  ImGui::SetNextItemWidth(120.0f);
  ImGui::SliderInt("Levels", &q.levels, 0, most_levels, q.levels == 0 ? "auto" : "%d");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("auto: the levels that bring the finest to about the mesh's vertex count");
  if (ImGui::Button("Preview base")) r.fit_preview = q;
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Draw the base the fit would start from over the mesh");
  if (d.fit_preview) {
    ImGui::SameLine();
    if (ImGui::Button("Hide")) r.fit_clear_preview = true;
  }
  ImGui::SameLine();
  if (ImGui::Button("Fit")) r.fit = q;
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Fit the base and levels (progress, Cancel); then edit at level 0. Clears the history.");
}

void draw_levels_section(const ModelerPanelData& d, ModelerPanelRequests& r) {
  if (!section("Hierarchy")) return;
  const char* schemes[] = {"linear", "cubic", "sqrt2", "linear-tri", "butterfly", "loop"};  // Scheme's order
  int scheme = d.scheme;
  ImGui::SetNextItemWidth(120.0f);
  if (ImGui::Combo("Scheme", &scheme, schemes, 6) && scheme != d.scheme) r.scheme = scheme;
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("linear / cubic: Bertram's lifted B-spline wavelets (1-to-4 per level)\n"
                      "sqrt2: Wang & Ma's interpolatory sqrt(2) wavelets (surfaces; 2x faces per level,\n"
                      "the limit passes through every control point)\n"
                      "linear-tri / butterfly / loop: Lounsbery, DeRose & Warren's triangle-mesh wavelets\n"
                      "(triangle meshes; k-disc wavelets with exact inner products; butterfly interpolates,\n"
                      "loop's analysis solves a sparse system)");
  int level = d.level;
  ImGui::SetNextItemWidth(120.0f);
  if (ImGui::SliderInt("Edit level", &level, 0, std::max(d.finest, 0)) && level != d.level) r.level = level;
  ImGui::SameLine();
  if (ImGui::Button("Subdivide")) r.subdivide = true;
  // Blender's viewport level: a coarser limit draws faster; edits and exports keep every level.
  int view = d.view_level < 0 ? d.finest : std::min(d.view_level, d.finest);
  ImGui::SetNextItemWidth(120.0f);
  if (ImGui::SliderInt("Viewport level", &view, 0, std::max(d.finest, 0)) && view != (d.view_level < 0 ? d.finest : d.view_level))
    r.view_level = view == d.finest ? -1 : view;
  ImGui::BeginDisabled(d.level >= d.finest);
  if (ImGui::Button("Delete higher")) r.delete_higher = true;
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) ImGui::SetTooltip("Remove the levels finer than the edit level");
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::BeginDisabled(d.level == 0);
  if (ImGui::Button("Delete lower")) r.delete_lower = true;
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip("Make the edit level the base: the coarser levels go, the shape stays");
  ImGui::EndDisabled();
  ImGui::SameLine();
  if (ImGui::Button("Apply base")) r.apply_base = true;
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("For Blender users: level 0 already is the coarse shape of the detail");
  if (d.rebuild_levels > 0) {
    ImGui::TextColored(kAccent, "This mesh was subdivided %d time%s elsewhere.", d.rebuild_levels, d.rebuild_levels == 1 ? "" : "s");
    char label[64];
    std::snprintf(label, sizeof label, "Rebuild %d level%s", d.rebuild_levels, d.rebuild_levels == 1 ? "" : "s");
    if (ImGui::Button(label)) r.rebuild = true;
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("Find the base mesh and analyse this shape into %s wavelets: edit it at level 0\n"
                        "with its detail kept (docs/rebuild.md). Clears the history.",
                        d.rebuild_scheme.c_str());
  }
  if (!d.rebuild_stop.empty()) {
    ImGui::PushTextWrapPos(0.0f);
    // At level 0 the reason names "the mesh", which the heading already says.
    const std::string_view own = "the mesh: ";
    const char* why = d.rebuild_stop.c_str();
    if (d.rebuild_levels == 0 && d.rebuild_stop.starts_with(own)) why += own.size();
    ImGui::TextColored(kMuted, "%s: %s", d.rebuild_levels > 0 ? "No more levels" : "Not a subdivided mesh", why);
    ImGui::PopTextWrapPos();
    if (d.rebuild_stop_located && ImGui::Button("Show where")) r.rebuild_show_stop = true;
  }

  if (ImGui::BeginTable("levels", 5, ImGuiTableFlags_SizingStretchProp | ImGuiTableFlags_RowBg)) {
    ImGui::TableSetupColumn("L", ImGuiTableColumnFlags_WidthStretch, 0.25f);
    ImGui::TableSetupColumn("verts", ImGuiTableColumnFlags_WidthStretch, 0.8f);
    ImGui::TableSetupColumn("wavelets", ImGuiTableColumnFlags_WidthStretch, 0.8f);
    ImGui::TableSetupColumn("|w| max", ImGuiTableColumnFlags_WidthStretch, 0.8f);
    ImGui::TableSetupColumn("|w| rms", ImGuiTableColumnFlags_WidthStretch, 0.8f);
    ImGui::TableHeadersRow();
    for (const LevelStats& l : d.levels) {
      ImGui::TableNextRow();
      ImGui::TableSetColumnIndex(0);
      if (l.level == d.level) {
        ImGui::TextColored(kAccent, "%d", l.level);
      } else {
        ImGui::Text("%d", l.level);
      }
      ImGui::TableSetColumnIndex(1);
      ImGui::Text("%u", l.vertices);
      ImGui::TableSetColumnIndex(2);
      if (l.level < d.finest) ImGui::Text("%u", l.wavelets);
      ImGui::TableSetColumnIndex(3);
      if (l.level < d.finest) ImGui::Text("%.3g", l.wavelet_max);
      ImGui::TableSetColumnIndex(4);
      if (l.level < d.finest) ImGui::Text("%.3g", l.wavelet_rms);
    }
    ImGui::EndTable();
  }
}

void draw_detail_section(const ModelerPanelData& d, ModelerPanelRequests& r) {
  if (!section("Detail")) return;
  ImGui::TextColored(kMuted, "Gain per level (equalizer)");
  for (std::size_t l = 0; l < d.gains.size(); ++l) {
    float g = static_cast<float>(d.gains[l]);
    char label[48];
    std::snprintf(label, sizeof label, "Level %zu##gain", l);
    ImGui::PushID(static_cast<int>(l));
    ImGui::SetNextItemWidth(180.0f);
    const bool changed = ImGui::SliderFloat(label, &g, 0.0f, 3.0f, "%.2f");
    if (ImGui::IsItemActivated()) {
      r.gain_begin = true;
      r.gain_level = static_cast<int>(l);
      r.gain_value = d.gains[l];
    }
    if (changed) {
      r.gain_level = static_cast<int>(l);
      r.gain_value = g;
    }
    if (ImGui::IsItemDeactivated()) r.gain_end = true;
    ImGui::PopID();
  }
  bool local = d.local_frames;
  ImGui::BeginDisabled(d.dim != 2);
  if (ImGui::Checkbox("Local detail frames", &local)) r.local_frames = local;
  ImGui::EndDisabled();
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
    ImGui::SetTooltip("Detail turns with the surface (surfaces only); off: world axes");
  }
  ImGui::TextColored(kMuted, d.channels.empty() ? "Colour by |w| of level" : "Colour by |w| of level or a channel");
  // Entries: off, the wavelet levels, then the attribute channels.
  const int channel_entry = 1 + d.finest;
  int colour = d.colour_channel >= 0 ? channel_entry + d.colour_channel : d.colour_level + 1;
  std::vector<std::string> names{"off (clay)"};
  for (int l = 0; l < d.finest; ++l) names.push_back("level " + std::to_string(l));
  for (const std::string& c : d.channels) names.push_back("channel " + c);
  ImGui::SetNextItemWidth(140.0f);
  if (ImGui::BeginCombo("##colour", names[static_cast<std::size_t>(std::clamp(colour, 0, int(names.size()) - 1))].c_str())) {
    for (int i = 0; i < static_cast<int>(names.size()); ++i) {
      if (ImGui::Selectable(names[static_cast<std::size_t>(i)].c_str(), i == colour)) {
        if (i >= channel_entry) {
          r.colour_channel = i - channel_entry;
        } else {
          r.colour_level = i - 1;
          if (d.colour_channel >= 0) r.colour_channel = -1;
        }
      }
    }
    ImGui::EndCombo();
  }
  if (d.colour_channel >= 0 && !d.channel_group.empty()) {  // compress that channel's group on its own
    float keep = static_cast<float>(100.0 * d.channel_keep);
    ImGui::SetNextItemWidth(140.0f);
    if (ImGui::SliderFloat(("Keep % of " + d.channel_group).c_str(), &keep, 0.0f, 100.0f, "%.1f%%")) r.channel_keep = keep / 100.0;
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("The largest wavelets of this channel group kept (shown, saved and exported); positions untouched; 100%%: all");
  }
  float radius = static_cast<float>(d.soft_radius);
  ImGui::SetNextItemWidth(140.0f);
  if (ImGui::InputFloat("Soft radius", &radius, 0.0f, 0.0f, "%.4g", ImGuiInputTextFlags_EnterReturnsTrue)) {
    r.soft_radius = std::max(0.0f, radius);
  }
  // The pivot of R and S (core/edit/transform.h Pivot, in its order).
  static const char* kPivots[] = {"Median point", "Active point", "3-D cursor", "World origin"};
  int pivot = std::clamp(d.pivot, 0, 3);
  ImGui::SetNextItemWidth(140.0f);
  if (ImGui::Combo("Pivot", &pivot, kPivots, 4)) r.pivot = pivot;
  ImGui::TextUnformatted("Mirror");
  for (int a = 0; a < 3; ++a) {
    ImGui::SameLine();
    bool on = d.symmetry[a];
    const char* names[] = {"X##mirror", "Y##mirror", "Z##mirror"};
    if (ImGui::Checkbox(names[a], &on)) r.symmetry_axis = a, r.symmetry_on = on;
  }
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Mirror editing across the world planes x = 0, y = 0, z = 0");
  ImGui::TextColored(kMuted, "%zu selected", d.selected);
}

// A curve function's values along the curve, with the pinned one over it (purple) and the zero
// line; both share the vertical scale.
void draw_basis_plot(const BasisPanelData& b) {
  const std::vector<float>& a = b.current.plot;
  const std::vector<float>* p = b.pinned && !b.pin.plot.empty() ? &b.pin.plot : nullptr;
  if (a.size() < 2 && p == nullptr) return;
  float lo = 0.0f, hi = 0.0f;
  for (const float v : a) lo = std::min(lo, v), hi = std::max(hi, v);
  if (p) {
    for (const float v : *p) lo = std::min(lo, v), hi = std::max(hi, v);
  }
  if (hi - lo <= 0.0f) hi = lo + 1.0f;
  const float width = ImGui::GetContentRegionAvail().x, height = 110.0f;
  const ImVec2 o = ImGui::GetCursorScreenPos();
  ImDrawList* dl = ImGui::GetWindowDrawList();
  dl->AddRectFilled(o, ImVec2(o.x + width, o.y + height), IM_COL32(24, 26, 30, 255));
  auto y_of = [&](float v) { return o.y + height - 4.0f - (v - lo) / (hi - lo) * (height - 8.0f); };
  dl->AddLine(ImVec2(o.x, y_of(0.0f)), ImVec2(o.x + width, y_of(0.0f)), IM_COL32(110, 110, 120, 255));
  auto line = [&](const std::vector<float>& v, ImU32 colour) {
    if (v.size() < 2) return;
    for (std::size_t i = 0; i + 1 < v.size(); ++i) {
      const float x0 = o.x + width * static_cast<float>(i) / static_cast<float>(v.size() - 1);
      const float x1 = o.x + width * static_cast<float>(i + 1) / static_cast<float>(v.size() - 1);
      dl->AddLine(ImVec2(x0, y_of(v[i])), ImVec2(x1, y_of(v[i + 1])), colour, 2.0f);
    }
  };
  if (p) line(*p, IM_COL32(150, 90, 200, 255));
  line(a, IM_COL32(40, 170, 220, 255));
  char label[64];
  std::snprintf(label, sizeof label, "%.3g", static_cast<double>(hi));
  dl->AddText(ImVec2(o.x + 3.0f, o.y + 2.0f), IM_COL32(170, 170, 180, 255), label);
  std::snprintf(label, sizeof label, "%.3g", static_cast<double>(lo));
  dl->AddText(ImVec2(o.x + 3.0f, o.y + height - 16.0f), IM_COL32(170, 170, 180, 255), label);
  ImGui::Dummy(ImVec2(width, height));
  ImGui::TextColored(kMuted, p ? "blue current, purple pinned, each over its support" : "along the curve (parameter order)");
}

void draw_basis_readout(const BasisReadout& o) {
  // Wrapped, so that two readouts fit side by side in the comparison table.
  ImGui::TextWrapped("%s", o.title.c_str());
  ImGui::TextWrapped("support %zu finest vertices", o.support);
  std::string per;
  for (const std::uint32_t n : o.support_per_level) {
    char one[16];
    std::snprintf(one, sizeof one, per.empty() ? "%u" : " %u", n);
    per += one;
  }
  ImGui::PushStyleColor(ImGuiCol_Text, kMuted);
  ImGui::TextWrapped("per level: %s", per.c_str());
  ImGui::PopStyleColor();
  ImGui::TextWrapped("integral %.6g", o.integral);
  ImGui::TextWrapped("min %.4g   max %.4g", o.min, o.max);
  ImGui::TextWrapped("moments %.3g %.3g %.3g", o.moment[0], o.moment[1], o.moment[2]);
}

void draw_basis_section(const ModelerPanelData& d, ModelerPanelRequests& r) {
  if (!section("Basis")) return;
  const BasisPanelData& b = d.basis;
  BasisSettings q = b.settings;
  BasisRequest& f = q.request;
  // The sliders edit floats: the settings carry the values they show.
  float height_scale = static_cast<float>(q.height_scale), slice_pos = static_cast<float>(q.slice_pos),
        iso_level = static_cast<float>(q.iso_level);
  bool changed = false;
  changed |= ImGui::Checkbox("Show basis function", &q.on);
  ImGui::BeginDisabled(!q.on);
  if (ImGui::RadioButton("scaling function", f.kind == BasisKind::Scaling)) f.kind = BasisKind::Scaling, changed = true;
  ImGui::SameLine();
  if (ImGui::RadioButton("wavelet", f.kind == BasisKind::Wavelet)) f.kind = BasisKind::Wavelet, changed = true;
  const bool wavelet = f.kind == BasisKind::Wavelet;
  if (f.kind != b.settings.request.kind) {  // keep the index in the new kind's range
    const int level = wavelet ? b.selected_wavelet_level : b.selected_scaling_level;
    const long long at = wavelet ? b.selected_wavelet : b.selected;
    if (at >= 0) {
      f.level = level, f.index = static_cast<std::uint32_t>(at);
    } else if (wavelet && f.index < b.scaling_count) {
      f.index = static_cast<std::uint32_t>(b.scaling_count);
    } else if (!wavelet && f.index >= b.scaling_count) {
      f.index = 0;
    }
  }
  const float column = ImGui::GetContentRegionAvail().x * 0.5f;
  changed |= ImGui::Checkbox("Dual (analysis)", &f.dual);
  ImGui::SameLine(column);
  ImGui::BeginDisabled(b.lattice);
  changed |= ImGui::Checkbox("Height field", &q.height);
  ImGui::EndDisabled();
  int level = f.level;
  ImGui::SetNextItemWidth(110.0f);
  if (ImGui::InputInt("Level j", &level, 1, 1)) f.level = std::clamp(level, 0, b.finest), changed = true;
  ImGui::SameLine(column + 40.0f);
  changed |= ImGui::Checkbox("Follow", &q.follow);
  if (ImGui::IsItemHovered()) {
    ImGui::SetTooltip("clicking a control point shows its function; for a wavelet, click an\n"
                      "edge, face or cell point of the level j+1 net (or a vertex: its first edge)");
  }
  int index = static_cast<int>(f.index);
  ImGui::SetNextItemWidth(110.0f);
  if (ImGui::InputInt("Index", &index, 1, 10, ImGuiInputTextFlags_EnterReturnsTrue)) {
    f.index = static_cast<std::uint32_t>(std::max(0, index)), changed = true;
  }
  if (ImGui::IsItemHovered()) {
    ImGui::SetTooltip(!wavelet ? "control point of level j (0..%lld)" : "e/f/c vertex of level j+1 (%lld..%lld)",
                      !wavelet ? b.scaling_count - 1 : b.scaling_count, b.wavelet_end - 1);
  }
  ImGui::SameLine();
  const long long at = !wavelet ? b.selected : b.selected_wavelet;
  ImGui::BeginDisabled(at < 0);
  if (ImGui::Button("At selection")) {
    f.level = !wavelet ? b.selected_scaling_level : b.selected_wavelet_level;
    f.index = static_cast<std::uint32_t>(at);
    changed = true;
  }
  ImGui::EndDisabled();
  int k = f.extra_levels < 0 ? b.default_extra_levels : f.extra_levels;
  ImGui::SetNextItemWidth(110.0f);
  if (ImGui::SliderInt("Extra levels K", &k, 0, 8)) f.extra_levels = k, changed = true;
  if (!b.lattice) {
    ImGui::BeginDisabled(!q.height);
    ImGui::SetNextItemWidth(140.0f);
    if (ImGui::SliderFloat("Height scale", &height_scale, 0.0f, 1.0f, "%.2f")) changed = true;
    ImGui::EndDisabled();
  } else {
    const char* axes[] = {"no slice", "slice x", "slice y", "slice z"};
    int axis = q.slice_axis + 1;
    ImGui::SetNextItemWidth(110.0f);
    if (ImGui::Combo("##slice", &axis, axes, 4)) q.slice_axis = axis - 1, changed = true;
    ImGui::SameLine();
    ImGui::BeginDisabled(q.slice_axis < 0);
    ImGui::SetNextItemWidth(120.0f);
    if (ImGui::SliderFloat("at", &slice_pos, 0.0f, 1.0f, "%.2f")) changed = true;
    ImGui::EndDisabled();
    changed |= ImGui::Checkbox("Iso-surface", &q.iso);
    ImGui::SameLine();
    ImGui::BeginDisabled(!q.iso);
    ImGui::SetNextItemWidth(120.0f);
    if (ImGui::SliderFloat("of max", &iso_level, 0.01f, 0.99f, "%.2f")) changed = true;
    ImGui::EndDisabled();
  }
  ImGui::EndDisabled();
  q.height_scale = height_scale, q.slice_pos = slice_pos, q.iso_level = iso_level;
  if (changed) r.basis = q;
  ImGui::BeginDisabled(!b.computed);
  if (ImGui::Button("Pin for comparison")) r.pin_basis = true;
  ImGui::EndDisabled();
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
    ImGui::SetTooltip("keep this function and draw it beside the next one\n(another index, level or scheme)");
  }
  ImGui::SameLine();
  ImGui::BeginDisabled(!b.pinned);
  if (ImGui::Button("Clear pin")) r.clear_pin = true;
  ImGui::EndDisabled();
  if (b.computed && b.curve) draw_basis_plot(b);
  if (b.computed && b.pinned && ImGui::BeginTable("##compare", 2, ImGuiTableFlags_BordersInnerV)) {
    ImGui::TableNextColumn();
    draw_basis_readout(b.current);
    ImGui::TableNextColumn();
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.78f, 0.66f, 0.95f, 1.0f));
    draw_basis_readout(b.pin);
    ImGui::PopStyleColor();
    ImGui::EndTable();
  } else if (b.computed) {
    draw_basis_readout(b.current);
  } else if (b.pinned) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.78f, 0.66f, 0.95f, 1.0f));
    draw_basis_readout(b.pin);
    ImGui::PopStyleColor();
  }
}

void draw_ffd_section(const ModelerPanelData& d, FileFields& f, ModelerPanelRequests& r) {
  if (!section("Free-form deformation", d.ffd.loaded)) return;
  const FfdPanelData& m = d.ffd;
  const float button = 70.0f;
  ImGui::SetNextItemWidth(-button - ImGui::GetStyle().ItemSpacing.x);
  const bool enter = ImGui::InputTextWithHint("##model", "model .gltf/.glb/.obj/.ply/.off", &f.model_path,
                                              ImGuiInputTextFlags_EnterReturnsTrue);
  ImGui::SameLine();
  if ((ImGui::Button("Model", ImVec2(button, 0)) || enter) && !f.model_path.empty()) r.load_model = f.model_path;
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("load a model; it is bound at once when a lattice is open");
  if (!m.loaded) {
    ImGui::TextColored(kMuted, "open a lattice (or wrap the model in a box), then bend it");
    return;
  }
  ImGui::Text("%s: %zu vertices, %zu faces", m.model_name.c_str(), m.vertices, m.faces);
  for (const std::string& n : m.notes) {
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextColored(kMuted, "%s", n.c_str());
    ImGui::PopTextWrapPos();
  }
  ImGui::SetNextItemWidth(140.0f);
  ImGui::InputInt3("cells", f.box);
  for (int& n : f.box) n = std::clamp(n, 1, 64);
  ImGui::SetNextItemWidth(140.0f);
  ImGui::SliderFloat("margin", &f.box_margin, 0.0f, 0.5f, "%.2f");
  if (ImGui::Button("Wrap in box lattice")) r.wrap_box = true;
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("replace the open shape by a box lattice around the model, and bind");
  int mode = m.outside_mode;
  ImGui::TextColored(kMuted, "Outside the lattice:");
  ImGui::SameLine();
  const bool stay = ImGui::RadioButton("stay", &mode, 0);
  ImGui::SameLine();
  const bool nearest = ImGui::RadioButton("follow nearest cell", &mode, 1);
  ImGui::BeginDisabled(!m.lattice);
  if (ImGui::Button(m.bound ? "Bind again" : "Bind") || ((stay || nearest) && m.bound)) r.bind = mode;
  ImGui::EndDisabled();
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
    ImGui::SetTooltip("bind the model as it is now to the lattice as it is now (needs a lattice)");
  }
  ImGui::SameLine();
  ImGui::BeginDisabled(!m.bound);
  if (ImGui::Button("Unbind")) r.unbind = true;
  ImGui::EndDisabled();
  ImGui::SameLine();
  if (ImGui::Button("Remove")) r.remove_model = true;
  if (m.bound) {
    ImGui::TextColored(kGood, "bound: %zu inside, %zu outside (%zu follow), %.1f ms", m.bound_count, m.outside, m.nearest,
                       m.bind_ms);
    ImGui::TextColored(kMuted, "last edit moved %zu vertices in %.2f ms", m.moved, m.deform_ms);
  } else {
    ImGui::TextColored(kWarning, "not bound: lattice edits leave the model alone");
  }
  if (!m.note.empty()) ImGui::TextColored(kWarning, "%s", m.note.c_str());
  ImGui::SetNextItemWidth(-button - ImGui::GetStyle().ItemSpacing.x);
  ImGui::InputTextWithHint("##model_export", "deformed model, same format", &f.model_export_path);
  ImGui::SameLine();
  if (ImGui::Button("Export##model", ImVec2(button, 0)) && !f.model_export_path.empty()) {
    r.export_model = f.model_export_path;
  }
}

// Animation (docs/animation.md): an animation as a space-time lattice; the frame shown, playback
// (Space), ghosts of the frames around it, export of every frame.
void draw_animation_section(const ModelerPanelData& d, FileFields& f, ModelerPanelRequests& r) {
  const AnimationPanelData& a = d.animation;
  if (!section("Animation", a.on)) return;
  const float button = 70.0f;
  ImGui::SetNextItemWidth(-button - ImGui::GetStyle().ItemSpacing.x);
  const bool enter = ImGui::InputTextWithHint("##animation", "anim.glb | frame0.obj frame1.obj ...", &f.animation_paths,
                                              ImGuiInputTextFlags_EnterReturnsTrue);
  ImGui::SameLine();
  if ((ImGui::Button("Open##animation", ImVec2(button, 0)) || enter) && !f.animation_paths.empty()) {
    AnimationOpenRequest q;
    std::istringstream words(f.animation_paths);
    for (std::string w; words >> w;) q.paths.push_back(w);
    q.frames = f.animation_frames;
    q.levels = f.animation_levels;
    q.clip = f.animation_clip;
    q.cyclic = f.animation_cyclic;
    r.animation_open = q;
  }
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("a glTF animation (morph targets, skin or nodes) or two or more OBJ/PLY/OFF frames");
  ImGui::SetNextItemWidth(90.0f);
  ImGui::InputInt("frames", &f.animation_frames, 8, 32);
  f.animation_frames = std::max(0, f.animation_frames);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("glTF samples: 2^J K + 1 (open) or 2^J K (cyclic); 0: K = 4");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(70.0f);
  ImGui::SliderInt("levels##animation", &f.animation_levels, 1, 4);
  ImGui::SetNextItemWidth(90.0f);
  ImGui::InputInt("clip", &f.animation_clip);
  f.animation_clip = std::max(0, f.animation_clip);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("the glTF animation's index");
  ImGui::SameLine();
  ImGui::Checkbox("cyclic (a loop)", &f.animation_cyclic);
  if (!a.on) return;
  ImGui::Separator();
  ImGui::Text("%d frames, %d base steps, %d levels%s", a.frames, a.base_steps, a.levels, a.cyclic ? ", cyclic" : "");
  float frame = static_cast<float>(a.frame);
  ImGui::SetNextItemWidth(-1.0f);
  if (ImGui::SliderFloat("##frame", &frame, 0.0f, static_cast<float>(a.frames - (a.cyclic ? 0 : 1)), "frame %.2f"))
    r.animation_frame = frame;
  if (ImGui::Button("|<")) r.animation_frame = 0.0;
  ImGui::SameLine();
  if (ImGui::Button("<")) r.animation_frame = std::ceil(a.frame) - 1.0;
  ImGui::SameLine();
  if (ImGui::Button(a.playing ? "Pause" : "Play", ImVec2(60, 0))) r.animation_play = !a.playing;
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Space");
  ImGui::SameLine();
  if (ImGui::Button(">")) r.animation_frame = std::floor(a.frame) + 1.0;
  ImGui::SameLine();
  if (ImGui::Button(">|")) r.animation_frame = a.frames - 1.0;
  ImGui::SameLine();
  ImGui::TextColored(kMuted, "%.3f s", a.time);
  int ghosts = a.ghosts;
  ImGui::SetNextItemWidth(120.0f);
  if (ImGui::SliderInt("ghosts", &ghosts, 0, 8)) r.animation_ghosts = ghosts;
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("wireframes of the frames around this one, at the edit level's layer spacing");
  ImGui::PushTextWrapPos(0.0f);
  ImGui::TextColored(kMuted, "Editing level %d on its layer %d (frame %d): a drag there spreads over the frames its time "
                             "support covers, finer motion kept.",
                     a.level, a.layer, a.layer_frame);
  ImGui::PopTextWrapPos();
  ImGui::SetNextItemWidth(-button - ImGui::GetStyle().ItemSpacing.x);
  ImGui::InputTextWithHint("##animation_export", "out.glb | frames_####.obj", &f.animation_export_path);
  ImGui::SameLine();
  if (ImGui::Button("Export##animation", ImVec2(button, 0)) && !f.animation_export_path.empty())
    r.animation_export = f.animation_export_path;
}

// Compression (docs/compression.md): a live preview of the shape from the largest fraction of
// its wavelets, with what it costs; Apply makes it an undoable edit, Off shows the full shape.
void draw_compression_section(const CompressionPanelData& c, ModelerPanelRequests& r) {
  if (!section("Compression", c.on)) return;
  ImGui::TextColored(kMuted, "Kept fraction of the wavelets (largest first)");
  float f = static_cast<float>(c.fraction);
  ImGui::SetNextItemWidth(170.0f);
  if (ImGui::SliderFloat("##compress_keep", &f, 0.0f, 1.0f, "%.3f", ImGuiSliderFlags_AlwaysClamp)) {
    r.compress_fraction = std::clamp(static_cast<double>(f), 0.0, 1.0);
  }
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("drag to preview; Ctrl+click or the box to type a value");
  ImGui::SameLine();
  float typed = static_cast<float>(c.fraction);
  ImGui::SetNextItemWidth(70.0f);
  if (ImGui::InputFloat("##compress_typed", &typed, 0.0f, 0.0f, "%.4f", ImGuiInputTextFlags_EnterReturnsTrue)) {
    r.compress_fraction = std::clamp(static_cast<double>(typed), 0.0, 1.0);
  }
  ImGui::BeginDisabled(!c.on);
  if (ImGui::Button("Apply")) r.compress_apply = true;
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
    ImGui::SetTooltip("make the compressed shape an edit (undoable)");
  }
  ImGui::SameLine();
  if (ImGui::Button("Off")) r.compress_off = true;
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) ImGui::SetTooltip("back to the full shape");
  ImGui::EndDisabled();
  if (c.on) {
    ImGui::Text("kept %zu / %zu wavelets (%.1f%%)", c.kept, c.total,
                c.total > 0 ? 100.0 * static_cast<double>(c.kept) / static_cast<double>(c.total) : 100.0);
    ImGui::Text("error L2 %.3g, L-inf %.3g of the diagonal", c.l2_error, c.linf_error);
    ImGui::TextColored(kWarning, "preview: Apply to edit, Off for the full shape");
  } else {
    ImGui::TextColored(kMuted, "%zu wavelets; move the slider to preview", c.total);
  }
}

void draw_history_section(const ModelerPanelData& d, ModelerPanelRequests& r) {
  if (!section("History")) return;
  ImGui::BeginDisabled(d.undo_position == 0);
  if (ImGui::Button("Undo")) r.undo = true;
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::BeginDisabled(d.undo_position >= d.history.size());
  if (ImGui::Button("Redo")) r.redo = true;
  ImGui::EndDisabled();
  if (ImGui::BeginListBox("##history", ImVec2(-1.0f, 110.0f))) {
    if (ImGui::Selectable("(opened)", d.undo_position == 0)) r.history_jump = 0;
    for (std::size_t i = 0; i < d.history.size(); ++i) {
      const bool applied = i < d.undo_position;
      ImGui::PushID(static_cast<int>(i));
      if (!applied) ImGui::PushStyleColor(ImGuiCol_Text, kMuted);
      if (ImGui::Selectable(d.history[i].c_str(), i + 1 == d.undo_position)) r.history_jump = i + 1;
      if (!applied) ImGui::PopStyleColor();
      ImGui::PopID();
    }
    ImGui::EndListBox();
  }
}

void draw_display_section(const ModelerPanelData& d, ModelerDisplay& v) {
  if (!section("Display")) return;
  const float column = ImGui::GetContentRegionAvail().x * 0.5f;
  ImGui::Checkbox("Smooth", &v.smooth);
  ImGui::SameLine(column);
  ImGui::Checkbox("Wireframe", &v.wireframe);
  ImGui::Checkbox("Control net", &v.net);
  ImGui::SameLine(column);
  ImGui::Checkbox("X-ray", &v.xray);
  ImGui::Checkbox("Depth cue", &v.depth_cue);
  ImGui::SameLine(column);
  ImGui::Checkbox("Orthographic", &v.orthographic);
  ImGui::Checkbox("Z up", &v.z_up);
  if (d.textured) {
    ImGui::SameLine(column);
    ImGui::Checkbox("Texture", &v.texture);
  }
  ImGui::SameLine(column);
  ImGui::Checkbox("Clip", &v.clip);
  if (v.clip || d.dim == 3) {
    const char* axes[] = {"X", "Y", "Z"};
    ImGui::SetNextItemWidth(60.0f);
    ImGui::Combo("##axis", &v.clip_axis, axes, 3);
    ImGui::SameLine();
    ImGui::SetNextItemWidth(140.0f);
    ImGui::SliderFloat("##offset", &v.clip_offset, 0.0f, 1.0f, "cut %.2f");
    ImGui::SameLine();
    ImGui::Checkbox("Flip", &v.clip_flip);
  }
}

CameraAction draw_view_buttons() {
  CameraAction action;
  if (ImGui::Button("Frame (F)")) action.type = CameraActionType::Frame;
  ImGui::SameLine();
  if (ImGui::Button("Front")) action.type = CameraActionType::ViewFront;
  ImGui::SameLine();
  if (ImGui::Button("Right")) action.type = CameraActionType::ViewRight;
  ImGui::SameLine();
  if (ImGui::Button("Top")) action.type = CameraActionType::ViewTop;
  return action;
}

void draw_keys_section() {
  if (!section("Mouse and keys", false)) return;
  if (ImGui::BeginTable("keys", 2, ImGuiTableFlags_SizingStretchProp)) {
    auto row = [](std::string_view k, std::string_view a) {
      ImGui::TableNextRow();
      ImGui::TableSetColumnIndex(0);
      ImGui::TextColored(kMuted, "%.*s", static_cast<int>(k.size()), k.data());
      ImGui::TableSetColumnIndex(1);
      ImGui::Text("%.*s", static_cast<int>(a.size()), a.data());
    };
    for (const KeyBinding& b : modeler_key_bindings()) row(b.keys, b.action);
    for (const MouseBinding& b : mouse_bindings()) row(b.blender, b.action);
    for (const KeyBinding& b : key_bindings()) row(b.keys, b.action);
    ImGui::EndTable();
  }
}

// Sculpt mode and the brush (core/edit/brush.h): Blender's brushes at the edit level.
void draw_sculpt_section(const ModelerPanelData& d, ModelerPanelRequests& r) {
  if (!section("Sculpt", d.sculpt)) return;
  bool on = d.sculpt;
  if (ImGui::Checkbox("Sculpt mode (Ctrl+Tab)", &on)) r.sculpt = on;
  BrushSettings b = d.brush;
  bool changed = false;
  static const char* kKinds[] = {"Draw (X)", "Inflate (I)", "Smooth (S)", "Grab (G)", "Flatten (Shift+T)", "Pinch (P)"};
  int kind = static_cast<int>(b.kind);
  ImGui::SetNextItemWidth(140.0f);
  if (ImGui::Combo("Brush", &kind, kKinds, 6)) b.kind = static_cast<BrushKind>(kind), changed = true;
  float radius = static_cast<float>(b.radius);
  ImGui::SetNextItemWidth(140.0f);
  if (ImGui::InputFloat("Radius (F)", &radius, 0.0f, 0.0f, "%.4g", ImGuiInputTextFlags_EnterReturnsTrue) && radius > 0.0f)
    b.radius = radius, changed = true;
  float strength = static_cast<float>(b.strength);
  ImGui::SetNextItemWidth(140.0f);
  if (ImGui::SliderFloat("Strength (Shift+F)", &strength, 0.0f, 1.0f, "%.2f")) b.strength = strength, changed = true;
  static const char* kFalloffs[] = {"Smooth", "Linear", "Sharp", "Constant"};
  int falloff = static_cast<int>(b.falloff);
  ImGui::SetNextItemWidth(140.0f);
  if (ImGui::Combo("Falloff", &falloff, kFalloffs, 4)) b.falloff = static_cast<Falloff>(falloff), changed = true;
  if (ImGui::Checkbox("Front faces only", &b.front_faces_only)) changed = true;
  if (changed) r.brush = b;
  ImGui::TextColored(kMuted, "Strokes move level %d's control points; finer detail rides along.", d.level);
}

}  // namespace

ModelerPanelRequests draw_modeler_panel(const ModelerPanelData& d, ModelerDisplay& display, FileFields& fields,
                                        float x, float y, float width, float height) {
  ModelerPanelRequests r;
  ImGui::SetNextWindowPos(ImVec2(x, y));
  ImGui::SetNextWindowSize(ImVec2(width, height));
  if (ImGui::Begin("Sublift##modeler_panel", nullptr, kDockedFlags)) {
    ImGui::TextColored(kAccent, "SUBLIFT");
    ImGui::SameLine();
    ImGui::TextColored(kMuted, "multiresolution modeler");
    ImGui::Separator();
    draw_file_section(d, fields, r);
    if (!d.warnings.empty() && section("Import warnings", false)) {
      for (const std::string& w : d.warnings) ImGui::TextColored(kWarning, "%s", w.c_str());
    }
    draw_levels_section(d, r);
    draw_fit_section(d, fields, r);
    draw_detail_section(d, r);
    draw_sculpt_section(d, r);
    draw_ffd_section(d, fields, r);
    draw_animation_section(d, fields, r);
    draw_basis_section(d, r);
    draw_compression_section(d.compression, r);
    draw_history_section(d, r);
    draw_display_section(d, display);
    r.camera = draw_view_buttons();
    ImGui::TextColored(kMuted, "resynthesis %.2f ms, %zu vertices", d.resynthesis_ms, d.vertices_updated);
    draw_keys_section();
  }
  ImGui::End();
  return r;
}

namespace {

PromptChoice prompt(bool open, const char* id, const std::string& text, bool recovery, bool confirm = false) {
  if (open && !ImGui::IsPopupOpen(id)) ImGui::OpenPopup(id);
  PromptChoice choice = PromptChoice::None;
  const ImVec2 center(ImGui::GetIO().DisplaySize.x * 0.5f, ImGui::GetIO().DisplaySize.y * 0.5f);
  ImGui::SetNextWindowPos(center, ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
  if (ImGui::BeginPopupModal(id, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::TextUnformatted(text.c_str());
    ImGui::Spacing();
    if (confirm) {
      if (ImGui::Button("Continue", ImVec2(100, 0))) choice = PromptChoice::Discard;
      ImGui::SameLine();
      if (ImGui::Button("Cancel", ImVec2(100, 0))) choice = PromptChoice::Cancel;
    } else if (recovery) {
      if (ImGui::Button("Recover", ImVec2(100, 0))) choice = PromptChoice::Recover;
      ImGui::SameLine();
      if (ImGui::Button("Discard", ImVec2(100, 0))) choice = PromptChoice::Discard;
    } else {
      if (ImGui::Button("Save", ImVec2(90, 0))) choice = PromptChoice::Save;
      ImGui::SameLine();
      if (ImGui::Button("Discard", ImVec2(90, 0))) choice = PromptChoice::Discard;
      ImGui::SameLine();
      if (ImGui::Button("Cancel", ImVec2(90, 0)) || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape))) choice = PromptChoice::Cancel;
    }
    if (choice != PromptChoice::None || !open) ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
  }
  return choice;
}

}  // namespace

PromptChoice draw_unsaved_prompt(bool open, const std::string& what) {
  return prompt(open, "Unsaved changes", "The model has unsaved changes.\nSave them before " + what + "?", false);
}

bool draw_progress_prompt(bool open, const std::string& title, const std::string& stage, float fraction) {
  const std::string id = title + "##progress";
  if (open && !ImGui::IsPopupOpen(id.c_str())) ImGui::OpenPopup(id.c_str());
  bool cancel = false;
  const ImVec2 center(ImGui::GetIO().DisplaySize.x * 0.5f, ImGui::GetIO().DisplaySize.y * 0.5f);
  ImGui::SetNextWindowPos(center, ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
  if (ImGui::BeginPopupModal(id.c_str(), nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::TextUnformatted(stage.c_str());
    ImGui::ProgressBar(std::clamp(fraction, 0.0f, 1.0f), ImVec2(280.0f, 0.0f));
    if (ImGui::Button("Cancel", ImVec2(100, 0)) || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape))) cancel = true;
    if (!open) ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
  }
  return cancel;
}

PromptChoice draw_recovery_prompt(bool open, const std::string& path) {
  return prompt(open, "Recover", "Sublift did not close cleanly last time.\nRecover the autosaved model?\n" + path,
                true);
}

void draw_modeler_status(const std::string& left, const std::string& right, float display_width,
                         float display_height, float height) {
  height = std::min(height, display_height);
  ImGui::SetNextWindowPos(ImVec2(0.0f, display_height - height));
  ImGui::SetNextWindowSize(ImVec2(display_width, height));
  ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(12.0f, 5.0f));
  ImGui::PushStyleColor(ImGuiCol_WindowBg, ImVec4(0.11f, 0.12f, 0.13f, 1.0f));
  const ImGuiWindowFlags flags = kDockedFlags | ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoInputs;
  if (ImGui::Begin("##modeler_status", nullptr, flags)) {
    ImGui::TextUnformatted(left.c_str());
    const float at = ImGui::GetWindowContentRegionMax().x - ImGui::CalcTextSize(right.c_str()).x;
    ImGui::SameLine(std::max(at, ImGui::GetCursorPosX() + 24.0f));
    ImGui::TextColored(kMuted, "%s", right.c_str());
  }
  ImGui::End();
  ImGui::PopStyleColor();
  ImGui::PopStyleVar();
}

}  // namespace sublift
