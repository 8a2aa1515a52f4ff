// Shell words: what sweep's job scripts and README.txt's commands quote.
#include "core/shell_words.hpp"

#include <gtest/gtest.h>

namespace fibermold {
namespace {

TEST(ShellWords, AQuotedWordKeepsItsQuotesAndAPlainOneIsLeftAsItIs)
{
  EXPECT_EQ(shell_quoted("out/my robot"), "'out/my robot'");
  EXPECT_EQ(shell_quoted("it's"), "'it'\\''s'");
  EXPECT_EQ(shell_word("out/notched-finger_2.toml"), "out/notched-finger_2.toml");
  EXPECT_EQ(shell_word("my robot"), "'my robot'");
  EXPECT_EQ(shell_word("$HOME"), "'$HOME'");
  EXPECT_EQ(shell_word(""), "''");
}

} // namespace
} // namespace fibermold
