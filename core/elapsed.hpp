#pragma once
// Elapsed time on the steady clock, for the timings of logs and reports.

#include <chrono>

namespace fibermold {

/// Seconds from `start` to now.
inline double since(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

} // namespace fibermold
