#pragma once
// The fibermold command line (README.md, "Using it"; docs/pipeline.md, "Commands and options").

namespace fibermold {

/// Exit codes (docs/pipeline.md, "Exit codes").
constexpr int kExitDone = 0, kExitStageFailed = 1, kExitBadInput = 2, kExitLocked = 3, kExitInterrupted = 130;

/// Runs the command line; returns the exit code.
int fibermold_main(int argc, char** argv);

} // namespace fibermold
