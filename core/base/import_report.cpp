#include <algorithm>

#include "core/base/import_report.h"

namespace sublift {

namespace {

// One occurrence of `what` at `line`, merged with earlier ones of the same kind in `list`; line 0
// (no line) is listed only when `keep_no_line`.
void count(std::vector<ImportWarning>& list, const std::string& what, std::size_t line, bool keep_no_line) {
  auto it = std::find_if(list.begin(), list.end(), [&](const ImportWarning& w) { return w.what == what; });
  if (it == list.end()) it = list.insert(list.end(), ImportWarning{what, 0, {}});
  ++it->count;
  if ((line > 0 || keep_no_line) && it->first_lines.size() < ImportReport::kMaxLines) it->first_lines.push_back(line);
}

}  // namespace

void ImportReport::add(const std::string& what, std::size_t line) { count(warnings, what, line, false); }

std::string ImportReport::format(const std::string& file) const {
  std::string out;
  for (const ImportWarning& w : warnings) {
    out += file + ": warning: " + std::to_string(w.count) + " x " + w.what;
    if (!w.first_lines.empty()) {
      out += w.first_lines.size() == 1 ? " (line " : " (lines ";
      for (std::size_t i = 0; i < w.first_lines.size(); ++i)
        out += (i ? ", " : "") + std::to_string(w.first_lines[i]);
      if (w.count > w.first_lines.size()) out += ", ...";
      out += ")";
    }
    out += "\n";
  }
  return out;
}

void ImportReport::note_not_kept(const std::string& what, std::size_t line) { count(not_kept, what, line, true); }

void ImportReport::note_attributes_not_kept(const std::vector<VertexAttribute>& attributes) {
  if (attributes.empty()) return;
  std::string names;
  for (const VertexAttribute& a : attributes) names += (names.empty() ? "" : ", ") + a.name;
  not_kept.push_back({"values of the vertex attributes " + names, attributes.front().values.size(), {}});
}

std::string ImportReport::not_kept_summary() const {
  std::string s;
  for (const ImportWarning& w : not_kept) s += (s.empty() ? "" : ", ") + std::to_string(w.count) + " " + w.what;
  return s;
}

}  // namespace sublift
