#pragma once
// Text engraved into a flat outside face of a printed mold part, so that the part says what it is
// (the design, the shot and the half) and which hole is the sprue. The letters are the Hershey
// simplex roman font's strokes (Debian's hershey-fonts-data, read at run time), each stroke a
// groove `stroke` wide with round ends and a flat floor `depth` under the face. Gaps between
// strokes narrower than a little over min_wall (the inside of a V, an A's counter) are cut too, so
// that no land between two grooves is a wall thinner than the printer takes. A label is placed
// where the groove stays min_wall + depth clear of every other face of the part (the cavity, holes,
// the face's edges): so it never comes within min_wall of the cavity or another engraving.

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mesh/surface_mesh.hpp"

namespace fibermold {

/// How labels are cut; each default here once.
struct LabelStyle {
  double depth = 0.6e-3;       ///< m, the grooves' floor under the face
  double stroke = 0.9e-3;      ///< m, a groove's width
  double min_height = 5e-3;    ///< m, the smallest capital height tried
  double max_height = 8e-3;    ///< m, the largest capital height tried
  double height_step = 0.5e-3; ///< m, between the heights tried
};

/// A flat face of a part that may take a label: a rectangle on the part's surface.
struct LabelFace {
  std::string name;       ///< for the log and report, e.g. "-y side"
  Eigen::Vector3d centre; ///< m, the rectangle's centre, on the face's plane
  Eigen::Vector3d normal; ///< unit, out of the part
  Eigen::Vector3d up;     ///< unit, in the plane: the letters' up; they read along up × normal
  Eigen::Vector2d size;   ///< m, along the reading direction and along up
  /// Where on the face the label is wanted: the placements nearest it are tried first (the centre by default).
  std::optional<Eigen::Vector3d> near;
};

/// A label as cut: its text in its place.
struct PlacedLabel {
  std::string text;
  std::string face;                                 ///< LabelFace::name
  Eigen::Vector3d centre;                           ///< m, the centre of the text's box, on the face
  Eigen::Vector3d normal;                           ///< unit, out of the part
  Eigen::Vector3d up;                               ///< unit, the letters' up
  double height = 0;                                ///< m, of a capital letter
  Eigen::Vector2d extent = Eigen::Vector2d::Zero(); ///< m, the grooves' box along the reading direction and up
  double depth = 0;                                 ///< m, of the grooves' floor under the face
};

/// The capital heights tried, from max_height down by height_step to min_height, each computed as
/// max − k·step (repeated subtraction drifted to 5.999999999999998 mm).
std::vector<double> label_heights(const LabelStyle& style);

/// The character the font cuts for `c`: lower case as capitals, anything but printable ASCII as '?'.
char label_character(char c);

/// The strokes of `text` (printable ASCII; lower case is cut as capitals, other characters as '?') as
/// polylines in the plane, m: capitals `height` high from the baseline y = 0, starting at x = 0; each
/// letter moved right from the font's spacing where needed to keep `gap` (m, axis to axis) from the
/// strokes of the letter before it (a pinch between two letters would be a land too thin to print).
/// Throws std::runtime_error naming the font file and the package when the font is not installed.
std::vector<std::vector<Eigen::Vector2d>> text_strokes(const std::string& text, double height, double gap = 0);

/// The text as engraved in the plane, the closed outlines of its grooves (m; outer outlines
/// counter-clockwise, holes clockwise), centred on the origin. `closing`: gaps narrower than twice
/// it are cut as well, and letters keep stroke + 2 closing between their strokes (text_strokes' gap).
std::vector<std::vector<Eigen::Vector2d>> text_outlines(const std::string& text, double height, double stroke,
                                                        double closing);

/// The area the outlines enclose, m² (holes subtracted).
double outlines_area(const std::vector<std::vector<Eigen::Vector2d>>& outlines);

/// Whether the label's lands print: cut into a plain slab, the part checks find no wall under
/// min_wall (a pinch between two strokes' ends that the closing leaves).
bool lands_print(const std::string& text, double height, const LabelStyle& style, double min_wall);

/// The first of `texts` that fits (largest height first) on the first of `faces` that takes it,
/// clear of every other face of `part` and of the labels `placed` already by min_wall + depth, and
/// whose lands print (lands_print); nothing when none fits.
std::optional<PlacedLabel> place_label(const SurfaceMesh& part, const std::vector<std::string>& texts,
                                       const std::vector<LabelFace>& faces, const LabelStyle& style, double min_wall,
                                       const std::vector<PlacedLabel>& placed = {});

/// The closed solid a label's engraving removes: its outlines from `depth` under the face to
/// 0.5 mm above it (outside the part).
SurfaceMesh label_solid(const PlacedLabel& label, const LabelStyle& style, double min_wall);

/// `part` with the labels cut into it (one boolean difference). Throws std::runtime_error when the
/// boolean fails.
SurfaceMesh engrave(const SurfaceMesh& part, const std::vector<PlacedLabel>& labels, const LabelStyle& style,
                    double min_wall);

} // namespace fibermold
