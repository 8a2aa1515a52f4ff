#include "optimize/levenberg_marquardt.hpp"

#include "optimize/ray_model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <fmt/format.h>

namespace fibermold {

namespace {

/// μ at the start, relative to the model's scaled diagonal (Marquardt's choice of a small value).
constexpr double kInitialDamping = 1e-3;
/// The least μ a rejected step raises: after a run of good steps μ can fall to 1e-16, and ×ν with ν
/// doubling from there took eleven rejections to reach a useful damping (the twisting bar).
constexpr double kLeastRaisedDamping = 1e-6;
/// Steps shorter than this in every variable (units: mm or 10 kPa) do not update the secant term:
/// over so short a step the gradient's change is ruled by whatever is not smooth at that scale
/// (on the twisting bar, the bend barrier's jump, since fixed: a 2e-6 step's update raised the
/// model's predicted decrease 16-fold, and the run stalled 1.4× short of converging).
constexpr double kLeastSecantStep = 1e-3;

/// Marquardt's scaling D = diag(B), with entries under 1e-8 of its largest raised to that (a
/// variable the model does not see yet still gets a bounded step).
Eigen::VectorXd scaling(const Eigen::MatrixXd& B)
{
  const Eigen::VectorXd d = B.diagonal().cwiseAbs();
  const double largest = d.maxCoeff();
  return d.cwiseMax(largest > 0 ? 1e-8 * largest : 1.0);
}

/// The model's whole decrease ½ gᵀB⁻¹g where B is positive definite; +∞ where it is not (the
/// model has no minimum).
double model_decrease(const Eigen::MatrixXd& B, const Eigen::VectorXd& g)
{
  const Eigen::LLT<Eigen::MatrixXd> llt(B);
  if (llt.info() != Eigen::Success) return HUGE_VAL;
  const double d = 0.5 * g.dot(llt.solve(g));
  return d >= 0 ? d : HUGE_VAL;
}

/// δ = −(B + μD)⁻¹g. Where B + μD is not positive definite (a model singular along some direction,
/// μ tiny), μ is raised to twice the least that makes it so, −λ_min(D^-½ B D^-½): raising it
/// ×ν with ν doubling overshot that by up to 10³ on the notched finger, and the steps then crawled
/// for as many iterations as μ took to come back down.
Eigen::VectorXd damped_step(const Eigen::MatrixXd& B, const Eigen::VectorXd& D, const Eigen::VectorXd& g, double& mu)
{
  const auto factor = [&] {
    Eigen::MatrixXd A = B;
    A.diagonal() += mu * D;
    return Eigen::LLT<Eigen::MatrixXd>(A);
  };
  Eigen::LLT<Eigen::MatrixXd> llt = factor();
  if (llt.info() != Eigen::Success) {
    const Eigen::VectorXd s = D.cwiseSqrt().cwiseInverse();
    const Eigen::MatrixXd scaled = s.asDiagonal() * B * s.asDiagonal();
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(scaled, Eigen::EigenvaluesOnly);
    mu = std::max(mu, -2 * eigen.eigenvalues()[0]);
    for (llt = factor(); llt.info() != Eigen::Success; llt = factor()) mu = std::max(2 * mu, 1e-12); // round-off
  }
  return -llt.solve(g);
}

/// B + S, with the eigenvalues of an indefinite sum replaced by their magnitudes (as saddle-free
/// Newton does): where the secant term outweighs B along a direction, the model still curves there
/// by as much, so a step goes down the slope by that measure. Shifting the whole model by μ until
/// it was positive definite shortened every step with it: the walking robot then crawled at
/// 0.02 units a step for ten iterations and stalled.
Eigen::MatrixXd secant_model(const Eigen::MatrixXd& B, const Eigen::MatrixXd& S)
{
  Eigen::MatrixXd M = B + S;
  if (Eigen::LLT<Eigen::MatrixXd>(M).info() == Eigen::Success) return M;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(M);
  return eigen.eigenvectors() * eigen.eigenvalues().cwiseAbs().asDiagonal() * eigen.eigenvectors().transpose();
}

/// The decrease a model (g, B) predicts for a step d.
double predicted_decrease(const Eigen::VectorXd& g, const Eigen::MatrixXd& B, const Eigen::VectorXd& d)
{
  return -(g.dot(d) + 0.5 * d.dot(B * d));
}

/// The secant term S, NL2SOL's update and sizing (Dennis, Gay & Welsch, "An adaptive nonlinear
/// least-squares algorithm", ACM TOMS 7(3), 1981): what the model B leaves out (the equilibria's
/// and residuals' second derivatives), so that B + S satisfies the secant equation (B⁺ + S⁺)s = y
/// of the step s just taken, y the change of the gradient (y# is taken with B at the new point,
/// where NL2SOL has the old Jacobian with the new residual: B here holds more than JᵀJ):
///   y# = y − B⁺s,  τ = min(1, |sᵀy#| / |sᵀSs|),  w = y# − τSs,
///   S⁺ = τS + (w yᵀ + y wᵀ) / (yᵀs) − (wᵀs) y yᵀ / (yᵀs)².
/// Unchanged when yᵀs ≤ 0 (no curvature along s to learn from).
void secant_update(Eigen::MatrixXd& S, const Eigen::MatrixXd& B_new, const Eigen::VectorXd& s, const Eigen::VectorXd& y)
{
  const double ys = y.dot(s);
  if (!(ys > 1e-12 * y.norm() * s.norm())) return;
  const Eigen::VectorXd ysharp = y - B_new * s;
  const Eigen::VectorXd Ss = S * s;
  const double sSs = s.dot(Ss);
  const double tau = sSs != 0 ? std::min(1.0, std::abs(s.dot(ysharp)) / std::abs(sSs)) : 1.0;
  const Eigen::VectorXd w = ysharp - tau * Ss;
  S = tau * S + (w * y.transpose() + y * w.transpose()) / ys - (w.dot(s) / (ys * ys)) * (y * y.transpose());
}

/// The secant term S and what it learns from: after each step s to x⁺, the gradient's change y and
/// the model B⁺ there, less the exact part's where it gives them (ExactPart::derivatives), so that
/// S holds only what B leaves out of the rest.
struct SecantTerm {
  const ExactPart& exact;
  Eigen::MatrixXd S;
  Eigen::VectorXd exact_gradient; ///< the exact part's at the current point, where given
  Eigen::MatrixXd exact_hessian;  ///< and the Hessian of it that B holds there

