#pragma once
// Content hashes for stamps (after ninja's build log): a stage reruns when the hash of what it
// depends on changes, never because of a modification time. XXH3, 128 bits, as 32 hex digits.

#include <filesystem>
#include <string>
#include <string_view>

namespace fibermold {

std::string hash_bytes(std::string_view bytes);

/// Hash of a file's content; throws std::runtime_error naming the file when it cannot be read.
std::string hash_file(const std::filesystem::path& path);

} // namespace fibermold
