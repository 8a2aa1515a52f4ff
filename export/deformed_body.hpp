#pragma once
// The body's skin in a deformed state that a stage wrote as JSON (collide/deformed-<target>.json,
// targets/<name>.json: "nodes_mm", every node's position in mm), for the overlay STL and the report.

#include <optional>

#include <nlohmann/json.hpp>

#include "mesh/surface_mesh.hpp"
#include "mesh/tet_mesh.hpp"

namespace fibermold {

/// The boundary of `body` with its nodes where `state` puts them (m); none without a state, or when its
/// "nodes_mm" is not one [x, y, z] of numbers per node of `body`.
std::optional<SurfaceMesh> deformed_body(const TetMesh& body, const std::optional<nlohmann::ordered_json>& state);

} // namespace fibermold