  SecantTerm(const ExactPart& e, const Eigen::VectorXd& x) : exact(e), S(Eigen::MatrixXd::Zero(x.size(), x.size()))
  {
    if (exact.derivatives) exact.derivatives(x, exact_gradient, exact_hessian);
  }

  void learn(const Eigen::VectorXd& x_new, const Eigen::VectorXd& s, Eigen::VectorXd y, Eigen::MatrixXd B_new)
  {
    if (exact.derivatives) {
      Eigen::VectorXd gradient;
      Eigen::MatrixXd hessian;
      exact.derivatives(x_new, gradient, hessian);
      y -= gradient - exact_gradient;
      B_new -= hessian;
      exact_gradient = std::move(gradient);
      exact_hessian = std::move(hessian);
    }
    if (s.cwiseAbs().maxCoeff() >= kLeastSecantStep) secant_update(S, B_new, s, y);
  }

  /// The model M = B + S at gradient g, and in `decrease` the larger of the whole decreases M and B
  /// alone predict (the convergence test's). Where M predicts at most `enough` left (the run has
  /// converged) and B alone more, S is the suspect (it overstates the curvature where it learnt it
  /// steeper): it is forgotten first, and the next steps are taken on B and teach S afresh. Kept,
  /// it held the twisting bar under OpenBLAS's SkylakeX kernels to steps of 0.02-0.05 units for 730
  /// iterations, f 0.968 → 0.940 at the limit of 1000; forgotten (three times), that run converges
  /// at 372 iterations, f 0.6226.
  Eigen::MatrixXd model(const Eigen::MatrixXd& B, const Eigen::VectorXd& g, double enough, double& decrease)
  {
    Eigen::MatrixXd M = secant_model(B, S);
    double by_model = model_decrease(M, g);
    const double by_B = model_decrease(B, g);
    if (S.any() && by_model <= enough && by_B > enough) {
      S.setZero();
      M = secant_model(B, S);
      by_model = model_decrease(M, g);
    }
    decrease = std::max(by_model, by_B);
    return M;
  }
};

/// The step along d on the model with the exact part's values, where there is one (ray_model.hpp),
/// taking out the exact part's expansion as B holds it where the derivatives are given.
RayStep step_on_ray(const ExactPart& exact, const SecantTerm& secant, const Eigen::VectorXd& x,
                    const Eigen::VectorXd& g, const Eigen::MatrixXd& M, const Eigen::VectorXd& d)
{
  if (!exact) return {1, predicted_decrease(g, M, d)};
  if (!exact.derivatives) return ray_step(exact.value, x, g, M, d);
  return ray_step(exact.value, x, g, M, d, secant.exact_gradient.dot(d), d.dot(secant.exact_hessian * d));
}

} // namespace

MinimizerResult minimize_levenberg_marquardt(const ModelObjective& f, Eigen::VectorXd x,
                                             const MinimizerOptions& options, const IterationCallback& on_iteration,
                                             Progress& progress, const ExactPart& exact)
{
  MinimizerResult result;
  Eigen::VectorXd g;
  Eigen::MatrixXd B;
  double fx;
  try {
    fx = f(x, g, B);
  } catch (const Interrupted&) {
    return interrupted_at_start(x);
  }
  result.evaluations = 1;
  if (!std::isfinite(fx)) throw std::invalid_argument("the objective is not finite at the starting point");

  double mu = kInitialDamping, nu = 2;
  SecantTerm secant(exact, x);
  const auto model = [&] { return secant_model(B, secant.S); };
  std::vector<double> values{fx};  // f after each iteration
  std::vector<double> predictions; // the model's whole decrease after each iteration
  int rejected = 0;                // trial steps rejected in a row
  auto finish = [&](Termination why, std::string message) {
    result.x = x;
    result.value = fx;
    result.gradient_norm = g.norm();
    result.termination = why;
    result.message = std::move(message);
    return result;
  };
  try {
    for (;;) {
      const double gnorm = g.norm();
      if (gnorm <= options.gradient_tolerance)
        return finish(Termination::gradient_tolerance, fmt::format("|∇f| = {:.3g} below tolerance", gnorm));
      // Converged where both B + S and B alone predict little left: a secant term that overstates
      // the curvature (learnt where it was steeper) claims too little (the twisting bar "converged"
      // at 0.941 on B + S's word alone, and went on to 0.648).
      double decrease = 0;
      const Eigen::MatrixXd M = secant.model(B, g, options.decrease_tolerance * std::abs(fx), decrease);
      if (decrease <= options.decrease_tolerance * std::abs(fx))
        return finish(Termination::decrease_tolerance,
                      fmt::format("the models' whole decrease (B + S's and B's) is at most {:.3g}, {:.2g} of f",
                                  decrease, decrease / std::abs(fx)));
      if (result.iterations == options.max_iterations)
        return finish(Termination::iteration_limit, fmt::format("{} iterations, the limit", options.max_iterations));
      if (progress.interrupted()) throw Interrupted();

      // A step longer than max_step in a variable is a sign that μ is too small for the model to
      // hold that far: μ doubles until it is not (the constrained model's minimizer, where
      // shortening the step along the same direction would follow the model's flattest, least
      // trusted, directions).
      const Eigen::VectorXd D = scaling(M);
      Eigen::VectorXd d = damped_step(M, D, g, mu);
      for (int k = 0; k < 60 && d.cwiseAbs().maxCoeff() > options.max_step; ++k) {
        mu = std::max(2 * mu, 1e-12);
        d = damped_step(M, D, g, mu);
      }
      if (const double largest = d.cwiseAbs().maxCoeff(); largest > options.max_step) d *= options.max_step / largest;
      // Along d on the model with the cheap part exact, where there is one: short of its walls.
      const RayStep ray = step_on_ray(exact, secant, x, g, M, d);
      d *= ray.alpha;
      const double predicted = ray.predicted;
      Eigen::VectorXd trial_g;
      Eigen::MatrixXd trial_B;
      double trial = HUGE_VAL;
      if (predicted > 0) {
        trial = f(x + d, trial_g, trial_B);
        ++result.evaluations;
      }
      const double rho = (fx - trial) / predicted;
      if (std::isfinite(trial) && trial < fx && rho > 0) {
        secant.learn(x + d, d, trial_g - g, trial_B);
        x += d;
        fx = trial;
        g = std::move(trial_g);
        B = std::move(trial_B);
        mu *= std::max(1.0 / 3, 1 - std::pow(2 * rho - 1, 3)); // eq. 2.21
        nu = 2;
        rejected = 0;
        ++result.iterations;
        const double ahead = model_decrease(model(), g);
        if (on_iteration) on_iteration({result.iterations, fx, g.norm(), d.norm(), result.evaluations, ahead}, x);
        values.push_back(fx);
        predictions.push_back(ahead);
        // A stall: a model that kept predicting more than it delivered (model_stall_message).
        if (auto message = model_stall_message(values, predictions, options))
          return finish(Termination::stalled, std::move(*message));
        continue;
      }
      if (++rejected >= options.max_line_search) // the last trial's length, not μ (which doubling takes to 1e68)
        return finish(Termination::line_search, fmt::format("{} trial steps in a row did not lower f, the last moving "
                                                            "no variable more than {:.2g} (mm, or 10 kPa)",
                                                            rejected, d.cwiseAbs().maxCoeff()));
      mu = std::max(mu, kLeastRaisedDamping) * nu;
      nu *= 2;
    }
  } catch (const Interrupted&) {
    finish(Termination::interrupted, "interrupted");
    result.interrupted = true;
    return result;
  }
}

} // namespace fibermold
