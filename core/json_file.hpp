#pragma once
// JSON outputs (reports, manifests, stamps) written whole and only with finite numbers: a NaN or
// an infinity would be written as null, and a reader would take null for "none" or fail on it.
// A non-finite number is a failure of the stage that computed it, named by its place in the file.

#include <cmath>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "core/atomic_file.hpp"

namespace fibermold {

/// The JSON pointer (e.g. "/shots/shot1/silicone_mass_g") of the first non-finite number or null
/// in `j`; empty when there is none.
template <typename Json> std::optional<std::string> first_non_finite(const Json& j, const std::string& at = "")
{
  if (j.is_null()) return at.empty() ? "/" : at;
  if (j.is_number_float() && !std::isfinite(j.template get<double>())) return at.empty() ? "/" : at;
  if (j.is_object())
    for (auto it = j.begin(); it != j.end(); ++it)
      if (auto found = first_non_finite(it.value(), at + "/" + it.key())) return found;
  if (j.is_array())
    for (std::size_t k = 0; k < j.size(); ++k)
      if (auto found = first_non_finite(j[k], at + "/" + std::to_string(k))) return found;
  return std::nullopt;
}

/// `j` as text (`indent` spaces, -1: on one line; a final newline); throws std::runtime_error naming
/// `path` and the place of a non-finite number or null.
template <typename Json> std::string checked_json(const Json& j, const std::filesystem::path& path, int indent = 2)
{
  if (auto at = first_non_finite(j))
    throw std::runtime_error(path.filename().string() + ": " + *at +
                             " is not a finite number (NaN, infinity or null): a computation "
                             "behind it went wrong; nothing was written");
  return j.dump(indent) + "\n";
}

/// Writes `j` to `path` atomically, after checked_json.
template <typename Json> void write_json_atomic(const std::filesystem::path& path, const Json& j)
{
  write_file_atomic(path, checked_json(j, path));
}

/// The JSON in `path`, or none when it does not exist or does not parse (an optional output of another
/// stage, or one an older version wrote otherwise).
template <typename Json> std::optional<Json> read_json_if_any(const std::filesystem::path& path)
{
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return std::nullopt;
  Json j = Json::parse(read_file(path), nullptr, false);
  if (j.is_discarded()) return std::nullopt;
  return j;
}

} // namespace fibermold
