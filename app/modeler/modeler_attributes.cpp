// The modeler's attribute channels: kept beside the session (which edits x, y, z), fitted to its
// levels when saved or exported (core/edit/attribute_channels.h).
#include "app/modeler/modeler_state.h"
#include "core/analysis/compress.h"
#include "core/base/errors.h"
#include "core/base/channels.h"
#include "core/edit/attribute_channels.h"

#include <algorithm>

namespace sublift {

std::vector<ChannelGroup> ModelerState::attribute_groups() const {
  return channel_groups(int(attribute_names_.size()), attribute_names_, 0);
}

void ModelerState::set_channel_keep(const std::string& name, double keep) {
  if (!(keep >= 0.0 && keep <= 1.0)) throw Error("a channel's kept fraction must be in 0..1");
  std::string all;
  for (const ChannelGroup& g : attribute_groups()) {
    all += (all.empty() ? "" : ", ") + g.name;
    if (g.name != name && std::find(g.channels.begin(), g.channels.end(), name) == g.channels.end()) continue;
    std::erase_if(channel_keep_, [&](const auto& k) { return k.first == g.name; });
    if (keep < 1.0) channel_keep_.emplace_back(g.name, keep);
    refresh_colour();
    return;
  }
  throw Error("no attribute channel or group '" + name + "'" + (all.empty() ? " (the model has none)" : " (the model's groups: " + all + ")"));
}

double ModelerState::channel_keep(const std::string& group) const {
  for (const auto& [g, k] : channel_keep_)
    if (g == group) return k;
  return 1.0;
}

std::optional<Hierarchy> ModelerState::fitted_attributes(std::string* why) const {
  const Complex& base = session_->hierarchy().levels.front();
  for (auto it = attribute_sets_.rbegin(); it != attribute_sets_.rend(); ++it) {
    const Complex& b = it->levels.front();
    if (b.num_vertices != base.num_vertices || b.faces.offsets != base.faces.offsets || b.faces.items != base.faces.items) continue;
    std::optional<Hierarchy> fitted = attributes_for(*it, session_->hierarchy(), why);
    if (!fitted || channel_keep_.empty()) return fitted;
    for (const ChannelGroup& g : attribute_groups()) {  // each compressed group ranked on its own
      const double keep = channel_keep(g.name);
      if (keep >= 1.0) continue;
      CompressOptions o;
      o.gains.assign(session_->gains().begin(), session_->gains().end());
      o.channels = g.range;
      try {
        fitted->coeffs = Compressor(*fitted, o).run(CompressMode::Keep, keep).coeffs;
      } catch (const Error&) {
        // a constant channel: no extent to rank by, nothing to drop
      }
    }
    return fitted;
  }
  if (why && !attribute_sets_.empty()) *why = "the base changed";
  return std::nullopt;
}

Hierarchy ModelerState::saved_hierarchy(std::string* why) const {
  const std::optional<Hierarchy> fitted = attribute_sets_.empty() ? std::nullopt : fitted_attributes(why);
  return fitted ? merge_channels(session_->hierarchy(), *fitted) : session_->hierarchy();
}

std::vector<VertexAttribute> ModelerState::attributes_at(int level) const {
  if (attribute_sets_.empty()) return {};
  std::optional<Hierarchy> fitted = fitted_attributes();
  if (!fitted) return {};
  apply_gains(*fitted, session_->gains());
  return attributes_of(synthesize(*fitted, level), fitted->channels, attribute_names_, 0);
}

std::vector<float> ModelerState::channel_colour(int k) const {
  const std::vector<VertexAttribute> at = attributes_at(shown_level());
  if (k < 0 || std::size_t(k) >= at.size()) return {};
  const VertexAttribute& a = at[std::size_t(k)];
  double lo = 0.0, hi = a.type == "uchar" || a.type == "char" ? 255.0 : a.type == "ushort" ? 65535.0 : 0.0;
  if (hi == 0.0 && !a.values.empty()) {  // the channel's own range
    lo = *std::min_element(a.values.begin(), a.values.end());
    hi = *std::max_element(a.values.begin(), a.values.end());
  }
  std::vector<float> out(a.values.size(), 0.5f);
  if (hi > lo)
    for (std::size_t v = 0; v < out.size(); ++v) out[v] = float(std::clamp((a.values[v] - lo) / (hi - lo), 0.0, 1.0));
  return out;
}

std::string ModelerState::attribute_list() const {
  std::string s;
  for (const VertexAttribute& a : attribute_names_) s += (s.empty() ? "" : ", ") + a.name;
  return s;
}

}  // namespace sublift
