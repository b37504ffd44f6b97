// The modeler's attribute channels: kept beside the session (which edits x, y, z), fitted to its
// levels when saved or exported (core/edit/attribute_channels.h).
#include "app/modeler/modeler_state.h"
#include "core/edit/attribute_channels.h"

namespace sublift {

Hierarchy ModelerState::saved_hierarchy(std::string* why) const {
  if (!attributes_) return session_->hierarchy();
  const std::optional<Hierarchy> fitted = attributes_for(*attributes_, session_->hierarchy(), why);
  return fitted ? merge_channels(session_->hierarchy(), *fitted) : session_->hierarchy();
}

std::vector<VertexAttribute> ModelerState::attributes_at(int level) const {
  if (!attributes_) return {};
  std::optional<Hierarchy> fitted = attributes_for(*attributes_, session_->hierarchy());
  if (!fitted) return {};
  apply_gains(*fitted, session_->gains());
  const std::vector<double> values = synthesize(*fitted, level);
  const std::size_t n = values.size() / attribute_names_.size();
  std::vector<VertexAttribute> out = attribute_names_;
  for (std::size_t k = 0; k < out.size(); ++k) {
    out[k].values.resize(n);
    for (std::size_t v = 0; v < n; ++v) out[k].values[v] = values[v * out.size() + k];
  }
  return out;
}

std::string ModelerState::attribute_list() const {
  std::string s;
  for (const VertexAttribute& a : attribute_names_) s += (s.empty() ? "" : ", ") + a.name;
  return s;
}

}  // namespace sublift
