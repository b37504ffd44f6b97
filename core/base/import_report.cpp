#include <algorithm>

#include "core/base/import_report.h"

namespace sublift {

void ImportReport::add(const std::string& what, std::size_t line) {
  auto it = std::find_if(warnings.begin(), warnings.end(),
                         [&](const ImportWarning& w) { return w.what == what; });
  if (it == warnings.end()) {
    warnings.push_back({what, 0, {}});
    it = warnings.end() - 1;
  }
  ++it->count;
  if (line > 0 && it->first_lines.size() < kMaxLines) it->first_lines.push_back(line);
}

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

void ImportReport::note_not_kept(const std::string& what, std::size_t line) {
  for (ImportWarning& w : not_kept)
    if (w.what == what) {
      ++w.count;
      if (w.first_lines.size() < kMaxLines) w.first_lines.push_back(line);
      return;
    }
  not_kept.push_back({what, 1, {line}});
}

std::string ImportReport::not_kept_summary() const {
  std::string s;
  for (const ImportWarning& w : not_kept) s += (s.empty() ? "" : ", ") + std::to_string(w.count) + " " + w.what;
  return s;
}

}  // namespace sublift
