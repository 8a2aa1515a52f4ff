#include "make/build_lock.hpp"

#include <cerrno>
#include <cstring>
#include <string>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <fmt/format.h>

#include "core/input_error.hpp"

namespace fibermold {

BuildLock::BuildLock(const std::filesystem::path& build_dir)
{
  // A build folder that cannot be made or written is bad input (exit 2), not a failed stage.
  const auto unusable = [&](const std::string& why) {
    return InputError(Diagnostic{build_dir, 0, 0, "", fmt::format("cannot be used as the build folder: {}", why)});
  };
  std::error_code ec;
  if (std::filesystem::exists(build_dir, ec) && !std::filesystem::is_directory(build_dir, ec))
    throw unusable("it is a file, not a folder; name another with --build-dir");
  std::filesystem::create_directories(build_dir, ec);
  if (ec) throw unusable(ec.message());
  const std::filesystem::path path = build_dir / ".lock";
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw unusable(fmt::format("cannot open {}: {}", path.filename().string(), std::strerror(errno)));
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    char buffer[32] = {};
    const ssize_t n = ::pread(fd_, buffer, sizeof buffer - 1, 0);
    ::close(fd_);
    fd_ = -1;
    const std::string holder = n > 0 ? std::string(buffer, static_cast<std::size_t>(n)) : "unknown";
    throw BuildLocked(
        fmt::format("another fibermold (pid {}) is working in {}; wait for it to finish", holder, build_dir.string()));
  }
  const std::string pid = std::to_string(::getpid());
  if (::ftruncate(fd_, 0) != 0 || ::pwrite(fd_, pid.data(), pid.size(), 0) < 0) {
    // The pid is only for the message; the lock itself is held.
  }
}

BuildLock::~BuildLock()
{
  if (fd_ >= 0) ::close(fd_);
}

} // namespace fibermold
