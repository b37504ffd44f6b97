#include "core/base/text_lines.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "core/base/errors.h"

namespace sublift {

LineReader::LineReader(std::string_view text, std::string file, std::size_t max_line_length)
    : text_(text), file_(std::move(file)), max_len_(max_line_length) {
  if (text_.size() >= 3 && text_.substr(0, 3) == "\xEF\xBB\xBF") pos_ = 3;  // UTF-8 BOM
}

bool LineReader::next(std::string_view& line) {
  if (pos_ >= text_.size()) return false;
  ++line_;
  std::size_t start = pos_;
  std::size_t end = start;
  while (end < text_.size() && text_[end] != '\n' && text_[end] != '\r') {
    const unsigned char c = static_cast<unsigned char>(text_[end]);
    // Control bytes other than tab/VT/FF never occur in a text mesh file: it is binary.
    if (c < 0x20 && c != '\t' && c != '\v' && c != '\f')
      throw InputError(file_, line_,
                       "binary data in a text file (byte 0x" +
                           std::string(1, "0123456789abcdef"[c >> 4]) +
                           std::string(1, "0123456789abcdef"[c & 15]) + " at offset " +
                           std::to_string(end) + ")");
    ++end;
    if (end - start > max_len_)
      throw InputError(file_, line_,
                       "line longer than " + std::to_string(max_len_) + " bytes");
  }
  line = text_.substr(start, end - start);
  pos_ = end;
  if (pos_ < text_.size() && text_[pos_] == '\r') ++pos_;           // CR or CRLF
  if (pos_ < text_.size() && text_[pos_] == '\n') ++pos_;           // LF or the LF of CRLF
  return true;
}

void split_tokens(std::string_view line, std::vector<std::string_view>& out) {
  out.clear();
  std::size_t i = 0;
  const auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\v' || c == '\f'; };
  while (i < line.size()) {
    while (i < line.size() && blank(line[i])) ++i;
    std::size_t j = i;
    while (j < line.size() && !blank(line[j])) ++j;
    if (j > i) out.push_back(line.substr(i, j - i));
    i = j;
  }
}

bool next_tokens(LineReader& lines, std::vector<std::string_view>& tokens) {
  std::string_view line;
  while (lines.next(line)) {
    if (const auto hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    split_tokens(line, tokens);
    if (!tokens.empty()) return true;
  }
  return false;
}

std::optional<double> parse_double(std::string_view t) {
  if (!t.empty() && t.front() == '+') t.remove_prefix(1);
  double v = 0.0;
  auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
  if (ec != std::errc() || p != t.data() + t.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

std::optional<std::int64_t> parse_int(std::string_view t) {
  if (!t.empty() && t.front() == '+') t.remove_prefix(1);
  std::int64_t v = 0;
  auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
  if (ec != std::errc() || p != t.data() + t.size()) return std::nullopt;
  return v;
}

std::vector<std::string> nonempty_lines(std::string_view text) {
  std::vector<std::string> out;
  for (std::size_t start = 0; start < text.size();) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    if (end > start) out.emplace_back(text.substr(start, end - start));
    start = end + 1;
  }
  return out;
}

std::string to_lower(std::string_view s) {
  std::string r(s);
  for (char& c : r)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return r;
}

std::string printable(std::string_view bytes, std::size_t max_bytes) {
  std::string out;
  const std::size_t n = std::min(bytes.size(), max_bytes);
  auto hex = [&](unsigned char c) {
    static const char* digits = "0123456789ABCDEF";
    out += "\\x";
    out.push_back(digits[c >> 4]);
    out.push_back(digits[c & 15]);
  };
  for (std::size_t i = 0; i < n;) {
    const auto c = static_cast<unsigned char>(bytes[i]);
    if (c < 0x20 || c == 0x7f) {
      hex(c);
      ++i;
      continue;
    }
    if (c < 0x80) {
      out.push_back(static_cast<char>(c));
      ++i;
      continue;
    }
    // A UTF-8 sequence: lead byte, then continuation bytes 10xxxxxx; overlong forms, surrogates
    // and values beyond U+10FFFF are not valid UTF-8.
    const std::size_t len = c >= 0xc2 && c <= 0xdf ? 2 : c >= 0xe0 && c <= 0xef ? 3 : c >= 0xf0 && c <= 0xf4 ? 4 : 0;
    bool ok = len > 0 && i + len <= n;
    for (std::size_t k = 1; ok && k < len; ++k) ok = (static_cast<unsigned char>(bytes[i + k]) & 0xc0) == 0x80;
    if (ok && len >= 3) {
      const auto c1 = static_cast<unsigned char>(bytes[i + 1]);
      if (c == 0xe0 && c1 < 0xa0) ok = false;  // overlong
      if (c == 0xed && c1 >= 0xa0) ok = false;  // surrogate
      if (c == 0xf0 && c1 < 0x90) ok = false;  // overlong
      if (c == 0xf4 && c1 >= 0x90) ok = false;  // beyond U+10FFFF
    }
    if (!ok) {
      hex(c);
      ++i;
      continue;
    }
    out.append(bytes.substr(i, len));
    i += len;
  }
  if (bytes.size() > max_bytes) out += "...";
  return out;
}

std::string format_shortest(double v) {
  char buf[40];
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    if (!std::isfinite(v) || std::strtod(buf, nullptr) == v) break;
  }
  return buf;
}

}  // namespace sublift
