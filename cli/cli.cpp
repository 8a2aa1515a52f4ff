#include "cli/cli.hpp"

#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <thread>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <pthread.h>
#include <semaphore.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include "cli/terminal_progress.hpp"
#include "core/input_error.hpp"
#include "core/units.hpp"
#include "design/design_file.hpp"
#include "design/unlikely_values.hpp"
#include "make/build_lock.hpp"
#include "make/runner.hpp"
#include "stages/check.hpp"
#include "stages/simulate_command.hpp"
#include "stages/stages.hpp"
#include "sweep/sweep_command.hpp"

#ifndef FIBERMOLD_DEFAULT_DESIGN
#define FIBERMOLD_DEFAULT_DESIGN "examples/twisting-bar/design.toml"
#endif

namespace fibermold {

namespace fs = std::filesystem;

namespace {

/// Posted by the signal handler (sem_post is async-signal-safe); the watchdog waits on it.
sem_t g_signalled;

void on_signal(int)
{
  request_interrupt();
  sem_post(&g_signalled);
}

/// After Ctrl-C or SIGTERM the running stage stops at its next checkpoint, cleans up and exits 130.
/// A step without checkpoints (a boolean of two large meshes, a level-set carving) would keep it
/// running: past kStopDeadline the watchdog ends the process as a kill would, which the pipeline
/// survives by design (docs/pipeline.md, "Atomic outputs"): the stage keeps its previous outputs
/// and no stamp, and its build lock is released with the process.
constexpr auto kStopDeadline = std::chrono::milliseconds(700);

void watch_for_stop()
{
  while (sem_wait(&g_signalled) != 0) {
  }
  std::this_thread::sleep_for(kStopDeadline);
  constexpr char message[] =
      "fibermold: interrupted; the running step had no checkpoint within 0.7 s, so it was stopped at once: the "
      "stage that was running is stale, its previous outputs kept\n";
  [[maybe_unused]] const auto written = ::write(STDERR_FILENO, message, sizeof message - 1);
  std::_Exit(kExitInterrupted);
}

/// Ctrl-C (or SIGTERM) asks the running stage to stop at its next checkpoint, within 1 s in any
/// case (watch_for_stop); a second Ctrl-C kills at once (SA_RESETHAND), still leaving the previous
/// outputs and a stale stamp. The watchdog thread blocks both signals, so that they interrupt the
/// main thread's system calls as before. `watchdog` false: the command's own loop answers at once
/// and must outlive its children (the sweep: it stops them, and stops waiting for Slurm's jobs).
void install_signal_handlers(bool watchdog)
{
  sem_init(&g_signalled, 0, 0);
  if (watchdog) {
    sigset_t stops, previous;
    sigemptyset(&stops);
    sigaddset(&stops, SIGINT);
    sigaddset(&stops, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &stops, &previous);
    std::thread(watch_for_stop).detach();
    pthread_sigmask(SIG_SETMASK, &previous, nullptr);
  }
  struct sigaction action {};
  action.sa_handler = on_signal;
  action.sa_flags = SA_RESETHAND;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

/// `[DESIGN] [STAGE...]`: the first word is the design when it names a file or ends in .toml.
struct DesignAndStages {
  fs::path design;
  std::vector<std::string> stages;
};

/// The first word is the design unless it names a stage; `check` and `simulate` take only a design.
DesignAndStages split_arguments(const std::vector<std::string>& words, const fs::path& default_design,
                                const std::vector<std::string>& stage_names)
{
  DesignAndStages result{default_design, {}};
  std::size_t first = 0;
  if (!words.empty() && std::find(stage_names.begin(), stage_names.end(), words[0]) == stage_names.end()) {
    result.design = words[0];
    first = 1;
  }
  result.stages.assign(words.begin() + static_cast<std::ptrdiff_t>(first), words.end());
  return result;
}

fs::path build_dir_for(const Design& design, const std::string& option)
{
  return option.empty() ? fs::path("out") / design.design.name : fs::path(option);
}

void print_status(const std::vector<StageStatus>& statuses)
{
  std::size_t width = 0;
  for (const StageStatus& s : statuses) width = std::max(width, s.stage.size());
  for (const StageStatus& s : statuses) {
    if (s.fresh) {
      fmt::print("{:<{}}  fresh\n", s.stage, width);
      continue;
    }
    fmt::print("{:<{}}  stale ({})\n", s.stage, width, s.summary());
  }
}

void print_design_summary(const Design& d)
{
  fmt::print("{}: ok\n", d.file.string());
  fmt::print("  design {}: surface {} ({}), basis {}, {} fixed region(s), {} fiber(s), {} target(s), "
             "{} tracking curve(s)\n",
             d.design.name, d.design.surface.filename().string(), d.design.units, choice_name(d.sim.basis),
             d.fixed.size(), d.fibers.size(), d.targets.size(), d.tracking_curves.size());
}

ProgressFactory terminal_progress()
{
  const bool tty = ::isatty(STDERR_FILENO) != 0;
  return [tty](const std::string& stage) { return std::make_unique<TerminalProgress>(stage, stderr, tty); };
}

int report_input_error(const InputError& e)
{
  for (const Diagnostic& d : e.diagnostics()) fmt::print(stderr, "{}\n", d.to_string());
  return kExitBadInput;
}

int run_simulate(const Design& design, const Runner& runner, const fs::path& build_dir, const SimulateRequest& request)
{
  const SimulateResult r = fibermold::simulate(design, runner, build_dir, request, terminal_progress());
  fmt::print("simulate {}: max displacement {:.3f} mm; Newton {} iterations, |∇E| {:.2e} N, {:.2f} s "
             "(assembly {:.2f} s, factorization {:.2f} s, solve {:.2f} s)\n  {}\n",
             r.name, r.max_displacement / units::mm, r.summary.iterations, r.summary.residual, r.summary.seconds_total,
             r.summary.seconds_assembly, r.summary.seconds_factorization, r.summary.seconds_solve, r.vtu.string());
  if (!r.conditioning.empty()) fmt::print("  warning: {}\n", r.conditioning);
  fmt::print("  {}\n", r.muscles);
  if (!r.as_built.empty()) fmt::print("  {}\n", r.as_built);
  if (!r.poses.empty()) fmt::print("{}", r.poses); // its lines end in a newline
  if (const auto& f = r.refinement) {
    fmt::print("refined: {} nodes, {} tets, mean edge {:.2f} mm; max displacement {:.3f} mm\n"
               "  difference: surface max {:.3f} mm, RMS {:.3f} mm",
               f->nodes, f->tets, f->edge_length / units::mm, f->max_displacement / units::mm,
               f->surface_max / units::mm, f->surface_rms / units::mm);
    if (f->curve_samples > 0)
      fmt::print("; tracking curves max {:.3f} mm, RMS {:.3f} mm ({} samples)", f->curves_max / units::mm,
                 f->curves_rms / units::mm, f->curve_samples);
    fmt::print("\n");
    if (f->surface_max > kCoarseMeshShare * r.max_displacement)
      fmt::print("  warning: the surface moves {:.1f} % of the largest displacement between the two meshes (more than "
                 "{:.0f} %): the design's mesh is coarse for this deformation; a smaller [mesh] edge_length brings its "
                 "figures closer to the refined ones\n",
                 100 * f->surface_max / r.max_displacement, 100 * kCoarseMeshShare);
  }
  return kExitDone;
}

/// The design's values that read as written in another unit (unlikely_values.hpp), as warnings; returns them.
std::vector<Diagnostic> warn_unlikely_values(const Design& design, bool to_log)
{
  std::vector<Diagnostic> unlikely = unlikely_values(design);
  for (const Diagnostic& w : unlikely)
    if (to_log)
      spdlog::warn("{}", w.to_string());
    else
      fmt::print("warning: {}\n", w.to_string());
  return unlikely;
}

int run_check(const Design& design)
{
  warn_unlikely_values(design, false); // before the checks that may stop on what such a value causes
  const DesignSurfaceCheck c = check_design_surface(design);
  print_design_summary(design);
  fmt::print("  surface: closed, manifold, outward, no self-intersections; {} component(s), {:.6g} mm³\n",
             c.surface.components, c.surface.volume / units::mm3);
  // Its size in mm, [design] units applied: a wrong unit shows as a body 10 or 1000 times off.
  const Eigen::Vector3d size = (c.hi - c.lo) / units::mm;
  fmt::print("  body: {:.4g} × {:.4g} × {:.4g} mm, from {} to {}\n", size.x(), size.y(), size.z(), format_mm(c.lo),
             format_mm(c.hi));
  fmt::print("  mesh: {:.3g} mm edges{}, the surface's triangles {}: about {:.0f} tets\n", c.edge_length / units::mm,
             design.mesh.edge_length ? "" : " (by default)",
             c.treatment == SurfaceTriangles::keep    ? "kept"
             : c.treatment == SurfaceTriangles::split ? "split"
                                                      : "remeshed",
             c.estimated_tets);
  for (const std::string& w : c.surface.warnings) fmt::print("  warning: {}\n", w);
  for (const std::string& r : c.repairs) fmt::print("  repair would: {}\n", r);
  return kExitDone;
}

int run_make(const Design& design, const Runner& runner, const MakeOptions& options)
{
  if (runner.closure(options.targets).empty()) {
    fmt::print("nothing to do: this build of fibermold has no stages yet\n");
    return kExitDone;
  }
  const auto runs = runner.make(design, options, terminal_progress());
  double seconds = 0;
  int ran = 0;
  for (const StageRun& r : runs) {
    seconds += r.seconds;
    ran += r.ran ? 1 : 0;
    if (r.ran) fmt::print("{}: done in {:.2f} s\n", r.stage, r.seconds);
  }
  fmt::print("make: {} stage(s) ran, {} fresh, {:.2f} s; outputs in {}\n", ran, runs.size() - ran, seconds,
             options.build_dir.string());
  return kExitDone;
}

/// A stage that fails on a design warned of a value in another unit most likely fails on it (a new user's
/// modulus in kPa: warned at the start, then "did not reach equilibrium" 20 s later, the warning scrolled away).
void repeat_unlikely_values(const std::vector<Diagnostic>& unlikely)
{
  if (unlikely.empty()) return;
  fmt::print(stderr,
             "fibermold: the design has {} that read{} as written in another unit, which can cause such a failure: "
             "check {} first\n",
             unlikely.size() == 1 ? "a value" : "values", unlikely.size() == 1 ? "s" : "",
             unlikely.size() == 1 ? "it" : "them");
  for (const Diagnostic& w : unlikely) fmt::print(stderr, "  {}\n", w.to_string());
}

/// The exit code for what a command threw, told on stderr; a failed stage with the design's `unlikely` values again.
int report_failure(const std::exception_ptr& error, const std::vector<Diagnostic>& unlikely)
{
  try {
    std::rethrow_exception(error);
  } catch (const InputError& e) {
    return report_input_error(e);
  } catch (const StageFailed& e) {
    fmt::print(stderr, "fibermold: stage {} failed: {}\n  log: {}\n", e.stage(), e.what(), e.log().string());
    repeat_unlikely_values(unlikely);
    return kExitStageFailed;
  } catch (const BuildLocked& e) {
    fmt::print(stderr, "fibermold: {}\n", e.what());
    return kExitLocked;
  } catch (const Interrupted&) {
    fmt::print(stderr, "fibermold: interrupted; the stage that was running is stale, its previous outputs kept\n");
    return kExitInterrupted;
  } catch (const std::exception& e) { // `simulate`'s "did not reach equilibrium" among them
    fmt::print(stderr, "fibermold: error: {}\n", e.what());
    repeat_unlikely_values(unlikely);
    return kExitStageFailed;
  }
}

/// `fibermold sweep SWEEP [options]`: its options into `request`.
CLI::App* add_sweep_command(CLI::App& app, SweepRequest& request)
{
  CLI::App* sweep =
      app.add_subcommand("sweep", "Many designs: the cases of a sweep file, as local processes or Slurm job arrays");
  sweep->add_option("SWEEP", request.sweep, "The sweep file (docs/sweep.md)")->required();
  sweep->add_option("--engine", request.engine, "local (processes on this machine) or slurm (job arrays)")
      ->capture_default_str();
  sweep->add_option("--jobs", request.jobs, "local: tasks at once (default: one per hardware thread)");
  sweep->add_option("--build-dir", request.build_dir, "Sweep folder (default: out/sweep-<name>)");
  sweep->add_flag("--no-wait{false}", request.wait, "slurm: return once the jobs are submitted");
  sweep->add_flag("--status", request.status, "Report each stage's builds and the queue; run nothing");
  sweep->add_option("--partition", request.slurm.partition, "slurm: partition");
  sweep->add_option("--time", request.slurm.time, "slurm: time limit per task, e.g. 02:00:00");
  sweep->add_option("--cpus-per-task", request.slurm.cpus_per_task, "slurm: CPUs per task");
  sweep->add_option("--sbatch-flag", request.slurm.extra,
                    "slurm: one more sbatch flag, repeatable (e.g. --sbatch-flag=--mem=4G)");
  return sweep;
}

} // namespace

int fibermold_main(int argc, char** argv)
{
  spdlog::set_pattern("%v");
  CLI::App app{"fibermold: from a soft robot's body to printable mold parts.\n"
               "Stages: mesh → targets → optimize → collide → molds → export; only stale stages run.",
               "fibermold"};
  app.require_subcommand(1);
  app.set_version_flag("--version", Runner::default_program());
  app.footer("Exit codes: 0 done, 1 a stage failed on valid input, 2 bad input (command line, design file, mesh,\n"
             "build folder), 3 another fibermold is working in the build folder, 130 interrupted.\n"
             "DESIGN defaults to the bundled demo, " FIBERMOLD_DEFAULT_DESIGN ".");

  std::vector<std::string> words;
  std::vector<Diagnostic> unlikely; // the design's values in another unit, said again if a stage fails
  std::string build_dir_option, target;
  bool force = false;

  CLI::App* make = app.add_subcommand("make", "Run what is stale, up to STAGE (default: every stage)");
  make->add_option("DESIGN_AND_STAGES", words,
                   "[DESIGN] [STAGE...]: the first word is the design unless it is a stage");
  make->add_flag("--force", force, "Rerun the selected stages even when fresh");
  make->add_option("--build-dir", build_dir_option, "Build folder (default: out/<design name>)");

  CLI::App* status = app.add_subcommand("status", "Each stage: fresh, or stale and which input changed");
  status->add_option("DESIGN_AND_STAGES", words, "[DESIGN] [STAGE...]");
  status->add_option("--build-dir", build_dir_option, "Build folder (default: out/<design name>)");

  CLI::App* clean = app.add_subcommand("clean", "Remove the outputs, stamps and logs of stages (default: all)");
  clean->add_option("DESIGN_AND_STAGES", words, "[DESIGN] [STAGE...]");
  clean->add_option("--build-dir", build_dir_option, "Build folder (default: out/<design name>)");

  CLI::App* check = app.add_subcommand("check", "Validate the design file and its files; run nothing");
  check->add_option("DESIGN", words, "[DESIGN]")->expected(0, 1);

  std::vector<std::string> pressures;
  CLI::App* simulate = app.add_subcommand("simulate", "Forward simulation of a design only");
  simulate->add_option("DESIGN", words, "DESIGN")->expected(0, 1);
  simulate->add_option("--target", target, "Simulate this target's loads");
  simulate->add_option("--pressure", pressures, "FIBER=kPa, repeatable");
  bool refine = false, as_built = false;
  simulate->add_flag("--refine", refine,
                     "Solve again at half the edge length and report the difference (the discretization error)");
  simulate->add_flag("--as-built", as_built,
                     "The routes the molds were made for (collide/fibers.json) and, with --target, its pressures "
                     "there: the cast robot with today's [material]");
  simulate->add_option("--build-dir", build_dir_option, "Build folder (default: out/<design name>)");

  SweepRequest sweep_request;
  CLI::App* sweep = add_sweep_command(app, sweep_request);

  std::vector<std::string> task_words;
  CLI::App* sweep_task = app.add_subcommand("sweep-task", "One task of a sweep (run by `fibermold sweep`)");
  sweep_task->group(""); // hidden from --help
  sweep_task->add_option("BUILD_DIR STAGE CASE", task_words)->expected(3)->required();

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kExitDone : kExitBadInput;
  }

