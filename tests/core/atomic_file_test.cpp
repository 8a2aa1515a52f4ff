#include "core/atomic_file.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "test_support.hpp"

namespace fibermold {
namespace {

namespace fs = std::filesystem;

TEST(AtomicFile, WritesCreatesFoldersAndLeavesNoTemporary)
{
  test::TempDir dir;
  const fs::path path = dir / "a" / "b" / "out.json";
  write_file_atomic(path, "first");
  write_file_atomic(path, "second, longer");
  EXPECT_EQ(read_file(path), "second, longer");
  int files = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(path.parent_path())) ++files;
  EXPECT_EQ(files, 1);
}

TEST(AtomicFile, UnwritableFolderNamesThePath)
{
  test::TempDir dir;
  test::write_text(dir / "file", "x");
  try {
    write_file_atomic(dir / "file" / "sub" / "out", "y"); // a file where a folder should be
    FAIL() << "expected an exception";
  } catch (const std::exception& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr((dir / "file").string()));
  }
  EXPECT_EQ(read_file(dir / "file"), "x");
}

TEST(AtomicFile, ReadingAMissingFileNamesIt) { EXPECT_THROW(read_file("/nonexistent/fibermold"), std::runtime_error); }

} // namespace
} // namespace fibermold
