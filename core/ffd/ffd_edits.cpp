#include "core/ffd/ffd_edits.h"

#include "core/base/errors.h"
#include "core/base/file_io.h"
#include "core/base/text_lines.h"

namespace sublift {

std::vector<FfdEdit> parse_ffd_edits(std::string_view text, const std::string& file) {
  LineReader lines(text, file, 1 << 16);
  std::vector<FfdEdit> edits;
  std::vector<std::string_view> tokens;
  while (next_tokens(lines, tokens)) {
    const std::size_t line = lines.line_number();
    if (tokens.size() != 5) {
      throw InputError(file, line, "expected 'level index dx dy dz', got " + std::to_string(tokens.size()) + " fields");
    }
    FfdEdit e;
    e.line = line;
    const auto level = parse_int(tokens[0]);
    if (!level || *level < 0 || *level > 64) {
      throw InputError(file, line, "level must be a non-negative integer, got '" + printable(tokens[0]) + "'");
    }
    const auto index = parse_int(tokens[1]);
    if (!index || *index < 0 || *index > 0xffffffffLL) {
      throw InputError(file, line, "index must be a non-negative integer, got '" + printable(tokens[1]) + "'");
    }
    e.level = static_cast<int>(*level);
    e.index = static_cast<std::uint32_t>(*index);
    for (int k = 0; k < 3; ++k) {
      const auto d = parse_double(tokens[static_cast<std::size_t>(2 + k)]);
      if (!d) {
        throw InputError(file, line, std::string("d") + static_cast<char>('x' + k) + " must be a finite number, got '" +
                                         printable(tokens[static_cast<std::size_t>(2 + k)]) + "'");
      }
      e.delta[k] = *d;
    }
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
