#include "export/casting_sheet.hpp"

#include <algorithm>
#include <array>
#include <utility>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/units.hpp"
#include "core/wrapped_text.hpp"

namespace fibermold {

namespace {

constexpr double kMinute = 60, kHour = 3600;

/// How much silicone to mix beyond a shot's volume: the cup's and the stirrer's film, the gun's nozzle.
constexpr double kMixMargin = 0.2;
/// g: the least of the smaller part to weigh out. On a 0.1 g kitchen scale that part is then within
/// 2 % of its share; shot 2 of a small robot (1.8 g in all) would otherwise be mixed from 0.9 g of
/// each part, ±11 %, and less than the nozzle holds.
constexpr double kLeastPart_g = 5;

/// What to mix for a shot of `grams` of silicone: kMixMargin more, and at least kLeastPart_g of the
/// smaller part; grams of A and of B.
struct Mix {
  double a = 0, b = 0;
  bool least = false; ///< the batch is the least one, not the shot + kMixMargin
  double total() const { return a + b; }
};
Mix silicone_mix(const SiliconePreset& s, double grams)
{
  const double share = std::min(s.mix_a, s.mix_b) / (s.mix_a + s.mix_b);
  const double least = kLeastPart_g / share, total = std::max((1 + kMixMargin) * grams, least);
  return {total * s.mix_a / (s.mix_a + s.mix_b), total * s.mix_b / (s.mix_a + s.mix_b), total == least};
}

/// The two shots in pouring order, with the names the molds give them.
std::vector<std::pair<const char*, const CastShot*>> shots(const CastingSheet& sheet)
{
  return {{"shot1", &sheet.shot1}, {"shot2", &sheet.shot2}};
}

std::string fixed(double value, int digits) { return fmt::format("{:.{}f}", value, digits); }

/// "the sprue hole", "the 2 sprue holes (one for each part that the others do not reach, …)".
std::string sprue_holes(int sprues)
{
  return sprues == 1
             ? "the sprue hole"
             : fmt::format("the {} sprue holes (one for each part that the others do not reach, one after the other)",
                           sprues);
}
/// "the vent", "every one of the 3 vents".
std::string vent_holes(int vents) { return vents == 1 ? "the vent" : fmt::format("every one of the {} vents", vents); }

/// The silicone: which one, the figures the simulation used, and per shot how much to mix of each part.
std::string silicone_text(const CastingSheet& sheet)
{
  const SiliconePreset& s = sheet.silicone;
  std::string text = wrapped(
      fmt::format(
          "Silicone: {} ({}), mixed {:g}A : {:g}B by weight; pot life {:.0f} min, demold after {:.0f} h at "
          "23 °C (the maker's data sheet). The simulation took E = {:.1f} kPa, Poisson's ratio {:.2f} and "
          "{:.0f} kg/m³ ({}).",
          s.name, s.hardness, s.mix_a, s.mix_b, s.pot_life / kMinute, s.demold_time / kHour,
          sheet.youngs_modulus / units::kPa, sheet.poisson_ratio, sheet.density,
          sheet.preset.empty()
              ? fmt::format(
                    "{}; the handling here is Ecoflex 00-30's, the default: name a [material] preset for another "
                    "silicone. {}'s preset, fitted to its published stress-strain data, has E = {:.1f} kPa "
                    "([material] preset = \"{}\"){}",
                    sheet.paper_material ? "[material]: the paper's figures" : "[material] as the design sets them",
                    s.name, s.youngs_modulus() / units::kPa, s.key,
                    sheet.paper_material && s.youngs_modulus() < sheet.youngs_modulus
                        ? ": cast in it, the robot moves otherwise than simulated; a strip of your own cast, pulled "
                          "with a known weight, settles it"
                        : "")
              : "[material] preset = \"" + sheet.preset + "\""),
      "", "  ");
  for (const auto& [shot, info] : shots(sheet)) {
    const double grams = info->mass / units::gram;
    const Mix mix = silicone_mix(s, grams);
    const std::string why =
        mix.least ? fmt::format("the least batch that weighs {:g} g or more of each part, so that a 0.1 g scale gets "
                                "the ratio within 2 %",
                                kLeastPart_g)
                  : fmt::format("{:.0f} % more, for the cup and the nozzle", 100 * kMixMargin);
    text += wrapped(fmt::format("{}: {:.1f} mL, {:.1f} g; mix {:.1f} g ({:.1f} g of A and {:.1f} g of B: {}).",
                                info == &sheet.shot1 ? "Shot 1" : "Shot 2", info->volume / units::mL, grams,
                                mix.total(), mix.a, mix.b, why),
                    "  ", "    ");
  }
  return text + wrapped(fmt::format("Before each shot: spray or brush mold release (one made for platinum silicone) "
                                    "onto the mold's cavity faces, and never onto the cast body or the muscles: shot "
                                    "2 must bond to them; weigh A and B, stir for 3 minutes scraping the cup's "
                                    "sides and bottom, {}, and inject within the pot life.",
                                    s.degas_recommended ? "vacuum-degas it (the data sheet recommends it)"
                                                        : "vacuum-degas it if you have a chamber"),
                        "  ", "    ");
}

/// Each muscle: its cut length, diameter, which end takes the supply tube and which is sealed.
std::string muscles_text(const CastingSheet& sheet)
{
  std::string text = "\n";
  // The channel as molds cuts it (two_shot_molds.cpp's end_channel): until session 45 the sheet gave the
  // socket's width as the tube's, which a new user found does not pass the hole through the wall.
  text += wrapped(fmt::format("Muscles ({0:.1f} mm in diameter): cut each to its length inside the "
                              "body, and before you lay it into its groove fit its supply tube and "
                              "seal its other end (shot 2 buries both). A supply tube leaves shot 2's mold "
                              "through a hole {0:.1f} mm wide, past a socket {1:.1f} mm wide reaching {2:.1f} mm "
                              "beyond the skin, where the silicone closes around the muscle's end and the "
                              "tube's fitting (join them with a fitting no wider than the socket, such as a "
                              "barbed connector or a glued sleeve; a Luer fitting to the pressure supply goes on "
                              "the tube's outer end, outside the mold): a tube of {0:.1f} mm outside diameter "
                              "plugs the hole while shot 2 is poured (wrap a thinner one with tape to that width).",
                              sheet.muscle_diameter / units::mm, sheet.end_channel_diameter / units::mm,
                              sheet.end_channel_length / units::mm),
                  "", "");
  for (const MuscleCut& c : sheet.cuts) {
    if (!c.supply) {
      text += wrapped(fmt::format("{}: {:.1f} mm. Neither end leaves the body: seal both; no channel leads a supply "
                                  "tube out (route the fiber so that one end reaches the skin).",
                                  c.name, c.length_inside / units::mm),
                      "  ", "    ");
      continue;
    }
    const MuscleEnd &supply = c.supply_end(), &sealed = c.sealed_end();
    text += wrapped(fmt::format("{}: {:.1f} mm. Fit the supply tube to its {} end, which leaves the "
                                "body at {}; seal its {} end, {}.",
                                c.name, c.length_inside / units::mm, *c.supply == 0 ? "first" : "last",
                                format_mm(supply.skin_point), *c.supply == 0 ? "last" : "first",
                                sealed.leaves_body
                                    ? "which leaves the body at " + format_mm(sealed.skin_point) +
                                          ": plug that channel's outer hole for shot 2 (e.g. with a short piece of "
                                          "tube) and trim the cast flush there"
                                    : "buried in the body at " + format_mm(sealed.at)),
                    "  ", "    ");
  }
  return text;
}

/// The metric bolt a hole of width `hole` (m) takes, by ISO 273: the largest whose medium clearance hole is no
/// wider than it, while it is no wider than that bolt's coarse one ("M3" for 3.4 mm; none for 2 mm, under M2's
/// 2.4 mm, nor for 20 mm, past M8's 10 mm).
std::string bolt_for(double hole)
{
  struct Clearance {
    double medium, coarse;
    const char* bolt;
  };
  static constexpr std::array<Clearance, 7> kIso273{{{2.4e-3, 2.6e-3, "M2"},
                                                     {2.9e-3, 3.1e-3, "M2.5"},
                                                     {3.4e-3, 3.6e-3, "M3"},
                                                     {4.5e-3, 4.8e-3, "M4"},
                                                     {5.5e-3, 5.8e-3, "M5"},
                                                     {6.6e-3, 7.0e-3, "M6"},
                                                     {9.0e-3, 10.0e-3, "M8"}}};
  std::string bolt;
  for (const Clearance& c : kIso273)
    if (c.medium <= hole * (1 + 1e-9)) bolt = hole <= c.coarse * (1 + 1e-9) ? c.bolt : "";
  return bolt;
}

/// "Close the two halves on their keys and clamp them", with the screws when the mold has them.
std::string clamp_text(const CastShot& shot, double screw_diameter)
{
  if (shot.screw_holes == 0) return "Close the two halves on their keys and clamp them (spring clamps or rubber bands)";
  const std::string bolt = bolt_for(screw_diameter);
  return fmt::format("Close the two halves on their keys and bolt them through the {} screw holes ({:.1f} mm{}: "
                     "bolts long enough to pass both halves, with nuts)",
                     shot.screw_holes, screw_diameter / units::mm, bolt.empty() ? "" : ", " + bolt);
}

/// The halves that stand thin deep ribs, to be printed solid; nothing where a draft tapers them.
std::string ribs_text(const CastingSheet& sheet, const std::string& ext)
{
  if (sheet.draft) return "";
  std::vector<std::string> parts;
  for (const auto& [shot, name] : {std::pair{&sheet.shot1, "shot1"}, std::pair{&sheet.shot2, "shot2"}})
    for (const auto& [ribs, half] : {std::pair{&shot->lower_ribs, "lower"}, std::pair{&shot->upper_ribs, "upper"}})
      if (ribs->count > 0)
        parts.push_back(fmt::format("{}-{}{} ({} rib{}, down to {:.1f} mm thick, up to {:.1f} mm deep)", name, half,
                                    ext, ribs->count, ribs->count > 1 ? "s" : "", ribs->thinnest / units::mm,
                                    ribs->deepest / units::mm));
  if (parts.empty()) return "";
  return wrapped(fmt::format("Print {} solid (100 % infill): {} thin deep ribs standing into the cavity, the mold's "
                             "side of the body's narrow slots or gaps, which printed hollow may break, or tear the "
                             "cast, as the half comes off: {}. Or set [mold] draft_deg (1–3°) to taper them "
                             "(molds/report.json lists each).",
                             parts.size() > 1 ? "these halves" : "this half", parts.size() > 1 ? "they have" : "it has",
                             fmt::format("{}", fmt::join(parts, "; "))),
                 "", "");
}

/// Which side of the body each half holds: the molds open along their pull.
std::string halves_text(const Eigen::Vector3d& pull)
{
  const auto direction = [](const Eigen::Vector3d& v) {
    return fmt::format("({:g}, {:g}, {:g})", v.x() + 0.0, v.y() + 0.0, v.z() + 0.0);
  };
  return wrapped(fmt::format("Each mold opens along {} in the design's frame: its lower half holds the side of the "
                             "body that faces {}, its upper half the side that faces {}.",
                             direction(pull), direction(-pull), direction(pull)),
                 "", "");
}

} // namespace

std::string casting_guide(const CastingSheet& sheet)
{
  const CastShot &one = sheet.shot1, &two = sheet.shot2;
  const std::string ext = "." + sheet.format, FORMAT = sheet.format == "3mf" ? "3MF file" : "STL";
  const double cure = sheet.silicone.demold_time / kHour;
  const auto step = [](int n, const std::string& text) { return wrapped(text, fmt::format("  {}. ", n), "     "); };
  const char* engraved = "Each part says which it is, engraved into a side (or its outer end) where it has room: the "
                         "design's name, the shot and the half (\"S1 LOWER\": shot 1's lower half); \"IN\" is "
                         "engraved beside each sprue.";
  const char* plain = "The parts are not engraved ([mold] labels = false): tell them apart by their file names as "
                      "you take them off the printer; a sprue is the countersunk hole.";
  std::string text = fmt::format("fibermold mold parts for \"{}\"\n\n", sheet.design_name);
  text += wrapped(fmt::format("Print every mold part (the {}s named shot1-… and shot2-…) as it lies (each stands on "
                              "its largest flat face; units mm), in PLA or PETG: platinum silicone can fail to cure "
                              "against some printed resins (test a resin with a small pour first).",
                              FORMAT),
                  "", "");
  text += ribs_text(sheet, ext);
  text += wrapped(sheet.labels ? engraved : plain, "", "") + halves_text(sheet.pull) + "\n";
  text += silicone_text(sheet) + muscles_text(sheet);
  text += fmt::format("\nShot 1, the grooved body: shot1-lower{} and shot1-upper{}.\n", ext, ext);
  text += step(1, clamp_text(one, sheet.screw_diameter) +
                      ". Stand the mold upright: lower half down, the sprue hole underneath, the vents "
                      "on top, the mold raised on two spacers (blocks or books) clear of the sprue so "
                      "that the dispenser's nozzle reaches it. A sprue is the countersunk hole (its seat "
                      "takes the dispenser's nozzle); the vents are plain.");
  text += step(2, fmt::format("Inject about {:.1f} mL ({:.1f} g) of silicone through {} from below, slowly, until "
                              "silicone comes out of {}; then plug the sprue.",
                              one.volume / units::mL, one.mass / units::gram, sprue_holes(one.sprues),
                              vent_holes(one.vents)));
  text +=
      step(3, fmt::format("Let it cure ({:.0f} h), and demold: the body has an open groove for each muscle.", cure));
  text += step(4, "Trim the cast's sprue and vent stubs flush with its skin: shot 2's cavity is the body's own shape "
                  "and has no room for them.");
  text += '\n';
  // The simulation put the muscle at the groove's bottom; shot 2's silicone, denser than a muscle holding air,
  // would lift it toward the skin while it cures unless it is held there.
  text += wrapped("Lay each muscle into its groove, resting on the groove's bottom, its ends and supply tubes "
                  "along the grooves' ends, and tack it there every 2 to 3 cm with small dots of silicone adhesive "
                  "(such as Smooth-On Sil-Poxy) between the muscle and the groove's wall, not under it (a dot under "
                  "it lifts it off the route), cured before shot 2: a muscle holding air is lighter than liquid "
                  "silicone and would float up the groove, off the route simulated.",
                  "", "");
  text += fmt::format("\nShot 2, the overmold: shot2-lower{} and shot2-upper{}.\n", ext, ext);
  text += step(5, "Put the grooved body with its muscles into the lower half, grooves up, and route the supply tubes "
                  "out through the channels at the fibers' ends (where a channel runs up through the upper half rather "
                  "than along the parting plane, thread its tube through it as you lower the half on). " +
                      clamp_text(two, sheet.screw_diameter) + ".");
  text += step(6, fmt::format("Stand the mold upright as in shot 1. In this shot the sprue comes in from the TOP of "
                              "the upper half, straight over the lowest point of the grooves: the cured body lies "
                              "below them, so they cannot be filled from below. Inject about {:.1f} mL ({:.1f} g) of "
                              "silicone slowly through {}; it runs down into the grooves and rises around the "
                              "muscles; go on until silicone comes out of {}.",
                              two.volume / units::mL, two.mass / units::gram, sprue_holes(two.sprues),
                              vent_holes(two.vents)));
  text += step(7, fmt::format("Let it cure ({:.0f} h), demold and trim the stubs as in step 4.", cure));
  return text + "\n" +
         wrapped(fmt::format("The fill of both shots was simulated (silicone rising level by level from the sprue): "
                             "shot 1 reaches {:.1f} % of its cavity and traps {:.2f} mm³ of air, shot 2 reaches "
                             "{:.1f} % of the grooves (the rest: crevices along the muscles thinner than the "
                             "simulation's voxel) and traps {:.2f} mm³ (allowed: {:.1f} mm³ per shot). manifest.json "
                             "lists where each sprue and vent meets the cavity, each part's size, volume, checks and "
                             "how its printed pose maps back to the body.",
                             100 * one.reached, one.trapped_air / units::mm3, 100 * two.reached,
                             two.trapped_air / units::mm3, one.trapped_air_tolerance / units::mm3),
                 "", "");
}

ReportTable silicone_table(const CastingSheet& sheet)
{
  const SiliconePreset& s = sheet.silicone;
  ReportTable t{
      fmt::format("Silicone: {}, {:g}A : {:g}B by weight, pot life {:.0f} min, demold after {:.0f} h; its fill "
                  "(simulated: rising level by level from the sprues)",
                  s.name, s.mix_a, s.mix_b, s.pot_life / kMinute, s.demold_time / kHour),
      {"shot", "volume (mL)", "mass (g)",
       fmt::format("mix, +{:.0f} %, at least {:g} g of each part (g of A + g of B)", 100 * kMixMargin, kLeastPart_g),
       "sprues", "vents", "fill reached", "air trapped (mm³)"},
      {}};
  for (const auto& [shot, info] : shots(sheet)) {
    const Mix mix = silicone_mix(s, info->mass / units::gram);
    t.rows.push_back({shot, fixed(info->volume / units::mL, 2), fixed(info->mass / units::gram, 2),
                      fixed(mix.a, 1) + " + " + fixed(mix.b, 1),
                      fmt::format("{} from {}", info->sprues, info->sprues == 0 ? "" : info->sprue_from),
                      std::to_string(info->vents), fixed(100 * info->reached, 1) + " %",
                      fixed(info->trapped_air / units::mm3, 2)});
  }
  return t;
}

ReportTable muscles_table(const CastingSheet& sheet)
{
  ReportTable t{fmt::format("Muscles to cut ({:.1f} mm in diameter)", sheet.muscle_diameter / units::mm),
                {"fiber", "cut length: inside the body (mm)", "supply tube at", "sealed end at"},
                {}};
  for (const MuscleCut& c : sheet.cuts) {
    if (!c.supply) {
      t.rows.push_back(
          {c.name, fixed(c.length_inside / units::mm, 1), "none: neither end leaves the body", "both ends"});
      continue;
    }
    const MuscleEnd &supply = c.supply_end(), &sealed = c.sealed_end();
    t.rows.push_back({c.name, fixed(c.length_inside / units::mm, 1), format_mm(supply.skin_point),
                      sealed.leaves_body ? format_mm(sealed.skin_point) : format_mm(sealed.at) + ", buried"});
  }
  return t;
}

} // namespace fibermold
