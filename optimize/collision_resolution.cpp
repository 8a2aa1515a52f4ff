#include "optimize/collision_resolution.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <tuple>

#include <Eigen/Cholesky>
#include <Eigen/SparseCore>
#include <fmt/format.h>

#include "core/units.hpp"

namespace fibermold {

namespace {

using RowMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor>;
using SparseMatrix = Eigen::SparseMatrix<double>;
using Triplets = std::vector<Eigen::Triplet<double>>;

std::string where_mm(const Eigen::Vector3d& p)
{
  return fmt::format("({:.2f}, {:.2f}, {:.2f}) mm", p.x() / units::mm, p.y() / units::mm, p.z() / units::mm);
}

/// The free parameters of the routes (interior points, all tangents; mm) and how the clearance
/// samples move with them. A sample is linear in the spline's parameters: slot 2k holds point k,
/// slot 2k + 1 tangent k, the same weights acting on each coordinate.
class RouteVariables {
public:
  RouteVariables(const FiberClearance& measure, const std::vector<Route>& routes)
  {
    for (int f = 0; f < measure.num_fibers(); ++f) {
      first_.push_back(size_);
      const Route& r = routes[f];
      const int n = static_cast<int>(r.points.size());
      std::vector<int> index(2 * n, -1);
      for (int slot = 0; slot < 2 * n; ++slot) {
        const bool end_point = slot % 2 == 0 && (slot == 0 || slot == 2 * (n - 1));
        if (!end_point) {
          index[slot] = size_;
          size_ += 3;
        }
      }
      slot_index_.push_back(std::move(index));
      const HermiteSpline s(r.points, r.tangents);
      std::vector<Eigen::VectorXd> weights;
      for (double t : measure.parameters(f)) {
        int span;
        double w[4];
        s.weights(t, span, w);
        Eigen::VectorXd phi = Eigen::VectorXd::Zero(2 * n);
        for (int j = 0; j < 4; ++j) phi[2 * span + j] = w[j];
        weights.push_back(std::move(phi));
      }
      weights_.push_back(std::move(weights));
    }
    first_.push_back(size_);
  }

  int size() const { return size_; }

  Eigen::VectorXd values(const std::vector<Route>& routes) const
  {
    Eigen::VectorXd y(size_);
    for (std::size_t f = 0; f < slot_index_.size(); ++f)
      for (std::size_t slot = 0; slot < slot_index_[f].size(); ++slot)
        if (const int i = slot_index_[f][slot]; i >= 0)
          y.segment<3>(i) = parameter(routes[f], static_cast<int>(slot)) / units::mm;
    return y;
  }

  std::vector<Route> routes(const Eigen::VectorXd& y, std::vector<Route> out) const
  {
    for (std::size_t f = 0; f < slot_index_.size(); ++f)
      for (std::size_t slot = 0; slot < slot_index_[f].size(); ++slot)
        if (const int i = slot_index_[f][slot]; i >= 0)
          parameter(out[f], static_cast<int>(slot)) = y.segment<3>(i) * units::mm;
    return out;
  }

  /// Adds coefficient · nᵀ (move of sample k of fiber f) to a constraint row.
  void add_sample(int f, int k, double coefficient, const Eigen::Vector3d& n, std::map<int, double>& row) const
  {
    const Eigen::VectorXd& phi = weights_[f][k];
    for (Eigen::Index slot = 0; slot < phi.size(); ++slot)
      if (const int i = slot_index_[f][slot]; i >= 0 && phi[slot] != 0)
        for (int c = 0; c < 3; ++c) row[i + c] += coefficient * phi[slot] * n[c];
  }

