#include "design/unlikely_values.hpp"

#include <cmath>
#include <string>

#include <fmt/format.h>

#include "core/units.hpp"

namespace fibermold {

namespace {
/// The extent (m) of a list of points: its bounding box's diagonal.
double span(const std::vector<Vec3>& points)
{
  if (points.empty()) return 0;
  Vec3 lo = points.front(), hi = points.front();
  for (const Vec3& p : points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  return (hi - lo).norm();
}

/// Whether `key` was written in the design file (not left at its default).
bool given(const Design& d, const std::string& key) { return d.places.contains(key); }

void tiny_span(const Design& d, const std::string& key, const char* what, const std::vector<Vec3>& points,
               std::vector<Diagnostic>& out)
{
  const double s = span(points);
  if (points.size() >= 2 && s < kLeastLikelySpanMm * units::mm)
    out.push_back(design_problem(
        d, key,
        fmt::format("the {}'s points span {:.3g} mm, less than any muscle or body part: the design file's "
                    "coordinates are in mm (if these are metres, they span {:.3g} mm)",
                    what, s / units::mm, s / units::mm * 1000)));
}

/// A key the design file gives, with a value (in the file's unit) under `least`: likely written in the
/// unit a thousand times larger. `what` formats the value and the value × 1000.
void thousandfold(const Design& d, const std::string& key, double value, double least,
                  fmt::format_string<double, double> what, std::vector<Diagnostic>& out)
{
  if (given(d, key) && value > 0 && value < least)
    out.push_back(design_problem(d, key, fmt::format(what, double{value}, value * 1000)));
}
} // namespace

std::vector<Diagnostic> unlikely_values(const Design& d)
{
  std::vector<Diagnostic> out;
  thousandfold(d, "[muscle].max_pressure", d.muscle.max_pressure / units::kPa, kLeastLikelyPressureKPa,
               "{:g} kPa is less than a pneumatic muscle works at (tens to hundreds of kPa): the design file's "
               "pressures are in kPa (if this is MPa, write {:g})",
               out);
  thousandfold(d, "[material].youngs_modulus", d.material.youngs_modulus, kLeastLikelyModulusPa,
               "{:g} Pa is softer than any casting silicone (Ecoflex 00-10 is about 22,000 Pa): the design file's "
               "modulus is in Pa (if this is kPa, write {:g})",
               out);
  thousandfold(d, "[material].density", d.material.density, kLeastLikelyDensity,
               "{:g} kg/m³ is lighter than any silicone (about 1,000–1,500 kg/m³): the design file's density is in "
               "kg/m³ (if this is g/cm³, write {:g})",
               out);
  for (const Fiber& f : d.fibers) tiny_span(d, fmt::format("[fiber.{}].points", f.name), "route", f.points, out);
  for (const TrackingCurve& c : d.tracking_curves)
    tiny_span(d, fmt::format("[tracking_curve.{}].points", c.name), "tracking curve", c.points, out);
  for (const Target& t : d.targets)
    for (std::size_t i = 0; i < t.poses.size(); ++i) {
      const Pose& p = t.poses[i];
      const std::string pose = fmt::format("[target.{}].pose[{}]", t.name, i + 1);
      const double deg = std::abs(p.angle) / units::degree;
      if (deg > 0 && deg < kLeastLikelyTurnDeg)
        out.push_back(design_problem(
            d, pose + ".angle_deg",
            fmt::format("a turn of {:g}° is smaller than a soft robot's pose is asked: angle_deg is in degrees (if "
                        "this is radians, write {:.1f})",
                        p.angle / units::degree, p.angle / units::degree / units::degree)));
      const double move = p.translation.norm();
      if (!p.curl_from && move > 0 && move < kLeastLikelyTranslationMm * units::mm)
        out.push_back(design_problem(
            d, pose + ".translation",
            fmt::format("a translation of {:.3g} mm is smaller than a soft robot's pose is asked: translation is in "
                        "mm (if this is metres, it is {:.3g} mm)",
                        move / units::mm, move / units::mm * 1000)));
    }
  return out;
}

} // namespace fibermold
