// Labels engraved into mold parts (molds/part_label.hpp): the grooves' area against the strokes',
// the volume a label removes, the parts still valid and thick enough, and a label kept min_wall
// from a cavity near its face (moved to another face, along the face, or left out).
#include <cmath>

#include <gtest/gtest.h>

#include "mesh/surface_check.hpp"
#include "mesh/surface_distance.hpp"
#include "molds/groove.hpp"
#include "molds/mesh_boolean.hpp"
#include "molds/mold_block.hpp"
#include "molds/part_checks.hpp"
#include "molds/part_label.hpp"
#include "molds/parting.hpp"
#include "molds/solids.hpp"

namespace fibermold {
namespace {

constexpr double mm = 1e-3;
const Eigen::Vector3d kPrinter(0.25, 0.21, 0.21);
const LabelStyle kStyle;

/// The strokes' groove area as their lengths imply: each polyline a band `width` wide with round
/// ends (overlaps at joints counted twice).
double stroke_area(const std::vector<std::vector<Eigen::Vector2d>>& strokes, double width)
{
  double a = 0;
  for (const auto& path : strokes) {
    for (std::size_t k = 0; k + 1 < path.size(); ++k) a += (path[k + 1] - path[k]).norm() * width;
    a += M_PI * width * width / 4;
  }
  return a;
}

TEST(PartLabel, AnIIsOneGrooveOfItsStrokesArea)
{
  const auto outlines = text_outlines("I", 6 * mm, 0.9 * mm, 0.55 * mm);
  ASSERT_EQ(outlines.size(), 1u);
  const double expected = 6 * mm * 0.9 * mm + M_PI * std::pow(0.45 * mm, 2); // 6.04 mm²
  std::printf("I: %.4f mm², strokes %.4f mm², %zu outline points\n", outlines_area(outlines) / 1e-6, expected / 1e-6,
              outlines[0].size());
  EXPECT_NEAR(outlines_area(outlines), expected, 0.02 * expected);
  EXPECT_LT(outlines[0].size(), 60u); // straight sides simplified to their ends
}

TEST(PartLabel, AnOHasAHoleAndAnAFilledCornerLeavesNoLandUnderMinWall)
{
  const auto o = text_outlines("O", 6 * mm, 0.9 * mm, 0.55 * mm);
  EXPECT_EQ(o.size(), 2u); // the ring and its counter
  const double open = outlines_area(text_outlines("V", 6 * mm, 0.9 * mm, 0)),
               cut = outlines_area(text_outlines("V", 6 * mm, 0.9 * mm, 0.55 * mm));
  std::printf("V: %.3f mm² cut, %.3f mm² of grooves without the closing\n", cut / 1e-6, open / 1e-6);
  EXPECT_GT(cut, open + 0.2e-6); // the inside of the V's point is cut with it
  EXPECT_LT(cut, 1.2 * open);
}

/// The mold of a 100 × 20 × 20 mm box, with and without labels.
struct BoxMold {
  SurfaceMesh cavity = box_solid({0, -10 * mm, -10 * mm}, {100 * mm, 10 * mm, 10 * mm});
  Parting parting = choose_parting(cavity, {0, 0, 1});
  PartLabels labels{"testbar", kStyle};
  Mold plain = make_mold(cavity, parting, {}, {}, "shot1");
  Mold labelled = make_mold(cavity, parting, {}, {}, "shot1", nullptr, &labels);
};

TEST(PartLabel, EachHalfOfABoxMoldSaysWhatItIsAndTheSprueIsMarked)
{
  const BoxMold b;
  ASSERT_EQ(b.labelled.parts.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    const MoldPart& p = b.labelled.parts[k];
    for (const auto& why : p.unlabelled) ADD_FAILURE() << p.name << ": " << why;
    ASSERT_FALSE(p.labels.empty()) << p.name;
    const PlacedLabel& l = p.labels.front();
    EXPECT_EQ(l.text, k == 0 ? "TESTBAR S1 LOWER" : "TESTBAR S1 UPPER");
    EXPECT_NEAR(std::abs(l.normal.z()), 0, 1e-12) << "on a side face";
    EXPECT_GE(l.height, kStyle.min_height);
    EXPECT_NEAR(l.depth, 0.6 * mm, 1e-12);

    // The volume removed is the grooves' area times the depth, and about what the strokes imply.
    const double removed = signed_volume(b.plain.parts[k].mesh) - signed_volume(p.mesh);
    double grooves = 0, strokes = 0;
    for (const PlacedLabel& q : p.labels) {
      grooves += outlines_area(text_outlines(q.text, q.height, kStyle.stroke, 0.55 * mm)) * q.depth;
      strokes += stroke_area(text_strokes(q.text, q.height), kStyle.stroke) * q.depth;
    }
    std::printf("%s: \"%s\" %.1f mm capitals, %zu label(s), removed %.2f mm³, grooves %.2f, strokes imply %.2f\n",
                p.name.c_str(), l.text.c_str(), l.height / mm, p.labels.size(), removed / 1e-9, grooves / 1e-9,
                strokes / 1e-9);
    EXPECT_NEAR(removed, grooves, 0.01 * grooves);
    EXPECT_NEAR(removed, strokes, 0.2 * strokes);

    // Still a valid part, no wall under min_wall (1 mm).
    const PartCheck c = check_part(p.mesh, 1 * mm, kPrinter);
    for (const auto& problem : c.problems) ADD_FAILURE() << p.name << " " << problem;
    EXPECT_GE(c.min_thickness, 1 * mm) << p.name;
  }
  // The sprue comes from below: "IN" on the lower half's bottom, beside the sprue's mouth.
  ASSERT_EQ(b.labelled.sprues.size(), 1u);
  ASSERT_EQ(b.labelled.parts[0].labels.size(), 2u);
  const PlacedLabel& in = b.labelled.parts[0].labels[1];
  EXPECT_EQ(in.text, "IN");
  EXPECT_NEAR(in.normal.z(), -1, 1e-12);
  const double off_axis = (in.centre - b.labelled.sprues[0]).head<2>().norm();
  std::printf("IN at %.1f mm from the sprue's axis\n", off_axis / mm);
  EXPECT_LT(off_axis, 12 * mm);
  EXPECT_GT(off_axis, 4 * mm); // clear of the 8 mm seat
  EXPECT_EQ(b.labelled.parts[1].labels.size(), 1u);
}

/// A mold half: a 80 × 30 × 20 mm block with a pocket open at its top whose wall comes within
/// 1.2 mm of the block's −y face over x in [x0, x1].
SurfaceMesh pocketed_block(double x0, double x1)
{
  return mesh_difference(box_solid({0, 0, 0}, {80 * mm, 30 * mm, 20 * mm}),
                         box_solid({x0, 1.2 * mm, 5 * mm}, {x1, 25 * mm, 21 * mm}));
}

LabelFace side_face(double y, double sign)
{
  return {"side", {40 * mm, y, 10 * mm}, {0, sign, 0}, {0, 0, 1}, {80 * mm, 20 * mm}, {}};
}

/// The least distance from the label's cut (its solid's vertices under the face) to the pocket's walls.
double distance_to_pocket(const PlacedLabel& l, const SurfaceMesh& pocket)
{
  const SurfaceMesh s = label_solid(l, kStyle, 1 * mm);
  const SurfaceDistance d(pocket.vertices, pocket.faces);
  double least = HUGE_VAL;
  for (Eigen::Index v = 0; v < s.num_vertices(); ++v)
    if ((s.vertices.row(v).transpose() - l.centre).dot(l.normal) < 0)
      least = std::min(least, d.closest(s.vertices.row(v).transpose()).distance);
  return least;
}

TEST(PartLabel, ALabelNeverComesWithinMinWallOfACavityNearItsFace)
{
  const SurfaceMesh pocket = box_solid({10 * mm, 1.2 * mm, 5 * mm}, {70 * mm, 25 * mm, 21 * mm});
  const SurfaceMesh block = pocketed_block(10 * mm, 70 * mm);
  // Offered the −y face first: 1.2 mm from the pocket, too thin for a 0.6 mm cut; the +y face takes it.
  const auto moved = place_label(block, {"S1 LOWER"}, {side_face(0, -1), side_face(30 * mm, 1)}, kStyle, 1 * mm);
  ASSERT_TRUE(moved);
  EXPECT_NEAR(moved->normal.y(), 1, 1e-12);
  const double clear = distance_to_pocket(*moved, pocket);
  std::printf("moved to the +y face: %.2f mm from the pocket\n", clear / mm);
  EXPECT_GE(clear, 1 * mm);
  const SurfaceMesh cut = engrave(block, {*moved}, kStyle, 1 * mm);
  const PartCheck c = check_part(cut, 1 * mm, kPrinter);
  for (const auto& problem : c.problems) ADD_FAILURE() << problem;
  EXPECT_GE(c.min_thickness, 1 * mm);

  // The −y face alone: no room anywhere on it, the label is left out.
  EXPECT_FALSE(place_label(block, {"S1 LOWER", "S1L"}, {side_face(0, -1)}, kStyle, 1 * mm));

  // A pocket over half the face's length: the label goes to the other half, min_wall + depth clear.
  const SurfaceMesh half_pocket = box_solid({10 * mm, 1.2 * mm, 5 * mm}, {35 * mm, 25 * mm, 21 * mm});
  const SurfaceMesh block2 = pocketed_block(10 * mm, 35 * mm);
  const auto along = place_label(block2, {"S1L"}, {side_face(0, -1)}, kStyle, 1 * mm);
  ASSERT_TRUE(along);
  EXPECT_NEAR(along->normal.y(), -1, 1e-12);
  const double left_edge = along->centre.x() - along->extent.x() / 2;
  std::printf("along the −y face: from x = %.2f mm, the pocket ends at 35 mm; %.2f mm from it\n", left_edge / mm,
              distance_to_pocket(*along, half_pocket) / mm);
  EXPECT_GE(left_edge, 35 * mm + 1 * mm + kStyle.depth - 1e-9);
  EXPECT_GE(distance_to_pocket(*along, half_pocket), 1 * mm);
  const PartCheck c2 = check_part(engrave(block2, {*along}, kStyle, 1 * mm), 1 * mm, kPrinter);
  for (const auto& problem : c2.problems) ADD_FAILURE() << problem;
}

TEST(PartLabel, EveryLetterAndDigitIsCutOnlyWhereItsLandsPrint)
{
  // Each row at 5, 6.5 and 8 mm capitals: where lands_print passes it, the part cut with it passes
  // its checks (no land under min_wall); at 8 mm every row prints.
  for (const std::string text : {"ABCDEFGHIJKLM", "NOPQRSTUVWXYZ", "0123456789-?"})
    for (const double h : {5 * mm, 6.5 * mm, 8 * mm}) {
      LabelStyle style = kStyle;
      style.min_height = style.max_height = h;
      const bool prints = lands_print(text, h, style, 1 * mm);
      std::printf("%s at %.1f mm: %s\n", text.c_str(), h / mm, prints ? "prints" : "a land under min_wall");
      if (h == 8 * mm) {
        EXPECT_TRUE(prints) << text;
      }
      if (!prints) continue;
      const SurfaceMesh block = box_solid({0, 0, 0}, {140 * mm, 20 * mm, 20 * mm});
      const auto l =
          place_label(block, {text}, {{"side", {70 * mm, 0, 10 * mm}, {0, -1, 0}, {0, 0, 1}, {140 * mm, 20 * mm}, {}}},
                      style, 1 * mm);
      ASSERT_TRUE(l) << text;
      const PartCheck c = check_part(engrave(block, {*l}, style, 1 * mm), 1 * mm, kPrinter);
      for (const auto& problem : c.problems) ADD_FAILURE() << text << ": " << problem;
      EXPECT_GE(c.min_thickness, 1 * mm) << text;
    }
}

TEST(PartLabel, TheHeightsTriedAreWholeHalfMillimetresToTheLastDigit)
{
  // As the report prints them in mm: 8, 7.5, …, 5 (repeated subtraction gave 6.999999999999999 on).
  const std::vector<double> heights = label_heights(kStyle);
  ASSERT_EQ(heights.size(), 7u);
  for (std::size_t k = 0; k < heights.size(); ++k) EXPECT_EQ(heights[k] / mm, 8.0 - 0.5 * static_cast<double>(k));
}

TEST(PartLabel, TextsShortenFromTheFullLabel)
{
  EXPECT_EQ(part_label_texts("gripper", "shot2", false),
            (std::vector<std::string>{"GRIPPER S2 UPPER", "GRIPPER S2U", "S2 UPPER", "S2U"}));
  EXPECT_EQ(part_label_texts("", "shot1", true), (std::vector<std::string>{"S1 LOWER", "S1L"}));
}

} // namespace
} // namespace fibermold
