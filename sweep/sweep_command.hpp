#pragma once
// `fibermold sweep SWEEP [--engine local|slurm] [--jobs N] [--build-dir DIR] [--no-wait] [--status]`
// (docs/sweep.md): expands the sweep into cases, plans which case builds which stage
// (sweep_plan.hpp) and runs the stale ones stage by stage: as N local processes, or as one Slurm
// job array per stage, each depending on the one before. Every task is `fibermold sweep-task`:
// adopt the shared upstream stages, then make one stage in one case's folder.

#include <filesystem>
#include <string>

#include "make/runner.hpp"
#include "sweep/sweep_file.hpp"

namespace fibermold {

struct SweepRequest {
  std::filesystem::path sweep;
  std::string engine = "local";    ///< local | slurm
  int jobs = 0;                    ///< local processes at once; 0: one per hardware thread
  std::filesystem::path build_dir; ///< empty: out/sweep-<name>
  bool wait = true;                ///< slurm: wait for the jobs to finish
  bool status = false;             ///< report the sweep's state, run nothing
  SlurmOptions slurm;              ///< set fields override the sweep file's [slurm]
};

/// The exit code: 0 when every case is built, 1 when a task failed, 2 for bad input (InputError
/// is thrown).
int run_sweep(const SweepRequest& request, const Runner& runner);

/// One task: makes `stage` in case `case_id`'s folder, after adopting the stages upstream of it
/// that other cases own. Exit code as `fibermold make`.
int run_sweep_task(const std::filesystem::path& build_dir, const std::string& stage, const std::string& case_id,
                   const Runner& runner);

} // namespace fibermold