  /// W of the header: Σ_k h_k |Δp_k|² + ℓ⁴ Σ_k h_k |Δp''_k|² over the samples of each fiber, with
  /// h_k the arc length a sample stands for and Δp'' the three-point second difference (mm); and
  /// its inverse. Both are block diagonal: one block per fiber, whose variables are consecutive.
  void smoothness(const FiberClearance::Lines& lines, double length, SparseMatrix& W, SparseMatrix& inverse) const
  {
    Triplets w, w_inverse;
    const double l4 = std::pow(length / units::mm, 4);
    for (std::size_t f = 0; f < slot_index_.size(); ++f) {
      const auto& phi = weights_[f];
      const std::size_t N = phi.size();
      std::vector<double> h(N - 1);
      for (std::size_t k = 0; k + 1 < N; ++k) h[k] = (lines[f][k + 1] - lines[f][k]).norm() / units::mm;
      const Eigen::Index slots = phi[0].size();
      Eigen::MatrixXd M = Eigen::MatrixXd::Zero(slots, slots);
      for (std::size_t k = 0; k < N; ++k) {
        const double hk = 0.5 * ((k > 0 ? h[k - 1] : 0) + (k + 1 < N ? h[k] : 0));
        M += hk * phi[k] * phi[k].transpose();
        if (k == 0 || k + 1 == N) continue;
        const Eigen::VectorXd second =
            2 * ((phi[k + 1] - phi[k]) / h[k] - (phi[k] - phi[k - 1]) / h[k - 1]) / (h[k] + h[k - 1]);
        M += l4 * hk * second * second.transpose();
      }
      const int first = first_[f], size = first_[f + 1] - first;
      Eigen::MatrixXd block = Eigen::MatrixXd::Zero(size, size);
      for (Eigen::Index p = 0; p < slots; ++p)
        for (Eigen::Index q = 0; q < slots; ++q) {
          const int i = slot_index_[f][p], j = slot_index_[f][q];
          if (i < 0 || j < 0) continue;
          for (int c = 0; c < 3; ++c) block(i - first + c, j - first + c) += M(p, q);
        }
      const Eigen::LLT<Eigen::MatrixXd> llt(block);
      if (llt.info() != Eigen::Success)
        throw std::runtime_error("collision resolution: the smoothness of a fiber is not positive definite");
      const Eigen::MatrixXd block_inverse = llt.solve(Eigen::MatrixXd::Identity(size, size));
      for (int i = 0; i < size; ++i)
        for (int j = 0; j < size; ++j) {
          if (block(i, j) != 0) w.emplace_back(first + i, first + j, block(i, j));
          w_inverse.emplace_back(first + i, first + j, block_inverse(i, j));
        }
    }
    W.resize(size_, size_);
    W.setFromTriplets(w.begin(), w.end());
    inverse.resize(size_, size_);
    inverse.setFromTriplets(w_inverse.begin(), w_inverse.end());
  }

private:
  static Eigen::Vector3d& parameter(Route& r, int slot) { return slot % 2 ? r.tangents[slot / 2] : r.points[slot / 2]; }
  static const Eigen::Vector3d& parameter(const Route& r, int slot)
  {
    return slot % 2 ? r.tangents[slot / 2] : r.points[slot / 2];
  }

