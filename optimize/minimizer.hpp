#pragma once
// What the routing problem's minimizers (bfgs.hpp, levenberg_marquardt.hpp) share: their options,
// the step they report, why they stopped and what they return.

#include <array>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/names.hpp"
#include "core/progress.hpp"

namespace fibermold {

/// Which minimizer the routing problem runs (docs/optimize.md, "Choosing the optimizer").
/// `hybrid` (hybrid_minimizer.hpp): BFGS until it slows down, then Levenberg-Marquardt from there.
enum class Method { bfgs, levenberg_marquardt, hybrid };
inline constexpr std::array<Named<Method>, 3> kMethodNames{
    {{Method::bfgs, "bfgs"}, {Method::levenberg_marquardt, "levenberg-marquardt"}, {Method::hybrid, "hybrid"}}};
inline std::string_view choice_name(Method m) { return name_in(kMethodNames, m); }

struct MinimizerOptions {
  Method method = Method::hybrid;
  int max_iterations = 400;
  double gradient_tolerance = 1e-6; ///< stop when |∇f| ≤ this
  double relative_tolerance = 1e-3; ///< stop when f fell by ≤ this × |f| over the last `window` iterations
  int window = 10;
  double max_step = 5;      ///< largest change of one variable in a line search's first trial (a
                            ///< Wolfe extension may try up to 2.1× that once) or an LM step
  int max_line_search = 20; ///< evaluations per line search (BFGS); trial steps rejected in a row (LM)
  /// Levenberg-Marquardt converges where its model's whole decrease ½ gᵀM⁻¹g is at most this share of f.
  double decrease_tolerance = 1e-4;
  /// hybrid: BFGS hands over to Levenberg-Marquardt where f fell by ≤ this × |f| over `window` iterations.
  double switch_tolerance = 1e-2;
};

struct MinimizerIteration {
  int iteration = 0;
  double value = 0, gradient_norm = 0, step = 0;
  int evaluations = 0; ///< objective evaluations so far
  /// What the minimizer's model predicts is left to gain from here: ½ gᵀHg with BFGS's inverse
  /// Hessian H, ½ gᵀM⁻¹g with Levenberg-Marquardt's model M (the Newton decrement, squared and halved).
  double predicted_decrease = 0;
};

/// Why a minimization stopped. Only the first two are convergence (a first-order point: the gradient,
/// or the decrease a model Hessian predicts from it, vanishes);
/// the others end at the best point seen, which may be short of one.
enum class Termination {
  gradient_tolerance, ///< |∇f| ≤ gradient_tolerance
  decrease_tolerance, ///< the model's whole decrease ½ gᵀB⁻¹g ≤ decrease_tolerance × f (levenberg_marquardt.hpp)
  stalled,            ///< f fell by ≤ relative_tolerance × |f| over `window` iterations
  line_search,        ///< the line search found no step that lowers f usefully (a kink or a jump ahead)
  iteration_limit,    ///< max_iterations taken
  interrupted,        ///< Ctrl-C or SIGTERM
};
inline constexpr std::array<Named<Termination>, 6> kTerminationNames{
    {{Termination::gradient_tolerance, "gradient tolerance met"},
     {Termination::decrease_tolerance, "converged"},
     {Termination::stalled, "stalled"},
     {Termination::line_search, "line search failed"},
     {Termination::iteration_limit, "iteration limit"},
     {Termination::interrupted, "interrupted"}}};
inline std::string_view choice_name(Termination t) { return name_in(kTerminationNames, t); }

struct MinimizerResult {
  Eigen::VectorXd x;
  double value = 0, gradient_norm = 0;
  int iterations = 0, evaluations = 0;
  Termination termination = Termination::iteration_limit;
  bool interrupted = false; ///< Ctrl-C: x is the best point found before it
  std::string message;      ///< why it stopped, with the figures

  bool converged() const
  {
    return termination == Termination::gradient_tolerance || termination == Termination::decrease_tolerance;
  }
};

/// f(x, g) returns the value and writes the gradient into g.
using Objective = std::function<double(const Eigen::VectorXd& x, Eigen::VectorXd& gradient)>;
/// Called after every accepted step.
using IterationCallback = std::function<void(const MinimizerIteration&, const Eigen::VectorXd& x)>;

/// The result of a run stopped (Ctrl-C, SIGTERM) during its first evaluation: x is the start, f unknown.
MinimizerResult interrupted_at_start(Eigen::VectorXd x);

/// The relative-tolerance rule, why a run stalled: f fell by at most relative_tolerance of its
/// value over the last `window` iterations (`values`: f after each iteration, the last one fx).
std::optional<std::string> stall_message(const std::vector<double>& values, double fx, const MinimizerOptions& options);

/// Levenberg-Marquardt's stall: a model that predicted more than relative_tolerance of f left after
/// every iteration of the window and did not deliver it (a wall it does not know): the rule above,
/// and each of the last `window` entries of `predicted` (the model's whole decrease after each
/// iteration; values[i + 1] is f then) above relative_tolerance of f. Where it predicted less at one
/// of them, the run is that close to converging and goes on: on the last prediction alone the
/// tentacle stalled 3 iterations short of converging, and the twisting bar 53 (one prediction of
/// 1.3e-3 of f after nine from 1.5e-4 to 7.6e-4).
std::optional<std::string> model_stall_message(const std::vector<double>& values, const std::vector<double>& predicted,
                                               const MinimizerOptions& options);

} // namespace fibermold
