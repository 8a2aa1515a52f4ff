#pragma once
// The routing problem of eq. 4: find the fibers' routes s (shared by all targets) and pressures
// p^t (per target) that bring the body's equilibria x^t(s, p^t) to the targets x̂^t:
//   min  Σ_t f_dist(x^t, x̂^t) + w_curv Σ_f L_f ∫ κ_f² ds + w_skin Σ_f B_skin(f) + w_bend Σ_f B_bend(f)
//        + w_p Σ_{t,f} [b(p/p_max) + b(1 − p/p_max)],
// with f_dist as in distance_objective.hpp, L_f the fiber's starting length (which makes the
// curvature term dimensionless), B_skin as in skin_barrier.hpp, B_bend as in bend_radius.hpp (the
// muscle's smallest bend radius) and b the log barrier acting within `pressure_margin` of either
// pressure bound. The end points of each route stay fixed. After
// collide, w_clear B_clear (clearance_barrier.hpp) may join, to keep fibers apart.
//
// The optimizer sees a flat vector z of the free variables, in mm (points, tangents) and 10 kPa
// (pressures), so that one unit is a comparable change of the design.

#include <cmath>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mesh/surface_distance.hpp"
#include "optimize/bend_radius.hpp"
#include "optimize/distance_objective.hpp"
#include "optimize/routing.hpp"
#include "optimize/skin_barrier.hpp"
#include "sim/simulation.hpp"

namespace fibermold {

class ClearanceBarrier;

struct RoutingSettings {
  double max_pressure = 425e3;      ///< Pa
  double segments_per_length = 500; ///< muscle segments per m
  double skin_distance = 2.5e-3;    ///< d_min of the skin barrier: muscle radius + clearance, m
  double skin_band = 1.5e-3;        ///< w: the barrier acts from d_min to d_min + w, m
  double weight_curvature = 1e-4;
  double min_bend_radius = 0; ///< m: the muscle bends no tighter (bend_radius.hpp); 0: no limit
  double weight_bend = 1;
  /// The skin barrier's weight per muscle segment: 0.1 matched the targets better than 1 on six of the seven
  /// optimized examples (the seventh ties), ending alike in about the same time (docs/optimize.md, "The barriers'
  /// weights"; session 44)
  double weight_skin = 0.1;
  double weight_pressure = 1;
  double pressure_margin = 0.02;      ///< of max_pressure
  std::vector<double> target_weights; ///< per target, multiplies its f_dist in eq. 4; empty: all 1
};

/// The skin barrier of eq. 4 on `route` as the routing problem builds it (its distance, band and
/// samples from `settings`; the stretches at exits on the skin left out), so that a check before the
/// optimizer asks what the optimizer will.
SkinBarrier route_skin_barrier(const SurfaceDistance& skin, const RoutingSettings& settings, const Route& route);

/// The value of each term at a routing.
struct RoutingTerms {
  double total = 0, distance = 0, curvature = 0, skin = 0, bend = 0, pressure = 0, clearance = 0;
  std::vector<double> per_target; ///< f_dist per target (0 for inactive ones)
};

class RoutingProblem {
public:
  /// `sim`: the body, held and under gravity, without muscles; `targets[t]`: x̂^t.
  /// Throws std::invalid_argument when the starting routing is unusable (a fiber leaving the body,
  /// a pressure outside (0, max_pressure)); skin_violation() tells which fiber comes too close.
  RoutingProblem(Simulation& sim, const MuscleModel& model, const SurfaceDistance& skin,
                 std::vector<Eigen::VectorXd> targets, const std::vector<TrackingSamples>& curves, Routing start,
                 RoutingSettings settings);

  /// What the optimizer may change: routes (interior points, all tangents), pressures per
  /// (target, fiber); and which targets count. Default: everything.
  void set_free(std::vector<bool> routes, Eigen::Matrix<bool, Eigen::Dynamic, Eigen::Dynamic> pressures,
                std::vector<bool> targets);
  /// Adds weight · B_clear (clearance_barrier.hpp) to the objective: fibers keep their clearance
  /// from each other. `barrier` must outlive the problem; null removes it.
  void set_clearance_barrier(const ClearanceBarrier* barrier, double weight)
  {
    clearance_barrier_ = barrier;
    weight_clearance_ = weight;
  }
  /// The routing that unfree variables take their values from.
  void set_base(const Routing& routing) { base_ = routing; }
  const Routing& base() const { return base_; }

