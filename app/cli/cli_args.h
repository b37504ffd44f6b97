#pragma once
// Minimal argument parsing for sublift-cli: positionals, `--flag`, `--key value`, `-o value`.
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace sublift::cli {

/// Bad command-line usage: sublift-cli exits with code 2.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Args {
  std::vector<std::string> positional;
  std::map<std::string, std::string> values;  // "--size" -> "800x600", "-o" -> "out.png"
  std::set<std::string> flags;                // "--json", "--help"
  std::map<std::string, std::vector<std::string>> lists;  // repeatable / multi-value options
  bool has(const std::string& flag) const { return flags.count(flag) != 0; }
  std::optional<std::string> value(const std::string& key) const;
};

/// Parses `argv[first..]`: options in `with_value` take the next argument; `flags` take none;
/// anything else starting with '-' is a UsageError.
Args parse_args(int argc, char** argv, int first, const std::set<std::string>& with_value,
                const std::set<std::string>& flags);

/// The same, plus options in `multi` that take the given number of values each (taken as they
/// are, so "-0.5" is a value) and may be repeated; their values collect in Args::lists.
Args parse_args(int argc, char** argv, int first, const std::set<std::string>& with_value,
                const std::set<std::string>& flags, const std::map<std::string, int>& multi);

/// The integer value of option `name` in lo..hi, `fallback` when it is absent. Throws
/// UsageError naming the option and the range.
long integer_option(const Args& a, const char* name, long fallback, long lo, long hi);

/// "a,b,c,...": finite numbers separated by commas. Throws UsageError naming `option`.
std::vector<double> number_list(const std::string& s, const std::string& option);

/// Parses "WxH" (each 16..8192). Throws UsageError.
void parse_size(const std::string& s, int& width, int& height);

}  // namespace sublift::cli
