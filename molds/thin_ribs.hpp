#pragma once
// Thin ribs: where a mold half stands deep into its cavity in a thin wall (the mold's side of a
// narrow slot in the body, or of a narrow gap between two of its parts). Without a draft such a
// printed rib can break, or tear the cast, as the half comes off. Found on the half's floor: seen
// along the half's pull, each column of the half ends where the cavity begins (a ray cast down onto
// the cavity, or the parting plane where the cavity lies below it), which makes a height map; its
// morphological closing with a disk of diameter `thickness` fills the valleys narrower than that, the
// ribs, and the closing less the map is how deep each stands. A rib is reported when it stands deeper
// than `aspect` times its thickness (twice the largest distance from a point of it to its edge on the
// map).

#include <vector>

#include <Eigen/Core>

#include "core/progress.hpp"
#include "mesh/surface_mesh.hpp"
#include "molds/parting.hpp"

namespace fibermold {

/// Ribs thinner than this (m) are thin: a printed wall of 3 mm stands firm.
inline constexpr double kThinRib = 3e-3;
/// A thin rib deeper than this many times its thickness may break or tear the cast without draft.
inline constexpr double kDeepRibAspect = 3;

struct ThinRib {
  bool upper = true;                            ///< in the upper half (along +pull); false: the lower
  Eigen::Vector3d at = Eigen::Vector3d::Zero(); ///< m: its deepest point, where it meets the cavity
  double thickness = 0;                         ///< m
  double depth = 0;                             ///< m, from the half's floor beside it to its tip
};

/// The thin deep ribs of both halves of the mold of `cavity` parted at `parting`, deepest first;
/// the height maps sampled every `cell` (m). Throws Interrupted when `progress` says so.
std::vector<ThinRib> thin_ribs(const SurfaceMesh& cavity, const Parting& parting, double cell,
                               Progress* progress = nullptr, double thickness = kThinRib,
                               double aspect = kDeepRibAspect);

} // namespace fibermold
