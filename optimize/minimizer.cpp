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

std::optional<std::string> model_stall_message(const std::vector<double>& values, const std::vector<double>& predicted,
                                               const MinimizerOptions& options)
{
  const auto window = static_cast<std::size_t>(options.window);
  if (predicted.size() < window || values.size() != predicted.size() + 1) return std::nullopt;
  for (std::size_t i = predicted.size() - window; i < predicted.size(); ++i)
    if (!(predicted[i] > options.relative_tolerance * std::abs(values[i + 1]))) return std::nullopt;
  return stall_message(values, values.back(), options);
}

} // namespace fibermold
