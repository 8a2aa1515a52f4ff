#pragma once
// Reading and validating the design file (TOML). Every problem is reported up front, all at once,
// as `file:line:column: [section].key: what is wrong`; the CLI exits with code 2.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "design/design.hpp"

namespace fibermold {

/// Parses and validates `path`. Throws InputError listing every problem found.
Design load_design(const std::filesystem::path& path);

/// Parses and validates TOML text as if it were the file `path` (which need not exist; relative
/// paths in the text resolve against its folder).
Design parse_design(std::string_view toml_text, const std::filesystem::path& path);

/// The design file's sections, and whether one is an array of tables ([[fiber]]).
const std::vector<std::string>& design_sections();
bool is_array_section(std::string_view section);

/// The design's name when [design] name is not given: the file's stem, or its folder's name for
/// a file named design.toml.
std::string default_design_name(const std::filesystem::path& file);

/// True when design-value `key` ("[fiber.m1].points") lies under `prefix` ("fiber", "sim.basis").
bool design_key_matches(std::string_view key, std::string_view prefix);

} // namespace fibermold
