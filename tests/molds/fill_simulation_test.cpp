// The fill simulation (molds/fill_simulation.hpp) and the sprues and vents it places
// (molds/ports.hpp): hand-made voxel cavities whose pockets are known by counting, and the grooves
// of shot 2 around laid muscles.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "molds/fill_simulation.hpp"
#include "molds/groove.hpp"
#include "molds/level_set.hpp"
#include "molds/mesh_boolean.hpp"
#include "molds/mold_block.hpp"
#include "molds/part_checks.hpp"
#include "molds/parting.hpp"
#include "molds/ports.hpp"
#include "molds/solids.hpp"
#include "primitives.hpp"

namespace fibermold {
namespace {

constexpr double mm = 1e-3, mm3 = 1e-9;

/// A region of 1 mm voxels, `size` of them, inside where `in(i, j, k)`.
template <class F> VoxelRegion voxels(const Eigen::Vector3i& size, F&& in)
{
  VoxelRegion r;
  r.voxel = 1 * mm;
  r.size = size;
  r.cells.assign(static_cast<std::size_t>(size.prod()), VoxelRegion::mold);
  for (int k = 0; k < size.z(); ++k)
    for (int j = 0; j < size.y(); ++j)
      for (int i = 0; i < size.x(); ++i) r.cells[static_cast<std::size_t>(r.index(i, j, k))] = in(i, j, k);
  return r;
}

/// A U of 3 × 3 mm legs 10 mm tall at i = 0..2 and 9..11, on a 12 × 3 × 2 mm bottom.
VoxelRegion u_cavity()
{
  return voxels({12, 3, 12}, [](int i, int, int k) { return k < 2 || i < 3 || i > 8; });
}

/// The union of boxes given in voxel indices [lo, hi] (inclusive), as a closed mesh: a cavity to
/// match a hand-made region.
SurfaceMesh boxes(const std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>>& spans)
{
  SurfaceMesh out;
  for (const auto& [lo, hi] : spans) {
    const SurfaceMesh b = box_solid((lo.array() - 0.5) * mm, (hi.array() + 0.5) * mm);
    out = out.num_faces() == 0 ? b : mesh_union(out, b);
  }
  return out;
}

Port from_below(const VoxelRegion& r, int i, int j, int k, double diameter = 1 * mm)
{
  return {r.centre(i, j, k) - r.voxel / 2 * r.axes.col(2), diameter, false};
}
Port from_above(const VoxelRegion& r, int i, int j, int k, double diameter = 1 * mm)
{
  return {r.centre(i, j, k) + r.voxel / 2 * r.axes.col(2), diameter, true};
}

TEST(FillSimulation, UShapedCavityWithOneVentTrapsTheOtherLeg)
{
  const VoxelRegion r = u_cavity();
  const FillResult f = simulate_fill(r, {from_below(r, 6, 1, 0)}, {from_above(r, 1, 1, 11)});
  EXPECT_NEAR(f.fill_volume / mm3, 12 * 3 * 2 + 2 * 3 * 3 * 10, 1e-9);
  EXPECT_NEAR(f.reachable_volume, f.fill_volume, 1e-15);
  ASSERT_EQ(f.pockets.size(), 1u);
  // The level seals the other leg where it covers the bottom's ceiling: the whole leg above it.
  EXPECT_NEAR(f.pockets[0].volume / mm3, 3 * 3 * 10, 1e-9);
  EXPECT_NEAR(f.pockets[0].at.z(), r.centre(0, 0, 11).z(), 1e-12);
  EXPECT_GE(f.pockets[0].at.x(), r.centre(9, 0, 0).x());
  EXPECT_TRUE(f.sprue_open[0]);
  EXPECT_TRUE(f.vent_open[0]);

  // A vent on each leg: nothing is trapped.
  const FillResult vented =
      simulate_fill(r, {from_below(r, 6, 1, 0)}, {from_above(r, 1, 1, 11), from_above(r, 10, 1, 11)});
  EXPECT_EQ(vented.pockets.size(), 0u);
  EXPECT_EQ(vented.trapped_volume, 0);
}

TEST(FillSimulation, WithoutAVentAllTheAirIsTrapped)
{
  const VoxelRegion r = u_cavity();
  const FillResult f = simulate_fill(r, {from_below(r, 6, 1, 0)}, {});
  EXPECT_NEAR(f.trapped_volume, f.fill_volume, 1e-15);
}

TEST(FillSimulation, AnInvertedUTrapsTheAirUnderItsBridge)
{
  // Legs from the bottom joined by a bridge at the top; a vent at the other leg's bottom is of
  // little use (the silicone spilling over the bridge covers it), a vent at the bridge's top lets
  // it all out. The sprue feeds one leg from below.
  const VoxelRegion r = voxels({12, 3, 12}, [](int i, int, int k) { return k >= 10 || i < 3 || i > 8; });
  const FillResult low_vent = simulate_fill(r, {from_below(r, 1, 1, 0)}, {from_below(r, 10, 1, 0)});
  EXPECT_GT(low_vent.trapped_volume, 0.9 * low_vent.fill_volume);
  const FillResult top_vent = simulate_fill(r, {from_below(r, 1, 1, 0)}, {from_above(r, 6, 1, 11)});
  EXPECT_EQ(top_vent.trapped_volume, 0);
}

TEST(FillSimulation, PartsNoSprueReachesAreReported)
{
  // Two boxes side by side, apart: the sprue feeds the first.
  const VoxelRegion r = voxels({12, 3, 4}, [](int i, int, int) { return i < 4 || i > 6; });
  const FillResult f = simulate_fill(r, {from_below(r, 1, 1, 0)}, {from_above(r, 1, 1, 3)});
  EXPECT_NEAR(f.reachable_volume / mm3, 4 * 3 * 4, 1e-9);
  ASSERT_EQ(f.unreachable.size(), 1u);
  EXPECT_NEAR(f.unreachable[0].volume / mm3, 5 * 3 * 4, 1e-9);
  EXPECT_NEAR(f.unreachable[0].at.z(), r.centre(0, 0, 0).z(), 1e-12);
  // A vent on the second box opens on no part that is filled.
  const FillResult g = simulate_fill(r, {from_below(r, 1, 1, 0)}, {from_above(r, 9, 1, 3)});
  EXPECT_FALSE(g.vent_open[0]);
}

TEST(FillPlan, VentsTheUShapedCavitysSecondLeg)
{
  const VoxelRegion r = u_cavity();
  const SurfaceMesh cavity = boxes({{{0, 0, 0}, {11, 2, 1}}, {{0, 0, 0}, {2, 2, 11}}, {{9, 0, 0}, {11, 2, 11}}});
  const FillPlan plan =
      plan_fill(r, cavity, {{from_below(r, 6, 1, 0)}, {from_above(r, 1, 1, 11)}}, 1 * mm, 1 * mm, 1 * mm, false);
  ASSERT_EQ(plan.ports.vents.size(), 2u);
  EXPECT_GE(plan.ports.vents[1].mouth.x(), r.centre(9, 0, 0).x() - 1e-9);
  EXPECT_NEAR(plan.ports.vents[1].mouth.z(), 12 * mm - r.voxel / 2, 1e-9); // the top of the leg
  EXPECT_EQ(plan.fill.trapped_volume, 0);
  EXPECT_TRUE(plan.fill.vent_open[1]);
}

TEST(FillPlan, APocketUnderCuredSiliconeCannotBeVented)
{
  // A 4 × 3 × 4 mm chamber whose ceiling is solid (cured silicone, as over a shot-2 groove that
  // runs under an overhang of the shot-1 body) beside a leg that reaches the mold, on a common
  // bottom. A vent over the chamber would open on the solid: the chamber's air stays.
  VoxelRegion r = voxels({12, 3, 10}, [](int i, int, int k) { return k < 2 || (i < 4 && k < 6) || i > 7; });
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 3; ++j) r.cells[static_cast<std::size_t>(r.index(i, j, 6))] = VoxelRegion::solid;
  const SurfaceMesh cavity = boxes({{{0, 0, 0}, {11, 2, 1}}, {{0, 0, 0}, {3, 2, 6}}, {{8, 0, 0}, {11, 2, 9}}});
  const FillPlan plan = plan_fill(r, cavity, {{from_below(r, 6, 1, 0)}, {}}, 1 * mm, 1 * mm, 1 * mm, false);
  ASSERT_EQ(plan.ports.vents.size(), 1u); // the leg's
  EXPECT_GE(plan.ports.vents[0].mouth.x(), r.centre(8, 0, 0).x() - 1e-9);
  ASSERT_EQ(plan.fill.pockets.size(), 1u);
  EXPECT_FALSE(plan.fill.pockets[0].ventable);
  EXPECT_NEAR(plan.fill.trapped_volume / mm3, 4 * 3 * 4, 1e-9);
  // A vent over it takes in no voxel.
  const FillResult f = simulate_fill(r, plan.ports.sprues, {from_above(r, 1, 1, 6)});
  EXPECT_FALSE(f.vent_open[0]);
}

/// Shot 2 of a 60 × 20 × 20 mm box body (its top at z = 10 mm) with straight fibers along x at
/// height z0: the fill region is each groove's slot from the laid muscle up to the skin. The faces
/// lie between voxel centres (0.05 mm off the grid's planes), so that each voxel is in or out.
struct GrooveBox {
  SurfaceMesh body = box_solid({0.05 * mm, -9.95 * mm, -9.95 * mm}, {60.05 * mm, 10.05 * mm, 10.05 * mm});
  double muscle = 1.5 * mm, radius = 1.8 * mm, voxel = 0.2 * mm;

