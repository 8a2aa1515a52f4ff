#pragma once
// `fibermold simulate DESIGN [--target NAME | --pressure FIBER=kPa ...]`: a forward simulation of
// the design on its mesh (made first when stale), written as <build>/simulate/deformed-<name>.vtu.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "design/design.hpp"
#include "make/runner.hpp"
#include "sim/newton_solver.hpp"

namespace fibermold {

struct SimulateRequest {
  std::string target;                  ///< a [[target]] name, or empty
  std::vector<std::string> pressures;  ///< "FIBER=kPa"
  bool refine = false;                 ///< solve again at half the edge length and compare
};

/// How far a result is from converged in the mesh (docs/sim.md, "Discretization error"): the same
/// load solved on a mesh of half the edge length, and the difference of the displacements.
struct Refinement {
  double edge_length = 0;            ///< m, of the refined mesh
  Eigen::Index nodes = 0, tets = 0;  ///< of the refined mesh
  double surface_max = 0, surface_rms = 0;  ///< m, at the input surface's vertices
  double curves_max = 0, curves_rms = 0;    ///< m, at the tracking curves' samples (0 without curves)
  int curve_samples = 0;
  double max_displacement = 0;       ///< m, on the refined mesh
};

struct SimulateResult {
  std::string name;                    ///< "twist", or "pressures"
  std::filesystem::path vtu;
  double max_displacement = 0;         ///< m
  NewtonSummary summary;
  std::string conditioning;            ///< where the MLS radius had to be widened; empty when nowhere
  std::optional<Refinement> refinement;  ///< with --refine
};

/// Throws InputError for a bad request or design (exit 2), std::runtime_error when the solve fails.
SimulateResult simulate(const Design& design, const Runner& runner, const std::filesystem::path& build_dir,
                        const SimulateRequest& request, const ProgressFactory& progress);

} // namespace fibermold
