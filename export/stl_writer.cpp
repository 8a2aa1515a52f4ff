#include "export/stl_writer.hpp"

#include <cstdint>
#include <cstring>

#include <Eigen/Geometry>

#include "core/atomic_file.hpp"
#include "core/units.hpp"

namespace fibermold {

namespace {
void put_vector(std::string& out, const Eigen::Vector3d& v)
{
  for (int k = 0; k < 3; ++k) {
    const float x = static_cast<float>(v[k]);
    out.append(reinterpret_cast<const char*>(&x), sizeof x);
  }
}
} // namespace

void write_stl(const std::filesystem::path& path, const SurfaceMesh& surface, const std::string& header)
{
  std::string out(80, ' ');
  std::memcpy(out.data(), header.data(), std::min<std::size_t>(header.size(), 80));
  const auto count = static_cast<std::uint32_t>(surface.num_faces());
  out.append(reinterpret_cast<const char*>(&count), sizeof count);
  for (Eigen::Index f = 0; f < surface.num_faces(); ++f) {
    const Eigen::Vector3d a = surface.vertices.row(surface.faces(f, 0)) / units::mm;
    const Eigen::Vector3d b = surface.vertices.row(surface.faces(f, 1)) / units::mm;
    const Eigen::Vector3d c = surface.vertices.row(surface.faces(f, 2)) / units::mm;
    const Eigen::Vector3d n = (b - a).cross(c - a);
    put_vector(out, n.norm() > 0 ? Eigen::Vector3d(n.normalized()) : n);
    put_vector(out, a);
    put_vector(out, b);
    put_vector(out, c);
    out.append(2, '\0');
  }
  write_file_atomic(path, out);
}

} // namespace fibermold
