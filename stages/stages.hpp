#pragma once
// The stages built into the shipped fibermold binary, in their order (docs/architecture.md).

#include <memory>
#include <vector>

#include "make/stage.hpp"

namespace fibermold {

std::vector<std::unique_ptr<Stage>> shipped_stages();

} // namespace fibermold