  int size_ = 0;
  std::vector<int> first_;                            ///< [fiber] → its first variable; then the count
  std::vector<std::vector<int>> slot_index_;          ///< [fiber][slot] → first variable, or −1 (fixed)
  std::vector<std::vector<Eigen::VectorXd>> weights_; ///< [fiber][sample] → weight per slot
};

/// The linearized constraints a_iᵀ (y − z) ≥ b_i of the contacts: b_i = c_min − c_i (mm).
void linearize(const RouteVariables& v, const std::vector<Contact>& contacts, double clearance, RowMatrix& A,
               Eigen::VectorXd& b)
{
  Triplets entries;
  b.resize(static_cast<Eigen::Index>(contacts.size()));
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const Contact& c = contacts[i];
    std::map<int, double> row;
    if (c.with_skin()) {
      v.add_sample(c.a, c.segment_a, 1, c.normal, row);
    } else {
      v.add_sample(c.a, c.segment_a, 1 - c.u_a, c.normal, row);
      v.add_sample(c.a, c.segment_a + 1, c.u_a, c.normal, row);
      v.add_sample(c.b, c.segment_b, -(1 - c.u_b), c.normal, row);
      v.add_sample(c.b, c.segment_b + 1, -c.u_b, c.normal, row);
    }
    for (const auto& [j, value] : row) entries.emplace_back(static_cast<int>(i), j, value);
    // A contact that no free parameter moves (near fixed ends) cannot be helped: left to the final check.
    const bool movable = std::any_of(row.begin(), row.end(), [](const auto& e) { return e.second != 0; });
    b[static_cast<Eigen::Index>(i)] = movable ? (clearance - c.clearance) / units::mm : -HUGE_VAL;
  }
  A.resize(static_cast<Eigen::Index>(contacts.size()), v.size());
  A.setFromTriplets(entries.begin(), entries.end());
}

/// min ½ (y − y0)ᵀ W (y − y0) s.t. A (y − z) ≥ b, by an augmented Lagrangian; each inner problem
///   min φ(y) = ½ (y − y0)ᵀ W (y − y0) + μ/2 Σ_i max(0, λ_i/μ − r_i(y))²,  r = A (y − z) − b,
/// convex and piecewise quadratic, by Newton on the set P of constraints that pull, with an exact
/// line search where the full step does not descend. Returns the last y (the constraints may be
/// inconsistent: the caller measures).
///
/// The Newton matrix W + μ A_Pᵀ A_P couples every pair of fibers in contact; W is block diagonal
/// (one block per fiber), so the step goes through the contacts instead (Woodbury):
///   (W + μ A_Pᵀ A_P)⁻¹ = W⁻¹ − W⁻¹ A_Pᵀ S⁻¹ A_P W⁻¹,  S = I/μ + A_P W⁻¹ A_Pᵀ,
/// one dense Cholesky of the size of P, which is far smaller than the variables.
class QuadraticProblem {
public:
  QuadraticProblem(const SparseMatrix& W, const SparseMatrix& W_inverse, const RowMatrix& A, const Eigen::VectorXd& b,
                   const Eigen::VectorXd& y0, const Eigen::VectorXd& z)
      : W_(W), W_inverse_(W_inverse), A_(A), B_(W_inverse * SparseMatrix(A.transpose())), Q_(SparseMatrix(A) * B_),
        y0_(y0), Az_b_(A * z + b), mu_(1e4 * std::max(1.0, max_diagonal(W)))
  {
  }

  /// From y and multipliers λ (the last round's, for the contacts seen before); both updated.
  /// False when a factorization failed (a non-finite value).
  bool solve(Eigen::VectorXd& y, Eigen::VectorXd& lambda)
  {
    lambda_ = lambda;
    for (int outer = 0; outer < 50; ++outer) {
      if (!minimize(y)) return false;
      const Eigen::VectorXd r = A_ * y - Az_b_;
      // The first-order multiplier update for inequalities (Nocedal & Wright, eq. 17.65).
      lambda_ = (lambda_ - mu_ * r).cwiseMax(0.0);
      if (r.size() == 0 || r.minCoeff() > -1e-5) break; // mm: 10 nm
    }
    lambda = lambda_;
    return true;
  }

private:
  static double max_diagonal(const SparseMatrix& W) { return W.rows() ? W.diagonal().maxCoeff() : 0.0; }

  /// max(0, λ_i − μ r_i): the multiplier each constraint would take at y.
  Eigen::VectorXd pull(const Eigen::VectorXd& y) const { return (lambda_ - mu_ * (A_ * y - Az_b_)).cwiseMax(0.0); }

  double phi(const Eigen::VectorXd& y) const
  {
    const Eigen::VectorXd d = y - y0_;
    return 0.5 * d.dot(W_ * d) + pull(y).squaredNorm() / (2 * mu_);
  }

