#include "app/cli/cli_args.h"

#include "core/base/text_lines.h"

#include <charconv>

namespace sublift::cli {

std::optional<std::string> Args::value(const std::string& key) const {
  auto it = values.find(key);
  if (it == values.end()) return std::nullopt;
  return it->second;
}

Args parse_args(int argc, char** argv, int first, const std::set<std::string>& with_value,
                const std::set<std::string>& flags) {
  return parse_args(argc, argv, first, with_value, flags, {});
}

Args parse_args(int argc, char** argv, int first, const std::set<std::string>& with_value,
                const std::set<std::string>& flags, const std::map<std::string, int>& multi) {
  Args a;
  for (int i = first; i < argc; ++i) {
    const std::string s = argv[i];
    if (const auto m = multi.find(s); m != multi.end()) {
      if (i + m->second >= argc)
        throw UsageError("option " + s + " needs " + std::to_string(m->second) + (m->second == 1 ? " value" : " values"));
      for (int k = 0; k < m->second; ++k) a.lists[s].push_back(argv[++i]);
    } else if (s == "-h") {
      a.flags.insert("--help");
    } else if (with_value.count(s)) {
      if (i + 1 >= argc) throw UsageError("option " + s + " needs a value");
      a.values[s] = argv[++i];
    } else if (flags.count(s)) {
      a.flags.insert(s);
    } else if (s.size() > 1 && s[0] == '-') {
      throw UsageError("unknown option " + s);
    } else {
      a.positional.push_back(s);
    }
  }
  return a;
}

long integer_option(const Args& a, const char* name, long fallback, long lo, long hi) {
  const auto v = a.value(name);
  if (!v) return fallback;
  long x = 0;
  const auto [p, ec] = std::from_chars(v->data(), v->data() + v->size(), x);
  if (ec != std::errc() || p != v->data() + v->size() || x < lo || x > hi)
    throw UsageError(std::string(name) + " must be an integer in " + std::to_string(lo) + ".." + std::to_string(hi) + ", got '" + *v + "'");
  return x;
}

void parse_size(const std::string& s, int& width, int& height) {
  const auto x = s.find('x');
  auto num = [&](std::string_view t, int& out) {
    auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), out);
    return ec == std::errc() && p == t.data() + t.size() && out >= 16 && out <= 8192;
  };
  if (x == std::string::npos || !num(std::string_view(s).substr(0, x), width) ||
      !num(std::string_view(s).substr(x + 1), height))
    throw UsageError("--size must be WIDTHxHEIGHT with each side in 16..8192, got '" + s + "'");
}

std::vector<double> number_list(const std::string& s, const std::string& option) {
  std::vector<double> out;
  std::size_t at = 0;
  for (;;) {
    const std::size_t comma = s.find(',', at);
    const std::string token = s.substr(at, comma == std::string::npos ? std::string::npos : comma - at);
    const auto v = parse_double(token);
    if (!v) throw UsageError(option + " takes finite numbers separated by commas, got '" + s + "'");
    out.push_back(*v);
    if (comma == std::string::npos) return out;
    at = comma + 1;
  }
}

}  // namespace sublift::cli
