#pragma once
// 3MF, the 3D Manufacturing Format that current slicers prefer to STL: a zip with the mesh as XML,
// indexed (shared vertices), in millimetres.

#include <filesystem>
#include <string>

#include "mesh/surface_mesh.hpp"

namespace fibermold {

/// Writes `surface` (metres) as a 3MF file in millimetres, atomically, with one object named `name`.
/// Throws std::runtime_error when assimp's 3MF exporter fails.
void write_3mf(const std::filesystem::path& path, const SurfaceMesh& surface, const std::string& name);

} // namespace fibermold
