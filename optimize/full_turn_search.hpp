#pragma once
// The pressure that turns a pose region its whole angle: every pressure of a target scaled by one
// factor s, and the turn θ(s) of the region about the axis asked found by the secant method,
//   s_{k+1} = s_k + (θ* − θ(s_k)) (s_k − s_{k−1}) / (θ(s_k) − θ(s_{k−1})),
// from two scales already solved (collide's sensitivity: the pressures 10 % lower and higher), at
// most `most` (max_pressure over the highest pressure). The turn of a soft body grows faster than
// the pressure: on the test bar one secant step from the ±10 % turns fell 20 % short of the angle.

#include <functional>
#include <optional>

namespace fibermold {

struct FullTurnOptions {
  int solves = 4;          ///< at most this many turns θ(s) solved
  double tolerance = 0.02; ///< stop within this share of the angle
};

struct FullTurn {
  double scale = 0;     ///< of every pressure
  double turn = 0;      ///< θ(scale), rad
  bool at_most = false; ///< scale is `most`: the highest pressure at max_pressure
  bool reached = false; ///< |θ − θ*| ≤ tolerance |θ*|
};

/// The solved scale whose turn is nearest `angle` (θ*, rad, not 0), from the two points (s0, a0)
/// and (s1, a1); `turn_at(s)` solves θ(s) and throws std::runtime_error where it finds no
/// equilibrium (the search ends there; Interrupted passes through). None where no scale was solved: the turn does not
/// grow toward the angle between the two points, or the first solve failed.
std::optional<FullTurn> full_turn_search(double angle, double s0, double a0, double s1, double a1, double most,
                                         const std::function<double(double)>& turn_at,
                                         const FullTurnOptions& options = {});

} // namespace fibermold