  /// The minimizer α of φ(y + α d) over α > 0: φ is piecewise quadratic along the line, so its
  /// derivative φ'(α) = C + K α is piecewise linear and non-decreasing, with breakpoints where a
  /// constraint enters or leaves the pull; walked in order until φ' changes sign.
  double exact_step(const Eigen::VectorXd& y, const Eigen::VectorXd& d) const
  {
    const Eigen::VectorXd s = A_ * d, c = lambda_ - mu_ * (A_ * y - Az_b_), Wd = W_ * d;
    double C = Wd.dot(y - y0_), K = Wd.dot(d);
    std::vector<std::pair<double, Eigen::Index>> breaks;
    for (Eigen::Index i = 0; i < s.size(); ++i) {
      if (s[i] == 0) continue;
      if (c[i] > 0 || (c[i] == 0 && s[i] < 0)) { // pulling just after α = 0
        C -= s[i] * c[i];
        K += mu_ * s[i] * s[i];
      }
      if (const double at = c[i] / (mu_ * s[i]); at > 0) breaks.emplace_back(at, i);
    }
    std::sort(breaks.begin(), breaks.end());
    for (const auto& [at, i] : breaks) {
      if (K > 0 && -C / K <= at) return std::max(0.0, -C / K);
      const double sign = c[i] > 0 ? 1.0 : -1.0; // leaves the pull, or enters it
      C += sign * s[i] * c[i];
      K -= sign * mu_ * s[i] * s[i];
    }
    return K > 0 ? std::max(0.0, -C / K) : 1.0;
  }

  /// −(W + μ A_Pᵀ A_P)⁻¹ g through the Woodbury identity of the class comment; false when S is not
  /// positive definite (a non-finite value).
  bool newton_step(const Eigen::VectorXd& g, const Eigen::VectorXd& q, Eigen::VectorXd& step)
  {
    std::vector<Eigen::Index> P;
    std::vector<Eigen::Index> position(static_cast<std::size_t>(q.size()), -1);
    for (Eigen::Index i = 0; i < q.size(); ++i)
      if (q[i] > 0) {
        position[static_cast<std::size_t>(i)] = static_cast<Eigen::Index>(P.size());
        P.push_back(i);
      }
    const auto n = static_cast<Eigen::Index>(P.size());
    Eigen::MatrixXd S = Eigen::MatrixXd::Identity(n, n) / mu_;
    for (Eigen::Index k = 0; k < n; ++k)
      for (SparseMatrix::InnerIterator e(Q_, P[static_cast<std::size_t>(k)]); e; ++e)
        if (const Eigen::Index row = position[static_cast<std::size_t>(e.row())]; row >= 0) S(row, k) += e.value();
    const Eigen::VectorXd u = W_inverse_ * g;
    const Eigen::VectorXd Au = A_ * u;
    Eigen::VectorXd v(n);
    for (Eigen::Index k = 0; k < n; ++k) v[k] = Au[P[static_cast<std::size_t>(k)]];
    llt_.compute(S);
    if (llt_.info() != Eigen::Success) return false;
    const Eigen::VectorXd w = llt_.solve(v);
    step = -u;
    for (Eigen::Index k = 0; k < n; ++k)
      for (SparseMatrix::InnerIterator e(B_, P[static_cast<std::size_t>(k)]); e; ++e) step[e.row()] += e.value() * w[k];
    return step.allFinite();
  }

  bool minimize(Eigen::VectorXd& y)
  {
    for (int iteration = 0; iteration < 100; ++iteration) {
      const Eigen::VectorXd q = pull(y);
      const Eigen::VectorXd g = W_ * (y - y0_) - A_.transpose() * q;
      if (g.lpNorm<Eigen::Infinity>() < 1e-12 * (1 + q.lpNorm<Eigen::Infinity>())) return true;
      Eigen::VectorXd step;
      if (!newton_step(g, q, step)) return false;
      // The pull may change along the step: the full step is taken when it descends (which lets
      // many constraints change at once), the exact minimizer along it otherwise.
      const double alpha = phi(y + step) < phi(y) ? 1.0 : exact_step(y, step);
      if (alpha <= 0) return true; // no descent left along the Newton step (rounding)
      y += alpha * step;
      const bool same_pull = (pull(y).array() > 0).matrix() == (q.array() > 0).matrix();
      if (std::abs(alpha - 1) < 1e-9 && same_pull) return true;
    }
    return true;
  }

