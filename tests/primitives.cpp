#include "primitives.hpp"

#include <cmath>
#include <fstream>
#include <functional>
#include <vector>

#include <fmt/format.h>

namespace fibermold::test {

namespace {

struct Builder {
  std::vector<Eigen::Vector3d> v;
  std::vector<Eigen::Vector3i> f;
  int add(const Eigen::Vector3d& p)
  {
    v.push_back(p);
    return static_cast<int>(v.size()) - 1;
  }
  void tri(int a, int b, int c) { f.emplace_back(a, b, c); }
  /// Quad a-b-c-d counter-clockwise seen from outside.
  void quad(int a, int b, int c, int d)
  {
    tri(a, b, c);
    tri(a, c, d);
  }
  SurfaceMesh mesh() const
  {
    SurfaceMesh s;
    s.vertices.resize(static_cast<Eigen::Index>(v.size()), 3);
    s.faces.resize(static_cast<Eigen::Index>(f.size()), 3);
    for (std::size_t i = 0; i < v.size(); ++i) s.vertices.row(static_cast<Eigen::Index>(i)) = v[i].transpose();
    for (std::size_t i = 0; i < f.size(); ++i) s.faces.row(static_cast<Eigen::Index>(i)) = f[i].transpose();
    return s;
  }
};

void write_with(const std::filesystem::path& path, const std::function<void(std::ofstream&)>& body)
{
  std::ofstream out(path);
  body(out);
}

} // namespace

SurfaceMesh voxel_body(const Eigen::Vector3d& lo, double cell, const Eigen::Vector3i& cells,
                       const std::function<bool(int, int, int)>& filled)
{
  Builder b;
  std::vector<int> id((cells.x() + 1) * (cells.y() + 1) * (cells.z() + 1), -1);
  const auto at = [&](const Eigen::Vector3i& g) {
    int& slot = id[(g.x() * (cells.y() + 1) + g.y()) * (cells.z() + 1) + g.z()];
    if (slot < 0) slot = b.add(lo + cell * g.cast<double>());
    return slot;
  };
  const auto inside = [&](const Eigen::Vector3i& g) {
    return (g.array() >= 0).all() && (g.array() < cells.array()).all() && filled(g.x(), g.y(), g.z());
  };
  for (int i = 0; i < cells.x(); ++i)
    for (int j = 0; j < cells.y(); ++j)
      for (int k = 0; k < cells.z(); ++k) {
        const Eigen::Vector3i g(i, j, k);
        if (!inside(g)) continue;
        for (int axis = 0; axis < 3; ++axis)
          for (int side = 0; side < 2; ++side) {
            const Eigen::Vector3i n = g + (side == 0 ? -1 : 1) * Eigen::Vector3i::Unit(axis);
            if (inside(n)) continue;
            const int u = (axis + 1) % 3, w = (axis + 2) % 3;
            const auto p = [&](int du, int dw) {
              Eigen::Vector3i c = g;
              c[axis] += side;
              c[u] += du;
              c[w] += dw;
              return at(c);
            };
            // (u, w, axis) is right-handed: p00 → p10 → p11 turns about +axis.
            if (side == 1)
              b.quad(p(0, 0), p(1, 0), p(1, 1), p(0, 1));
            else
              b.quad(p(0, 0), p(0, 1), p(1, 1), p(1, 0));
          }
      }
  return b.mesh();
}

SurfaceMesh box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, int n)
{
  return box(lo, hi, Eigen::Vector3i(n, n, n));
}

SurfaceMesh box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, const Eigen::Vector3i& cells)
{
  // Grid points on the surface, shared between faces through a map from integer coordinates.
  Builder b;
  const Eigen::Vector3i c = cells;
  std::vector<int> id((c.x() + 1) * (c.y() + 1) * (c.z() + 1), -1);
  const auto at = [&](int i, int j, int k) {
    int& slot = id[(i * (c.y() + 1) + j) * (c.z() + 1) + k];
    if (slot < 0) {
      const Eigen::Vector3d t(double(i) / c.x(), double(j) / c.y(), double(k) / c.z());
      slot = b.add(lo + (hi - lo).cwiseProduct(t));
    }
    return slot;
  };
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, w = (axis + 2) % 3;
    for (int side = 0; side <= c[axis]; side += c[axis])
      for (int i = 0; i < c[u]; ++i)
        for (int j = 0; j < c[w]; ++j) {
          const auto p = [&](int di, int dj) {
            int c[3];
            c[axis] = side;
            c[u] = i + di;
            c[w] = j + dj;
            return at(c[0], c[1], c[2]);
          };
          // (u, w, axis) is right-handed: p00 → p10 → p11 turns about +axis.
          if (side == c[axis])
            b.quad(p(0, 0), p(1, 0), p(1, 1), p(0, 1));
          else
            b.quad(p(0, 0), p(0, 1), p(1, 1), p(1, 0));
        }
  }
  return b.mesh();
}

SurfaceMesh cylinder(double radius, double height, int segments, int rings)
{
  Builder b;
  std::vector<std::vector<int>> ring(rings + 1);
  for (int r = 0; r <= rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const double a = 2 * M_PI * s / segments;
      ring[r].push_back(b.add({radius * std::cos(a), radius * std::sin(a), height * r / rings}));
    }
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const int t = (s + 1) % segments;
      b.quad(ring[r][s], ring[r][t], ring[r + 1][t], ring[r + 1][s]);
    }
  const int bottom = b.add({0, 0, 0}), top = b.add({0, 0, height});
  for (int s = 0; s < segments; ++s) {
    const int t = (s + 1) % segments;
    b.tri(bottom, ring[0][t], ring[0][s]);
    b.tri(top, ring[rings][s], ring[rings][t]);
  }
  return b.mesh();
}

