#include <cmath>

#include <gtest/gtest.h>

#include "core/base/edit_lines.h"
#include "core/base/errors.h"
#include "core/base/text_lines.h"

using namespace sublift;

static std::vector<std::string> all_lines(std::string_view text) {
  LineReader r(text, "t.txt", 100);
  std::vector<std::string> out;
  std::string_view l;
  while (r.next(l)) out.emplace_back(l);
  return out;
}

TEST(LineReader, AcceptsLfCrlfAndCrEndings) {
  const std::vector<std::string> want{"a", "b", "", "c"};
  EXPECT_EQ(all_lines("a\nb\n\nc\n"), want);
  EXPECT_EQ(all_lines("a\r\nb\r\n\r\nc\r\n"), want);
  EXPECT_EQ(all_lines("a\rb\r\rc"), want);
}

TEST(LineReader, StripsUtf8BomOnlyAtStart) {
  EXPECT_EQ(all_lines("\xEF\xBB\xBFv 1\n"), std::vector<std::string>{"v 1"});
}

TEST(LineReader, CountsLinesAndRefusesBinaryAndLongLines) {
  LineReader r("ok\nbad\x01here\n", "f.obj", 100);
  std::string_view l;
  ASSERT_TRUE(r.next(l));
  EXPECT_EQ(r.line_number(), 1u);
  try {
    r.next(l);
    FAIL() << "binary byte accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 2u);
    EXPECT_NE(std::string(e.what()).find("f.obj:2"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("binary"), std::string::npos);
  }
  const std::string long_line(200, 'x');  // the reader views its text: keep it alive
  LineReader longer(long_line, "g.obj", 100);
  EXPECT_THROW(longer.next(l), InputError);
}

TEST(ParseNumbers, RejectsNonFiniteOverflowAndTrailingGarbage) {
  EXPECT_EQ(parse_double("1.5"), 1.5);
  EXPECT_EQ(parse_double("+2e3"), 2000.0);
  EXPECT_EQ(parse_double("-0.25"), -0.25);
  EXPECT_FALSE(parse_double("nan"));
  EXPECT_FALSE(parse_double("inf"));
  EXPECT_FALSE(parse_double("1e400"));
  EXPECT_FALSE(parse_double("1.0x"));
  EXPECT_FALSE(parse_double(""));
  EXPECT_EQ(parse_int("-7"), -7);
  EXPECT_FALSE(parse_int("7.0"));
  EXPECT_FALSE(parse_int("99999999999999999999999"));
}

TEST(SplitTokens, SplitsOnAnyBlank) {
  std::vector<std::string_view> t;
  split_tokens("  f\t1  2\v3 ", t);
  ASSERT_EQ(t.size(), 4u);
  EXPECT_EQ(t[0], "f");
  EXPECT_EQ(t[3], "3");
}

// Issue 18: file content quoted in messages is escaped by one function.
TEST(Printable, EscapesControlAndNonUtf8BytesAndKeepsUtf8) {
  EXPECT_EQ(printable("plain"), "plain");
  EXPECT_EQ(printable(std::string_view("a\0b", 3)), "a\\x00b");  // a NUL does not cut the message
  EXPECT_EQ(printable("tab\there\x7f"), "tab\\x09here\\x7F");
  EXPECT_EQ(printable("caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x98\x80"), "caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x98\x80");  // é € 😀 kept
  EXPECT_EQ(printable("\xff\xfe"), "\\xFF\\xFE");
  EXPECT_EQ(printable("\xc0\xaf"), "\\xC0\\xAF");          // overlong '/'
  EXPECT_EQ(printable("\xed\xa0\x80"), "\\xED\\xA0\\x80");  // a surrogate
  EXPECT_EQ(printable("\xc3"), "\\xC3");                    // a sequence cut short
  EXPECT_EQ(printable(std::string(40, 'x')), std::string(32, 'x') + "...");
  EXPECT_EQ(printable("abcdef", 3), "abc...");
}

TEST(FormatShortest, ReadsBackAndIsShort) {
  EXPECT_EQ(format_shortest(1.7e308), "1.7e+308");
  EXPECT_EQ(format_shortest(0.1), "0.1");
  EXPECT_EQ(format_shortest(1.0 / 3.0), "0.3333333333333333");
  EXPECT_EQ(format_shortest(-HUGE_VAL), "-inf");
}

// The edits files' one reader: comments and blank lines skipped, fields in order, and every
// refusal naming the file, the line and the field.
TEST(EditLines, ReadsFieldsAndNamesWhatIsWrong) {
  static constexpr EditField kFields[] = {{"level", 64}, {"index", 1000}};
  const std::vector<EditLine> e = parse_edit_lines("# level index dx dy dz\n\n2 7 0.5 -1 1e-3\n0 0 0 0 0\n", "e.txt", kFields);
  ASSERT_EQ(e.size(), 2u);
  EXPECT_EQ(e[0].line, 3u);
  EXPECT_EQ(e[0].whole[0], 2);
  EXPECT_EQ(e[0].whole[1], 7);
  EXPECT_EQ(e[0].delta[0], 0.5);
  EXPECT_EQ(e[0].delta[1], -1.0);
  EXPECT_EQ(e[0].delta[2], 1e-3);
  EXPECT_EQ(e[1].line, 4u);
  const auto refused = [&](const char* text) {
    try {
      (void)parse_edit_lines(text, "e.txt", kFields);
    } catch (const InputError& err) {
      return std::string(err.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(refused("0 1 2 3\n").find("e.txt:1: expected 'level index dx dy dz', got 4 fields"), std::string::npos);
  EXPECT_NE(refused("\n-1 0 0 0 0\n").find("e.txt:2: level must be a non-negative integer, got '-1'"), std::string::npos);
  EXPECT_NE(refused("0 1.5 0 0 0\n").find("e.txt:1: index must be a non-negative integer"), std::string::npos);
  EXPECT_NE(refused("65 0 0 0 0\n").find("e.txt:1: level 65 is too large (at most 64)"), std::string::npos);
  EXPECT_NE(refused("0 1001 0 0 0\n").find("index 1001 is too large (at most 1000)"), std::string::npos);
  EXPECT_NE(refused("0 1 0 nan 0\n").find("e.txt:1: dy must be a finite number"), std::string::npos);
  EXPECT_NE(refused("0 1 0 0 1e999\n").find("e.txt:1: dz must be a finite number"), std::string::npos);
}
