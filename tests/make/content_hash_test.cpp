#include "make/content_hash.hpp"

#include <gtest/gtest.h>

#include "test_support.hpp"

namespace fibermold {
namespace {

TEST(ContentHash, KnownValueAndSensitivity)
{
  // XXH3-128 of the empty input (xxHash's reference value).
  EXPECT_EQ(hash_bytes(""), "99aa06d3014798d86001c324468d497f");
  EXPECT_EQ(hash_bytes("wall = 4").size(), 32u);
  EXPECT_NE(hash_bytes("wall = 4"), hash_bytes("wall = 5"));
}

TEST(ContentHash, FileHashEqualsBytesHashAcrossBufferBoundaries)
{
  test::TempDir dir;
  std::string big(3 * (1 << 20) + 17, 'x');
  big[1 << 20] = 'y';
  test::write_text(dir / "big", big);
  EXPECT_EQ(hash_file(dir / "big"), hash_bytes(big));
  EXPECT_THROW(hash_file(dir / "missing"), std::runtime_error);
}

} // namespace
} // namespace fibermold
