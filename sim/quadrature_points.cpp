#include "sim/quadrature_points.hpp"

#include <algorithm>
#include <numeric>
#include <stdexcept>

#include <tbb/parallel_for.h>

#include "sim/quadrature.hpp"

namespace fibermold {

QuadraturePoints build_quadrature_points(const TetMesh& mesh, const Basis& basis, int points_per_tet)
{
  const TetQuadrature& rule = tet_quadrature(points_per_tet);
  const Eigen::Index nq = mesh.num_tets() * points_per_tet;
  std::vector<ShapeEval> evals(static_cast<std::size_t>(nq));
  QuadraturePoints qp;
  qp.X.resize(nq);
  qp.volume.resize(nq);
  tbb::parallel_for(Eigen::Index{0}, mesh.num_tets(), [&](Eigen::Index t) {
    const double v = mesh.tet_volume(t);
    for (int k = 0; k < points_per_tet; ++k) {
      const Eigen::Index q = t * points_per_tet + k;
      Eigen::Vector3d X = Eigen::Vector3d::Zero();
      for (int c = 0; c < 4; ++c) X += rule.barycentric[k][c] * mesh.nodes.row(mesh.tets(t, c)).transpose();
      qp.X[q] = X;
      qp.volume[q] = rule.weights[k] * v;
      evals[q] = basis.at(X, 1, t);
    }
  });
  qp.offset.assign(1, 0);
  for (const ShapeEval& e : evals) qp.offset.push_back(qp.offset.back() + static_cast<int>(e.size()));
  qp.node.resize(qp.offset.back());
  qp.N.resize(qp.offset.back());
  qp.dN.resize(qp.offset.back());
  // Each point's entries in ascending node order: the nodes ≥ j follow node j, which the
  // lower-triangle Hessian assembly relies on.
  tbb::parallel_for(Eigen::Index{0}, nq, [&](Eigen::Index q) {
    const ShapeEval& e = evals[q];
    std::vector<int> order(static_cast<std::size_t>(e.size()));
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](int a, int b) { return e.nodes[a] < e.nodes[b]; });
    if (std::adjacent_find(order.begin(), order.end(), [&](int a, int b) { return e.nodes[a] == e.nodes[b]; }) != order.end())
      throw std::logic_error("quadrature point with a node twice in its shape functions");
    for (Eigen::Index k = 0; k < e.size(); ++k) {
      const int from = order[k];
      qp.node[qp.offset[q] + k] = e.nodes[from];
      qp.N[qp.offset[q] + k] = e.N[from];
      qp.dN[qp.offset[q] + k] = e.dN.row(from).transpose();
    }
  });
  return qp;
}

NodeIncidence node_incidence(const QuadraturePoints& qp, Eigen::Index num_nodes)
{
  NodeIncidence inc;
  inc.offset.assign(static_cast<std::size_t>(num_nodes) + 1, 0);
  for (int n : qp.node) ++inc.offset[n + 1];
  for (std::size_t i = 1; i < inc.offset.size(); ++i) inc.offset[i] += inc.offset[i - 1];
  inc.entry.resize(qp.node.size());
  std::vector<int> fill(inc.offset.begin(), inc.offset.end() - 1);
  for (Eigen::Index q = 0; q < qp.size(); ++q)
    for (int k = qp.offset[q]; k < qp.offset[q + 1]; ++k) inc.entry[fill[qp.node[k]]++] = {static_cast<int>(q), k};
  return inc;
}

} // namespace fibermold
