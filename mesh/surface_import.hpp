#pragma once
// Importing the body's surface from any triangle format assimp reads (STL ascii and binary, OBJ,
// PLY, OFF, 3MF, glTF, ...). Duplicate vertices (same coordinates) are welded, polygons
// triangulated, scene transforms applied.

#include <filesystem>
#include <string>
#include <vector>

#include "mesh/surface_mesh.hpp"

namespace fibermold {

/// Reads `file`, scaled by `metres_per_unit`. Throws InputError naming the file for a missing,
/// empty, unreadable or unsupported file, one without triangles, or non-finite coordinates.
SurfaceMesh import_surface(const std::filesystem::path& file, double metres_per_unit);

/// The files a surface is read from: the file itself and, for glTF, its external buffers, so that
/// a change to any of them is noticed.
std::vector<std::filesystem::path> surface_files(const std::filesystem::path& file);

/// File extensions assimp reads here, lower case with the dot (".stl").
std::vector<std::string> supported_surface_extensions();

} // namespace fibermold
