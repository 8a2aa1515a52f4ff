#pragma once
// Deterministic mutants of a design file and of a surface mesh, for fuzzing the command line the
// way the world will feed it: numbers at the ends of what a double holds, wrong types, lost and
// doubled lines, misspelt keys, huge and NUL-bearing strings, truncated files; and meshes with
// non-finite, huge and tiny coordinates, flipped, lost and doubled triangles, wrong counts and noise.
// The same seed gives the same mutants on every machine (a 64-bit LCG, no <random> distributions).

#include <cstdint>
#include <string>
#include <vector>

namespace fibermold::test {

/// A mutant and what was done to make it (for a failure's message).
struct Mutant {
  std::string text;
  std::string what;
};

/// `count` mutants of a TOML design text, each one to three mutations away from it.
std::vector<Mutant> design_mutants(const std::string& design, int count, std::uint64_t seed);

/// `count` mutants of an STL file's bytes (ASCII or binary), one mutation each.
std::vector<Mutant> mesh_mutants(const std::string& stl, int count, std::uint64_t seed);

} // namespace fibermold::test
