#include "optimize/perturbed_start.hpp"

#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>

#include "optimize/routing_problem.hpp"

namespace fibermold {

namespace {

/// A tangent's random change, as a share of its length (RMS per coordinate).
constexpr double kTangentSpread = 0.2;
/// Halvings of the perturbation tried before the start is given up for the first guess.
constexpr int kHalvings = 10;

/// A standard normal deviate from `bits` (Box-Muller on two 53-bit uniforms): the same on every
/// standard library, which std::normal_distribution is not.
double normal(std::mt19937_64& bits)
{
  const auto uniform = [&] { return (static_cast<double>(bits() >> 11) + 0.5) * 0x1p-53; };
  const double u = uniform(), v = uniform();
  return std::sqrt(-2 * std::log(u)) * std::cos(2 * std::numbers::pi * v);
}

Eigen::Vector3d normal3(std::mt19937_64& bits)
{
  const double x = normal(bits), y = normal(bits);
  return {x, y, normal(bits)};
}

} // namespace

Routing perturbed_start(RoutingProblem& problem, const Routing& start, int k, double spread)
{
  std::mt19937_64 bits(static_cast<std::uint64_t>(k));
  // The random directions, drawn once; their size is halved until the design is accepted.
  std::vector<std::vector<Eigen::Vector3d>> point_moves, tangent_moves;
  for (const Route& route : start.routes) {
    const auto n = route.points.size();
    point_moves.emplace_back(n, Eigen::Vector3d::Zero());
    tangent_moves.emplace_back(n, Eigen::Vector3d::Zero());
    for (std::size_t i = 0; i < n; ++i) {
      if (i > 0 && i + 1 < n) point_moves.back()[i] = normal3(bits);
      tangent_moves.back()[i] = normal3(bits) * kTangentSpread * route.tangents[i].norm();
    }
  }
  const int T = problem.num_targets(), F = problem.num_fibers();
  // The routes free (their terms are scored only then), the pressures not (they are start's).
  problem.set_free(std::vector<bool>(F, true),
                   Eigen::Matrix<bool, Eigen::Dynamic, Eigen::Dynamic>::Constant(T, F, false),
                   std::vector<bool>(T, true));
  double scale = 1;
  for (int h = 0; h <= kHalvings; ++h, scale /= 2) {
    Routing r = start;
    for (std::size_t f = 0; f < r.routes.size(); ++f)
      for (std::size_t i = 0; i < r.routes[f].points.size(); ++i) {
        r.routes[f].points[i] += scale * spread * point_moves[f][i];
        r.routes[f].tangents[i] += scale * tangent_moves[f][i];
      }
    problem.set_base(r);
    const bool accepted = std::isfinite(problem.regularizer_value(problem.variables(r)));
    problem.set_base(start);
    if (accepted) return r;
  }
  return start;
}

} // namespace fibermold
