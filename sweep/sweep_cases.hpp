#pragma once
// A sweep's cases: the base design with each case's values put in (and, for a restart, its
// fibers' interior control points moved at random), one design file each. A case is named by the
// hash of its design's text, so that its build folder is the same whenever the same design comes up.

#include <string>
#include <vector>

#include "sweep/sweep_file.hpp"

namespace fibermold {

struct SweepCase {
  std::string id;                  ///< 10 hex digits of the design text's hash
  std::vector<std::string> values; ///< per SweepFile::axes, as TOML ("4", "[...]"; restart: "2")
  std::string design;              ///< the case's design file (paths absolute)
};

/// Throws InputError: the base design's problems as its own, a value the design file rejects at the
/// sweep file's line that sets it.
std::vector<SweepCase> expand_sweep(const SweepFile& sweep);

} // namespace fibermold
