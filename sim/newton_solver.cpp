#include "sim/newton_solver.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <fmt/format.h>

#include "core/elapsed.hpp"
#include "sim/lbfgs_correction.hpp"

namespace fibermold {

namespace {
using Clock = std::chrono::steady_clock;

/// |∇E| within this factor of the tolerance: steps on the exact Hessian there converge.
constexpr double kNearTolerance = 1e3;
/// Where a solve that finishes on a fresh factorization ends, relative to the tolerance.
constexpr double kFarBelow = 1e-2;
/// The round-off floor of |∇E|: a step on a fresh factorization of the exact Hessian that had to
/// shrink below kRoundOffStep finds no lower |∇E| in double precision. Within kRoundOffAccept of the
/// tolerance that is convergence. The tolerance scales with the silicone (E h²), and a stiff
/// passive muscle in it can put the floor above it: the walking robot's twist at 0.1 kPa stopped at
/// 6.4e-8 N against 1.8e-8 N for 100 iterations under OpenBLAS's Sandybridge kernels, and converged
/// in 4 under the others (session 17).
constexpr double kRoundOffStep = 1e-6, kRoundOffAccept = 1e2;
/// Products at most in the conjugate gradients of an adjoint solve, and of an exact Newton step
/// (where a failure costs the products, about two assemblies' worth, once in a solve: the step
/// falls back to the factorization's). Most take 5–6; a strong muscle on a coarse stencil (the
/// test's bar of 4 segments) 23.
constexpr int kAdjointProducts = 50, kNewtonProducts = 40;
/// Steps on one factorization at most.
constexpr int kLongestReuse = 50;
/// A solve takes at most max_iterations steps on fresh factorizations and this many times
/// max_iterations steps in all (from rest the examples take at most 155).
constexpr int kStepsPerIteration = 10;

SparseHessian make_pattern(const std::vector<const Energy*>& energies, Eigen::Index n)
{
  std::vector<std::vector<int>> stencils;
  for (const Energy* e : energies) e->stencils(stencils);
  return SparseHessian(n, stencils);
}
} // namespace

std::string NewtonSummary::brief() const
{
  return fmt::format("{} after {} iterations: |∇E| = {:.3e} N (from {:.3e}), {:.3f} s",
                     converged ? "converged" : "NOT converged", iterations, residual, initial_residual, seconds_total);
}

NewtonTotals& NewtonTotals::operator+=(const NewtonSummary& s)
{
  ++solves;
  iterations += s.iterations;
  assemblies += s.assemblies;
  factorizations += s.factorizations;
  products += s.products;
  seconds_assembly += s.seconds_assembly;
  seconds_factorization += s.seconds_factorization;
  return *this;
}

NewtonSolver::NewtonSolver(std::vector<const Energy*> energies, Eigen::Index num_nodes, bool keep_pattern)
    : energies_(std::move(energies)), fixed_energies_(energies_.size()), hessian_(make_pattern(energies_, num_nodes)),
      keep_pattern_(keep_pattern)
{
}

void NewtonSolver::set_variable_energies(const std::vector<const Energy*>& energies)
{
  adjoint_ready_ = false;
  energies_.resize(fixed_energies_);
  energies_.insert(energies_.end(), energies.begin(), energies.end());
  variable_stencils_.clear();
  for (const Energy* e : energies) e->stencils(variable_stencils_);
  if (!keep_pattern_ && !hessian_.contains(variable_stencils_)) hessian_ = SparseHessian(hessian_, variable_stencils_);
}

Eigen::VectorXd NewtonSolver::gradient(const Eigen::VectorXd& x) const
{
  Eigen::VectorXd g = Eigen::VectorXd::Zero(x.size());
  for (const Energy* term : energies_) term->add_gradient(x, g);
  return g;
}

const SparseHessian& NewtonSolver::hessian(const Eigen::VectorXd& x, bool project)
{
  hessian_.set_zero();
  for (const Energy* term : energies_) term->add_hessian(x, hessian_, project);
  return hessian_;
}

double NewtonSolver::value_and_gradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const
{
  g.setZero(x.size());
  double e = 0;
  for (const Energy* term : energies_)
    if (!((e += term->value_and_gradient(x, g)) < HUGE_VAL)) return HUGE_VAL;
  return e;
}

bool NewtonSolver::solve_with_hessian(const Eigen::VectorXd& x, const Eigen::VectorXd& b, Eigen::VectorXd& lambda)
{
  int products = 0;
  if (adjoint_ready_ && x.size() == adjoint_x_.size() && x == adjoint_x_ &&
      conjugate_gradient_solve(x, b, lambda, kAdjointProducts, products))
    return true;
  adjoint_ready_ = false;
  if (keep_pattern_ && hessian(x, true).lumped() > 0) {
    // The projected Hessian with lumped pairs (semi-definite as they are) preconditions conjugate
    // gradients on the exact one; where that does not converge, the pattern grows to hold the
    // pairs (a symbolic analysis).
    if (cholmod_.factorize(hessian_.matrix(), 0) &&
        conjugate_gradient_solve(x, b, lambda, kAdjointProducts, products)) {
      kind_ = Factorization::projected; // of the Hessian at x all the same: a solve from x may begin on it
      return true;
    }
    hessian_ = SparseHessian(hessian_, variable_stencils_);
  }
  hessian(x, false);
  kind_ = cholmod_.factorize(hessian_.matrix(), 0) ? Factorization::exact : Factorization::none;
  if (kind_ != Factorization::exact) {
    restart_ready_ = false;
    return false;
  }
  lambda = cholmod_.solve(b);
  return lambda.allFinite();
}

bool NewtonSolver::solve_with_factorization(const Eigen::MatrixXd& B, Eigen::MatrixXd& X) const
{
  if (kind_ == Factorization::none) return false;
  X = cholmod_.solve(B);
  return X.allFinite();
}

bool NewtonSolver::conjugate_gradient_solve(const Eigen::VectorXd& x, const Eigen::VectorXd& b, Eigen::VectorXd& lambda,
                                            int max_products, int& products) const
{
  // Preconditioned conjugate gradients (Nocedal & Wright, Algorithm 5.3) on H(x) λ = b, with the
  // factorization K held as the preconditioner and H(x)v from the energies' products in closed
  // form (energy.hpp), each energy's Hessian at x built once (Energy::hessian_at). K is of the Hessian a few steps
  // before x (the last solve's finishing factorization), or at x with lumped pairs: close to H(x),
  // so a few products do (on the test's bar K⁻¹b is 3e-7 from H(x)⁻¹b, and one product brings it to
  // 8e-10). H(x) must be positive definite (a stable equilibrium).
  constexpr double kResidual = 1e-8; // of |b|
  products = 0;
  if (b.isZero(0)) {
    lambda = Eigen::VectorXd::Zero(b.size());
    return true;
  }
  std::vector<std::unique_ptr<HessianProduct>> at_x;
  for (const Energy* e : energies_) at_x.push_back(e->hessian_at(x));
  const auto product = [&](const Eigen::VectorXd& v) {
    Eigen::VectorXd Hv = Eigen::VectorXd::Zero(v.size());
    for (const auto& H : at_x) H->add(v, Hv);
    ++products;
    return Hv;
  };
  lambda = cholmod_.solve(b);
  Eigen::VectorXd r = b - product(lambda), z = cholmod_.solve(r), p = z;
  double rz = r.dot(z);
  while (r.norm() > kResidual * b.norm()) { // false for NaN too, which r.allFinite() then refuses
    if (products >= max_products) return false;
    const Eigen::VectorXd q = product(p);
    const double pq = p.dot(q);
    if (!(pq > 0)) return false; // not definite
    const double alpha = rz / pq;
    lambda += alpha * p;
    r -= alpha * q;
    z = cholmod_.solve(r);
    const double next = r.dot(z);
    p = z + (next / rz) * p;
    rz = next;
  }
  return lambda.allFinite() && r.allFinite();
}

NewtonSolver::Factorization NewtonSolver::factorize_at(const Eigen::VectorXd& x, NewtonSummary& s, double& shift,
                                                       bool exact_first)
{
  // The exact Hessian where it is positive definite (quadratic convergence near a stable
  // equilibrium); shifted by τI where it is indefinite but only softly (a state passing a snap or
  // a buckling mode); the per-point PSD projection where it is far from definite.
  shift = 0;
  if (exact_first) {
    auto t = Clock::now();
    hessian(x, false);
    s.seconds_assembly += since(t);
    ++s.assemblies;
    t = Clock::now();
    ++s.factorizations;
    Factorization kind = cholmod_.factorize(hessian_.matrix(), 0) ? Factorization::exact
                         : factorize_shifted(s, shift)            ? Factorization::shifted
                                                                  : Factorization::none;
    s.seconds_factorization += since(t);
    if (kind != Factorization::none) return kind;
  }
  auto t = Clock::now();
  hessian(x, true);
  s.seconds_assembly += since(t);
  ++s.assemblies;
  // A PSD-projected Hessian can be singular (e.g. at rest with no load); shift until it factorizes.
  t = Clock::now();
  const double diagonal = hessian_.matrix().diagonal().cwiseAbs().maxCoeff();
  if (!(diagonal > 0 && std::isfinite(diagonal))) {
    s.message = "the Hessian is zero or not finite";
    return Factorization::none;
  }
  bool factorized = false;
  shift = 0;
  while (!factorized && shift <= diagonal) { // at most 11 attempts
    factorized = cholmod_.factorize(hessian_.matrix(), shift);
    ++s.factorizations;
    if (!factorized) shift = shift == 0 ? 1e-10 * diagonal : shift * 10;
  }
  s.seconds_factorization += since(t);
  if (!factorized) s.message = "the Hessian is singular: is the body held (a [[fixed]] region)?";
  return factorized ? Factorization::projected : Factorization::none;
}

bool NewtonSolver::factorize_shifted(NewtonSummary& s, double& shift)
{
  // H + τI for the first τ of τ₀·4ᵏ that is positive definite, τ₀ a small fraction of the largest
  // diagonal entry or a quarter of the last τ that served, in this solve or an earlier one (so τ
  // shrinks 4× per search that succeeds at once); a multiple of the identity added until Cholesky
  // succeeds: Nocedal & Wright, Numerical Optimization, Algorithm 3.3, with 4× steps. Starting
  // each solve's search from the smallest τ cost the walking robot's coarse optimization 505
  // factorizations where this takes 394.
  // Along a soft mode of slightly negative curvature (stiff terms that nearly cancel) the step
  // then follows the mode; the per-point projection drops the negative part, makes the mode as
  // stiff as the elements, and Newton crawls: on the walking robot 40 to 100 full steps, each
  // lowering |∇E| by at most 4 %. Beyond kLargestShift the projection is the better model.
  constexpr double kSmallestShift = 1e-8, kLargestShift = 1e-2;
  const double diagonal = hessian_.matrix().diagonal().cwiseAbs().maxCoeff();
  if (!(diagonal > 0 && std::isfinite(diagonal))) return false;
  for (shift = std::max(kSmallestShift * diagonal, last_shift_ / 4); shift <= kLargestShift * diagonal; shift *= 4) {
    ++s.factorizations;
    if (cholmod_.factorize(hessian_.matrix(), shift)) {
      last_shift_ = shift;
      return true;
    }
  }
  last_shift_ = 0;
  return false;
}

/// One solve's state: where it is, and what the factorization held is of.
struct NewtonSolver::SolveState {
  SolveState(Eigen::VectorXd& x, const NewtonOptions& options)
      : x(x), options(options), secant(options.quasi_newton_pairs)
  {
  }

