#pragma once
// Closed, outward-oriented triangle surfaces for tests (metres), and ways to break them.

#include <filesystem>
#include <functional>
#include <string>

#include "mesh/surface_mesh.hpp"

namespace fibermold::test {

/// Box [lo, hi] with each face a grid of `n` × `n` cells (cells along each edge).
SurfaceMesh box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, int n = 2);
/// Box [lo, hi] with `cells[k]` grid cells along axis k.
SurfaceMesh box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, const Eigen::Vector3i& cells);
/// Cylinder along z from 0 to `height`, `segments` around, `rings` along, fan-triangulated caps.
SurfaceMesh cylinder(double radius, double height, int segments = 24, int rings = 6);
/// UV sphere centred at the origin.
SurfaceMesh sphere(double radius, int segments = 24, int stacks = 12);
/// Torus about z: tube radius `r` around a circle of radius `R`.
SurfaceMesh torus(double R, double r, int segments = 32, int sides = 12);

/// The skin of a body made of cubes of edge `cell` on a grid of `cells` from `lo`: the faces
/// between a filled cube and an empty one (or the grid's outside), each two triangles. The filled
/// cubes must not meet along an edge or a corner only. Notches, slots and thin webs for tests; a
/// dense, scan-like skin at a small `cell`.
SurfaceMesh voxel_body(const Eigen::Vector3d& lo, double cell, const Eigen::Vector3i& cells,
                       const std::function<bool(int, int, int)>& filled);

/// Both surfaces in one (their vertices and faces appended).
SurfaceMesh combine(const SurfaceMesh& a, const SurfaceMesh& b);

/// Writers for import tests; coordinates written in `units_per_metre` (1000: mm).
void write_ascii_stl(const std::filesystem::path& path, const SurfaceMesh& s, double units_per_metre = 1000);
void write_obj(const std::filesystem::path& path, const SurfaceMesh& s, double units_per_metre = 1000);
void write_off(const std::filesystem::path& path, const SurfaceMesh& s, double units_per_metre = 1000);
void write_ply(const std::filesystem::path& path, const SurfaceMesh& s, double units_per_metre = 1000);

} // namespace fibermold::test
