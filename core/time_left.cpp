#include "core/time_left.hpp"

#include <cmath>

#include <fmt/format.h>

namespace fibermold {

std::optional<double> TimeLeft::seconds(double fraction, Clock::time_point now)
{
  if (!(fraction >= 0) || fraction > 1) return std::nullopt;
  if (!start_) {
    start_ = now;
    first_ = fraction;
    return std::nullopt;
  }
  const double elapsed = std::chrono::duration<double>(now - *start_).count(), done = fraction - first_;
  if (elapsed < kMinSeconds || done < kMinShare) return std::nullopt;
  return elapsed * (1 - fraction) / done;
}

std::string TimeLeft::format(double seconds)
{
  const long s = std::lround(std::max(0.0, seconds));
  if (s < 60) return fmt::format("{} s", s);
  if (s < 3600) return s % 60 ? fmt::format("{} min {} s", s / 60, s % 60) : fmt::format("{} min", s / 60);
  return fmt::format("{} h {} min", s / 3600, (s % 3600) / 60);
}

} // namespace fibermold
