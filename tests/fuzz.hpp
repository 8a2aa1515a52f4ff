#pragma once
// One fuzz run: a mutant design (and its surface) through `fibermold check`, then `make`, held to
// the rules of the house (docs/pipeline.md, "Exit codes"): exit codes 0, 1 or 2 only (no signal),
// no hang, no NaN or null in any JSON output, and a design that `check` passes is never refused as
// bad input (exit 2) later by `make`.

#include <filesystem>
#include <string>

namespace fibermold::test {

struct FuzzRun {
  int check = -1;      ///< check's exit code
  int make = -1;       ///< make's exit code; -1: not run
  std::string problem; ///< the rule broken, with what was printed; empty: none
};

/// Runs check on `dir`/design.toml (and make when `make_too` and check passed, into `dir`/out),
/// each under a time limit in seconds.
FuzzRun fuzz_run(const std::filesystem::path& dir, bool make_too, int check_seconds, int make_seconds);

} // namespace fibermold::test
