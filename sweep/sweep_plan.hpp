#pragma once
// Which case builds which stage. Cases whose designs agree on a stage's fingerprint (its design
// values, input files and upstream fingerprints: Runner::fingerprints) share that stage: the first
// such case builds it in its own folder (it owns it), and the others adopt its outputs by hard
// links before they build downstream of it. A sweep over [mold] values thus optimizes once.
//
// The sweep's build folder:
//   sweep.json              the plan: cases, their axis values, and each case's owner per stage
//   cases/<id>/design.toml  a case's design; cases/<id>/ is its build folder
//   summary.csv, summary.html

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "make/runner.hpp"
#include "sweep/sweep_cases.hpp"

namespace fibermold {

struct SweepPlan {
  std::filesystem::path sweep_file;
  std::string name;
  std::vector<std::string> axes;
  std::vector<SweepCase> cases;                                    ///< design text left empty when read back
  std::vector<std::string> stages;                                 ///< dependency order
  std::map<std::string, std::map<std::string, std::string>> owner; ///< case → stage → owning case

  /// The cases that build `stage` (own it), in case order.
  std::vector<std::string> builders(const std::string& stage) const;
  std::filesystem::path case_dir(const std::filesystem::path& build_dir, const std::string& id) const
  {
    return build_dir / "cases" / id;
  }
};

/// Loads each case's design (written to its folder first) and assigns owners: of the cases that
/// agree on a stage, the one that owned it in the last plan, else the first.
SweepPlan plan_sweep(const SweepFile& sweep, const std::vector<SweepCase>& cases, const Runner& runner,
                     const std::filesystem::path& build_dir);

void write_plan(const SweepPlan& plan, const std::filesystem::path& build_dir);
/// Throws std::runtime_error when the build folder has no readable sweep.json.
SweepPlan read_plan(const std::filesystem::path& build_dir);

/// Replaces `stage` in build folder `to` by hard links to its outputs, stamp and a copy of its log
/// in `from` (copies where hard links are not possible). Nothing changes when `from` has no stamp,
/// or when `to` holds this very build already (the same stamp file).
void adopt_stage(const std::filesystem::path& from, const std::filesystem::path& to, const std::string& stage);

} // namespace fibermold
