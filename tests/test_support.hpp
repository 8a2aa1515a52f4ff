#pragma once
// Helpers shared by the test suites: temporary folders, files, running the fibermold binary.

#include <filesystem>
#include <string>

namespace fibermold::test {

/// A fresh folder under the system's temp dir, removed with its content at destruction.
class TempDir {
public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

private:
  std::filesystem::path path_;
};

void write_text(const std::filesystem::path& path, const std::string& text);
std::string read_text(const std::filesystem::path& path);

/// Result of running a command: exit code and what it printed.
struct CommandResult {
  int exit_code = -1;
  std::string out;  ///< stdout
  std::string err;  ///< stderr
};

/// Runs the fibermold binary under test with `arguments` (a shell-quoted string), in `cwd`, under
/// `launcher` when given (e.g. "timeout -s INT 5").
CommandResult run_fibermold(const std::string& arguments, const std::filesystem::path& cwd = {},
                            const std::string& launcher = {});

} // namespace fibermold::test
