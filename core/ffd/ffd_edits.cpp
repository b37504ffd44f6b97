#include "core/ffd/ffd_edits.h"

#include "core/base/edit_lines.h"
#include "core/base/errors.h"
#include "core/base/file_io.h"

namespace sublift {

std::vector<FfdEdit> parse_ffd_edits(std::string_view text, const std::string& file) {
  static constexpr EditField kFields[] = {{"level", 64}, {"index", 0xffffffffLL}};
  std::vector<FfdEdit> edits;
  for (const EditLine& l : parse_edit_lines(text, file, kFields)) {
    FfdEdit e;
    e.line = l.line;
    e.level = static_cast<int>(l.whole[0]);
    e.index = static_cast<std::uint32_t>(l.whole[1]);
    for (int k = 0; k < 3; ++k) e.delta[k] = l.delta[static_cast<std::size_t>(k)];
    edits.push_back(e);
  }
  return edits;
}

std::vector<FfdEdit> read_ffd_edits(const std::string& path) {
  const std::string bytes = read_file_bytes(path, std::size_t(64) << 20);
  return parse_ffd_edits(bytes, path);
}

void check_ffd_edits(const std::vector<FfdEdit>& edits, const Hierarchy& h, const std::string& file) {
  for (const FfdEdit& e : edits) {
    if (e.level > h.finest_level()) {
      throw InputError(file, e.line, "level " + std::to_string(e.level) + " is beyond the lattice's finest level " +
                                         std::to_string(h.finest_level()));
    }
    if (e.index >= h.num_vertices(e.level)) {
      throw InputError(file, e.line, "index " + std::to_string(e.index) + " is not a vertex of level " +
                                         std::to_string(e.level) + " (it has " +
                                         std::to_string(h.num_vertices(e.level)) + ")");
    }
  }
}

}  // namespace sublift
