#pragma once
// A binary artifact holding one array of doubles (a deformed state, a routing), versioned and
// checksummed, written atomically: later stages read it back exactly.

#include <filesystem>
#include <string>

#include <Eigen/Core>

namespace fibermold {

/// Writes `values` under `kind` (a short name checked on reading).
void save_array(const std::filesystem::path& path, const std::string& kind, const Eigen::VectorXd& values);
/// Throws std::runtime_error naming the file when it is missing, of another kind, truncated or corrupt.
Eigen::VectorXd load_array(const std::filesystem::path& path, const std::string& kind);

} // namespace fibermold
