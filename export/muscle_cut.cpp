#include "export/muscle_cut.hpp"

namespace fibermold {

MuscleCut muscle_cut(std::string name, const std::vector<Eigen::Vector3d>& centre_line, const SurfaceDistance& skin,
                     double reach, const std::optional<Eigen::Vector3d>& mount)
{
  MuscleCut cut{std::move(name), 0, 0, {}, {}, std::nullopt};
  if (centre_line.empty()) return cut;
  for (std::size_t i = 1; i < centre_line.size(); ++i) {
    const double step = (centre_line[i] - centre_line[i - 1]).norm();
    cut.length += step;
    if (skin.closest(0.5 * (centre_line[i] + centre_line[i - 1])).inside) cut.length_inside += step;
  }
  const auto end_of = [&](const Eigen::Vector3d& p) {
    const SurfaceDistance::Closest c = skin.closest(p);
    return MuscleEnd{p, c.distance < reach, c.point};
  };
  cut.start = end_of(centre_line.front());
  cut.end = end_of(centre_line.back());
  if (cut.start.leaves_body && cut.end.leaves_body)
    cut.supply = mount && (cut.end.skin_point - *mount).norm() < (cut.start.skin_point - *mount).norm() ? 1 : 0;
  else if (cut.start.leaves_body || cut.end.leaves_body)
    cut.supply = cut.start.leaves_body ? 0 : 1;
  return cut;
}

} // namespace fibermold