  const SparseMatrix &W_, &W_inverse_;
  const RowMatrix& A_;
  const SparseMatrix B_, Q_; ///< W⁻¹ Aᵀ and A W⁻¹ Aᵀ
  const Eigen::VectorXd& y0_;
  Eigen::VectorXd Az_b_, lambda_;
  double mu_;
  Eigen::LLT<Eigen::MatrixXd> llt_;
};

std::string describe(const Contact& c, const std::vector<Route>& routes)
{
  if (c.with_skin()) return fmt::format("fiber {} and the skin", routes[c.a].name);
  return fmt::format("fibers {} and {}", routes[c.a].name, routes[c.b].name);
}

void check_end_points(const std::vector<Route>& routes, double radius, const ResolutionSettings& s)
{
  for (std::size_t a = 0; a < routes.size(); ++a)
    for (std::size_t b = a + 1; b < routes.size(); ++b)
      for (const Eigen::Vector3d& p : {routes[a].points.front(), routes[a].points.back()})
        for (const Eigen::Vector3d& q : {routes[b].points.front(), routes[b].points.back()})
          if ((p - q).norm() - 2 * radius < s.clearance - s.tolerance)
            throw CollisionError(fmt::format(
                "fibers {} and {} have fixed end points {:.2f} mm apart, at {} and {}: two muscles and their clearance "
                "need {:.2f} mm; move an end point apart in the design file",
                routes[a].name, routes[b].name, (p - q).norm() / units::mm, where_mm(p), where_mm(q),
                (2 * radius + s.clearance) / units::mm));
}

using Key = std::tuple<int, int, int>; // (a, segment or sample of a, b or −1)
Key key_of(const Contact& c) { return {c.a, c.segment_a, c.b}; }

/// The contacts whose clearance no contact of the same pair within two segments undercuts.
std::vector<Contact> local_minima(const std::vector<Contact>& contacts)
{
  std::map<Key, double> clearance;
  for (const Contact& c : contacts) clearance[key_of(c)] = c.clearance;
  std::vector<Contact> out;
  for (const Contact& c : contacts) {
    bool minimum = true;
    for (int k : {-2, -1, 1, 2})
      if (auto it = clearance.find({c.a, c.segment_a + k, c.b}); it != clearance.end() && it->second < c.clearance)
        minimum = false;
    if (minimum) out.push_back(c);
  }
  return out;
}

} // namespace

std::vector<Contact> worst_per_pair(const std::vector<Contact>& contacts)
{
  std::map<std::pair<int, int>, Contact> worst;
  for (const Contact& c : contacts)
    if (auto it = worst.find({c.a, c.b}); it == worst.end() || c.clearance < it->second.clearance)
      worst[{c.a, c.b}] = c;
  std::vector<Contact> out;
  for (const auto& [pair, c] : worst) out.push_back(c);
  return out;
}

namespace {

/// The rounds of the sequential linearization, and what they keep between them: every contact
/// seen (measured again each round, so that one pushed away does not drop out and come back) and
/// its multiplier.
class Resolver {
public:
  Resolver(const FiberClearance& measure, const std::vector<Route>& routes, const ResolutionSettings& s)
      : measure_(measure), routes_(routes), s_(s), v_(measure, routes), lines_(measure.lines(routes)),
        near_(measure.contacts(lines_, aim() + measure.radius())), y0_(v_.values(routes)), y_(y0_)
  {
    v_.smoothness(lines_, s.smoothness, W_, W_inverse_);
  }