  /// Along x at (y, z), moved 0.05 mm in y so that the groove's walls too lie between voxel centres.
  static std::vector<Eigen::Vector3d> fiber(double y, double z)
  {
    y += 0.05 * mm;
    return {{0, y, z}, {30 * mm, y, z}, {60 * mm, y, z}};
  }
};

TEST(FillPlan, Shot2SprueGoesToTheGrooveFromAbove)
{
  const GrooveBox b;
  const double z0 = 2 * mm; // the fiber: its groove's bottom is 12 mm above the body's at −10 mm
  // The slot from the fiber up to the top (2r wide, with its round bottom), less the muscle. The
  // crescent between muscle and groove is 0.6 mm at its widest: sampled at 0.1 mm.
  const double slot =
      60 * mm * (2 * b.radius * (10.05 * mm - z0) + M_PI * b.radius * b.radius / 2 - M_PI * b.muscle * b.muscle);
  const VoxelRegion fine =
      fill_regions(b.body, {GrooveBox::fiber(0, z0)}, b.radius, b.muscle, {0, 0, 1}, 0.1 * mm).shot2;
  std::printf("groove space %.1f mm³, analytic %.1f mm³\n", fine.volume() / mm3, slot / mm3);
  EXPECT_NEAR(fine.volume(), slot, 0.01 * slot);

  const FillRegions regions = fill_regions(b.body, {GrooveBox::fiber(0, z0)}, b.radius, b.muscle, {0, 0, 1}, b.voxel);
  const VoxelRegion& r = regions.shot2;
  // Shot 1 fills the rest of the body.
  EXPECT_NEAR(regions.shot1.volume(), signed_volume(b.body) - slot - 60 * mm * M_PI * b.muscle * b.muscle,
              0.01 * signed_volume(b.body));
  // The body's lowest point, from below, reaches none of it: the cured shot-1 body lies there.
  const FillResult old = simulate_fill(r, {{{30 * mm, 0, -10 * mm}, 4 * mm, false}}, {});
  EXPECT_FALSE(old.sprue_open[0]);
  EXPECT_EQ(old.reachable_volume, 0);

  const FillPlan plan = plan_fill(r, b.body, {}, 4 * mm, 1.5 * mm, 1 * mm, true);
  ASSERT_EQ(plan.ports.sprues.size(), 1u);
  const Port& sprue = plan.ports.sprues[0];
  std::printf("sprue at (%.2f, %.2f, %.2f) mm, %zu vents, %.3f mm³ trapped\n", sprue.mouth.x() / mm,
              sprue.mouth.y() / mm, sprue.mouth.z() / mm, plan.ports.vents.size(), plan.fill.trapped_volume / mm3);
  EXPECT_TRUE(sprue.upward);
  EXPECT_LT(std::abs(sprue.mouth.y() - 0.05 * mm), b.radius); // over the groove
  EXPECT_NEAR(sprue.mouth.z(), 10 * mm, b.voxel);             // at the skin
  // All but the wedges along the muscle's line of contact (under 1 % of it).
  EXPECT_NEAR(plan.fill.reachable_volume + plan.fill.crevice_volume, plan.fill.fill_volume, 1e-15);
  EXPECT_LT(plan.fill.crevice_volume, 0.01 * plan.fill.fill_volume);
  EXPECT_LE(plan.fill.trapped_volume, kTrappedAirTolerance);
  ASSERT_GE(plan.ports.vents.size(), 1u);
  for (std::size_t k = 0; k < plan.ports.vents.size(); ++k) {
    EXPECT_TRUE(plan.fill.vent_open[k]);
    EXPECT_LT(std::abs(plan.ports.vents[k].mouth.y() - 0.05 * mm), b.radius); // over the groove
  }
}

/// Shot 2 of the box with a slot 5 mm wide across its top, 8 mm deep, over the groove's middle (a
/// gripper finger's back): a sprue from above down to the slot's floor through the mold's rib in
/// the slot, 4 mm across, would leave the rib walls of 0.5 mm (the gripper finger's shot 2 failed
/// its part check so, a wall of 0.27 mm, until session 25). No hole comes within min_wall of a
/// wall of the cavity that rises beside it.
TEST(FillPlan, NoHoleRunsDownASlotCloserThanMinWallToItsSides)
{
  const GrooveBox b;
  const double slot_lo = 28.05 * mm, slot_hi = 33.05 * mm, floor = 2.05 * mm;
  const SurfaceMesh body = test::voxel_body({0.05 * mm, -9.95 * mm, -9.95 * mm}, 1 * mm, {60, 20, 20},
                                            [](int i, int, int k) { return !(i >= 28 && i < 33 && k >= 12); });
  const std::vector<Eigen::Vector3d> fiber{
      {0, 0.05 * mm, -4 * mm}, {30 * mm, 0.05 * mm, -4 * mm}, {60 * mm, 0.05 * mm, -4 * mm}};
  const VoxelRegion r = fill_regions(body, {fiber}, b.radius, b.muscle, {0, 0, 1}, b.voxel).shot2;
  const double min_wall = 1 * mm, diameter = 4 * mm;
  const FillPlan plan = plan_fill(r, body, {}, diameter, 1.5 * mm, min_wall, true);
  ASSERT_GE(plan.ports.sprues.size(), 1u);
  EXPECT_NEAR(plan.fill.reachable_volume + plan.fill.crevice_volume, plan.fill.fill_volume, 1e-15);
  EXPECT_LE(plan.fill.trapped_volume, kTrappedAirTolerance);
  for (const std::vector<Port>* holes : {&plan.ports.sprues, &plan.ports.vents})
    for (const Port& p : *holes) {
      std::printf("hole %.1f mm at (%.2f, %.2f, %.2f) mm\n", p.diameter / mm, p.mouth.x() / mm, p.mouth.y() / mm,
                  p.mouth.z() / mm);
      // Down in the slot, the hole's wall keeps min_wall from both of its sides.
      if (p.mouth.z() < floor + b.voxel) {
        EXPECT_GE(std::min(p.mouth.x() - slot_lo, slot_hi - p.mouth.x()), p.diameter / 2 + min_wall);
      }
    }
}

TEST(FillPlan, NoVentLeavesAFinThinnerThanMinWallToTheCavityBesideIt)
{
  // Two chambers on a common base, 6 mm wide (x) each, 6 mm deep (y), split by a fin of mold 0.3 mm
  // thick from the base up: A's top at 5 mm, its highest strip (x 5..6 mm, next to the fin) at
  // 5.25 mm; B's top at 5.6 mm, too little above A's for a slope from the hole's axis to the ring of
  // rises_beside to count. A vent in A's strip has its rim over A and over the fin's deep floor
  // ("a drop of 2 mm or more"), and its cut, 0.5 mm into A, leaves the fin as the mold's only wall
  // toward B: 0.3 mm, where the printer holds 1 mm (the walking robot's shot 1 in session 43: a vent
  // over a slit between two ribs, under a third groove crossing, left a wall of 0.09 mm). A vent's
  // wall now keeps min_wall from every cavity beside it above its cut's bottom; the strip's own air
  // is what that costs.
  const double v = 0.25 * mm, r = 0.75 * mm, min_wall = 1 * mm, fin_lo = 6 * mm, fin_hi = 6.3 * mm;
  const auto chamber = [&](double x0, double x1, double top) { return box_solid({x0, 0, 3 * mm}, {x1, 6 * mm, top}); };
  SurfaceMesh cavity = box_solid({0, 0, 0}, {12.3 * mm, 6 * mm, 3.01 * mm});
  for (const SurfaceMesh& part :
       {chamber(0, fin_lo, 5 * mm), chamber(5 * mm, fin_lo, 5.25 * mm), chamber(fin_hi, 12.3 * mm, 5.6 * mm)})
    cavity = mesh_union(cavity, part);
  VoxelRegion region;
  region.voxel = v;
  region.first = Eigen::Vector3i(0, 0, 0);
  region.size = Eigen::Vector3i(50, 25, 24);
  region.cells.assign(static_cast<std::size_t>(region.size.prod()), VoxelRegion::mold);
  for (int k = 0; k < region.size.z(); ++k)
    for (int j = 0; j < region.size.y(); ++j)
      for (int i = 0; i < region.size.x(); ++i) {
        const Eigen::Vector3d c = region.centre(i, j, k);
        const bool base = c.z() < 3 * mm, in_a = c.x() < fin_lo &&
                                                 c.z()<(c.x() > 5 * mm ? 5.25 : 5.0) * mm, in_b = c.x()> fin_hi &&
                                                 c.z() < 5.6 * mm;
        if (c.y() > 0 && c.y() < 6 * mm && c.x() > 0 && c.x() < 12.3 * mm && (base || in_a || in_b))
          region.cells[static_cast<std::size_t>(region.index(i, j, k))] = VoxelRegion::fill;
      }
  const FillPlan plan = plan_fill(region, cavity, {{from_below(region, 2, 12, 0)}, {}}, 1 * mm, 2 * r, min_wall, false);
  // No vent fits in the strip: the air above A's top there stays (it holds 1 × 6 × 0.25 mm³).
  EXPECT_LE(plan.fill.trapped_volume / mm3, 1.5);
  ASSERT_GE(plan.ports.vents.size(), 2u); // A's and B's
  int in_a = 0;
  for (const Port& p : plan.ports.vents) {
    std::printf("vent at (%.2f, %.2f, %.2f) mm\n", p.mouth.x() / mm, p.mouth.y() / mm, p.mouth.z() / mm);
    if (p.mouth.x() < fin_lo) {
      ++in_a;
      EXPECT_LE(p.mouth.x() + r + min_wall, fin_hi + 1e-9) << "the vent's wall toward B is thinner than min_wall";
    }
  }
  EXPECT_GE(in_a, 1);
}

TEST(FillPlan, SeparateGrooveBasinsGetASprueAndAVentEach)
{
  const GrooveBox b;
  const VoxelRegion r = fill_regions(b.body, {GrooveBox::fiber(-5 * mm, 0), GrooveBox::fiber(5 * mm, 3 * mm)}, b.radius,
                                     b.muscle, {0, 0, 1}, b.voxel)
                            .shot2;
  const FillPlan plan = plan_fill(r, b.body, {}, 4 * mm, 1.5 * mm, 1 * mm, true);
  ASSERT_EQ(plan.ports.sprues.size(), 2u);
  EXPECT_LT(plan.ports.sprues[0].mouth.y() * plan.ports.sprues[1].mouth.y(), 0); // one over each groove
  EXPECT_NEAR(plan.fill.reachable_volume + plan.fill.crevice_volume, plan.fill.fill_volume, 1e-15);
  EXPECT_LE(plan.fill.trapped_volume, kTrappedAirTolerance);
  int left = 0, right = 0;
  for (const Port& v : plan.ports.vents) (v.mouth.y() < 0 ? left : right)++;
  EXPECT_GE(left, 1);
  EXPECT_GE(right, 1);
}

TEST(FillPlan, AGrooveAlongARoundArmsTopGetsAVentOnEachRidge)
{
  // Shot 1 of a round arm along x (radius 8 mm) with its muscle 2.5 mm above the axis (so that the
  // parting plane can pass below the groove at the arm's widest): the groove splits the cavity's
  // top into two ridges. Vents spread along the top land on one of them (the tentacle trapped
  // 3.4 mL so); the fill simulation vents the other.
  SurfaceMesh arm = cylinder_solid({0, 0, 0}, {80 * mm, 0, 0}, 8 * mm, 48);
  const std::vector<Eigen::Vector3d> axis{{0, 0, 2.5 * mm}, {80 * mm, 0, 2.5 * mm}};
  const GrooveBody g = groove_body(arm, {axis}, 1.8 * mm, {0, 0, 1}, 0.25 * mm);
  const VoxelRegion r = fill_regions(arm, {axis}, 1.8 * mm, 1.5 * mm, {0, 0, 1}, fill_voxel(0.25 * mm, 1.8 * mm)).shot1;
  const Ports start =
      cavity_ports(g.mesh, {0, 0, 1}, 2 * mm, 2, 1.5 * mm, 1 * mm, "shot1"); // a 4 mm circle fits the round bottom
  const FillResult before = simulate_fill(r, start.sprues, start.vents);
  const Parting parting = choose_parting(g.mesh, {0, 0, 1});
  std::printf("parting at z = %.2f mm\n", parting.point.z() / mm);
  const FillPlan plan = plan_fill(r, g.mesh, start, 2 * mm, 1.5 * mm, 1 * mm, false);
  std::printf("trapped %.1f mm³ with the %zu vents that fit along the top, %.3f mm³ with %zu vents\n",
              before.trapped_volume / mm3, start.vents.size(), plan.fill.trapped_volume / mm3, plan.ports.vents.size());
  int left = 0, right = 0;
  for (const Port& v : plan.ports.vents) {
    (v.mouth.y() < 0 ? left : right)++;
    std::printf("vent at (%.2f, %.2f, %.2f) mm, cut %.2f mm deep\n", v.mouth.x() / mm, v.mouth.y() / mm,
                v.mouth.z() / mm, v.dip() / mm);
  }
  for (const Port& v : plan.ports.sprues)
    std::printf("sprue at (%.2f, %.2f, %.2f) mm, cut %.2f mm deep\n", v.mouth.x() / mm, v.mouth.y() / mm,
                v.mouth.z() / mm, v.dip() / mm);
  EXPECT_GE(left, 1);
  EXPECT_GE(right, 1);
  EXPECT_LE(plan.fill.trapped_volume, kTrappedAirTolerance);
  EXPECT_NEAR(plan.fill.reachable_volume, plan.fill.fill_volume, 1e-15);

  // The mold with those holes: no knife edge beside a vent on the sloping ridges.
  const Mold mold = make_mold(g.mesh, parting, {}, {}, "shot1", &plan.ports);
  for (const MoldPart& p : mold.parts) {
    const PartCheck c = check_part(p.mesh, 1 * mm, {0.25, 0.21, 0.21});
    for (const auto& problem : c.problems) ADD_FAILURE() << p.name << " " << problem;
  }
}

TEST(LevelSet, VoxelsOfABoxCountItsVolume)
{
  // Faces between voxel centres (0.1 mm off the grid's planes), so that each voxel is in or out.
  const SurfaceMesh box = box_solid({0.1 * mm, 0.1 * mm, 0.1 * mm}, {10.1 * mm, 6.1 * mm, 4.1 * mm});
  const VoxelRegion r = LevelSet::from_mesh(box, 0.25 * mm).voxels();
  EXPECT_EQ(r.count(), 40 * 24 * 16);
  EXPECT_EQ(r.size, Eigen::Vector3i(40, 24, 16));
  EXPECT_NEAR(r.centre(0, 0, 0).x(), 0.25 * mm, 1e-12);
}

} // namespace
} // namespace fibermold
