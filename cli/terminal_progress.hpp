#pragma once
// Progress of a stage on the terminal: one redrawn line on a TTY, plain lines otherwise (when
// another tenth of the work is done, or the message changes: for a line of no stated fraction,
// every kHeartbeat at most where only its numbers change), with the time left once it can be
// estimated (core/time_left.hpp).

#include <chrono>
#include <cstdio>
#include <string>

#include "core/progress.hpp"
#include "core/time_left.hpp"

namespace fibermold {

class TerminalProgress final : public Progress {
public:
  /// Off a TTY, the least time between two lines that differ only in their numbers.
  static constexpr std::chrono::seconds kHeartbeat{5};

  TerminalProgress(std::string stage, std::FILE* out, bool tty);
  ~TerminalProgress() override;
  void update(double fraction, std::string_view what) override;

private:
  std::string stage_;
  std::FILE* out_;
  bool tty_;
  bool line_open_ = false;
  std::string last_what_;
  std::string last_stem_; ///< the last line's, when it stated no fraction: its text before ':', numbers blanked
  int last_tenth_ = -1;
  std::chrono::steady_clock::time_point last_draw_{};
  TimeLeft time_left_;
};

} // namespace fibermold
