#pragma once
// The fibermold command line (README.md, "Using it"; docs/pipeline.md, "Commands and options").

namespace fibermold {

/// Runs the command line; returns the exit code (0 done, 1 a stage failed, 2 bad input, 130 interrupted).
int fibermold_main(int argc, char** argv);

} // namespace fibermold
