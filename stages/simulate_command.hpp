#pragma once
// `fibermold simulate DESIGN [--target NAME | --pressure FIBER=kPa ...] [--as-built]`: a forward
// simulation of the design on its mesh (made first when stale), written as
// <build>/simulate/deformed-<name>.vtu. --as-built takes the routes the molds were carved for
// (<build>/collide/fibers.json) instead of the design's first guess, and with --target that target's
// pressures from the same file: the cast robot predicted again with today's [material], e.g. the
// Young's modulus measured on a strip of the cast silicone.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "design/design.hpp"
#include "make/runner.hpp"
#include "sim/newton_solver.hpp"
#include "stages/design_simulation.hpp"

namespace fibermold {

struct SimulateRequest {
  std::string target;                 ///< a [[target]] name, or empty
  std::vector<std::string> pressures; ///< "FIBER=kPa"
  bool refine = false;                ///< solve again at half the edge length and compare
  bool as_built = false;              ///< the routes (and a target's pressures) of collide/fibers.json
};

struct SimulateResult {
  std::string name; ///< the target's ("twist"), or "pressures-flexor-300kPa" (--pressure), or "unactuated"
  std::filesystem::path vtu;
  double max_displacement = 0; ///< m
  NewtonSummary summary;
  std::string conditioning;             ///< where the MLS radius had to be widened; empty when nowhere
  std::optional<Refinement> refinement; ///< with --refine
  /// Where the target's regions (a target's loads or poses) and the tracking curves' ends went, the
  /// lines README.txt gives to compare with the cast robot (poses_to_compare); empty with neither.
  std::string poses;
  /// With --as-built: what was simulated (the routes' file, the pressures, the material); empty otherwise.
  std::string as_built;
  /// What drove the body: each muscle's pressure ("m1 300 kPa, spine 0 kPa"), or that none did.
  std::string muscles;
};

/// Throws InputError for a bad request or design (exit 2), std::runtime_error when the solve fails.
SimulateResult simulate(const Design& design, const Runner& runner, const std::filesystem::path& build_dir,
                        const SimulateRequest& request, const ProgressFactory& progress);

} // namespace fibermold
