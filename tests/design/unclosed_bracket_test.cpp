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

TEST(UnclosedBracket, BracketsInStringsAndCommentsNeitherOpenNorClose)
{
  // Each line's string or comment holds a "]" that would close the list opened on line 1 if it
  // counted, and a "[" that would be the innermost open one: a basic string with escaped quotes, a
  // literal string, a multi-line basic string with an escaped quote and four closing quotes, a
  // multi-line literal string, a comment.
  const std::string text = "load = [\n"
                           "  \"a \\\" ] [\", # ] [\n"
                           "  'b ] [',\n"
                           "  \"\"\"c \\\"\"\" ] [\n] [\"\"\"\",\n"
                           "  '''d ] [''',\n"
                           "  1\n"
                           "x = 2\n";
  const auto open = unclosed_bracket(text, {8, 1});
  ASSERT_TRUE(open.has_value());
  EXPECT_EQ(open->at.line, 1);
  EXPECT_EQ(open->at.column, 8);
  // Closed, the list leaves nothing open.
  EXPECT_FALSE(unclosed_bracket(text + "]\n", {9, 5}).has_value());
}

TEST(UnclosedBracket, NamesTheInnermostOpenTableAndCountsCharactersNotBytes)
{
  const std::string load = "load = [{ box = { min = [0, 0, 0], max = [1, 1, 1] }, force = [0, 0, -1] }\n";
  // At "force" (column 55), after the box closes: the load's inline table, opened at column 9.
  const auto inner = unclosed_bracket(load, {1, 55});
  ASSERT_TRUE(inner.has_value());
  EXPECT_EQ(inner->at.column, 9);
  EXPECT_EQ(inner->bracket, '{');
  // "×" is two bytes and one column, as the parser counts: the "[" after it is at column 9. A
  // byte-order mark before it counts nothing.
  for (const std::string prefix : {"", "\xEF\xBB\xBF"}) {
    EXPECT_FALSE(unclosed_bracket(prefix + "a = \"×\" [\n", {1, 9}).has_value());
    const auto open = unclosed_bracket(prefix + "a = \"×\" [\n", {1, 10});
    ASSERT_TRUE(open.has_value());
    EXPECT_EQ(open->at.column, 9);
  }
}

TEST(UnclosedBracket, NothingWhereEveryBracketIsClosed)
{
  EXPECT_FALSE(unclosed_bracket("[mold]\nwall = 4\n[[fiber]]\npoints = [[0, 0, 0], [1, 0, 0]]\n", {5, 1}).has_value());
}

} // namespace
} // namespace fibermold