  /// The first fiber that comes closer to the skin than skin_distance anywhere between its first
  /// and last barrier sample (−1: none), its closest approach (m) and where.
  int skin_violation(const Routing& r, double& distance, Eigen::Vector3d& where) const;
  /// The first fiber that leaves the body closer to the skin than its exit ramp (skin_barrier.hpp)
  /// allows (−1: none), and where.
  int exit_violation(const Routing& r, ExitShortfall& shortfall) const;

  Eigen::Index size() const { return static_cast<Eigen::Index>(entries_.size()); }
  Eigen::VectorXd variables(const Routing& r) const;
  Routing routing(const Eigen::VectorXd& z) const;

  /// The objective at z, and its gradient (adjoint, eq. 9) when asked. +∞ when a fiber leaves the
  /// body, a pressure its bounds, or an equilibrium cannot be found; `gradient` is then untouched.
  /// `model` (with `gradient`): the Gauss-Newton Hessian of the distances, Σ_t S_tᵀ ∇²f_dist S_t with
  /// the sensitivities S_t = dx^t/dz (sensitivities()), plus the regularizers' Hessian
  /// (regularizer_hessian()): the model Hessian of levenberg_marquardt.hpp.
  double evaluate(const Eigen::VectorXd& z, Eigen::VectorXd* gradient = nullptr, RoutingTerms* terms = nullptr,
                  Eigen::MatrixXd* model = nullptr);
  /// The forward sensitivities dx/dz = −H⁻¹ ∂²E/∂x∂z (3n × size()) of target t's equilibrium x
  /// under routing r, one column per free variable, each a back-substitution with the
  /// factorization the equilibrium's solve (or adjoint solve) left (so accurate to how near that is
  /// to H(x): the test bar's within 1.0e-3 of central differences). Empty when no factorization is held.
  Eigen::MatrixXd sensitivities(const Routing& r, int t, const Eigen::VectorXd& x);
  /// The Hessian of the curvature, skin, bend, pressure and clearance terms at z: central
  /// differences of their analytic gradient, one route at a time (a route's terms see only its own
  /// variables; of the clearance barrier, the pairs with that route), the pressure barrier's
  /// exactly; projected to be positive semi-definite.
  Eigen::MatrixXd regularizer_hessian(const Eigen::VectorXd& z) const;
  /// The curvature, skin, bend, pressure and clearance terms at z, which need no simulation: +∞
  /// past a wall (as evaluate scores it) or with a fiber outside the body. The exact part of
  /// Levenberg-Marquardt's ray model (ray_model.hpp). Counts no refusal.
  double regularizer_value(const Eigen::VectorXd& z) const;
  /// The gradient of those terms at z and their Hessian as the model holds it (regularizer_hessian()):
  /// Levenberg-Marquardt's exact part, which its secant term does not learn. At the last point
  /// evaluate built a model at, what it computed there.
  void regularizer_derivatives(const Eigen::VectorXd& z, Eigen::VectorXd& gradient, Eigen::MatrixXd& hessian) const;

  /// The terms of the finite evaluation whose total is `value`: the last one, or the best one
  /// since set_free (the two points a line search can accept).
  const RoutingTerms& terms_at(double value) const { return value == last_terms_.total ? last_terms_ : best_terms_; }

