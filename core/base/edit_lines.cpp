#include "core/base/edit_lines.h"

#include <stdexcept>

#include "core/base/errors.h"
#include "core/base/text_lines.h"

namespace sublift {

std::vector<EditLine> parse_edit_lines(std::string_view text, const std::string& file, std::span<const EditField> fields) {
  if (fields.size() > 3) throw std::logic_error("parse_edit_lines: at most 3 whole-number fields");
  std::string form;  // "level index dx dy dz"
  for (const EditField& f : fields) form += std::string(f.name) + " ";
  form += "dx dy dz";
  LineReader lines(text, file, 1 << 16);
  std::vector<EditLine> out;
  std::vector<std::string_view> tokens;
  while (next_tokens(lines, tokens)) {
    EditLine e;
    e.line = lines.line_number();
    if (tokens.size() != fields.size() + 3)
      throw InputError(file, e.line, "expected '" + form + "', got " + std::to_string(tokens.size()) + " fields");
    for (std::size_t k = 0; k < fields.size(); ++k) {
      const auto v = parse_int(tokens[k]);
      if (!v || *v < 0)
        throw InputError(file, e.line,
                         std::string(fields[k].name) + " must be a non-negative integer, got '" + printable(tokens[k]) + "'");
      if (*v > fields[k].max)
        throw InputError(file, e.line, std::string(fields[k].name) + " " + std::to_string(*v) + " is too large (at most " +
                                           std::to_string(fields[k].max) + ")");
      e.whole[k] = *v;
    }
    for (std::size_t k = 0; k < 3; ++k) {
      const auto d = parse_double(tokens[fields.size() + k]);
      if (!d)
        throw InputError(file, e.line, std::string("d") + char('x' + k) + " must be a finite number, got '" +
                                           printable(tokens[fields.size() + k]) + "'");
      e.delta[k] = *d;
    }
    out.push_back(e);
  }
  return out;
}

}  // namespace sublift
