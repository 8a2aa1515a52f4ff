#include "design/undeclared_value.hpp"

#include <fmt/format.h>

namespace fibermold {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// A polyline's points (a fiber's, a tracking curve's): two, so that it is a line, of NaN.
void make_undeclared_line(std::vector<Vec3>& points) { points.assign(2, Vec3::Constant(kNaN)); }

} // namespace

std::string undeclared_text(std::string_view key) { return fmt::format("<undeclared {}>", key); }

void make_undeclared(double& v, std::string_view) { v = kNaN; }
void make_undeclared(int& v, std::string_view) { v = kUndeclaredInt; }
void make_undeclared(bool&, std::string_view) {}
void make_undeclared(std::string& v, std::string_view key) { v = undeclared_text(key); }
void make_undeclared(std::filesystem::path& v, std::string_view key) { v = undeclared_text(key); }
void make_undeclared(Eigen::Vector3d& v, std::string_view) { v.setConstant(kNaN); }

void make_undeclared(TwoPieceLine& v, std::string_view) { v = {kNaN, kNaN, kNaN, kNaN}; }

void make_undeclared(PartingPlane& v, std::string_view key)
{
  make_undeclared(v.point, key);
  make_undeclared(v.normal, key);
}

void make_undeclared(Region& v, std::string_view key)
{
  make_undeclared(v.box, key);
  make_undeclared(v.vertices, key);
  make_undeclared(v.point, key);
}

void make_undeclared(FixedRegion& v, std::string_view key)
{
  make_undeclared(v.name, key);
  make_undeclared(v.region, key);
}

void make_undeclared(Fiber& v, std::string_view key)
{
  make_undeclared(v.name, key);
  make_undeclared_line(v.points);
  make_undeclared_line(v.tangents);
}

void make_undeclared(TrackingCurve& v, std::string_view key)
{
  make_undeclared(v.name, key);
  make_undeclared_line(v.points);
  make_undeclared(v.samples, key);
  make_undeclared(v.weight_position, key);
  make_undeclared(v.weight_orientation, key);
}

void make_undeclared(Load& v, std::string_view key)
{
  make_undeclared(v.region, key);
  make_undeclared(v.force, key);
  make_undeclared(v.torque, key);
}

void make_undeclared(FiberActuation& v, std::string_view key)
{
  make_undeclared(v.name, key);
  make_undeclared_line(v.points);
  make_undeclared(v.pressure, key);
}

void make_undeclared(Pose& v, std::string_view key)
{
  make_undeclared(v.region, key);
  make_undeclared(v.axis, key);
  make_undeclared(v.angle, key);
  make_undeclared(v.about, key);
  make_undeclared(v.translation, key);
  make_undeclared(v.curl_from, key);
}

void make_undeclared(Target& v, std::string_view key)
{
  make_undeclared(v.name, key);
  make_undeclared(v.kind, key);
  make_undeclared(v.loads, key);
  make_undeclared(v.surface, key);
  make_undeclared(v.strain_penalty, key);
  make_undeclared(v.fibers, key);
  make_undeclared(v.poses, key);
  make_undeclared(v.actuators, key);
  make_undeclared(v.weight, key);
}

} // namespace fibermold
