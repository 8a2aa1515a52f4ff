#include "export/deformed_body.hpp"

#include "core/units.hpp"

namespace fibermold {

using Json = nlohmann::ordered_json;

std::optional<SurfaceMesh> deformed_body(const TetMesh& body, const std::optional<Json>& state)
{
  if (!state || !state->contains("nodes_mm") || !(*state)["nodes_mm"].is_array() ||
      (*state)["nodes_mm"].size() != static_cast<std::size_t>(body.nodes.rows()))
    return std::nullopt;
  Eigen::MatrixX3d nodes(body.nodes.rows(), 3);
  for (Eigen::Index i = 0; i < body.nodes.rows(); ++i) {
    const Json& p = (*state)["nodes_mm"][static_cast<std::size_t>(i)];
    if (!p.is_array() || p.size() != 3) return std::nullopt;
    for (int k = 0; k < 3; ++k) {
      if (!p[static_cast<std::size_t>(k)].is_number()) return std::nullopt;
      nodes(i, k) = p[static_cast<std::size_t>(k)].get<double>() * units::mm;
    }
  }
  return boundary_surface(body, nodes);
}

} // namespace fibermold