  /// One round: measure, linearize, solve. Returns the largest parameter change (mm).
  double round()
  {
    std::vector<Contact> contacts = local_minima(near_);
    std::set<Key> fresh;
    for (const Contact& c : contacts) fresh.insert(key_of(c));
    for (const Key& k : seen_)
      if (!fresh.count(k))
        contacts.push_back(measure_.remeasure(lines_, std::get<0>(k), std::get<1>(k), std::get<2>(k)));
    for (const Contact& c : contacts) {
      seen_.insert(key_of(c));
      moved_.insert(c.a);
      if (!c.with_skin()) moved_.insert(c.b);
    }
    RowMatrix A;
    Eigen::VectorXd b;
    linearize(v_, contacts, aim(), A, b);
    Eigen::VectorXd lambda(A.rows()), next = y_;
    for (std::size_t i = 0; i < contacts.size(); ++i) {
      const auto it = multipliers_.find(key_of(contacts[i]));
      lambda[static_cast<Eigen::Index>(i)] = it == multipliers_.end() ? 0.0 : it->second;
    }
    if (!QuadraticProblem(W_, W_inverse_, A, b, y0_, y_).solve(next, lambda))
      throw std::runtime_error("collision resolution: a factorization failed (non-finite values in the routes?)");
    for (std::size_t i = 0; i < contacts.size(); ++i)
      multipliers_[key_of(contacts[i])] = lambda[static_cast<Eigen::Index>(i)];
    const double step = (next - y_).lpNorm<Eigen::Infinity>();
    y_ = next;
    lines_ = measure_.lines(current());
    near_ = measure_.contacts(lines_, aim() + measure_.radius());
    return step;
  }

  /// The smallest clearance now, among contacts within reach of the aim.
  double smallest() const { return smallest_clearance(near_); }
  double aim() const { return s_.clearance + s_.room; }

  /// The routes now; fibers that no contact involved are the originals, bit for bit.
  std::vector<Route> current() const
  {
    std::vector<Route> out = v_.routes(y_, routes_);
    for (int f = 0; f < measure_.num_fibers(); ++f)
      if (!moved_.count(f)) out[f] = routes_[f];
    return out;
  }

private:
  const FiberClearance& measure_;
  const std::vector<Route>& routes_;
  const ResolutionSettings& s_;
  RouteVariables v_;
  FiberClearance::Lines lines_;
  std::vector<Contact> near_; ///< measured at lines_, within reach of the aim
  SparseMatrix W_, W_inverse_;
  Eigen::VectorXd y0_, y_;
  std::set<Key> seen_;
  std::map<Key, double> multipliers_;
  std::set<int> moved_;
};

[[noreturn]] void impossible(const std::vector<Contact>& left, const std::vector<Route>& routes, double clearance)
{
  const Contact& worst = *std::min_element(
      left.begin(), left.end(), [](const Contact& x, const Contact& y) { return x.clearance < y.clearance; });
  throw CollisionError(fmt::format(
      "{} cannot be given {:.2f} mm of clearance near {}: the most found there is {:.2f} mm{}", describe(worst, routes),
      clearance / units::mm, where_mm(worst.point_a), worst.clearance / units::mm,
      worst.with_skin() ? "; the body is too thin there for the muscle and its clearance"
                        : "; the passage is narrower than two muscles and their clearance, or the fibers are locked "
                          "together by their fixed end points"));
}

} // namespace

CollisionResolution resolve_collisions(const FiberClearance& measure, const std::vector<Route>& routes,
                                       const ResolutionSettings& s)
{
  CollisionResolution result;
  result.routes = routes;
  const std::vector<Contact> near = measure.contacts(routes, s.clearance + measure.radius());
  result.before = result.after = smallest_clearance(near);
  std::vector<Contact> short_of;
  for (const Contact& c : near)
    if (c.clearance < s.clearance - s.tolerance) short_of.push_back(c);
  result.collided = worst_per_pair(short_of);
  if (short_of.empty()) return result;
  check_end_points(routes, measure.radius(), s);

  Resolver resolver(measure, routes, s);
  double last_step = HUGE_VAL;
  for (result.iterations = 1; result.iterations <= s.max_iterations; ++result.iterations) {
    const double step = resolver.round();
    result.after = resolver.smallest();
    // Done when every clearance holds and the routes stop moving, or only flip between two
    // linearizations (a closest point hopping between neighbouring segments moves them by µm).
    const bool flipping = step < 0.05 && step > 0.9 * last_step; // mm
    if (result.after >= resolver.aim() - s.tolerance && (step < 1e-4 || flipping)) break;
    last_step = step;
  }
  result.routes = resolver.current();
  result.changed = true;
  const std::vector<Contact> left = measure.contacts(result.routes, s.clearance - s.tolerance);
  if (!left.empty()) impossible(left, routes, s.clearance);
  return result;
}

} // namespace fibermold
