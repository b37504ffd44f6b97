#pragma once
// The edits files of `sublift-cli ffd` and `animation` (docs/file_formats.md): a line per edit,
// whole-number fields that say where (level, index; level, frame, point) and then dx dy dz.
// One reader for both, so both check their fields alike.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace sublift {

/// A whole-number field: its name in messages and its largest value.
struct EditField {
  const char* name;
  std::int64_t max;
};

struct EditLine {
  std::size_t line = 0;                // 1-based, for messages
  std::array<std::int64_t, 3> whole{};  // the fields, in order
  std::array<double, 3> delta{};
};

/// Every line of `text` that is not blank or a `#` comment, as `fields` (at most 3) then
/// dx dy dz. Throws InputError (file, line) naming the field: a wrong field count, a field that
/// is not a whole number from 0 to its maximum, a delta that is not a finite number.
std::vector<EditLine> parse_edit_lines(std::string_view text, const std::string& file, std::span<const EditField> fields);

}  // namespace sublift
