#pragma once
// The casting and assembly sheet: README.txt's steps from the printer to the cast robot (what to
// print, the silicone and how much of it to mix per shot, each muscle's cut and ends, the two shots)
// and report.html's tables of the silicone and the muscles. Built from what the molds and the
// muscles' cuts give, with no design file in it: the export stage fills it in.

#include <string>
#include <vector>

#include <Eigen/Core>

#include "export/muscle_cut.hpp"
#include "export/report_html.hpp"
#include "molds/silicone_presets.hpp"

namespace fibermold {

/// A mold half's thin deep ribs (molds/report.json's thin_ribs): how many, the thinnest, the deepest (m).
struct HalfRibs {
  int count = 0;
  double thinnest = 0, deepest = 0;
};

/// One shot of the molds (molds/report.json's "shots").
struct CastShot {
  double volume = 0;                ///< m³ of silicone the cavity takes
  double mass = 0;                  ///< kg of it
  int screw_holes = 0;              ///< bolts through the two halves; 0: they are clamped
  int sprues = 1, vents = 1;        ///< holes of each kind
  std::string sprue_from = "below"; ///< "below" or "above": where the first sprue comes in
  double reached = 0;               ///< fraction of the cavity the simulated fill reaches
  double trapped_air = 0;           ///< m³ the simulated fill traps
  double trapped_air_tolerance = 0; ///< m³ a shot may trap (the part checks' limit)
  HalfRibs lower_ribs, upper_ribs;  ///< thin deep ribs each half stands into the cavity
};

struct CastingSheet {
  std::string design_name;
  std::string format = "stl"; ///< the parts' file format: "stl" or "3mf"
  bool labels = true;         ///< the parts are engraved with which they are
  SiliconePreset silicone;    ///< whose handling the sheet gives
  std::string preset;         ///< `[material] preset` as named; empty: the paper's default material
  double youngs_modulus = 0, poisson_ratio = 0, density = 0; ///< Pa, –, kg/m³: what the simulation took
  bool paper_material = false; ///< no preset and those three at the paper's EcoFlex 00-30 figures
  double muscle_diameter = 0;  ///< m
  /// m: shot 2's channel where a supply tube leaves the body, a socket end_channel_diameter wide reaching
  /// end_channel_length beyond the skin, then a hole muscle_diameter wide out through the wall
  double end_channel_diameter = 0, end_channel_length = 0;
  double screw_diameter = 0; ///< m: the screw holes' width
  bool draft = false;        ///< [mold] draft_deg > 0: the ribs are tapered
  std::vector<MuscleCut> cuts;
  Eigen::Vector3d pull = Eigen::Vector3d::UnitZ(); ///< the molds open along it
  CastShot shot1, shot2;
};

/// README.txt's sheet: printing, the silicone, the muscles, and the two shots step by step.
std::string casting_guide(const CastingSheet& sheet);

/// report.html's silicone table: per shot the volume, mass, what to mix, the ports and the fill.
ReportTable silicone_table(const CastingSheet& sheet);

/// report.html's muscles table: per muscle its cut length and where its supply and sealed ends are.
ReportTable muscles_table(const CastingSheet& sheet);

} // namespace fibermold
