#include "optimize/bfgs.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <vector>

#include <LBFGSpp/Param.h> // before the line search, which uses it

#include <LBFGSpp/LineSearchBacktracking.h>
#include <fmt/format.h>

namespace fibermold {

namespace {

/// Line-search trials beyond which the next search starts shorter.
constexpr int kManyTrials = 4;

/// The objective as the line search calls it, remembering the best point it saw.
struct Tracked {
  explicit Tracked(const Objective& objective) : f(objective) {}
  const Objective& f;
  int evaluations = 0;
  double best = HUGE_VAL;
  Eigen::VectorXd best_x, best_g;

  double operator()(const Eigen::VectorXd& x, Eigen::VectorXd& g)
  {
    ++evaluations;
    const double v = f(x, g);
    if (v < best) {
      best = v;
      best_x = x;
      best_g = g;
    }
    return std::isfinite(v) ? v : HUGE_VAL;
  }
};

/// eq. 6.17: H ← (I − ρ s yᵀ) H (I − ρ y sᵀ) + ρ s sᵀ,  ρ = 1 / yᵀs.
void bfgs_update(Eigen::MatrixXd& H, const Eigen::VectorXd& s, const Eigen::VectorXd& y)
{
  const double rho = 1 / y.dot(s);
  const Eigen::VectorXd Hy = H * y;
  H += rho * rho * (y.dot(Hy) + 1 / rho) * s * s.transpose() - rho * (Hy * s.transpose() + s * Hy.transpose());
}

/// The curvature pair (s, y) taken into H when it is one (y·s > 0): on the first, H is scaled
/// first (Nocedal & Wright, eq. 6.20).
void take_pair(Eigen::MatrixXd& H, bool& scaled, const Eigen::VectorXd& s, const Eigen::VectorXd& y)
{
  if (!(y.dot(s) > 1e-12 * s.norm() * y.norm())) return;
  if (!scaled) {
    H *= y.dot(s) / y.dot(y); // eq. 6.20
    scaled = true;
  }
  bfgs_update(H, s, y);
}

/// `result` ending at the best point `tracked` saw.
MinimizerResult finished(MinimizerResult& result, const Tracked& tracked, Termination termination, std::string message)
{
  result.x = tracked.best_x;
  result.value = tracked.best;
  result.gradient_norm = tracked.best_g.norm();
  result.evaluations = tracked.evaluations;
  result.termination = termination;
  result.message = std::move(message);
  return result;
}

} // namespace

MinimizerResult minimize_bfgs(const Objective& f, Eigen::VectorXd x, const MinimizerOptions& options,
                              const IterationCallback& on_iteration, Progress& progress)
{
  const Eigen::Index n = x.size();
  Tracked tracked(f);
  MinimizerResult result;
  Eigen::VectorXd g(n);
  double fx;
  try {
    fx = tracked(x, g);
  } catch (const Interrupted&) {
    return interrupted_at_start(x);
  }
  if (!std::isfinite(fx)) throw std::invalid_argument("the objective is not finite at the starting point");

  LBFGSpp::LBFGSParam<double> param;
  param.linesearch = LBFGSpp::LBFGS_LINESEARCH_BACKTRACKING_WOLFE;
  param.max_linesearch = options.max_line_search;
  param.min_step = 1e-14;

  std::vector<double> values{fx}; // f after each iteration
  Eigen::MatrixXd H = Eigen::MatrixXd::Identity(n, n);
  bool scaled = false; // H is the identity, not yet scaled by eq. 6.20
  // The first trial of a BFGS line search, as a fraction of the full step: 1, or 4× the last
  // search's step where that one needed many trials (near a design where f jumps up, the walking
  // robot's last line searches each spent their 20 evaluations halving from 1).
  double first_trial = 1;
  auto finish = [&](Termination why, std::string message) {
    return finished(result, tracked, why, std::move(message));
  };
  try {
    for (;;) {
      const double gnorm = g.norm();
      if (gnorm <= options.gradient_tolerance)
        return finish(Termination::gradient_tolerance, fmt::format("|∇f| = {:.3g} below tolerance", gnorm));
      if (result.iterations == options.max_iterations)
        return finish(Termination::iteration_limit, fmt::format("{} iterations, the limit", options.max_iterations));
      if (progress.interrupted()) throw Interrupted();

      Eigen::VectorXd d = -H * g;
      if (!(g.dot(d) < 0)) { // lost positive definiteness to round-off: restart from steepest descent
        H.setIdentity();
        scaled = false;
        d = -g;
      }
      const double largest = d.cwiseAbs().maxCoeff();
      param.max_step = options.max_step / largest;
      double step = scaled ? std::min({1.0, param.max_step, first_trial}) : std::min(1.0, 1.0 / largest);
      const Eigen::VectorXd xp = x, gp = g;
      const double fp = fx;
      const bool along_bfgs = scaled;
      const int evaluations_before = tracked.evaluations;
      bool exhausted = false; // the line search used all its evaluations
      try {
        LBFGSpp::LineSearchBacktracking<double>::LineSearch(tracked, fx, x, g, step, d, xp, param);
      } catch (const Interrupted&) {
        throw;
      } catch (const std::exception& e) {
        // No Wolfe step (e.g. against a region where f is +∞); a sufficient decrease still counts.
        const bool decreased = tracked.best < fp;
        if (!decreased && !scaled)
          return finish(Termination::line_search, fmt::format("the line search found no decrease ({})", e.what()));
        x = tracked.best_x;
        g = tracked.best_g;
        fx = tracked.best;
        if (!decreased) { // retry along steepest descent
          H.setIdentity();
          scaled = false;
          continue;
        }
        step = (x - xp).norm() / d.norm();
        exhausted = true;
      }
      first_trial = along_bfgs && tracked.evaluations - evaluations_before > kManyTrials ? 4 * step : 1;
      ++result.iterations;
      take_pair(H, scaled, x - xp, g - gp);
      const double predicted = 0.5 * g.dot(H * g);
      if (on_iteration)
        on_iteration({result.iterations, fx, g.norm(), step * d.norm(), tracked.evaluations, predicted}, x);
      values.push_back(fx);
      // All its evaluations for less than a window's tolerance spread over its iterations: where f
      // jumps up within a short step (a body that snaps to another equilibrium just past this
      // design), every later line search does the same; the walking robot spent its last 45 s
      // there. Steepest descent gets one try, then the run stops.
      if (exhausted && fp - fx <= options.relative_tolerance / options.window * std::abs(fp)) {
        if (!along_bfgs)
          return finish(Termination::line_search,
                        fmt::format("the line search used all {} evaluations and f fell by only {:.3g} of its value",
                                    options.max_line_search, (fp - fx) / std::abs(fp)));
        H.setIdentity();
        scaled = false;
      }
      if (auto message = stall_message(values, fx, options)) return finish(Termination::stalled, std::move(*message));
    }
  } catch (const Interrupted&) {
    finish(Termination::interrupted, "interrupted");
    result.interrupted = true;
    return result;
  }
}

} // namespace fibermold
