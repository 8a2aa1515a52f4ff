#include "cli/terminal_progress.hpp"

#include <cmath>

#include <fmt/format.h>

namespace fibermold {

namespace {

/// `text` with each number (a run of digits, signs, points and exponents holding a digit) made '#'.
std::string digits_blanked(std::string_view text)
{
  const auto numeric = [](char c) { return (c >= '0' && c <= '9') || c == '.' || c == '+' || c == '-' || c == 'e'; };
  std::string out;
  for (std::size_t i = 0; i < text.size();) {
    std::size_t j = i;
    while (j < text.size() && numeric(text[j])) ++j;
    if (j == i) {
      out += text[i++];
      continue;
    }
    const std::string_view run = text.substr(i, j - i);
    out += run.find_first_of("0123456789") == std::string_view::npos ? std::string(run) : std::string("#");
    i = j;
  }
  return out;
}

} // namespace

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
  // A line of no stated fraction (a solver's iteration) that differs from the last such line only in
  // its numbers before any ':' waits kHeartbeat since the last line: a log gets a heartbeat, not
  // every Newton iteration of every target (a new user's jaw printed hundreds). Lines with a
  // fraction (a stage's steps: "writing target pose1", "pose2") all print.
  const auto now = std::chrono::steady_clock::now();
  const std::string stem = digits_blanked(what.substr(0, what.find(':')));
  if (fraction < 0 && stem == last_stem_ && now - last_draw_ < kHeartbeat) return;
  last_stem_ = fraction < 0 ? stem : std::string();
  last_draw_ = now;
  last_what_ = what;
  last_tenth_ = tenth;
  fmt::print(out_, "[{}]{} {}\n", stage_, percent, what);
  std::fflush(out_);
}

} // namespace fibermold
