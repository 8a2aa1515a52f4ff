#pragma once
// Quasi-Newton minimization with the standard (dense) BFGS update of the inverse Hessian
// (Nocedal & Wright, Numerical Optimization, eq. 6.17, with the initial scaling of eq. 6.20) and
// LBFGSpp's backtracking line search on the Wolfe conditions. A design has tens to hundreds of
// variables, so the dense n×n matrix is cheap next to one simulation.
//
// The objective may return +∞ (a failed simulation, a barrier crossed): the line search then
// shrinks the step. The best point evaluated is always what is returned.

#include <array>
#include <functional>
#include <string>

#include <Eigen/Core>

#include "core/names.hpp"
#include "core/progress.hpp"

namespace fibermold {

struct BfgsOptions {
  int max_iterations = 400;
  double gradient_tolerance = 1e-6;   ///< stop when |∇f| ≤ this
  double relative_tolerance = 1e-3;   ///< stop when f fell by ≤ this × |f| over the last `window` iterations
  int window = 10;
  double max_step = 5;                ///< largest change of one variable in a line search's first trial; a
                                      ///< Wolfe extension may try up to 2.1× that once
  int max_line_search = 20;           ///< evaluations per line search
};

struct BfgsIteration {
  int iteration = 0;
  double value = 0, gradient_norm = 0, step = 0;
  int evaluations = 0;  ///< objective evaluations so far
};

/// Why a minimization stopped. Only the first is convergence (a point where the gradient vanishes);
/// the others end at the best point seen, which may be short of one.
enum class Termination {
  gradient_tolerance,  ///< |∇f| ≤ gradient_tolerance
  stalled,             ///< f fell by ≤ relative_tolerance × |f| over `window` iterations
  line_search,         ///< the line search found no step that lowers f usefully (a kink or a jump ahead)
  iteration_limit,     ///< max_iterations taken
  interrupted,         ///< Ctrl-C or SIGTERM
};
inline constexpr std::array<Named<Termination>, 5> kTerminationNames{{{Termination::gradient_tolerance, "gradient tolerance met"},
                                                                      {Termination::stalled, "stalled"},
                                                                      {Termination::line_search, "line search failed"},
                                                                      {Termination::iteration_limit, "iteration limit"},
                                                                      {Termination::interrupted, "interrupted"}}};
inline std::string_view choice_name(Termination t) { return name_in(kTerminationNames, t); }

struct BfgsResult {
  Eigen::VectorXd x;
  double value = 0, gradient_norm = 0;
  int iterations = 0, evaluations = 0;
  Termination termination = Termination::iteration_limit;
  bool interrupted = false;  ///< Ctrl-C: x is the best point found before it
  std::string message;       ///< why it stopped, with the figures

  bool converged() const { return termination == Termination::gradient_tolerance; }
};

/// f(x, g) returns the value and writes the gradient into g.
using Objective = std::function<double(const Eigen::VectorXd& x, Eigen::VectorXd& gradient)>;
/// Called after every accepted step.
using IterationCallback = std::function<void(const BfgsIteration&, const Eigen::VectorXd& x)>;

/// Throws std::invalid_argument when f is not finite at x0.
BfgsResult minimize_bfgs(const Objective& f, Eigen::VectorXd x0, const BfgsOptions& options,
                         const IterationCallback& on_iteration, Progress& progress);

} // namespace fibermold
