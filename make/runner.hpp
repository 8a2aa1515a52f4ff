#pragma once
// The Make-style runner (docs/pipeline.md). Each stage's stamp records the content
// hash of everything it read; a stage runs when that no longer matches. Outputs are made in a
// staging folder and renamed into place, stamp last, so a failed or killed stage leaves the
// previous outputs and no stamp (stale).

#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "design/design.hpp"
#include "make/stage.hpp"
#include "make/stamp.hpp"

namespace fibermold {

/// A stage threw: which one, why, and where its log is.
class StageFailed : public std::runtime_error {
public:
  StageFailed(std::string stage, const std::string& why, std::filesystem::path log);
  const std::string& stage() const { return stage_; }
  const std::filesystem::path& log() const { return log_; }

private:
  std::string stage_;
  std::filesystem::path log_;
};

struct StageStatus {
  std::string stage;
  bool fresh = false;
  std::vector<std::string> reasons; ///< why it is stale, most telling first

  /// The first `shown` reasons and how many more, for a line on the terminal ("a; b; c; and 40
  /// more"); logs/make.log has them all.
  std::string summary(std::size_t shown = 3) const;
};

struct MakeOptions {
  std::filesystem::path build_dir;
  std::vector<std::string> targets; ///< run up to these stages; empty: all
  bool force = false;               ///< rerun every selected stage, fresh or not
};

struct StageRun {
  std::string stage;
  bool ran = false;
  double seconds = 0;
};

/// Builds the progress object for a stage (the CLI draws a line on a terminal; tests pass none).
using ProgressFactory = std::function<std::unique_ptr<Progress>(const std::string& stage)>;

class Runner {
public:
  /// Stages in any order; throws std::logic_error on a duplicate name, an unknown upstream or a cycle.
  explicit Runner(std::vector<std::unique_ptr<Stage>> stages, std::string program = default_program());

  static std::string default_program();

  /// Stage names in dependency order.
  std::vector<std::string> stage_names() const;

  /// The named stages and everything upstream of them, in dependency order; all stages when empty.
  /// Throws InputError for an unknown name, with the closest valid one.
  std::vector<std::string> closure(const std::vector<std::string>& targets) const;

  /// Fresh or stale, and why, for every stage in `closure(targets)`.
  std::vector<StageStatus> status(const Design& design, const std::filesystem::path& build_dir,
                                  const std::vector<std::string>& targets = {}) const;

  /// Runs what is stale up to the targets. Takes the build lock (BuildLocked when held).
  /// Throws StageFailed, InputError (bad input found by a stage) or Interrupted.
  std::vector<StageRun> make(const Design& design, const MakeOptions& options,
                             const ProgressFactory& progress = {}) const;

  /// Per stage, a hash of everything that decides its outputs before it runs: its design values,
  /// input files and upstream stages' fingerprints. Designs that agree on a stage's fingerprint
  /// can share its outputs (fibermold sweep).
  std::map<std::string, std::string> fingerprints(const Design& design) const;

  /// Removes the outputs, stamps and logs of the given stages (all when empty).
  void clean(const std::filesystem::path& build_dir, const std::vector<std::string>& targets = {}) const;

  /// Where the runner keeps things in a build folder.
  static std::filesystem::path stamp_path(const std::filesystem::path& build_dir, const std::string& stage);
  static std::filesystem::path log_path(const std::filesystem::path& build_dir, const std::string& stage);
  static std::filesystem::path make_log_path(const std::filesystem::path& build_dir);

private:
  const Stage& stage(const std::string& name) const;
  StageStatus stage_status(const Stage& stage, const Design& design, const std::filesystem::path& build_dir,
                           const std::vector<StageStatus>& done) const;
  Stamp current_inputs(const Stage& stage, const Design& design, const std::filesystem::path& build_dir) const;
  StageRun run_stage(const Stage& stage, const Design& design, const std::filesystem::path& build_dir,
                     const ProgressFactory& progress) const;

  std::vector<std::unique_ptr<Stage>> stages_; ///< in dependency order
  std::string program_;
};

} // namespace fibermold
