#include "optimize/minimizer.hpp"

#include <cmath>

#include <fmt/format.h>

namespace fibermold {

MinimizerResult interrupted_at_start(Eigen::VectorXd x)
{
  MinimizerResult result;
  result.x = std::move(x); // nothing better seen yet
  result.value = HUGE_VAL;
  result.interrupted = true;
  result.termination = Termination::interrupted;
  result.message = "interrupted";
  return result;
}

std::optional<std::string> stall_message(const std::vector<double>& values, double fx, const MinimizerOptions& options)
{
  if (static_cast<int>(values.size()) <= options.window) return std::nullopt;
  const double before = values[values.size() - 1 - options.window];
  if (before - fx > options.relative_tolerance * std::abs(fx)) return std::nullopt;
  return fmt::format("f fell by {:.3g} of its value over the last {} iterations", (before - fx) / std::abs(fx),
                     options.window);
}

} // namespace fibermold
