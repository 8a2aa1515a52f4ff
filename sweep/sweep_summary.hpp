#pragma once
// A sweep's results side by side: sweep/summary.csv and summary.html, one row per case with its
// axis values, each target's error (RMSE and max over the tracking curves after collide, mm) and a
// pose target's turn reached (%), the pressures (kPa), how the optimization ended, silicone (mL),
// mold parts, each stage's time and the case's report.html; the best cases per target marked, and on
// the page a scatter plot of each target's error against the first axis.

#include <filesystem>

#include "sweep/sweep_plan.hpp"

namespace fibermold {

/// Reads each case's outputs (absent ones leave empty cells) and writes both files.
void write_sweep_summary(const SweepPlan& plan, const std::filesystem::path& build_dir);

} // namespace fibermold
