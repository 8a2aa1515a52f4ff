#include "sim/quadrature_points.hpp"

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <stdexcept>

#include <Eigen/Geometry>
#include <tbb/parallel_for.h>

#include "sim/quadrature.hpp"

namespace fibermold {

namespace {
/// Spreads the low 21 bits of v to every third bit (for a 63-bit Morton code).
std::uint64_t spread_bits(std::uint64_t v)
{
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffffULL;
  v = (v | v << 16) & 0x1f0000ff0000ffULL;
  v = (v | v << 8) & 0x100f00f00f00f00fULL;
  v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}

/// Indices of `X` in Morton (Z-curve) order: points near in space come near in memory.
std::vector<Eigen::Index> spatial_order(const std::vector<Eigen::Vector3d>& X)
{
  Eigen::AlignedBox3d box;
  for (const auto& p : X) box.extend(p);
  const double scale = ((1 << 21) - 1) / std::max(box.sizes().maxCoeff(), 1e-30);
  std::vector<std::uint64_t> code(X.size());
  for (std::size_t q = 0; q < X.size(); ++q) {
    const Eigen::Vector3d c = (X[q] - box.min()) * scale;
    code[q] = spread_bits(static_cast<std::uint64_t>(c.x())) | spread_bits(static_cast<std::uint64_t>(c.y())) << 1 |
              spread_bits(static_cast<std::uint64_t>(c.z())) << 2;
  }
  std::vector<Eigen::Index> order(X.size());
  std::iota(order.begin(), order.end(), Eigen::Index{0});
  std::stable_sort(order.begin(), order.end(), [&](Eigen::Index a, Eigen::Index b) { return code[a] < code[b]; });
  return order;
}
} // namespace

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
  const std::vector<Eigen::Index> order = spatial_order(qp.X);
  {
    std::vector<Eigen::Vector3d> X(qp.X.size());
    std::vector<double> volume(qp.volume.size());
    std::vector<ShapeEval> sorted(evals.size());
    for (std::size_t q = 0; q < order.size(); ++q) {
      X[q] = qp.X[order[q]];
      volume[q] = qp.volume[order[q]];
      sorted[q] = std::move(evals[order[q]]);
    }
    qp.X = std::move(X);
    qp.volume = std::move(volume);
    evals = std::move(sorted);
  }
  qp.offset.assign(1, 0);
  for (const ShapeEval& e : evals) qp.offset.push_back(qp.offset.back() + static_cast<int>(e.size()));
  qp.node.resize(qp.offset.back());
  qp.N.resize(qp.offset.back());
  qp.dN.resize(qp.offset.back());
  // Each point's entries in ascending node order: the nodes ≤ j precede node j, which the
  // upper-triangle Hessian assembly relies on.
  tbb::parallel_for(Eigen::Index{0}, nq, [&](Eigen::Index q) {
    const ShapeEval& e = evals[q];
    std::vector<int> order(static_cast<std::size_t>(e.size()));
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](int a, int b) { return e.nodes[a] < e.nodes[b]; });
    if (std::adjacent_find(order.begin(), order.end(), [&](int a, int b) { return e.nodes[a] == e.nodes[b]; }) !=
        order.end())
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
