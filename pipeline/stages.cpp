#include "pipeline/stages.hpp"

namespace fibermold {

// Only real stages are registered here; each arrives with its module (mesh, targets, optimize,
// collide, molds, export).
std::vector<std::unique_ptr<Stage>> shipped_stages()
{
  std::vector<std::unique_ptr<Stage>> stages;
  return stages;
}

} // namespace fibermold
