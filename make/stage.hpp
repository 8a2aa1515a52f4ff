#pragma once
// A pipeline stage (docs/architecture.md, "Stages"): what it reads, and how it makes its outputs.
// The runner decides when it runs; a stage only writes files into its output folder.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "core/progress.hpp"
#include "design/design.hpp"

namespace spdlog {
class logger;
}

namespace fibermold {

/// What a running stage sees.
struct StageContext {
  const Design& design;
  std::filesystem::path build_dir;
  /// A fresh, empty folder: everything the stage writes here becomes its outputs once it succeeds.
  std::filesystem::path output_dir;
  Progress& progress;
  spdlog::logger& log;

  /// The committed output `file` of upstream stage `stage` (fresh when this stage runs).
  std::filesystem::path upstream(std::string_view stage, std::string_view file) const
  {
    return build_dir / stage / file;
  }
};

class Stage {
public:
  virtual ~Stage() = default;

  virtual std::string name() const = 0;
  /// Stages whose outputs this one reads.
  virtual std::vector<std::string> upstream() const { return {}; }
  /// Design values this stage reads, as prefixes: "mold", "sim.basis", "fiber".
  virtual std::vector<std::string> design_keys() const = 0;
  /// Those it reads for `design`: design_keys(), less the keys it has no use for in this design
  /// (the targets stage reads the fibers for a kind = "fibers" target only). The runner hashes
  /// these and the stage sees these, so editing the others leaves it fresh.
  virtual std::vector<std::string> design_keys_used(const Design& design) const
  {
    (void)design;
    return design_keys();
  }
  /// Files outside the build folder this stage reads (the surface, target surfaces), named by the
  /// design as the stage sees it (its view: design_view.hpp).
  virtual std::vector<std::filesystem::path> input_files(const Design&) const { return {}; }
  /// Bump when the stage's algorithm changes, so that old outputs go stale.
  virtual int version() const { return 1; }
  /// Makes the outputs in ctx.output_dir. Throws InputError for bad input, Interrupted when
  /// ctx.progress says so, anything else for a failure.
  virtual void run(StageContext& ctx) const = 0;
};

} // namespace fibermold
