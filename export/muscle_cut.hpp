#pragma once
// What to cut and fit for each muscle before it is laid into its groove: its length inside the body,
// and which of its ends takes the supply tube (an end where it leaves the body, the one nearest the
// robot's mount) and which is sealed. The paper's robots: "a Luer Lock fitting to one end and sealing
// the other" (section VIII).

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mesh/surface_distance.hpp"

namespace fibermold {

struct MuscleEnd {
  Eigen::Vector3d at;         ///< m, the centre line's end
  bool leaves_body = false;   ///< within the groove's reach of the skin: the molds give it a channel out
  Eigen::Vector3d skin_point; ///< m, where it meets the skin (its nearest skin point)
};

struct MuscleCut {
  std::string name;
  double length = 0;        ///< m, of the whole centre line
  double length_inside = 0; ///< m, of its stretches inside the body: the muscle's cut length
  MuscleEnd start, end;
  /// 0: the start takes the supply tube, 1: the end; nullopt: neither end leaves the body.
  std::optional<int> supply;

  /// The end that takes the supply tube, and the one sealed; only when `supply` is set.
  const MuscleEnd& supply_end() const { return *supply == 0 ? start : end; }
  const MuscleEnd& sealed_end() const { return *supply == 0 ? end : start; }
};

/// The cut of the muscle along `centre_line` (points at most a fraction of a millimetre apart): an end
/// leaves the body when it is within `reach` of the skin (the groove's radius: molds' end channels use
/// the same rule); of two such ends the one nearer `mount` (the [[fixed]] regions' centroid; none: the
/// start) takes the supply tube.
MuscleCut muscle_cut(std::string name, const std::vector<Eigen::Vector3d>& centre_line, const SurfaceDistance& skin,
                     double reach, const std::optional<Eigen::Vector3d>& mount);

} // namespace fibermold
