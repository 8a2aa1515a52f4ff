#pragma once
// The time left on long work, from its progress fraction: elapsed × (1 − f) / (f − f₀) since the
// first fraction reported (f₀), once kMinSeconds and kMinShare of the work have passed; before
// that, no estimate. The optimizer's fraction is over its iteration budget, so its estimate is the
// time to the iteration limit: at most what is left.

#include <chrono>
#include <optional>
#include <string>

namespace fibermold {

class TimeLeft {
public:
  static constexpr double kMinSeconds = 2, kMinShare = 0.02;
  using Clock = std::chrono::steady_clock;

  /// Seconds left at `fraction` ∈ [0, 1] reported at `now`, or none yet.
  std::optional<double> seconds(double fraction, Clock::time_point now = Clock::now());
  /// "40 s", "3 min 10 s", "2 h 5 min".
  static std::string format(double seconds);

private:
  std::optional<Clock::time_point> start_;
  double first_ = 0;
};

} // namespace fibermold
