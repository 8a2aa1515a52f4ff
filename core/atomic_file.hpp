#pragma once
// Outputs are written under a temporary name and renamed into place, so that a reader never sees
// a half-written file that looks complete.

#include <filesystem>
#include <string_view>

namespace fibermold {

/// Writes `content` to `path` through `path.tmp-<pid>` and an atomic rename.
/// Creates missing parent folders. Throws std::runtime_error naming the path on failure.
void write_file_atomic(const std::filesystem::path& path, std::string_view content);

/// Reads a whole file; throws std::runtime_error naming the path when it cannot.
std::string read_file(const std::filesystem::path& path);

} // namespace fibermold