  Eigen::VectorXd& x;
  const NewtonOptions& options;
  NewtonSummary s;
  Eigen::VectorXd g; // ∇E(x)
  double E = 0;      // E(x)
  double goal = 0;   // the tolerance on |∇E|, N
  double last_alpha = 0, shift = 0;
  bool fresh = false;         // the factorization is of the Hessian at x
  bool stale = true;          // the next step needs a new factorization
  bool exact_first = true;    // false: the next factorization is the projected Hessian
  bool near = false;          // the factorization is of the Hessian at a state within kNearTolerance
  bool finishing = false;     // below the tolerance, taking the step that finish_on_fresh_step asks for
  bool krylov_failed = false; // an exact Newton step failed: its conjugate gradients, or its line search
  bool exact_step = false;    // the step being tried is an exact Newton step
  int full_steps = 0;         // steps on a fresh factorization: what max_iterations bounds
  int reused_run = 0;         // steps on the factorization held
  LbfgsCorrection secant;     // the steps since the last factorization
};

/// A line search's outcome: the state it accepted, or found = false.
struct NewtonSolver::Trial {
  bool found = false;
  double alpha = 1, E = HUGE_VAL;
  Eigen::VectorXd x, g;
};

// The states of a solve and their rules:
//   before a step: converged (below the tolerance, on a factorization that lets it end), out of
//     iterations, or on to a step (stops_before_step);
//   a stale factorization is replaced: exact, shifted or projected (refactorizes_if_stale);
//   the step: a (quasi-)Newton direction and a backtracking line search (line_search); one that
//     fails on an old or shifted factorization retries on a new one (retries_after_failed_search);
//   after a step: the round-off floor, or the finishing step done (stops_at_step); else the step
//     is taken and the factorization kept while its steps go well (take_step).
NewtonSummary NewtonSolver::solve(Eigen::VectorXd& x, const NewtonOptions& options, Progress& progress)
{
  const auto start = Clock::now();
  SolveState st(x, options);
  adjoint_ready_ = false;
  st.E = value_and_gradient(x, st.g);
  if (!(st.E < HUGE_VAL)) {
    st.s.message = "the starting state is invalid (an inverted element)";
    return st.s;
  }
  st.s.initial_residual = st.g.norm();
  st.goal = options.tolerance * options.force_scale;
  // A solve that starts where the last one ended (the optimizer's warm start, with the muscles
  // moved a little) takes its first step on that solve's factorization of the exact Hessian: a
  // design step that changes little then costs no assembly before the finishing one.
  st.stale = !(restart_ready_ && x.size() == restart_x_.size() && x == restart_x_);
  restart_ready_ = false;
  while (!stops_before_step(st) && refactorizes_if_stale(st)) {
    progress.checkpoint(-1, fmt::format("Newton iteration {}: |∇E| = {:.3e} N, last step {:.3g}, shift {:.3g}{}",
                                        st.s.iterations, st.s.residual, st.last_alpha, st.shift,
                                        st.fresh ? "" : ", Hessian reused"));
    auto t = Clock::now();
    if (st.fresh) st.secant.clear();
    const Eigen::VectorXd dx = step(st);
    st.s.seconds_solve += since(t);
    Trial trial = line_search(st, dx);
    if (!trial.found) {
      if (retries_after_failed_search(st)) continue;
      break;
    }
    if (stops_at_step(st, trial)) break;
    take_step(st, trial);
  }
  st.s.seconds_total = since(start);
  return st.s;
}

Eigen::VectorXd NewtonSolver::step(SolveState& st) const
{
  // Near the tolerance, on a fresh factorization of the exact Hessian with lumped pairs
  // (keep_pattern), the exact Newton step: conjugate gradients on the exact Hessian's products
  // preconditioned by that factorization, as the adjoint solve does. Steps on the lumped Hessian
  // alone contract |∇E| only linearly there, and a solve that must finish far below the tolerance
  // crawled: the tentacle tip's from rest took its last 29 of 100 steps, and 15 of its 26
  // assemblies, from 1e3× the tolerance to it. Elsewhere (far from equilibrium, where the Hessian
  // may be indefinite and a line search cuts the step anyway), and once conjugate gradients have
  // failed in this solve (lumped pairs too heavy for the factorization to precondition, or a step
  // that does not descend: the lumped Hessian can be definite where the exact one is not), the
  // quasi-Newton step on the factorization held.
  st.exact_step = false;
  if (st.fresh && st.near && !st.krylov_failed && kind_ == Factorization::exact && hessian_.lumped() > 0) {
    Eigen::VectorXd dx;
    int products = 0;
    const bool solved = conjugate_gradient_solve(st.x, -st.g, dx, kNewtonProducts, products);
    st.s.products += products;
    if (solved && st.g.dot(dx) < 0) {
      st.exact_step = true;
      return dx;
    }
    st.krylov_failed = true;
  }
  return -st.secant.apply(st.g, [&](const Eigen::VectorXd& q) { return cholmod_.solve(q); });
}

void NewtonSolver::converge(SolveState& st, bool factorization_serves_adjoint)
{
  st.s.converged = true;
  st.s.message = "gradient below tolerance";
  adjoint_ready_ = factorization_serves_adjoint;
  if (adjoint_ready_) adjoint_x_ = st.x;
  restart_ready_ = kind_ == Factorization::exact;
  restart_x_ = st.x;
}

bool NewtonSolver::stops_before_step(SolveState& st)
{
  NewtonSummary& s = st.s;
  const NewtonOptions& options = st.options;
  s.residual = st.g.norm();
  s.energy = st.E;
  if (!std::isfinite(s.residual)) {
    s.message = "the gradient is not finite";
    return true;
  }
  // A solve that must end on a fresh factorization takes it near the tolerance, where steps on it
  // contract by 1e-2 or more, and ends far below the tolerance (or where its steps stop shrinking
  // |∇E|: round-off); reused ones from farther only approach it.
  if (s.residual <= st.goal) {
    if (!options.finish_on_fresh_step || (st.near && (s.residual <= kFarBelow * st.goal || st.stale))) {
      converge(st, st.near && kind_ == Factorization::exact);
      return true;
    }
    if (!st.near) {
      st.finishing = true;
      st.stale = true;
    }
  }
  if (options.finish_on_fresh_step && !st.fresh && !st.near && s.residual <= kNearTolerance * st.goal) st.stale = true;
  if ((st.full_steps >= options.max_iterations || s.iterations >= kStepsPerIteration * options.max_iterations) &&
      !st.finishing) {
    if (s.residual <= st.goal)
      converge(st, st.near && kind_ == Factorization::exact);
    else
      s.message = fmt::format("no convergence in {} iterations ({} steps)", options.max_iterations, s.iterations);
    return true;
  }
  return false;
}

bool NewtonSolver::refactorizes_if_stale(SolveState& st)
{
  if (!st.stale) return true;
  kind_ = factorize_at(st.x, st.s, st.shift, st.exact_first);
  if (kind_ == Factorization::none) {
    if (st.finishing) converge(st, false); // x is below the tolerance all the same
    return false;
  }
  st.stale = false;
  st.reused_run = 0;
  st.fresh = true;
  st.exact_first = true;
  st.near = st.s.residual <= kNearTolerance * st.goal;
  return true;
}

NewtonSolver::Trial NewtonSolver::line_search(SolveState& st, const Eigen::VectorXd& dx)
{
  // Backtracking (Armijo) that rejects any invalid state.
  const double slope = st.g.dot(dx);
  Trial t;
  int halvings = 0;
  // A kept factorization whose step needs more than a few halvings is refactorized instead.
  const int max_halvings = st.fresh ? st.options.max_halvings : std::min(st.options.max_halvings, 4);
  for (; slope < 0 && halvings <= max_halvings; ++halvings, t.alpha /= 2) {
    t.x = st.x + t.alpha * dx;
    t.E = value_and_gradient(t.x, t.g);
    if (!(t.E < HUGE_VAL)) continue;
    if (t.E <= st.E + 1e-4 * t.alpha * slope) break;
    // Near the minimum the energy difference drowns in round-off: accept a step that lowers |∇E|.
    if (std::abs(t.E - st.E) <= 1e-12 * std::abs(st.E) && t.g.norm() < st.s.residual) break;
  }
  t.found = slope < 0 && halvings <= max_halvings;
  return t;
}

bool NewtonSolver::retries_after_failed_search(SolveState& st)
{
  if (st.exact_step) { // the factorization's own step next, on the same factorization
    st.krylov_failed = true;
    return true;
  }
  if (!st.fresh || kind_ == Factorization::shifted) { // an old Hessian's direction: refactorize
    st.stale = true;                                  // and try again; a shifted one's: project
    st.exact_first = !st.fresh;
    return true;
  }
  if (st.s.residual <= st.goal) { // the factorization is of the Hessian at x, which is below the tolerance
    converge(st, kind_ == Factorization::exact);
    return false;
  }
  st.s.message = "the line search found no decrease";
  return false;
}

bool NewtonSolver::stops_at_step(SolveState& st, const Trial& t)
{
  if (st.fresh && kind_ == Factorization::exact && t.alpha < kRoundOffStep &&
      st.s.residual <= kRoundOffAccept * st.goal) {
    converge(st, true); // the factorization is of the exact Hessian at x
    st.s.message = fmt::format("gradient at its round-off floor, {:.2g}× the tolerance", st.s.residual / st.goal);
    return true;
  }
  if (st.finishing && !(t.g.norm() <= st.goal)) { // the extra step must not undo convergence
    converge(st, false);
    return true;
  }
  return false;
}

void NewtonSolver::take_step(SolveState& st, Trial& t)
{
  st.secant.add(t.x - st.x, t.g - st.g);
  st.x = std::move(t.x);
  st.E = t.E;
  st.g = std::move(t.g);
  st.last_alpha = t.alpha;
  ++st.s.iterations;
  if (st.fresh) ++st.full_steps;
  st.finishing = false;
  // The factorization is kept for the next step while its steps go well: a step then costs a
  // gradient and a solve instead of an assembly and a factorization. Quasi-Newton: while a step
  // needs at most one halving, unless the factorization is of a shifted Hessian (a poor model:
  // kept, a bent muscle bar crawled 21 steps at α = 0.5 on one; a projected one is kept, and
  // its steps are corrected by the pairs like any other). Plain: while full steps halve |∇E|.
  // From rest, sim_bench's twisting bar at 2,433 DoFs took 16 factorizations in 29 steps with
  // plain reuse, 10 in 39 when only full quasi-Newton steps kept it, 5 in 57 with this rule.
  // Below the tolerance a kept factorization must still halve |∇E|: where it stops doing so
  // (round-off), a solve that finishes on a fresh factorization ends there.
  const double residual = st.s.residual, goal = st.goal;
  const bool contracted = st.g.norm() <= st.options.reuse_contraction * residual;
  st.stale = st.options.quasi_newton_pairs > 0
                 ? !(t.alpha >= 0.5 && kind_ != Factorization::shifted && (residual > goal || contracted))
                 : !(t.alpha == 1 && contracted);
  st.reused_run = st.stale ? 0 : st.reused_run + 1;
  if (st.reused_run > kLongestReuse) st.stale = true;
  st.fresh = false;
}

} // namespace fibermold
