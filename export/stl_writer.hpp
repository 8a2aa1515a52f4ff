#pragma once
// Binary STL, in millimetres, the format slicers expect.

#include <filesystem>
#include <string>

#include "mesh/surface_mesh.hpp"

namespace fibermold {

/// Writes `surface` (metres) as binary STL in millimetres (float32), atomically. Facets whose
/// corners coincide in float32 are left out.
void write_stl(const std::filesystem::path& path, const SurfaceMesh& surface, const std::string& header = "fibermold");

} // namespace fibermold