  install_signal_handlers(!sweep->parsed());
  try {
    const Runner runner(shipped_stages());
    if (sweep->parsed()) return run_sweep(sweep_request, runner);
    if (sweep_task->parsed()) return run_sweep_task(task_words[0], task_words[1], task_words[2], runner);
    const DesignAndStages args =
        split_arguments(words, FIBERMOLD_DEFAULT_DESIGN,
                        check->parsed() || simulate->parsed() ? std::vector<std::string>{} : runner.stage_names());
    const Design design = load_design(args.design);
    if (simulate->parsed() || make->parsed()) unlikely = warn_unlikely_values(design, true);
    if (simulate->parsed())
      return run_simulate(design, runner, build_dir_for(design, build_dir_option),
                          {target, pressures, refine, as_built});
    if (check->parsed()) return run_check(design);
    const fs::path build_dir = build_dir_for(design, build_dir_option);
    if (status->parsed()) {
      if (runner.stage_names().empty()) fmt::print("this build of fibermold has no stages yet\n");
      // Which folder was looked in: the default is relative to the folder fibermold runs in.
      const fs::path absolute = fs::absolute(build_dir).lexically_normal();
      fmt::print("build folder {}{}\n", absolute.string(),
                 fs::exists(build_dir) ? ""
                 : build_dir_option.empty()
                     ? fmt::format(": none yet (the default, out/{} under the folder you run in; --build-dir "
                                   "names another)",
                                   design.design.name)
                     : ": none yet");
      print_status(runner.status(design, build_dir, args.stages));
      return 0;
    }
    if (clean->parsed()) {
      runner.clean(build_dir, args.stages);
      fmt::print("cleaned {}\n", build_dir.string());
      return 0;
    }
    return run_make(design, runner, {build_dir, args.stages, force});
  } catch (...) {
    return report_failure(std::current_exception(), unlikely);
  }
}

} // namespace fibermold
