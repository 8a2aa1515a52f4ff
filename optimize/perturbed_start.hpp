#pragma once
// The other starts of a multi-start optimization (`[optimize] starts`): the first guess with its
// routes' interior control points moved and their tangents turned at random, so that a run from
// each may end in another local minimum of eq. 4, and the best of them is kept. A start must be a
// design the optimizer accepts (inside the body, clear of the skin, within the bend radius, fibers
// apart): the perturbation is halved until RoutingProblem::regularizer_value scores it finite.

#include "optimize/routing.hpp"

namespace fibermold {

class RoutingProblem;

/// Start `k` (k ≥ 1; k = 0 is `start` itself): each interior control point of each route of `start`
/// moved by a random vector of `spread` RMS per coordinate (m), each tangent by one of 0.2 of its
/// length, from a generator seeded by k (the same design gives the same starts on any machine),
/// halved up to 10 times until the problem accepts it; `start` when it never does. Pressures are
/// `start`'s. Leaves `problem`'s base at `start` and its routes (not its pressures) free.
Routing perturbed_start(RoutingProblem& problem, const Routing& start, int k, double spread);

} // namespace fibermold
