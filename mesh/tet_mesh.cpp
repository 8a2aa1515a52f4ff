#include "mesh/tet_mesh.hpp"

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>

#include <Eigen/Geometry>

#include "core/atomic_file.hpp"

namespace fibermold {

namespace {

constexpr char kMagic[8] = {'F', 'M', 'T', 'E', 'T', 'M', 'S', 'H'};
constexpr std::uint32_t kVersion = 2; // 2: the surface places

/// FNV-1a over the payload: enough to tell a truncated or damaged artifact from a good one.
std::uint64_t checksum(std::string_view bytes)
{
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char c : bytes) h = (h ^ c) * 1099511628211ull;
  return h;
}

template <typename T> void put(std::string& out, const T& value)
{
  out.append(reinterpret_cast<const char*>(&value), sizeof(T));
}

template <typename Matrix> void put_matrix(std::string& out, const Matrix& m)
{
  put<std::int64_t>(out, m.rows());
  put<std::int64_t>(out, m.cols());
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    for (Eigen::Index j = 0; j < m.cols(); ++j) put(out, m(i, j));
}

struct Reader {
  std::string_view bytes;
  std::size_t at = 0;
  const std::filesystem::path& path;

  template <typename T> T get()
  {
    if (at + sizeof(T) > bytes.size()) throw std::runtime_error(path.string() + ": truncated tet mesh");
    T value;
    std::memcpy(&value, bytes.data() + at, sizeof(T));
    at += sizeof(T);
    return value;
  }
  template <typename Matrix> void get_matrix(Matrix& m)
  {
    const auto rows = get<std::int64_t>(), cols = get<std::int64_t>();
    if (rows < 0 || cols < 0 || static_cast<std::uint64_t>(rows * cols) > bytes.size())
      throw std::runtime_error(path.string() + ": corrupt tet mesh");
    m.resize(rows, cols);
    for (Eigen::Index i = 0; i < rows; ++i)
      for (Eigen::Index j = 0; j < cols; ++j) m(i, j) = get<typename Matrix::Scalar>();
  }
};

} // namespace

double TetMesh::tet_volume(Eigen::Index t) const
{
  const Eigen::Vector3d a = nodes.row(tets(t, 0)), b = nodes.row(tets(t, 1)), c = nodes.row(tets(t, 2)),
                        d = nodes.row(tets(t, 3));
  return (b - a).dot((c - a).cross(d - a)) / 6.0;
}

double TetMesh::volume() const
{
  double v = 0;
  for (Eigen::Index t = 0; t < num_tets(); ++t) v += tet_volume(t);
  return v;
}

SurfaceMesh boundary_surface(const TetMesh& mesh, const Eigen::MatrixX3d& nodes)
{
  Eigen::VectorXi vertex = Eigen::VectorXi::Constant(nodes.rows(), -1);
  SurfaceMesh skin{Eigen::MatrixX3d(nodes.rows(), 3), mesh.boundary_faces, {}};
  int used = 0;
  for (Eigen::Index f = 0; f < skin.faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      int& v = vertex(mesh.boundary_faces(f, k));
      if (v < 0) {
        v = used++;
        skin.vertices.row(v) = nodes.row(mesh.boundary_faces(f, k));
      }
      skin.faces(f, k) = v;
    }
  skin.vertices.conservativeResize(used, 3);
  return skin;
}

void save_tet_mesh(const TetMesh& mesh, const std::filesystem::path& path)
{
  std::string payload;
  put_matrix(payload, mesh.nodes);
  put_matrix(payload, mesh.tets);
  put_matrix(payload, mesh.boundary_faces);
  put_matrix(payload, mesh.surface_to_node);
  put_matrix(payload, mesh.surface_faces);
  put_matrix(payload, mesh.surface_vertices);
  put_matrix(payload, mesh.place_face);
  put_matrix(payload, mesh.place_weights);
  std::string out(kMagic, sizeof kMagic);
  put(out, kVersion);
  put<std::uint64_t>(out, payload.size());
  put(out, checksum(payload));
  write_file_atomic(path, out + payload);
}

TetMesh load_tet_mesh(const std::filesystem::path& path)
{
  const std::string bytes = read_file(path);
  Reader header{bytes, 0, path};
  if (bytes.size() < sizeof kMagic || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0)
    throw std::runtime_error(path.string() + ": not a fibermold tet mesh");
  header.at = sizeof kMagic;
  if (header.get<std::uint32_t>() != kVersion) throw std::runtime_error(path.string() + ": unknown tet mesh version");
  const auto size = header.get<std::uint64_t>();
  const auto sum = header.get<std::uint64_t>();
  const std::string_view payload = std::string_view(bytes).substr(header.at);
  if (payload.size() != size || checksum(payload) != sum)
    throw std::runtime_error(path.string() + ": truncated or corrupt tet mesh");
  Reader r{payload, 0, path};
  TetMesh mesh;
  r.get_matrix(mesh.nodes);
  r.get_matrix(mesh.tets);
  r.get_matrix(mesh.boundary_faces);
  r.get_matrix(mesh.surface_to_node);
  r.get_matrix(mesh.surface_faces);
  r.get_matrix(mesh.surface_vertices);
  r.get_matrix(mesh.place_face);
  r.get_matrix(mesh.place_weights);
  const bool placed = mesh.place_face.size() == mesh.nodes.rows() && mesh.place_weights.rows() == mesh.nodes.rows();
  if (!(placed || (mesh.place_face.size() == 0 && mesh.place_weights.rows() == 0)) ||
      (mesh.place_face.size() > 0 &&
       (mesh.place_face.minCoeff() < -1 || mesh.place_face.maxCoeff() >= mesh.surface_faces.rows())))
    throw std::runtime_error(path.string() + ": corrupt tet mesh (surface places)");
  return mesh;
}

} // namespace fibermold
