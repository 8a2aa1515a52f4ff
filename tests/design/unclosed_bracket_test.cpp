// unclosed_bracket: the list or inline table a TOML parser found open, where it was opened, past
// strings, comments and table headers.
#include "design/unclosed_bracket.hpp"

#include <gtest/gtest.h>

namespace fibermold {
namespace {

TEST(UnclosedBracket, FindsTheListThatLacksItsBracketOnAnEarlierLine)
{
  // The parser stops at line 4's header; the list was opened on line 3, column 10.
  const std::string text = "[[fiber]]\nname = \"m1\"\npoints = [[0, 0, 0], [26, 1, 0], [129, 0, 0]\n"
                           "[[tracking_curve]]\n";
  const auto open = unclosed_bracket(text, {4, 1});
  ASSERT_TRUE(open.has_value());
  EXPECT_EQ(open->at.line, 3);
  EXPECT_EQ(open->at.column, 10);
  EXPECT_EQ(open->bracket, '[');
}

TEST(UnclosedBracket, SkipsBracketsInStringsAndCommentsAndCountsCharactersNotBytes)
{
  // "[" in a basic string (with an escaped quote), a literal string, a multi-line string and a
  // comment does not open anything; "×" is one column though two bytes.
  const std::string text = "name = \"a \\\" [b\"  # [ not this\nnote = 'c ['\nmore = \"\"\"\n[\n\"\"\"\n"
                           "load = [{ box = { min = [0, 0, 0], max = [1, 1, 1] }, force = [0, 0, -1] }\n"
                           "x = 1 # ×\n";
  const auto open = unclosed_bracket(text, {7, 1});
  ASSERT_TRUE(open.has_value());
  EXPECT_EQ(open->at.line, 6);
  EXPECT_EQ(open->at.column, 8);
  EXPECT_EQ(open->bracket, '[');
  // Within the list, after the box closes and before the load's table does (at "force"): that table.
  const auto inner = unclosed_bracket(text, {6, 55});
  ASSERT_TRUE(inner.has_value());
  EXPECT_EQ(inner->at.column, 9);
  EXPECT_EQ(inner->bracket, '{');
  // "×" counts one column: the "#" after it is at column 7.
  EXPECT_FALSE(unclosed_bracket("a = \"×\" [\n", {1, 9}).has_value());
  EXPECT_TRUE(unclosed_bracket("a = \"×\" [\n", {1, 10}).has_value());
}

TEST(UnclosedBracket, NothingWhereEveryBracketIsClosed)
{
  EXPECT_FALSE(unclosed_bracket("[mold]\nwall = 4\n[[fiber]]\npoints = [[0, 0, 0], [1, 0, 0]]\n", {5, 1}).has_value());
}

} // namespace
} // namespace fibermold
