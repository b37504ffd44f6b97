#pragma once
// Line and token scanning for the text readers: strips a UTF-8 BOM, accepts LF, CRLF and CR
// endings, counts 1-based lines, refuses binary bytes and over-long lines, and parses numbers
// with std::from_chars (locale-independent, no allocation).
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace sublift {

class LineReader {
 public:
  /// `file` names the source in error messages. The reader views `text`: keep it alive.
  LineReader(std::string_view text, std::string file, std::size_t max_line_length);
  /// Next line without its ending; false at end of input. Throws InputError on NUL/binary bytes
  /// or a line longer than the limit.
  bool next(std::string_view& line);
  std::size_t line_number() const { return line_; }
  /// Byte offset just past the current line's ending (where binary payloads start).
  std::size_t offset() const { return pos_; }
  const std::string& file() const { return file_; }

 private:
  std::string_view text_;
  std::string file_;
  std::size_t max_len_;
  std::size_t pos_ = 0;
  std::size_t line_ = 0;
};

/// Reads the next line that holds anything besides blanks and a `#` comment, split into
/// tokens; false at end of input. `lines.line_number()` is then that line's number.
bool next_tokens(LineReader& lines, std::vector<std::string_view>& tokens);

/// Splits on blanks (space, tab, vertical tab, form feed); never allocates strings.
void split_tokens(std::string_view line, std::vector<std::string_view>& out);

/// Parses a whole token as a finite double; nullopt when it is not a number, not finite or
/// does not fit a double.
std::optional<double> parse_double(std::string_view token);

/// Parses a whole token as a signed 64-bit integer; nullopt otherwise.
std::optional<std::int64_t> parse_int(std::string_view token);

/// File content quoted in a message, as the one place that makes it safe to print: at most
/// `max_bytes` bytes (then "..."), control bytes, DEL and bytes that are not valid UTF-8 written
/// as \xNN (so a NUL cannot cut the message nor raw bytes garble a terminal); valid UTF-8 is
/// kept. Used by every message that quotes what a file holds.
std::string printable(std::string_view bytes, std::size_t max_bytes = 32);

/// The shortest "%g" form that reads back as v, for messages: "1.7e+308", not
/// "1.6999999999999999e+308"; "nan", "inf", "-inf" as printf writes them.
std::string format_shortest(double v);

/// The non-empty lines of `text` (split at '\n'): a message of several lines as notes.
std::vector<std::string> nonempty_lines(std::string_view text);

/// Lower-case ASCII copy (for extensions and keywords).
std::string to_lower(std::string_view s);

}  // namespace sublift