  /// Equilibrium of target t under routing r, warm-started from the equilibria of the best
  /// evaluation so far (so that a multi-stable body shows the state the optimizer scored); throws
  /// std::runtime_error when Newton fails.
  Eigen::VectorXd equilibrium(const Routing& r, int t);
  /// Solves from here on start from the rest state, as a robot does.
  void forget_states()
  {
    warm_.assign(targets_.size(), sim_.rest());
    best_warm_.clear();
  }
  const DistanceObjective& distance(int t) const { return distances_[t]; }
  const Eigen::VectorXd& target(int t) const { return targets_[t]; }
  int num_targets() const { return static_cast<int>(targets_.size()); }
  int num_fibers() const { return static_cast<int>(base_.routes.size()); }
  Simulation& simulation() { return sim_; }
  /// The muscles of target t under routing r, as the simulation used them.
  std::vector<std::unique_ptr<MuscleEnergy>> muscles(const Routing& r, int t) const;
  /// The Newton solves so far, and the seconds spent in simulation and in adjoint solves.
  const NewtonTotals& newton() const { return newton_; }
  double seconds_simulation() const { return seconds_simulation_; }
  double seconds_adjoint() const { return seconds_adjoint_; }
  /// Seconds in the model Hessians' sensitivities and regularizer Hessians.
  double seconds_model() const { return seconds_model_; }
  /// How many designs evaluate scored +∞, by why (kRefusalNames): the walls the optimizer met.
  const std::map<std::string, int>& refusals() const { return refusals_; }

private:
  struct Entry {
    enum Kind { Point, Tangent, Pressure } kind;
    int fiber, index, component; ///< index: the point, or the target for a pressure
  };
  double scale(const Entry& e) const;
  /// Each skin barrier sample's weight.
  double skin_weight() const;
  /// Equilibrium x of target t with its muscles' `energies`, warm-started; whether Newton converged.
  bool solve(int t, std::vector<std::unique_ptr<Energy>> energies, Eigen::VectorXd& x);
  double regularizers(const Routing& r, Eigen::VectorXd* gradient, RoutingTerms& terms) const;
  /// Adds the gradient of fiber f's route terms (curvature, skin, bend) to `out`.
  void add_route_gradient(const Routing& r, int f, Eigen::VectorXd& out) const;
  /// With `only` ≥ 0, of the pairs that include fiber `only` alone (ClearanceBarrier::gradient).
  void add_clearance_gradient(const Routing& r, Eigen::VectorXd& out, int only = -1) const;
  /// The free variables whose columns of ∂²E/∂x∂z are not zero for target t (its pressures, the
  /// free routes' points and tangents), and those columns with `muscles` at x.
  Eigen::MatrixXd mixed_columns(int t, const Eigen::VectorXd& x, const std::vector<const MuscleEnergy*>& muscles,
                                std::vector<Eigen::Index>& columns) const;
  void add_fiber_gradient(int f, const FiberParameterGradient& g, double weight, int target,
                          Eigen::VectorXd& out) const;
  bool fibers_inside(const Routing& r) const;

  Simulation& sim_;
  const MuscleModel& model_;
  const SurfaceDistance& skin_;
  std::vector<Eigen::VectorXd> targets_, warm_;
  std::vector<DistanceObjective> distances_;
  Routing base_;
  RoutingSettings settings_;
  std::vector<std::vector<double>> segment_t_; ///< per fiber, fixed at the start
  std::vector<SkinBarrier> skin_barriers_;
  std::optional<BendBarrier> bend_barrier_;
  std::vector<double> start_length_;
  std::vector<bool> target_active_;
  std::vector<Entry> entries_;
  std::vector<std::vector<int>> entry_of_; ///< [fiber][6·point + 3·is_tangent + component] → entry or −1
  Eigen::MatrixXi pressure_entry_;         ///< targets × fibers → entry or −1
  RoutingTerms last_terms_, best_terms_;
  std::vector<Eigen::VectorXd> best_warm_; ///< equilibria at the best evaluation since set_free
  const ClearanceBarrier* clearance_barrier_ = nullptr;
  double weight_clearance_ = 0;
  NewtonTotals newton_;
  mutable std::map<std::string, int> refusals_;
  mutable bool counting_refusals_ = true; ///< false while regularizer_value probes a design
  /// The regularizers' gradient and model Hessian at the last z evaluate built a model at.
  struct RegularizerDerivatives {
    Eigen::VectorXd z, gradient;
    Eigen::MatrixXd hessian;
  } last_regularizer_;
  /// Counts a refused design under `why` and returns its score, +∞.
  double refuse(const char* why) const
  {
    if (counting_refusals_) ++refusals_[why];
    return HUGE_VAL;
  }
  double seconds_simulation_ = 0, seconds_adjoint_ = 0, seconds_model_ = 0;
};

} // namespace fibermold
