#pragma once
// One `fibermold make` (or `clean`) per build folder at a time: an advisory lock on
// <build>/.lock, released by the kernel when the holder exits, however it exits.

#include <filesystem>
#include <stdexcept>

namespace fibermold {

class BuildLocked : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

class BuildLock {
public:
  /// Takes the lock or throws BuildLocked naming the folder and the holder's pid.
  explicit BuildLock(const std::filesystem::path& build_dir);
  ~BuildLock();
  BuildLock(const BuildLock&) = delete;
  BuildLock& operator=(const BuildLock&) = delete;

private:
  int fd_ = -1;
};

} // namespace fibermold
