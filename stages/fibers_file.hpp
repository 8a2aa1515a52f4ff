#pragma once
// fibers.json, the routing that optimize and collide write and molds reads: per fiber its control
// points and tangents (mm), length (mm) and pressure per target (kPa).

#include <filesystem>
#include <string>
#include <vector>

#include "optimize/routing_problem.hpp"

namespace fibermold {

struct FibersFile {
  Routing routing;                  ///< SI
  std::vector<std::string> targets; ///< names of the pressure matrix's rows
  bool optimized = false;
};

/// JSON text of `f`, written with write_file_atomic by the caller.
std::string fibers_json(const FibersFile& f);
/// Throws std::runtime_error naming the file and the problem.
FibersFile read_fibers_json(const std::filesystem::path& path);

} // namespace fibermold
