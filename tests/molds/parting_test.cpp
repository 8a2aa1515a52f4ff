// The parting plane's sense of pull: a gripper-like finger (flat palm, deep slots on its back, the
// muscle near the palm) parted with the grooves opening toward the back leaves the lower half a plate
// under the grooves; opening them toward the palm, the plane sits between the grooves and the slots'
// floors, and both halves are deep. A body where both senses part alike keeps the given one.
#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "molds/parting.hpp"
#include "primitives.hpp"

namespace fibermold {
namespace {

constexpr double mm = 1e-3;

/// 115 × 30 × 20 mm of 2.5 mm cubes from the origin, the palm at z = 0; six slots 5 mm wide and
/// 12.5 mm deep in its back, every 15 mm from x = 20 mm.
SurfaceMesh slotted_finger()
{
  return test::voxel_body({0, -15 * mm, 0}, 2.5 * mm, {46, 12, 8}, [](int i, int, int k) {
    const bool slot = i >= 8 && i < 44 && (i - 8) % 6 < 2 && k >= 3;
    return !slot;
  });
}

TEST(PullSense, AFingerWithItsMuscleNearThePalmIsPartedWithTheGroovesOpeningTowardThePalm)
{
  const SurfaceMesh finger = slotted_finger();
  const std::vector<std::vector<Eigen::Vector3d>> fibers{
      {{0, 0, 4 * mm}, {57.5 * mm, 0, 4 * mm}, {115 * mm, 0, 4 * mm}}};
  const double radius = 1.8 * mm;
  const PullSense up = pull_sense(finger, fibers, radius, {0, 0, 1}),
                  down = pull_sense(finger, fibers, radius, {0, 0, -1});
  std::printf(
      "pull +z: plane at z = %.2f mm, shallower half %.2f mm, undercut %.2f mm²; pull -z: z = %.2f mm, %.2f mm, "
      "%.2f mm²\n",
      up.parting.point.z() / mm, up.thinner_half / mm, up.parting.undercut_area / 1e-6, down.parting.point.z() / mm,
      down.thinner_half / mm, down.parting.undercut_area / 1e-6);
  // +z: under the grooves' bottoms, 4 − 1.8 = 2.2 mm, in the middle of [0, 2.2].
  EXPECT_NEAR(up.parting.point.z(), 1.1 * mm, 0.01 * mm);
  EXPECT_NEAR(up.thinner_half, 1.1 * mm, 0.01 * mm);
  // −z: above the grooves' bottoms, 4 + 1.8 = 5.8 mm, and below the slots' floors, 7.5 mm.
  EXPECT_NEAR(down.parting.point.z(), 6.65 * mm, 0.01 * mm);
  EXPECT_NEAR(down.thinner_half, 6.65 * mm, 0.01 * mm);
  EXPECT_NEAR(up.parting.undercut_area, 0, 1e-12);
  EXPECT_NEAR(down.parting.undercut_area, 0, 1e-12);

  const std::vector<PullSense> chosen = choose_pull_sense(finger, fibers, radius, {0, 0, 1}, kUndercutWarning);
  ASSERT_EQ(chosen.size(), 2u);
  EXPECT_NEAR(chosen.front().pull.z(), -1, 1e-12);
  // Given −z to begin with, it stays.
  EXPECT_NEAR(choose_pull_sense(finger, fibers, radius, {0, 0, -1}, kUndercutWarning).front().pull.z(), -1, 1e-12);
}

TEST(PullSense, ABarWithItsMuscleOnTheAxisKeepsThePullAsGiven)
{
  const SurfaceMesh bar = test::box({0, -8 * mm, -8 * mm}, {60 * mm, 8 * mm, 8 * mm});
  const std::vector<std::vector<Eigen::Vector3d>> fibers{{{0, 0, 0}, {60 * mm, 0, 0}}};
  const std::vector<PullSense> chosen = choose_pull_sense(bar, fibers, 1.8 * mm, {0, 0, 1}, kUndercutWarning);
  EXPECT_NEAR(chosen.front().pull.z(), 1, 1e-12);
  EXPECT_NEAR(chosen.front().thinner_half, 3.1 * mm, 0.01 * mm); // the middle of [−8, −1.8] mm
}

/// `m` with a lone triangle of about 0.001 mm² (projected) tilted 45° at height z, facing up or
/// down: what a meshed level set's facets leave along a wall.
void add_facet(SurfaceMesh& m, double z, bool up)
{
  const Eigen::Vector3d a(50 * mm, -0.5 * mm, z), b = a + Eigen::Vector3d(0.05 * mm, 0, 0),
                                                  c = a + Eigen::Vector3d(0, 0.04 * mm, 0.04 * mm);
  const bool faces_up = (b - a).cross(c - a).z() > 0;
  const Eigen::Index n = m.num_vertices();
  m.vertices.conservativeResize(n + 3, 3);
  m.vertices.row(n) = a, m.vertices.row(n + 1) = faces_up == up ? b : c, m.vertices.row(n + 2) = faces_up == up ? c : b;
  m.faces.conservativeResize(m.num_faces() + 1, 3);
  m.faces.row(m.num_faces() - 1) = Eigen::RowVector3i(int(n), int(n + 1), int(n + 2));
}

// A plate 12 mm thick whose walls carry two facets: one facing down at 0.5 mm and one up at 0.6 mm.
// Between them nothing is an undercut; elsewhere a thousandth of a mm². The plane goes through the
// middle of the plate, not between the facets (it went to 0.55 mm: a starfish's lower half was a
// 0.4 mm plate), and says the undercut it has there.
TEST(ChooseParting, UndercutsThatDifferByFacetsAlonePartInTheMiddleOfTheirRange)
{
  SurfaceMesh plate = test::box({0, 0, 0}, {100 * mm, 100 * mm, 12 * mm});
  add_facet(plate, 0.5 * mm, false);
  add_facet(plate, 0.6 * mm, true);
  const Parting p = choose_parting(plate, {0, 0, 1});
  EXPECT_NEAR(p.point.z(), 6 * mm, 0.01 * mm);
  EXPECT_GT(p.undercut_area, 0.5e-3 * 1e-6); // the up-facing facet's, below the plane
  EXPECT_LT(p.undercut_area, 2e-3 * 1e-6);
  EXPECT_NEAR(p.undercut_area, undercut_area(plate, p.point, {0, 0, 1}), 1e-15);
  // Half a mm² is not a facet: a narrow range of none between a down-facing and an up-facing ledge
  // of 0.5 mm² each (at 4 and 5 mm) holds the plane, where a slack of 1 mm² took it to the middle of
  // the plate (as on the continuum robot's round flank, into a 0.00 mm wedge).
  SurfaceMesh ledges = test::box({0, 0, 0}, {100 * mm, 100 * mm, 12 * mm});
  for (const auto& [z, up] : {std::pair{4.0, false}, std::pair{5.0, true}}) {
    const Eigen::Index n = ledges.num_vertices();
    ledges.vertices.conservativeResize(n + 3, 3);
    ledges.vertices.row(n) = Eigen::RowVector3d(10, 10, z) * mm;
    ledges.vertices.row(n + 1) = Eigen::RowVector3d(up ? 11 : 10, up ? 10 : 11, z) * mm;
    ledges.vertices.row(n + 2) = Eigen::RowVector3d(up ? 10 : 11, up ? 11 : 10, z) * mm;
    ledges.faces.conservativeResize(ledges.num_faces() + 1, 3);
    ledges.faces.row(ledges.num_faces() - 1) = Eigen::RowVector3i(int(n), int(n + 1), int(n + 2));
  }
  const Parting held = choose_parting(ledges, {0, 0, 1});
  EXPECT_NEAR(held.point.z(), 4.5 * mm, 0.01 * mm);
  EXPECT_NEAR(held.undercut_area, 0, 1e-15);
  // An undercut a mold holds on to (1 mm² and more) still decides: a down-facing ledge of 4 mm² at
  // 8 mm moves the plane above it, into the middle of [8, 12] mm.
  const Eigen::Index n = plate.num_vertices();
  plate.vertices.conservativeResize(n + 3, 3);
  plate.vertices.row(n) = Eigen::RowVector3d(10, 10, 8) * mm;
  plate.vertices.row(n + 1) = Eigen::RowVector3d(10, 12, 8) * mm;
  plate.vertices.row(n + 2) = Eigen::RowVector3d(14, 10, 8) * mm;
  plate.faces.conservativeResize(plate.num_faces() + 1, 3);
  plate.faces.row(plate.num_faces() - 1) = Eigen::RowVector3i(int(n), int(n + 1), int(n + 2)); // normal −z
  EXPECT_NEAR(choose_parting(plate, {0, 0, 1}).point.z(), 10 * mm, 0.01 * mm);
}

} // namespace
} // namespace fibermold
