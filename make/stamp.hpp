#pragma once
// The stamp of a stage: what its last successful run read and wrote, by content hash.
// Written last, after the outputs are in place; removed before a run starts.

#include <filesystem>
#include <map>
#include <optional>
#include <string>

namespace fibermold {

struct Stamp {
  std::string program; ///< "fibermold 0.1.0"
  int stage_version = 0;
  std::map<std::string, std::string> design;   ///< design key → effective value
  std::map<std::string, std::string> files;    ///< absolute path → content hash
  std::map<std::string, std::string> upstream; ///< "<stage>/<file>" → content hash
  std::map<std::string, std::string> outputs;  ///< file relative to the stage folder → content hash
  double seconds = 0;                          ///< wall time of the run
  std::string finished;                        ///< UTC, ISO 8601

  std::string to_json() const;
  /// Null when the file is absent or unreadable (an unreadable stamp is as good as none).
  static std::optional<Stamp> load(const std::filesystem::path& path);
};

} // namespace fibermold
