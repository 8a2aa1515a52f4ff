#include "design/did_you_mean.hpp"

#include <gtest/gtest.h>

namespace fibermold {
namespace {

TEST(EditDistance, CountsInsertionsDeletionsSubstitutions)
{
  EXPECT_EQ(edit_distance("", ""), 0u);
  EXPECT_EQ(edit_distance("wall", "wall"), 0u);
  EXPECT_EQ(edit_distance("wal", "wall"), 1u);
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);
  EXPECT_EQ(edit_distance("", "abc"), 3u);
  EXPECT_EQ(edit_distance("voxle", "voxel"), 1u); // a transposition counts once
}

TEST(ClosestMatch, SuggestsOnlyPlausibleMisspellings)
{
  const std::vector<std::string> keys{"wall", "voxel", "pull", "parting", "keys"};
  EXPECT_EQ(closest_match("wal", keys), "wall");
  EXPECT_EQ(closest_match("partng", keys), "parting");
  EXPECT_EQ(closest_match("voxels", keys), "voxel");
  EXPECT_FALSE(closest_match("temperature", keys).has_value());
  EXPECT_FALSE(closest_match("x", {}).has_value());
}

TEST(ClosestMatch, AOneLetterPrefixIsNoHint)
{
  // A new user's units = "millimetres" was asked whether they meant "m" (metres).
  const std::vector<std::string> units{"mm", "cm", "m", "in"};
  EXPECT_FALSE(closest_match("millimetres", units).has_value());
  EXPECT_EQ(closest_match("inches", units), "in");
  EXPECT_EQ(closest_match("mmm", units), "mm");
}

} // namespace
} // namespace fibermold
