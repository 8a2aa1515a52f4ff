#pragma once
// What a stage sees of the design (docs/architecture.md, "Stages"): the values of the keys it
// declares, and in place of every other an undeclared value (undeclared_value.hpp: NaN, an int below
// every range, "<undeclared key>", one undeclared element of an array section) that makes a use fail.
// A stage that reads a value it did not declare fails instead of seeing the default whatever the file
// says, so its outputs depend on what it declares and nothing else of the design file: the runner's
// staleness, which hashes exactly those keys, cannot miss an edit.

#include <string>
#include <vector>

#include "design/design.hpp"

namespace fibermold {

/// `design` with only the values under `prefixes` ("mold", "sim.basis", "fiber": as
/// Stage::design_keys() gives them) kept, every other undeclared; the file, its folder and where each
/// key was written are kept too, for error messages.
Design design_view(const Design& design, const std::vector<std::string>& prefixes);

/// The parts a view is made of, as flat keys ("mold.wall", "fiber"): every key of the design file
/// lies under one of them.
std::vector<std::string> design_view_parts();

/// True when view part `part` ("mold.wall") lies under declared prefix `prefix` ("mold").
bool view_part_under(const std::string& part, const std::string& prefix);

} // namespace fibermold
