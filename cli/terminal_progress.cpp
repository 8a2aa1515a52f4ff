#include "cli/terminal_progress.hpp"

#include <cmath>

#include <fmt/format.h>

namespace fibermold {

TerminalProgress::TerminalProgress(std::string stage, std::FILE* out, bool tty)
    : stage_(std::move(stage)), out_(out), tty_(tty)
{
}

TerminalProgress::~TerminalProgress()
{
  if (line_open_) std::fputs("\r\033[K", out_);
  std::fflush(out_);
}

void TerminalProgress::update(double fraction, std::string_view what)
{
  std::string percent = fraction >= 0 ? fmt::format(" {:3.0f}%", 100 * std::min(fraction, 1.0)) : "";
  if (const auto left = time_left_.seconds(fraction)) percent += fmt::format(" (~{} left)", TimeLeft::format(*left));
  if (tty_) {
    const auto now = std::chrono::steady_clock::now();
    if (what == last_what_ && now - last_draw_ < std::chrono::milliseconds(100)) return;
    last_draw_ = now;
    last_what_ = what;
    fmt::print(out_, "\r\033[K[{}]{} {}", stage_, percent, what);
    std::fflush(out_);
    line_open_ = true;
    return;
  }
  const int tenth = fraction >= 0 ? static_cast<int>(std::floor(10 * fraction)) : last_tenth_;
  if (what == last_what_ && tenth == last_tenth_) return;
  if (what == "done") return;
  last_what_ = what;
  last_tenth_ = tenth;
  fmt::print(out_, "[{}]{} {}\n", stage_, percent, what);
  std::fflush(out_);
}

} // namespace fibermold
