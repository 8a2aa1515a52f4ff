#include "export/stl_writer.hpp"

#include <cstdint>
#include <cstring>
#include <stdexcept>

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
  if (!surface.vertices.allFinite())
    throw std::runtime_error(path.filename().string() + ": a vertex is not finite; nothing was written");
  std::string body;
  std::uint32_t count = 0;
  for (Eigen::Index f = 0; f < surface.num_faces(); ++f) {
    Eigen::Vector3d p[3];
    for (int c = 0; c < 3; ++c)
      p[c] = (surface.vertices.row(surface.faces(f, c)) / units::mm).transpose().cast<float>().cast<double>();
    // A sliver whose corners fall on the same float32 point would be a degenerate facet for every
    // STL reader; its neighbours meet at that point anyway, so the surface stays closed without it.
    if (p[0] == p[1] || p[1] == p[2] || p[0] == p[2]) continue;
    const Eigen::Vector3d n = (p[1] - p[0]).cross(p[2] - p[0]);
    put_vector(body, n.norm() > 0 ? Eigen::Vector3d(n.normalized()) : n);
    for (const auto& v : p) put_vector(body, v);
    body.append(2, '\0');
    ++count;
  }
  std::string out(80, ' ');
  std::memcpy(out.data(), header.data(), std::min<std::size_t>(header.size(), 80));
  out.append(reinterpret_cast<const char*>(&count), sizeof count);
  out += body;
  write_file_atomic(path, out);
}

} // namespace fibermold
