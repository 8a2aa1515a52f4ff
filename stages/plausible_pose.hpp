#pragma once
// A plausible pose: the rigid motion a pose target asks of its region keeps it within reach of
// the body (checked by the targets stage and by `fibermold check`).

#include <string>

#include <Eigen/Core>

#include "design/design.hpp"

namespace fibermold {

/// Refuses a pose that moves a point of its region (rows, m) more than twice the diagonal of the
/// body (rows, m) away: a wrong unit or a misplaced `about`, which no soft body follows.
void require_plausible_pose(const Design& d, const std::string& key, const Pose& p, const Eigen::MatrixX3d& region,
                            const Eigen::MatrixX3d& body);

} // namespace fibermold
