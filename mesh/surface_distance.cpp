#include "mesh/surface_distance.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <vector>

#include <Eigen/Geometry>

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>

namespace fibermold {

namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using Primitive = CGAL::AABB_face_graph_triangle_primitive<Mesh>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
using Side = CGAL::Side_of_triangle_mesh<Mesh, Kernel>;
} // namespace

struct SurfaceDistance::Impl {
  Mesh mesh;
  Tree tree;
  std::unique_ptr<Side> side;
  std::vector<Eigen::Index> face_row; ///< Surface_mesh face index → row of the input's faces
};

SurfaceDistance::SurfaceDistance(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces)
    : impl_(std::make_unique<Impl>())
{
  std::vector<Mesh::Vertex_index> index(static_cast<std::size_t>(vertices.rows()));
  std::vector<bool> used(index.size(), false);
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int c = 0; c < 3; ++c) used[faces(f, c)] = true;
  for (std::size_t v = 0; v < index.size(); ++v)
    if (used[v]) index[v] = impl_->mesh.add_vertex(Point(vertices(v, 0), vertices(v, 1), vertices(v, 2)));
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const Mesh::Face_index added = impl_->mesh.add_face(index[faces(f, 0)], index[faces(f, 1)], index[faces(f, 2)]);
    if (added == Mesh::null_face()) continue;
    impl_->face_row.resize(std::max<std::size_t>(impl_->face_row.size(), added.idx() + 1), -1);
    impl_->face_row[added.idx()] = f;
  }
  impl_->tree.insert(CGAL::faces(impl_->mesh).first, CGAL::faces(impl_->mesh).second, impl_->mesh);
  impl_->tree.accelerate_distance_queries();
  impl_->side = std::make_unique<Side>(impl_->tree);
}

SurfaceDistance::~SurfaceDistance() = default;

SurfaceDistance::Closest SurfaceDistance::closest(const Eigen::Vector3d& p) const
{
  const Point q(p.x(), p.y(), p.z());
  const auto [c, face] = impl_->tree.closest_point_and_primitive(q);
  Closest out;
  out.point = {c.x(), c.y(), c.z()};
  out.face = impl_->face_row[face.idx()];
  out.distance = (out.point - p).norm();
  out.inside = (*impl_->side)(q) == CGAL::ON_BOUNDED_SIDE;
  return out;
}

double SurfaceDistance::ray_distance(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double skip) const
{
  return ray_hit(origin, direction, skip).distance;
}

SurfaceDistance::Hit SurfaceDistance::ray_hit(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                                              double skip) const
{
  const Eigen::Vector3d start = origin + skip * direction;
  const Kernel::Ray_3 ray(Point(start.x(), start.y(), start.z()),
                          Kernel::Vector_3(direction.x(), direction.y(), direction.z()));
  std::vector<Tree::Intersection_and_primitive_id<Kernel::Ray_3>::Type> hits;
  impl_->tree.all_intersections(ray, std::back_inserter(hits));
  Hit best;
  for (const auto& h : hits) {
    const Point* p = boost::get<Point>(&h.first);
    if (!p) continue;
    const double d = std::sqrt(CGAL::squared_distance(*p, ray.source()));
    if (d >= best.distance) continue;
    best.distance = d;
    const Mesh::Halfedge_index he = impl_->mesh.halfedge(h.second);
    const auto at = [&](Mesh::Halfedge_index e) {
      const Point& q = impl_->mesh.point(impl_->mesh.target(e));
      return Eigen::Vector3d(q.x(), q.y(), q.z());
    };
    const Eigen::Vector3d a = at(he), b = at(impl_->mesh.next(he)), c = at(impl_->mesh.next(impl_->mesh.next(he)));
    best.normal = (b - a).cross(c - a).normalized();
  }
  best.distance += skip;
  return best;
}

} // namespace fibermold
