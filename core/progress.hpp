#pragma once
// Progress and interruption for long operations (Newton, optimization, voxelization, booleans),
// after OpenVDB's util::NullInterrupter: the same object drives a progress line and Ctrl-C.

#include <stdexcept>
#include <string_view>

namespace fibermold {

/// Thrown by a long operation that noticed an interrupt request; the caller cleans up.
class Interrupted : public std::runtime_error {
public:
  Interrupted() : std::runtime_error("interrupted") {}
};

class Progress {
public:
  virtual ~Progress() = default;
  /// Reports `fraction` ∈ [0, 1] of the work done (negative: unknown) and what is being done.
  virtual void update(double fraction, std::string_view what) = 0;
  /// True once the user asked to stop (Ctrl-C).
  virtual bool interrupted() const;
  /// update(), then throws Interrupted when the user asked to stop.
  void checkpoint(double fraction, std::string_view what);
};

/// Reports nothing; still honours interrupt requests.
class NullProgress final : public Progress {
public:
  void update(double, std::string_view) override {}
};

/// Process-wide interrupt flag, set from the SIGINT/SIGTERM handler (async-signal-safe).
void request_interrupt() noexcept;
bool interrupt_requested() noexcept;
void clear_interrupt() noexcept;

} // namespace fibermold
