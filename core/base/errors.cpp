#include "core/base/errors.h"

namespace sublift {

static std::string located(const std::string& file, std::size_t line, const std::string& what) {
  std::string s = file;
  if (line > 0) {
    s.push_back(':');
    s.append(std::to_string(line));
  }
  s.append(": ");
  s.append(what);
  return s;
}

InputError::InputError(const std::string& file, std::size_t line, const std::string& what)
    : Error(located(file, line, what)), file_(file), line_(line) {}

}  // namespace sublift
