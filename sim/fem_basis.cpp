#include "sim/fem_basis.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/LU>
#include <nanoflann.hpp>

namespace fibermold {

struct FemBasis::Locator {
  Eigen::MatrixX3d centroids;
  double reach = 0; ///< the largest distance from a tet's centroid to one of its corners
  std::unique_ptr<nanoflann::KDTreeEigenMatrixAdaptor<Eigen::MatrixX3d>> tree;
};

FemBasis::FemBasis(const TetMesh& mesh)
    : mesh_(mesh), quadratic_(mesh.nodes_per_tet() == 10), locator_(std::make_unique<Locator>())
{
  locator_->centroids.resize(mesh.num_tets(), 3);
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    Eigen::RowVector3d c = Eigen::RowVector3d::Zero();
    for (int k = 0; k < 4; ++k) c += mesh.nodes.row(mesh.tets(t, k));
    locator_->centroids.row(t) = c / 4;
    for (int k = 0; k < 4; ++k)
      locator_->reach = std::max(locator_->reach, (mesh.nodes.row(mesh.tets(t, k)) - c / 4).norm());
  }
  locator_->tree =
      std::make_unique<nanoflann::KDTreeEigenMatrixAdaptor<Eigen::MatrixX3d>>(3, std::cref(locator_->centroids), 16);
}

FemBasis::~FemBasis() = default;

Eigen::Vector4d FemBasis::barycentric(Eigen::Index t, const Eigen::Vector3d& X,
                                      Eigen::Matrix<double, 4, 3>* gradients) const
{
  const Eigen::Vector3d x0 = mesh_.nodes.row(mesh_.tets(t, 0));
  Eigen::Matrix3d D;
  for (int k = 0; k < 3; ++k) D.col(k) = mesh_.nodes.row(mesh_.tets(t, k + 1)).transpose() - x0;
  const Eigen::Matrix3d Dinv = D.inverse();
  const Eigen::Vector3d l = Dinv * (X - x0);
  if (gradients) {
    gradients->bottomRows<3>() = Dinv;
    gradients->row(0) = -Dinv.colwise().sum();
  }
  return {1 - l.sum(), l.x(), l.y(), l.z()};
}

Eigen::Index FemBasis::locate(const Eigen::Vector3d& X) const
{
  // The tet holding X is most often among the 32 with the nearest centroids; where tets of very
  // different sizes meet, it can be further down that list (on a 16 mm cylinder meshed at 8 mm, the
  // 34th). Any tet holding X has its centroid within `reach` of X: those are searched next.
  Eigen::Index best = 0;
  double best_inside = -HUGE_VAL;
  const auto consider = [&](Eigen::Index t) {
    const double inside = barycentric(t, X).minCoeff();
    if (inside > best_inside) {
      best_inside = inside;
      best = t;
    }
    return inside >= 0;
  };
  const std::size_t k = std::min<std::size_t>(32, static_cast<std::size_t>(mesh_.num_tets()));
  std::vector<Eigen::Index> index(k);
  std::vector<double> distance(k);
  if (k > 0) locator_->tree->index->knnSearch(X.data(), k, index.data(), distance.data());
  for (Eigen::Index t : index)
    if (consider(t)) return t;
  std::vector<std::pair<Eigen::Index, double>> found;
  const double r = locator_->reach * (1 + 1e-9);
  locator_->tree->index->radiusSearch(X.data(), r * r, found, nanoflann::SearchParams(32, 0, false));
  for (const auto& [t, squared] : found)
    if (consider(t)) return t;
  return best;
}

ShapeEval FemBasis::at(const Eigen::Vector3d& X, int order, Eigen::Index tet) const
{
  const Eigen::Index t = tet >= 0 ? tet : locate(X);
  Eigen::Matrix<double, 4, 3> dl;
  const Eigen::Vector4d l = barycentric(t, X, &dl);
  ShapeEval out;
  const int n = quadratic_ ? 10 : 4;
  for (int k = 0; k < n; ++k) out.nodes.push_back(mesh_.tets(t, k));
  out.N.resize(n);
  out.dN.resize(n, 3);
  if (order >= 2) out.ddN.assign(n, Eigen::Matrix3d::Zero());
  if (!quadratic_) {
    out.N = l;
    out.dN = dl;
    return out;
  }
  // Corners: λ(2λ − 1); edge (i, j) in VTK order: 4 λ_i λ_j.
  constexpr int kEdges[6][2] = {{0, 1}, {1, 2}, {0, 2}, {0, 3}, {1, 3}, {2, 3}};
  for (int k = 0; k < 4; ++k) {
    out.N[k] = l[k] * (2 * l[k] - 1);
    out.dN.row(k) = (4 * l[k] - 1) * dl.row(k);
    if (order >= 2) out.ddN[k] = 4 * dl.row(k).transpose() * dl.row(k);
  }
  for (int e = 0; e < 6; ++e) {
    const int i = kEdges[e][0], j = kEdges[e][1];
    out.N[4 + e] = 4 * l[i] * l[j];
    out.dN.row(4 + e) = 4 * (l[i] * dl.row(j) + l[j] * dl.row(i));
    if (order >= 2) out.ddN[4 + e] = 4 * (dl.row(i).transpose() * dl.row(j) + dl.row(j).transpose() * dl.row(i));
  }
  return out;
}

} // namespace fibermold
