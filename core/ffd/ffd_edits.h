#pragma once
// The lattice edits file of `sublift-cli ffd --edits` (issue 6): one edit per line,
//
//   level index dx dy dz
//
// moving control point `index` (the engine's order of that level; level 0 is the lattice file's
// vertex order) of lattice level `level` by (dx, dy, dz), as the modeler's drag does (finer
// levels resynthesised, coarser ones take the change as detail). Edits apply in file order.
// Blank lines and `#` comments (whole-line or trailing) are allowed; an empty file means no edit.
// Errors name the file and line: a wrong number of fields, a field that is not a number, a
// negative or fractional level or index, a non-finite delta. Ranges (level and index) are
// checked against the hierarchy by check_ffd_edits.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/multires/hierarchy.h"

namespace sublift {

struct FfdEdit {
  int level = 0;
  std::uint32_t index = 0;
  double delta[3] = {0, 0, 0};
  std::size_t line = 0;  // 1-based source line
};

/// Parses the text of an edits file (`file` names it in errors). Throws InputError.
std::vector<FfdEdit> parse_ffd_edits(std::string_view text, const std::string& file);

/// Reads and parses an edits file. Throws IoError or InputError.
std::vector<FfdEdit> read_ffd_edits(const std::string& path);

/// Throws InputError (file, line) for an edit whose level exceeds `h`'s finest level or whose
/// index is not a vertex of that level.
void check_ffd_edits(const std::vector<FfdEdit>& edits, const Hierarchy& h, const std::string& file);

}  // namespace sublift