SurfaceMesh sphere(double radius, int segments, int stacks)
{
  Builder b;
  const int south = b.add({0, 0, -radius});
  std::vector<std::vector<int>> ring(stacks - 1);
  for (int k = 1; k < stacks; ++k) {
    const double phi = -M_PI / 2 + M_PI * k / stacks;
    for (int s = 0; s < segments; ++s) {
      const double a = 2 * M_PI * s / segments;
      ring[k - 1].push_back(
          b.add(radius * Eigen::Vector3d(std::cos(phi) * std::cos(a), std::cos(phi) * std::sin(a), std::sin(phi))));
    }
  }
  const int north = b.add({0, 0, radius});
  for (int s = 0; s < segments; ++s) {
    const int t = (s + 1) % segments;
    b.tri(south, ring[0][t], ring[0][s]);
    for (int k = 0; k + 1 < stacks - 1; ++k) b.quad(ring[k][s], ring[k][t], ring[k + 1][t], ring[k + 1][s]);
    b.tri(north, ring[stacks - 2][s], ring[stacks - 2][t]);
  }
  return b.mesh();
}

SurfaceMesh torus(double R, double r, int segments, int sides)
{
  Builder b;
  std::vector<std::vector<int>> id(segments, std::vector<int>(sides));
  for (int s = 0; s < segments; ++s)
    for (int k = 0; k < sides; ++k) {
      const double a = 2 * M_PI * s / segments, c = 2 * M_PI * k / sides;
      id[s][k] = b.add({(R + r * std::cos(c)) * std::cos(a), (R + r * std::cos(c)) * std::sin(a), r * std::sin(c)});
    }
  for (int s = 0; s < segments; ++s)
    for (int k = 0; k < sides; ++k) {
      const int t = (s + 1) % segments, l = (k + 1) % sides;
      b.quad(id[s][k], id[t][k], id[t][l], id[s][l]);
    }
  return b.mesh();
}

SurfaceMesh combine(const SurfaceMesh& a, const SurfaceMesh& b)
{
  SurfaceMesh s;
  s.vertices.resize(a.num_vertices() + b.num_vertices(), 3);
  s.vertices << a.vertices, b.vertices;
  s.faces.resize(a.num_faces() + b.num_faces(), 3);
  s.faces << a.faces, (b.faces.array() + static_cast<int>(a.num_vertices())).matrix();
  return s;
}

void write_ascii_stl(const std::filesystem::path& path, const SurfaceMesh& s, double k)
{
  write_with(path, [&](std::ofstream& out) {
    out << "solid test\n";
    for (Eigen::Index f = 0; f < s.num_faces(); ++f) {
      out << "facet normal 0 0 0\nouter loop\n";
      for (int c = 0; c < 3; ++c) {
        const Eigen::RowVector3d p = s.vertices.row(s.faces(f, c)) * k;
        out << fmt::format("vertex {:.9g} {:.9g} {:.9g}\n", p.x(), p.y(), p.z());
      }
      out << "endloop\nendfacet\n";
    }
    out << "endsolid test\n";
  });
}

void write_obj(const std::filesystem::path& path, const SurfaceMesh& s, double k)
{
  write_with(path, [&](std::ofstream& out) {
    for (Eigen::Index v = 0; v < s.num_vertices(); ++v)
      out << fmt::format("v {:.9g} {:.9g} {:.9g}\n", s.vertices(v, 0) * k, s.vertices(v, 1) * k, s.vertices(v, 2) * k);
    for (Eigen::Index f = 0; f < s.num_faces(); ++f)
      out << fmt::format("f {} {} {}\n", s.faces(f, 0) + 1, s.faces(f, 1) + 1, s.faces(f, 2) + 1);
  });
}

void write_off(const std::filesystem::path& path, const SurfaceMesh& s, double k)
{
  write_with(path, [&](std::ofstream& out) {
    out << fmt::format("OFF\n{} {} 0\n", s.num_vertices(), s.num_faces());
    for (Eigen::Index v = 0; v < s.num_vertices(); ++v)
      out << fmt::format("{:.9g} {:.9g} {:.9g}\n", s.vertices(v, 0) * k, s.vertices(v, 1) * k, s.vertices(v, 2) * k);
    for (Eigen::Index f = 0; f < s.num_faces(); ++f)
      out << fmt::format("3 {} {} {}\n", s.faces(f, 0), s.faces(f, 1), s.faces(f, 2));
  });
}

void write_ply(const std::filesystem::path& path, const SurfaceMesh& s, double k)
{
  write_with(path, [&](std::ofstream& out) {
    out << fmt::format(
        "ply\nformat ascii 1.0\nelement vertex {}\nproperty float x\nproperty float y\nproperty float z\n"
        "element face {}\nproperty list uchar int vertex_indices\nend_header\n",
        s.num_vertices(), s.num_faces());
    for (Eigen::Index v = 0; v < s.num_vertices(); ++v)
      out << fmt::format("{:.9g} {:.9g} {:.9g}\n", s.vertices(v, 0) * k, s.vertices(v, 1) * k, s.vertices(v, 2) * k);
    for (Eigen::Index f = 0; f < s.num_faces(); ++f)
      out << fmt::format("3 {} {} {}\n", s.faces(f, 0), s.faces(f, 1), s.faces(f, 2));
  });
}

} // namespace fibermold::test
