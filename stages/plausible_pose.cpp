#include "stages/plausible_pose.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "core/input_error.hpp"
#include "core/units.hpp"
#include "sim/rigid_motion.hpp"

namespace fibermold {

void require_plausible_pose(const Design& d, const std::string& key, const Pose& p, const Eigen::MatrixX3d& region,
                            const Eigen::MatrixX3d& body)
{
  if (region.rows() == 0) return;
  const Eigen::Vector3d about = p.about ? *p.about : Eigen::Vector3d(region.colwise().mean().transpose());
  const Eigen::Vector3d translation =
      p.curl_from ? uniform_curl_translation(*p.curl_from, about, p.axis, p.angle) : p.translation;
  const RigidMotion m = rotation_about(p.axis, p.angle, about, translation);
  double farthest = 0;
  for (Eigen::Index i = 0; i < region.rows(); ++i)
    farthest = std::max(farthest, (m.apply(region.row(i).transpose()) - region.row(i).transpose()).norm());
  const double size = (body.colwise().maxCoeff() - body.colwise().minCoeff()).norm();
  if (farthest > 2 * size)
    throw InputError(
        design_problem(d, key,
                       fmt::format("the pose moves the region up to {:.4g} mm, more than twice the body's {:.4g} "
                                   "mm diagonal: no soft body gets there; check `about`, `translation` and "
                                   "`curl_from` (mm)",
                                   farthest / units::mm, size / units::mm)));
}

} // namespace fibermold
