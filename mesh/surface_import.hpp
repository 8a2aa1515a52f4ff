#pragma once
// Importing the body's surface from any triangle format assimp reads (STL ascii and binary, OBJ,
// PLY, OFF, 3MF, glTF, ...). Duplicate vertices (same coordinates) are welded, polygons
// triangulated, scene transforms applied.

#include <filesystem>
#include <string>
#include <vector>

#include "mesh/surface_mesh.hpp"

namespace fibermold {

/// A body's extent corner to corner, m: smaller or larger is a unit mistake or a damaged file.
constexpr double kMinBodySize = 1e-4, kMaxBodySize = 10;

/// Reads `file`, scaled by `metres_per_unit`. Throws InputError naming the file for a missing,
/// empty, unreadable, truncated or unsupported file, one without triangles, non-finite coordinates,
/// or a body outside [kMinBodySize, kMaxBodySize] across.
SurfaceMesh import_surface(const std::filesystem::path& file, double metres_per_unit);

/// The files a surface is read from: the file itself and, for glTF, its external buffers, so that
/// a change to any of them is noticed.
std::vector<std::filesystem::path> surface_files(const std::filesystem::path& file);

/// File extensions assimp reads here, lower case with the dot (".stl").
std::vector<std::string> supported_surface_extensions();

} // namespace fibermold
