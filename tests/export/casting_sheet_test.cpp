// The casting sheet read back as a user reads it: how much to mix per shot (20 % over the shot, at
// least 5 g of the smaller part), the screws or clamps, the holes named by their count, the muscles'
// cut lengths and ends, and every line within 100 characters, whatever the counts and the names.
#include <regex>
#include <sstream>

#include <gtest/gtest.h>

#include "export/casting_sheet.hpp"

namespace fibermold {
namespace {

CastShot shot(double grams, int screws, int sprues, int vents)
{
  CastShot s;
  s.mass = grams * 1e-3;
  s.volume = grams / 1.07 * 1e-6;
  s.screw_holes = screws;
  s.sprues = sprues;
  s.vents = vents;
  s.sprue_from = sprues > 0 ? "below" : "";
  s.reached = 0.9987;
  s.trapped_air = 0.25e-9;
  s.trapped_air_tolerance = 5e-9;
  return s;
}

CastingSheet sheet()
{
  CastingSheet s;
  s.design_name = "finger";
  s.silicone = *find_silicone_preset("dragon-skin-10");
  s.preset = "dragon-skin-10";
  s.youngs_modulus = s.silicone.youngs_modulus();
  s.poisson_ratio = kPresetPoissonRatio;
  s.density = s.silicone.density;
  s.muscle_diameter = 3e-3;
  s.end_channel_diameter = 4e-3;
  s.end_channel_length = 5e-3;
  s.screw_diameter = 3.4e-3;
  MuscleCut supplied{"m1", 0.110, 0.108, {}, {}, 0};
  supplied.start = {{0, 0, 0}, true, {-0.001, 0, 0}};
  supplied.end = {{0.1, 0, 0}, false, {0.1, 0.005, 0}};
  MuscleCut buried{"m2", 0.050, 0.050, {}, {}, std::nullopt};
  buried.start = {{0.02, 0, 0}, false, {0.02, 0.005, 0}};
  buried.end = {{0.07, 0, 0}, false, {0.07, 0.005, 0}};
  s.cuts = {supplied, buried};
  s.shot1 = shot(40.0, 4, 1, 3);
  s.shot2 = shot(1.8, 0, 2, 1);
  return s;
}

/// True when `text`, read with its line breaks and indents as single spaces, holds `part`.
bool has(const std::string& text, const std::string& part)
{
  std::string flat;
  for (std::size_t i = 0; i < text.size(); ++i)
    if (text[i] != '\n')
      flat += text[i];
    else if (flat.empty() || flat.back() != ' ')
      flat += ' ';
  for (std::size_t at; (at = flat.find("  ")) != std::string::npos;) flat.erase(at, 1);
  return flat.find(part) != std::string::npos;
}

TEST(CastingSheet, MixesTwentyPercentMoreOrTheLeastBatchAScaleWeighs)
{
  const std::string guide = casting_guide(sheet());
  // 40 g: 48 g, 24 g of each part; 1.8 g: under the least batch, 5 g of each part.
  EXPECT_TRUE(has(guide, "Shot 1: 37.4 mL, 40.0 g; mix 48.0 g (24.0 g of A and 24.0 g of B: 20 % more"));
  EXPECT_TRUE(has(guide, "Shot 2: 1.7 mL, 1.8 g; mix 10.0 g (5.0 g of A and 5.0 g of B: the least batch"));
  const ReportTable t = silicone_table(sheet());
  ASSERT_EQ(t.rows.size(), 2U);
  EXPECT_EQ(t.rows[0][3], "24.0 + 24.0");
  EXPECT_EQ(t.rows[1][3], "5.0 + 5.0");
  EXPECT_EQ(t.rows[1][4], "2 from below");
  EXPECT_EQ(t.rows[0][6], "99.9 %");
  EXPECT_EQ(t.rows[0][7], "0.25");
}

TEST(CastingSheet, SaysHowToCloseEachMoldAndNamesItsHoles)
{
  const std::string guide = casting_guide(sheet());
  EXPECT_TRUE(has(guide, "bolt them through the 4 screw holes (3.4 mm, M3: bolts long enough to pass both halves, "
                         "with nuts)"));
  // A hole no metric bolt's clearance is: its width alone.
  CastingSheet wide = sheet();
  wide.screw_diameter = 20e-3;
  EXPECT_TRUE(has(casting_guide(wide), "bolt them through the 4 screw holes (20.0 mm: bolts long enough"));
  wide.screw_diameter = 4.5e-3;
  EXPECT_TRUE(has(casting_guide(wide), "bolt them through the 4 screw holes (4.5 mm, M4: bolts"));
  EXPECT_TRUE(has(guide, "clamp them (spring clamps or rubber bands)"));
  EXPECT_TRUE(has(guide, "through the sprue hole from below"));
  EXPECT_TRUE(has(guide, "every one of the 3 vents"));
  EXPECT_TRUE(has(guide, "through the 2 sprue holes"));
  EXPECT_TRUE(has(guide, "Smooth-On Dragon Skin 10 Medium (Shore 10A), mixed 1A : 1B by weight; pot life 20 min, "
                         "demold after 5 h"));
  EXPECT_TRUE(has(guide, "vacuum-degas it (the data sheet recommends it)"));
  EXPECT_TRUE(has(guide, "Let it cure (5 h)"));
  EXPECT_TRUE(has(guide, "shot1-lower.stl"));
}

// A new user's finger with 2 mm notches: the molds' log warned 13 times per shot of thin deep ribs to print
// solid, and README.txt, which the person at the printer reads, said "print every STL as it lies".
TEST(CastingSheet, HalvesWithThinDeepRibsArePrintedSolidUnlessADraftTapersThem)
{
  CastingSheet s = sheet();
  EXPECT_FALSE(has(casting_guide(s), "solid"));
  s.shot1.lower_ribs = {13, 1.9e-3, 12e-3};
  std::string guide = casting_guide(s);
  EXPECT_TRUE(has(guide, "Print this half solid (100 % infill): it has thin deep ribs standing into the cavity"));
  EXPECT_TRUE(has(guide, ": shot1-lower.stl (13 ribs, down to 1.9 mm thick, up to 12.0 mm deep). Or set [mold] "
                         "draft_deg (1–3°) to taper them"));
  s.shot2.upper_ribs = {1, 2.4e-3, 6e-3};
  guide = casting_guide(s);
  EXPECT_TRUE(has(guide, "Print these halves solid (100 % infill): they have"));
  EXPECT_TRUE(has(guide, "12.0 mm deep); shot2-upper.stl (1 rib, down to 2.4 mm thick, up to 6.0 mm deep)"));
  s.draft = true;
  EXPECT_FALSE(has(casting_guide(s), "solid"));
  // Only the mold parts are printed as they lie: deformed-<target>.stl is for comparing.
  EXPECT_TRUE(has(guide, "Print every mold part (the STLs named shot1-… and shot2-…) as it lies"));
}

// The muscle's end and the tube's joint sit in the socket: a Luer fitting, wider than it, does not.
TEST(CastingSheet, TheMuscleAndItsTubeJoinWithinTheSocket)
{
  const std::string guide = casting_guide(sheet());
  EXPECT_TRUE(has(guide,
                  "join them with a fitting no wider than the socket, such as a barbed connector or a glued "
                  "sleeve; a Luer fitting to the pressure supply goes on the tube's outer end, outside the mold"));
  EXPECT_TRUE(has(guide, "m1: 108.0 mm. Fit the supply tube to its first end, which leaves the body"));
  // Held at the groove's bottom while shot 2 cures: it would float otherwise.
  EXPECT_TRUE(has(guide,
                  "and tack it there every 2 to 3 cm with small dots of silicone adhesive (such as Smooth-On "
                  "Sil-Poxy) between the muscle and the groove's wall, not under it (a dot under it lifts it off "
                  "the route), cured before shot 2: a muscle holding air is lighter than liquid silicone"));
}

TEST(CastingSheet, GivesEachMuscleItsCutAndItsEnds)
{
  const std::string guide = casting_guide(sheet());
  EXPECT_TRUE(has(guide, "Muscles (3.0 mm in diameter)"));
  EXPECT_TRUE(has(guide, "before you lay it into its groove fit its supply tube and seal its other end"));
  // shot 2's channel: a 4 mm socket 5 mm beyond the skin, then a hole as wide as the muscle, which
  // the tube plugs (the sheet named the socket's 4 mm until session 45).
  EXPECT_TRUE(has(guide, "through a hole 3.0 mm wide, past a socket 4.0 mm wide reaching 5.0 mm beyond the skin"));
  EXPECT_TRUE(has(guide, "a tube of 3.0 mm outside diameter plugs the hole"));
  EXPECT_TRUE(has(guide, "m1: 108.0 mm. Fit the supply tube"));
  EXPECT_TRUE(has(guide, "to its first end, which leaves the body at (-1.0, 0.0, 0.0) mm"));
  EXPECT_TRUE(has(guide, "buried in the body at (100.0, 0.0, 0.0) mm"));
  EXPECT_TRUE(has(guide, "m2: 50.0 mm. Neither end leaves the body: seal both"));
  const ReportTable t = muscles_table(sheet());
  ASSERT_EQ(t.rows.size(), 2U);
  EXPECT_EQ(t.rows[0][1], "108.0");
  EXPECT_EQ(t.rows[0][3], "(100.0, 0.0, 0.0) mm, buried");
  EXPECT_EQ(t.rows[1][3], "both ends");
}

TEST(CastingSheet, NoLineIsLongerThanAHundredCharacters)
{
  CastingSheet s = sheet();
  s.preset.clear(); // the longest paragraph: the default material and the preset it stands for
  s.silicone = *find_silicone_preset(kDefaultSilicone);
  s.youngs_modulus = 86.4e3;
  s.paper_material = true;
  std::istringstream lines(casting_guide(s));
  int n = 0;
  for (std::string line; std::getline(lines, line); ++n) {
    std::size_t width = 0;
    for (char c : line) width += (c & 0xC0) != 0x80;
    EXPECT_LE(width, 100U) << line;
  }
  EXPECT_GT(n, 40);
  EXPECT_TRUE(has(casting_guide(s), "E = 86.4 kPa"));
  EXPECT_TRUE(has(casting_guide(s), "the robot moves otherwise than simulated"));
  EXPECT_TRUE(has(casting_guide(s), "([material]: the paper's figures;"));
}

TEST(CastingSheet, AModulusTheDesignSetsIsNotCalledThePapers)
{
  CastingSheet s = sheet(); // a modulus measured on the cast silicone, set without a preset
  s.preset.clear();
  s.silicone = *find_silicone_preset(kDefaultSilicone);
  s.youngs_modulus = 166.2e3;
  const std::string guide = std::regex_replace(casting_guide(s), std::regex("\n  "), " ");
  EXPECT_TRUE(has(guide, "The simulation took E = 166.2 kPa")) << guide;
  EXPECT_TRUE(has(guide, "([material] as the design sets them;")) << guide;
  EXPECT_FALSE(has(guide, "the paper's figures")) << guide;
  EXPECT_FALSE(has(guide, "moves otherwise than simulated")) << guide;
}

} // namespace
} // namespace fibermold
