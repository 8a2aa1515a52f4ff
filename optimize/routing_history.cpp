#include "optimize/routing_history.hpp"

#include <cmath>

#include <fmt/format.h>

namespace fibermold {

RoutingHistory::RoutingHistory(const std::vector<std::string>& targets)
{
  text_ = "iteration,stage,objective,distance,curvature,skin_barrier,bend_barrier,pressure_barrier,clearance_barrier";
  for (const std::string& t : targets) text_ += ",distance_" + t;
  text_ += ",gradient_norm,predicted_decrease,step,evaluations,seconds,start\n";
}

void RoutingHistory::add(int iteration, int stage, const MinimizerIteration& it, const RoutingTerms& terms,
                         double seconds, int start)
{
  text_ += fmt::format("{},{},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g}", iteration, stage + 1, terms.total,
                       terms.distance, terms.curvature, terms.skin, terms.bend, terms.pressure, terms.clearance);
  for (double v : terms.per_target) text_ += fmt::format(",{:.9g}", v);
  // Levenberg-Marquardt's model may be indefinite (no decrease predicted): the cell stays empty.
  const std::string predicted =
      std::isfinite(it.predicted_decrease) ? fmt::format("{:.6g}", it.predicted_decrease) : "";
  text_ += fmt::format(",{:.6g},{},{:.6g},{},{:.3f},{}\n", it.gradient_norm, predicted, it.step, it.evaluations,
                       seconds, start);
}

} // namespace fibermold
