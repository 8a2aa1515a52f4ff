#pragma once
// A report as one self-contained HTML page that opens in any browser without network access:
// tables, and a 3D view (plain WebGL, no library) of meshes and polylines that can be turned,
// zoomed and switched on and off.

#include <array>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "mesh/surface_mesh.hpp"

namespace fibermold {

struct ReportMesh {
  std::string name;
  SurfaceMesh mesh; ///< m
  std::array<float, 3> colour{0.7F, 0.7F, 0.7F};
  bool visible = true;
  Eigen::Vector3d offset = Eigen::Vector3d::Zero(); ///< m, where it is drawn (e.g. a mold half lifted off)
};

struct ReportLine {
  std::string name;
  std::vector<Eigen::Vector3d> points; ///< m
  std::array<float, 3> colour{0.8F, 0.1F, 0.1F};
  bool visible = true;
};

/// A line plot drawn as inline SVG: each series a polyline over shared axes.
struct ReportPlot {
  std::string title, x_label, y_label;
  std::vector<std::pair<std::string, std::vector<Eigen::Vector2d>>> series; ///< name, (x, y) points
  bool log_y = false;                                                       ///< y on a log scale (values > 0)
  bool whole_x = false; ///< x counts (iterations): its ticks whole numbers
};

/// About `count` + 1 round values within [lo, hi], 1, 2 or 5 × 10^k apart, for a plot's axis
/// (Heckbert, "Nice numbers for graph labels", Graphics Gems, 1990): iterations 0, 20, 40, 60, where
/// quarters of the range labelled a 63-iteration run 15.75, 31.5, 47.25.
/// `least_step`: no closer than that (1 for a count: a 3-iteration run at 1, 2, 3, not 1, 1.5, …).
std::vector<double> nice_ticks(double lo, double hi, int count = 4, double least_step = 0);

struct ReportTable {
  std::string title;
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
};

/// The page; `warnings` (what a user must not miss: a target far from reached, a muscle at its
/// limit) as a banner under the title. Once the 3D view has drawn, the element #status says "drawn N of M triangles, P
/// of Q pixels painted" (the visible meshes' triangles, and the pixels of the first view that are not background), or
/// why it could not draw, so that a headless browser can check it.
std::string report_html(const std::string& title, const std::vector<ReportMesh>& meshes,
                        const std::vector<ReportLine>& lines, const std::vector<ReportTable>& tables,
                        const std::vector<ReportPlot>& plots = {}, const std::vector<std::string>& warnings = {});

} // namespace fibermold
