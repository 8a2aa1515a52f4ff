// The collide stage's clearance measure and resolution for 2, 8 and 32 fibers of 200 samples each:
// half of them run along x, half along y, 1 mm apart where they cross (every x fiber crosses every
// y fiber), in a 140 × 140 × 60 mm block. Goal: ≤ 1 s for 32 fibers.
//   build/bench/collide_bench
#include <chrono>
#include <cstdio>

#include "core/units.hpp"
#include "optimize/collision_resolution.hpp"
#include "primitives.hpp"

namespace fibermold {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

Eigen::Vector3d mm(double x, double y, double z) { return Eigen::Vector3d(x, y, z) * units::mm; }

/// `n` fibers 100 mm long with 5 control points: n/2 along x at z = −0.5 mm, n/2 along y at +0.5 mm,
/// 6 mm apart side by side.
std::vector<Route> grid(int n)
{
  std::vector<Route> routes;
  const int half = n / 2;
  for (int i = 0; i < n; ++i) {
    const bool along_x = i < half;
    const double offset = 6.0 * ((along_x ? i : i - half) - (half - 1) / 2.0);
    std::vector<Eigen::Vector3d> points;
    for (int k = 0; k < 5; ++k) {
      const double s = -50 + 25.0 * k;
      points.push_back(along_x ? mm(s, offset, -0.5) : mm(offset, s, 0.5));
    }
    const HermiteSpline spline(points);
    std::string name(1, along_x ? 'x' : 'y');
    name += std::to_string(i);
    routes.push_back({name, spline.points(), spline.tangents()});
  }
  return routes;
}

} // namespace
} // namespace fibermold

int main()
{
  using namespace fibermold;
  const SurfaceMesh block = test::box(mm(-70, -70, -30), mm(70, 70, 30), 8);
  const SurfaceDistance skin(block.vertices, block.faces);
  const double radius = 1.5e-3, clearance = 1e-3, samples_per_length = 1990; // 200 samples on 100 mm
  std::printf(
      "| fibers | samples/fiber | contacts | measure (ms) | resolve (s) | rounds | clearance before → after (mm) |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  for (int n : {2, 8, 32}) {
    const std::vector<Route> routes = grid(n);
    const FiberClearance measure(skin, routes, radius, clearance, samples_per_length);
    const int repeats = 20;
    auto t = Clock::now();
    std::size_t contacts = 0;
    for (int r = 0; r < repeats; ++r) contacts = measure.contacts(routes, clearance).size();
    const double measure_ms = 1e3 * since(t) / repeats;
    ResolutionSettings s;
    s.clearance = clearance;
    t = Clock::now();
    const CollisionResolution result = resolve_collisions(measure, routes, s);
    const double resolve_s = since(t);
    std::printf("| %d | %zu | %zu | %.2f | %.3f | %d | %.3f → %.3f |\n", n, measure.parameters(0).size(), contacts,
                measure_ms, resolve_s, result.iterations, result.before / units::mm, result.after / units::mm);
  }
}
