#include "molds/part_checks.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <Eigen/Geometry>
#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "core/units.hpp"
#include "mesh/surface_check.hpp"
#include "mesh/surface_distance.hpp"
#include "molds/mesh_boolean.hpp"

namespace fibermold {

namespace {

/// How far a ray from inside a part goes to the opposite side of the wall: the first surface it
/// leaves through, unless it leaves through a face more than 53° off its direction (cos = 0.6). That
/// face meets the ray's own at an edge of more than 53°, a corner of the part (where a cavity's wall
/// meets the parting face, or a level-set mesh's step a few µm high), which is no wall; knife edges
/// sharper than about 45° still count (most of the cone's rays see their far side). The cone's rays,
/// 30° off the inward normal, see a face at a right angle to their own at 60° at least.
double through_wall(const SurfaceDistance& surface, const Eigen::Vector3d& origin, const Eigen::Vector3d& direction)
{
  const SurfaceDistance::Hit hit = surface.ray_hit(origin, direction, 1e-7);
  return hit.normal.dot(direction) >= 0.6 ? hit.distance : HUGE_VAL;
}

/// Wall thickness at a face, as the shape diameter function does it: the median over a cone of
/// rays into the material (the inward normal and 8 rays 30° off it) of the distance to the opposite
/// surface projected on the normal. A single ray would see the facets of a voxelized surface as
/// walls a few µm thick.
double cone_thickness(const SurfaceDistance& surface, const Eigen::Vector3d& centre, const Eigen::Vector3d& inward)
{
  const Eigen::Vector3d u = inward.unitOrthogonal(), w = inward.cross(u);
  const double tilt = M_PI / 6;
  std::vector<double> d{through_wall(surface, centre, inward)};
  for (int k = 0; k < 8; ++k) {
    const double a = 2 * M_PI * k / 8;
    const Eigen::Vector3d dir = std::cos(tilt) * inward + std::sin(tilt) * (std::cos(a) * u + std::sin(a) * w);
    d.push_back(through_wall(surface, centre, dir) * std::cos(tilt));
  }
  std::nth_element(d.begin(), d.begin() + 4, d.end());
  return d[4];
}

/// The thinnest wall: each face's inward ray, confirmed by the cone where it looks thin. Faces in
/// parallel; the first face (by index) of the least thickness wins, so the answer does not depend on
/// the threads.
double thinnest_wall(const SurfaceMesh& m, double min_wall, Eigen::Vector3d& where)
{
  const SurfaceDistance surface(m.vertices, m.faces);
  if (m.num_faces() == 0) return HUGE_VAL;
  surface.ray_distance(m.vertices.row(0),
                       Eigen::Vector3d::UnitZ()); // builds the search trees before the threads share them
  struct Thinnest {
    double thickness = HUGE_VAL;
    Eigen::Index face = -1;
    bool operator<(const Thinnest& o) const
    {
      return thickness < o.thickness || (thickness == o.thickness && face < o.face);
    }
  };
  const auto centre_of = [&](Eigen::Index f) {
    return Eigen::Vector3d(
        (m.vertices.row(m.faces(f, 0)) + m.vertices.row(m.faces(f, 1)) + m.vertices.row(m.faces(f, 2))) / 3);
  };
  const Thinnest best = tbb::parallel_reduce(
      tbb::blocked_range<Eigen::Index>(0, m.num_faces(), 1024), Thinnest{},
      [&](const tbb::blocked_range<Eigen::Index>& range, Thinnest t) {
        for (Eigen::Index f = range.begin(); f != range.end(); ++f) {
          const Eigen::Vector3d a = m.vertices.row(m.faces(f, 0)), b = m.vertices.row(m.faces(f, 1)),
                                c = m.vertices.row(m.faces(f, 2));
          const Eigen::Vector3d n = (b - a).cross(c - a);
          if (!(n.norm() > 0)) continue;
          const Eigen::Vector3d centre = centre_of(f), inward = -n.normalized();
          double d = through_wall(surface, centre, inward);
          // A short ray, or one that left through a steep face (a corner, or a tilted facet of a
          // thin wall): the cone decides.
          if (d < min_wall || !std::isfinite(d)) d = cone_thickness(surface, centre, inward);
          t = std::min(t, Thinnest{d, f});
        }
        return t;
      },
      [](const Thinnest& x, const Thinnest& y) { return std::min(x, y); });
  if (best.face >= 0) where = centre_of(best.face);
  return best.thickness;
}

/// The part as its STL file holds it: coordinates as float32 millimetres. Its measures do not depend
/// on the last bits of the booleans' arithmetic, which vary from run to run (CGAL's corefinement),
/// so that the same design gives the same report, and they are the printed part's.
SurfaceMesh as_written(SurfaceMesh m)
{
  m.vertices = (m.vertices / units::mm).cast<float>().cast<double>() * units::mm;
  return m;
}

} // namespace

std::optional<Eigen::Vector3i> printer_orientation(const Eigen::Vector3d& size, const Eigen::Vector3d& printer)
{
  // The 6 axis-aligned orientations: which part axis goes along the printer's x, y, z; the lowest
  // build height among those that fit.
  std::array<int, 3> axes{0, 1, 2};
  double best = HUGE_VAL;
  std::optional<Eigen::Vector3i> out;
  do {
    const Eigen::Vector3d s(size[axes[0]], size[axes[1]], size[axes[2]]);
    if ((s.array() <= printer.array()).all() && s.z() < best) {
      best = s.z();
      out = Eigen::Vector3i(axes[0], axes[1], axes[2]);
    }
  } while (std::next_permutation(axes.begin(), axes.end()));
  return out;
}

PartCheck check_part(const SurfaceMesh& part, double min_wall, const Eigen::Vector3d& printer)
{
  PartCheck out;
  const SurfaceCheck surface = check_surface(part);
  for (const SurfaceProblem& p : surface.problems)
    out.problems.push_back(fmt::format("{}, e.g. near ({:.1f}, {:.1f}, {:.1f}) mm", p.message, p.where.x() / units::mm,
                                       p.where.y() / units::mm, p.where.z() / units::mm));
  const SurfaceMesh written = as_written(part);
  out.volume = signed_volume(written);
  out.size = written.vertices.colwise().maxCoeff() - written.vertices.colwise().minCoeff();
  const auto orientation = printer_orientation(out.size, printer);
  out.fits = orientation.has_value();
  if (orientation) out.orientation = *orientation;
  if (!out.fits)
    out.problems.push_back(fmt::format("is {} and does not fit the printer's {} in any of the 6 orientations",
                                       format_size_mm(out.size), format_size_mm(printer)));
  if (!surface.ok()) return out; // the rest needs a valid solid
  if (const int shells = count_shells(part); shells != 1)
    out.problems.push_back(fmt::format("is {} separate pieces or has a closed void, not one solid", shells));
  Eigen::Vector3d where = Eigen::Vector3d::Zero();
  out.min_thickness = thinnest_wall(written, min_wall, where);
  out.min_thickness_at = where;
  out.thin_wall = out.min_thickness < min_wall * (1 - 1e-6);
  if (out.thin_wall)
    out.problems.push_back(fmt::format(
        "has a wall of {:.2f} mm near ({:.1f}, {:.1f}, {:.1f}) mm, thinner than [export] min_wall = {:.2f} mm",
        out.min_thickness / units::mm, where.x() / units::mm, where.y() / units::mm, where.z() / units::mm,
        min_wall / units::mm));
  return out;
}

} // namespace fibermold
