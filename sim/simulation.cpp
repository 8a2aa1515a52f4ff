#include "sim/simulation.hpp"

#include <stdexcept>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "mesh/mesh_quality.hpp"
#include "sim/external_forces.hpp"
#include "sim/fem_basis.hpp"
#include "sim/mls_basis.hpp"
#include "sim/neo_hookean.hpp"
#include "sim/soft_dirichlet.hpp"

namespace fibermold {

namespace {
std::unique_ptr<Basis> make_basis(const TetMesh& mesh, const SimulationOptions& o, double mean_edge)
{
  if (o.basis == BasisKind::fem_p1 || o.basis == BasisKind::fem_p2) {
    if ((o.basis == BasisKind::fem_p2) != (mesh.nodes_per_tet() == 10))
      throw std::invalid_argument(fmt::format("basis {} needs {}-node tets, the mesh has {}", choice_name(o.basis),
                                              o.basis == BasisKind::fem_p2 ? 10 : 4, mesh.nodes_per_tet()));
    return std::make_unique<FemBasis>(mesh);
  }
  MlsOptions mls;
  mls.quadratic = o.basis == BasisKind::mls_quadratic;
  mls.radius = o.mls_radius * mean_edge;
  return std::make_unique<MlsBasis>(mesh.nodes, mls);
}
} // namespace

Simulation::Simulation(const TetMesh& mesh, SimulationOptions options)
    : mesh_(mesh), options_(std::move(options)), mean_edge_(mesh_quality(mesh).mean_edge_length)
{
  basis_ = make_basis(mesh_, options_, mean_edge_);
  qp_ = build_quadrature_points(mesh_, *basis_, options_.quadrature_points);
  masses_ = nodal_masses(qp_, mesh_.nodes.rows(), options_.density);

  const Eigen::Index n = mesh_.nodes.rows();
  at_nodes_.resize(static_cast<std::size_t>(n));
  tbb::parallel_for(Eigen::Index{0}, n,
                    [&](Eigen::Index i) { at_nodes_[i] = basis_->at(mesh_.nodes.row(i).transpose(), 0); });

  energies_.push_back(std::make_unique<NeoHookean>(
      qp_, n, LameParameters::from_young_poisson(options_.youngs_modulus, options_.poisson_ratio)));
  if (options_.gravity.norm() > 0 && options_.density > 0)
    energies_.push_back(std::make_unique<ExternalForces>(gravity_forces(masses_, options_.gravity)));

  std::vector<ShapeEval> held;
  std::vector<Eigen::Vector3d> targets;
  for (std::size_t r = 0; r < options_.fixed_nodes.size(); ++r) {
    if (options_.fixed_nodes[r].empty())
      throw std::invalid_argument(fmt::format("fixed region {} holds no node", r + 1));
    for (int i : options_.fixed_nodes[r]) {
      held.push_back(at_nodes_[i]);
      targets.push_back(mesh_.nodes.row(i).transpose());
    }
  }
  fixed_points_ = held.size();
  for (const auto& [i, position] : options_.moved_nodes) {
    held.push_back(at_nodes_[i]);
    targets.push_back(position);
  }
  if (held.empty()) throw std::invalid_argument("the body is held nowhere: give at least one [[fixed]] region");
  const double k = options_.dirichlet_penalty * options_.youngs_modulus * mean_edge_;
  auto dirichlet = std::make_unique<SoftDirichlet>(std::move(held), std::move(targets), k);
  dirichlet_ = dirichlet.get();
  energies_.push_back(std::move(dirichlet));
}

void Simulation::move_nodes(const std::vector<Eigen::Vector3d>& positions)
{
  if (positions.size() != options_.moved_nodes.size())
    throw std::invalid_argument(
        fmt::format("move_nodes: {} positions for {} moved nodes", positions.size(), options_.moved_nodes.size()));
  dirichlet_->move_targets(fixed_points_, positions);
}

Simulation::~Simulation() = default;

Eigen::VectorXd Simulation::rest() const
{
  Eigen::VectorXd x(3 * mesh_.nodes.rows());
  for (Eigen::Index i = 0; i < mesh_.nodes.rows(); ++i) x.segment<3>(3 * i) = mesh_.nodes.row(i).transpose();
  return x;
}

Eigen::VectorXd Simulation::load_weights() const { return nodal_volumes(qp_, mesh_.nodes.rows()); }

void Simulation::add_energy(std::unique_ptr<Energy> energy)
{
  if (!solvers_.empty()) throw std::logic_error("Simulation::add_energy after the first solve");
  energies_.push_back(std::move(energy));
}

void Simulation::set_variable_energies(std::vector<std::unique_ptr<Energy>> energies)
{
  std::vector<const Energy*> terms;
  for (const auto& e : energies) terms.push_back(e.get());
  solver().set_variable_energies(terms); // before the old terms it points to are freed
  variable_energies_[slot_] = std::move(energies);
}

void Simulation::use_solver(int slot)
{
  if (slot < 0) throw std::invalid_argument("Simulation::use_solver: a negative slot");
  slot_ = static_cast<std::size_t>(slot);
}

NewtonSolver& Simulation::solver()
{
  if (solvers_.size() <= slot_) {
    solvers_.resize(slot_ + 1);
    variable_energies_.resize(slot_ + 1);
  }
  if (!solvers_[slot_]) {
    std::vector<const Energy*> terms;
    for (const auto& e : energies_) terms.push_back(e.get());
    // MLS: one pattern (and one symbolic analysis) however the muscles move (newton_solver.hpp).
    const bool mls = options_.basis == BasisKind::mls_linear || options_.basis == BasisKind::mls_quadratic;
    solvers_[slot_] = std::make_unique<NewtonSolver>(std::move(terms), mesh_.nodes.rows(), mls);
  }
  return *solvers_[slot_];
}

int Simulation::symbolic_analyses() const
{
  int n = 0;
  for (const auto& s : solvers_)
    if (s) n += s->analyses();
  return n;
}

NewtonSummary Simulation::solve(Eigen::VectorXd& x, Progress& progress)
{
  NewtonOptions o = options_.newton;
  // Force scale: the net force on the body at rest (loads, gravity, muscles), floored by the
  // elastic force of a unit strain over one element face, E h².
  o.force_scale = solver().gradient(rest()).norm() + options_.youngs_modulus * mean_edge_ * mean_edge_;
  return solver().solve(x, o, progress);
}

Eigen::MatrixX3d Simulation::deformed_nodes(const Eigen::VectorXd& x) const
{
  Eigen::MatrixX3d p(mesh_.nodes.rows(), 3);
  for (Eigen::Index i = 0; i < p.rows(); ++i) p.row(i) = at_nodes_[i].position(x).transpose();
  return p;
}

} // namespace fibermold
