#include "stages/design_simulation.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/LU>
#include <fmt/format.h>

#include "core/input_error.hpp"
#include "core/units.hpp"
#include "export/vtu_writer.hpp"
#include "mesh/mesh_quality.hpp"
#include "mesh/surface_distance.hpp"
#include "mesh/surface_places.hpp"
#include "optimize/tracking_curve.hpp"
#include "sim/external_forces.hpp"
#include "sim/fem_basis.hpp"
#include "stages/plausible_pose.hpp"

namespace fibermold {

namespace fs = std::filesystem;

namespace {
[[noreturn]] void bad(const Design& d, const std::string& key, const std::string& message)
{
  throw InputError(design_problem(d, key, message));
}

/// The body's equilibria need it held: the targets' and optimize's solves (and simulate's).
[[noreturn]] void refuse_held_nowhere(const Design& d)
{
  bad(d, "[[fixed]]", "the body is held nowhere: add a [[fixed]] region (a free body under load has no equilibrium)");
}

/// True when P lies in a tet of the mesh (within 1e-6 in barycentric coordinates).
bool inside_body(const FemBasis& locator, const Eigen::Vector3d& P)
{
  return locator.barycentric(locator.locate(P), P).minCoeff() >= -1e-6;
}

} // namespace

/// The mesh nodes a region (box or surface vertices) selects.
std::vector<int> region_nodes(const Region& r, const TetMesh& mesh, const Design& d, const std::string& key)
{
  std::vector<int> nodes;
  if (r.box) nodes = nodes_in_box(mesh.nodes, (*r.box)[0], (*r.box)[1]);
  for (int v : r.vertices)
    if (v >= mesh.surface_to_node.size())
      bad(d, key, fmt::format("vertex {} does not exist: the surface has {} vertices", v, mesh.surface_to_node.size()));
  if (!r.vertices.empty())
    for (int n : nodes_of_vertices(mesh, r.vertices)) nodes.push_back(n);
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  return nodes;
}

void require_regions_reach_the_body(const Design& d, const SurfaceMesh& surface)
{
  // Held: optimize's solves, and the targets stage's but for a surface target (the whole surface
  // prescribed).
  const bool solved_held =
      (d.optimize.enabled && !d.targets.empty()) ||
      std::any_of(d.targets.begin(), d.targets.end(), [](const Target& t) { return t.kind != TargetKind::surface; });
  if (d.fixed.empty() && solved_held) refuse_held_nowhere(d);
  const Eigen::Vector3d lo = surface.vertices.colwise().minCoeff(), hi = surface.vertices.colwise().maxCoeff();
  const SurfaceDistance skin(surface.vertices, surface.faces);
  const auto require = [&](const Region& r, const std::string& key, const std::string& what) {
    for (int v : r.vertices)
      if (v >= surface.num_vertices())
        bad(d, key, fmt::format("vertex {} does not exist: the surface has {} vertices", v, surface.num_vertices()));
    if (r.box && (((*r.box)[1].array() < lo.array()).any() || ((*r.box)[0].array() > hi.array()).any()))
      bad(d, key,
          fmt::format("{} no node of the mesh: the box {} to {} misses the body, which spans {} to {}", what,
                      format_mm((*r.box)[0]), format_mm((*r.box)[1]), format_mm(lo), format_mm(hi)));
    if (r.point && !skin.closest(*r.point).inside)
      bad(d, key, fmt::format("the point {} lies outside the body", format_mm(*r.point)));
  };
  for (const FixedRegion& f : d.fixed) require(f.region, fmt::format("[fixed.{}]", f.name), "holds");
  // The surface vertices a region selects (each is a node of a mesh that keeps or splits the surface).
  const auto selected = [&](const Region& r) {
    std::vector<bool> in(static_cast<std::size_t>(surface.num_vertices()), false);
    for (int v : r.vertices) in[static_cast<std::size_t>(v)] = true;
    if (r.box)
      for (int v : nodes_in_box(surface.vertices, (*r.box)[0], (*r.box)[1])) in[static_cast<std::size_t>(v)] = true;
    return in;
  };
  // A pose's vertices held by another region too: refused, naming it.
  const auto refuse_shared = [&](const std::string& key, const std::vector<bool>& moved, const Region& other,
                                 const std::string& name) {
    const std::vector<bool> held = selected(other);
    int shared = 0;
    for (std::size_t v = 0; v < moved.size(); ++v) shared += moved[v] && held[v];
    if (shared > 0)
      bad(d, key,
          fmt::format(
              "the region shares {} surface vertices with {}: a node cannot be held in two places; shrink one of them",
              shared, name));
  };
  for (const Target& t : d.targets) {
    for (std::size_t i = 0; i < t.loads.size(); ++i)
      require(t.loads[i].region, fmt::format("[target.{}].load[{}]", t.name, i + 1), "the load's region holds");
    for (std::size_t i = 0; i < t.poses.size(); ++i) {
      const std::string key = fmt::format("[target.{}].pose[{}]", t.name, i + 1);
      require(t.poses[i].region, key, "the region selects");
      const std::vector<bool> moved = selected(t.poses[i].region);
      std::vector<Eigen::Index> rows;
      for (std::size_t v = 0; v < moved.size(); ++v)
        if (moved[v]) rows.push_back(static_cast<Eigen::Index>(v));
      require_plausible_pose(d, key, t.poses[i], surface.vertices(rows, Eigen::all), surface.vertices);
      for (std::size_t j = 0; j < i; ++j)
        refuse_shared(key, moved, t.poses[j].region, fmt::format("[target.{}].pose[{}]", t.name, j + 1));
      for (const FixedRegion& f : d.fixed) refuse_shared(key, moved, f.region, fmt::format("[fixed.{}]", f.name));
    }
  }
}

SimulationOptions simulation_options(const Design& d, const TetMesh& mesh, bool held)
{
  SimulationOptions o;
  o.basis = d.sim.basis;
  o.mls_radius = d.sim.mls_radius;
  o.quadrature_points = d.sim.quadrature_points;
  o.youngs_modulus = d.material.youngs_modulus;
  o.poisson_ratio = d.material.poisson_ratio;
  o.density = d.material.density;
  o.gravity = d.material.gravity;
  if (!held) return o;
  if (d.fixed.empty()) refuse_held_nowhere(d);
  for (const FixedRegion& f : d.fixed) {
    const std::string key = fmt::format("[fixed.{}]", f.name);
    std::vector<int> nodes = region_nodes(f.region, mesh, d, key);
    if (nodes.empty()) {
      const Eigen::Vector3d lo = mesh.nodes.colwise().minCoeff(), hi = mesh.nodes.colwise().maxCoeff();
      bad(d, key, fmt::format("holds no node of the mesh, which spans {} to {}", format_mm(lo), format_mm(hi)));
    }
    o.fixed_nodes.push_back(std::move(nodes));
  }
  return o;
}

/// The nodal forces of a forces target's loads.
Eigen::VectorXd target_forces(const Design& d, const Target& t, const Simulation& sim)
{
  const TetMesh& mesh = sim.mesh();
  Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * mesh.nodes.rows());
  const Eigen::VectorXd weights = sim.load_weights();
  const FemBasis locator(mesh);
  for (std::size_t i = 0; i < t.loads.size(); ++i) {
    const Load& load = t.loads[i];
    const std::string key = fmt::format("[target.{}].load[{}]", t.name, i + 1);
    if (load.region.point) {
      const Eigen::Vector3d& P = *load.region.point;
      if (!inside_body(locator, P)) bad(d, key, fmt::format("the point {} lies outside the body", format_mm(P)));
      f += point_force(sim.basis().at(P, 0), mesh.nodes.rows(), *load.force);
      continue;
    }
    const std::vector<int> nodes = region_nodes(load.region, mesh, d, key);
    if (nodes.empty()) bad(d, key, "the load's region holds no node of the mesh");
    if (load.force) f += region_force(nodes, weights, mesh.nodes, *load.force);
    try {
      if (load.torque) f += region_torque(nodes, weights, mesh.nodes, *load.torque);
    } catch (const std::invalid_argument& e) {
      bad(d, key, fmt::format("{}; the region holds {} node(s)", e.what(), nodes.size()));
    }
  }
  return f;
}

std::string points_key(const std::string& section, const std::vector<Eigen::Vector3d>& points,
                       const std::function<bool(const Eigen::Vector3d&)>& inside)
{
  std::vector<std::size_t> outside;
  for (std::size_t k = 0; k < points.size(); ++k)
    if (!inside(points[k])) outside.push_back(k + 1);
  return outside.size() == 1 ? fmt::format("{}.points[{}]", section, outside.front()) : section + ".points";
}

std::string leaves_the_body(const std::string& what, const std::vector<Eigen::Vector3d>& points,
                            const Eigen::Vector3d& where, const std::function<bool(const Eigen::Vector3d&)>& inside,
                            const std::function<double(const Eigen::Vector3d&)>& depth, const SkinDistance* need)
{
  std::vector<std::string> outside;
  for (std::size_t k = 0; k < points.size(); ++k)
    if (!inside(points[k])) outside.push_back(fmt::format("point {} {}", k + 1, format_mm(points[k])));
  if (!outside.empty())
    return fmt::format("the {} leaves the body at {}; of its {} points, {} {} outside: move {} inside the body", what,
                       format_mm(where), points.size(), fmt::join(outside, ", "), outside.size() == 1 ? "lies" : "lie",
                       outside.size() == 1 ? "it" : "them");
  std::vector<std::string> near; // the ends may lie on the skin: a muscle leaves the body there
  if (depth && need)
    for (std::size_t k = 1; k + 1 < points.size(); ++k)
      if (const double d = depth(points[k]); d < need->distance)
        near.push_back(fmt::format("point {} {} is {:.3f} mm from it", k + 1, format_mm(points[k]), d / units::mm));
  if (!near.empty())
    return fmt::format("the {} leaves the body at {}, between its points, which lie inside but too near the skin: {}; "
                       "a curve through points on or near the skin runs out of the body between them, and a fiber's "
                       "centre line must stay more than {:.3f} mm inside ({}): move {} inward",
                       what, format_mm(where), fmt::join(near, ", "), need->distance / units::mm, need->terms,
                       near.size() == 1 ? "it" : "them");
  return fmt::format("the {} leaves the body at {}, between its points, which all lie inside: the curve through them "
                     "bulges out there; add a point near it, inside, or move its neighbours inward",
                     what, format_mm(where));
}

namespace {

/// Refuses a fiber that leaves the body: every segment end must lie in a tet (within 1e-6 of it); where
/// one does not, the message measures the fiber's points from `mesh`'s skin.
void require_inside(const Design& d, const Actuation& fiber, const TetMesh& mesh, const FemBasis& locator,
                    const HermiteSpline& spline, const FiberSegments& segments)
{
  for (double t : segments.t) {
    const Eigen::Vector3d p = spline.position(t);
    if (inside_body(locator, p)) continue;
    const SurfaceMesh skin = boundary_surface(mesh, mesh.nodes);
    const SurfaceDistance distance(skin.vertices, skin.faces);
    const SkinDistance need = skin_distance(d);
    const auto inside = [&](const Eigen::Vector3d& q) { return inside_body(locator, q); };
    const std::string section = fmt::format("[fiber.{}]", fiber.fiber);
    bad(d, fiber.as_drawn ? points_key(section, fiber.points, inside) : section,
        leaves_the_body(
            "fiber", fiber.points, p, inside, [&](const Eigen::Vector3d& q) { return distance.closest(q).distance; },
            &need));
  }
}

} // namespace

std::vector<Actuation> target_actuations(const Design& d, const Target& t)
{
  std::vector<Actuation> out;
  for (const FiberActuation& a : t.fibers) {
    const Fiber* f = nullptr;
    for (const Fiber& fb : d.fibers)
      if (fb.name == a.name) f = &fb;
    if (a.points.empty())
      out.push_back({a.name, f->points, f->tangents, a.pressure, true});
    else
      out.push_back({a.name, a.points, {}, a.pressure});
  }
  return out;
}

std::vector<const MuscleEnergy*> add_muscles(Simulation& sim, const Design& d, const MuscleModel& model,
                                             const std::vector<Actuation>& actuations)
{
  const FemBasis locator(sim.mesh());
  std::vector<const MuscleEnergy*> muscles;
  for (const Actuation& a : actuations) {
    HermiteSpline spline(a.points, a.tangents);
    const int count = segment_count(spline, d.muscle.segments_per_length);
    std::vector<double> t = segment_parameters(spline, count);
    const FiberSegments segments = segments_at(spline, t);
    for (std::size_t j = 0; j < segments.vectors.size(); ++j)
      if (!(segments.vectors[j].norm() > 1e-9))
        bad(d, fmt::format("[fiber.{}]{}", a.fiber, a.as_drawn ? ".points" : ""),
            fmt::format("the fiber has no length near {} (repeated points?)", format_mm(segments.centres[j])));
    require_inside(d, a, sim.mesh(), locator, spline, segments);
    auto muscle = std::make_unique<MuscleEnergy>(sim.basis(), model, std::move(spline), std::move(t), a.pressure);
    muscles.push_back(muscle.get());
    sim.add_energy(std::move(muscle));
  }
  return muscles;
}

/// VTU of the deformed body (points at x(X_i), displacement in mm, von Mises stress in kPa at each
/// tet's centre) with the fibers as deformed polylines.
void write_deformed(const fs::path& path, const Simulation& sim, const Eigen::VectorXd& x,
                    const std::vector<const MuscleEnergy*>& muscles, const LameParameters& lame)
{
  const TetMesh& mesh = sim.mesh();
  const Eigen::MatrixX3d deformed = sim.deformed_nodes(x);
  std::vector<Eigen::Vector3d> rest_points, points;
  for (Eigen::Index i = 0; i < mesh.nodes.rows(); ++i) {
    rest_points.push_back(mesh.nodes.row(i).transpose());
    points.push_back(deformed.row(i).transpose());
  }
  std::vector<std::vector<int>> lines;
  for (std::size_t m = 0; m < muscles.size(); ++m) {
    std::vector<int> line;
    for (double t : muscles[m]->segments().t) {
      const Eigen::Vector3d X = muscles[m]->spline().position(t);
      line.push_back(static_cast<int>(points.size()));
      rest_points.push_back(X);
      points.push_back(sim.basis().at(X, 0).position(x));
    }
    lines.push_back(std::move(line));
  }
  Eigen::MatrixX3d P(static_cast<Eigen::Index>(points.size()), 3);
  Eigen::MatrixXd u(P.rows(), 3);
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    P.row(i) = points[i].transpose();
    u.row(i) = (points[i] - rest_points[i]).transpose() / units::mm;
  }
  VtuGrid grid(P);
  grid.add_cells(mesh.tets, mesh.nodes_per_tet() == 10 ? VtkCell::quadratic_tetra : VtkCell::tetra);
  for (const auto& line : lines) grid.add_cell(line, VtkCell::poly_line);
  Eigen::MatrixXd von_mises = Eigen::MatrixXd::Zero(grid.num_cells(), 1);
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int k = 0; k < 4; ++k) c += mesh.nodes.row(mesh.tets(t, k)).transpose() / 4;
    const Eigen::Matrix3d F = sim.basis().at(c, 1, t).deformation_gradient(x);
    const Eigen::Matrix3d sigma = neo_hookean_stress(F, lame) * F.transpose() / F.determinant(); // Cauchy
    const Eigen::Matrix3d s = sigma - sigma.trace() / 3 * Eigen::Matrix3d::Identity();
    von_mises(t, 0) = std::sqrt(1.5 * s.squaredNorm()) / units::kPa;
  }
  grid.add_point_field("displacement_mm", u);
  grid.add_cell_field("von_mises_kPa", von_mises);
  grid.write(path);
}

Refinement compare_refined(const Design& d, const Simulation& coarse, const Eigen::VectorXd& coarse_x,
                           const Simulation& fine, const Eigen::VectorXd& fine_x)
{
  const TetMesh& coarse_mesh = coarse.mesh();
  const TetMesh& fine_mesh = fine.mesh();
  Refinement r;
  r.nodes = fine_mesh.nodes.rows();
  r.tets = fine_mesh.num_tets();
  r.max_displacement = (fine.deformed_nodes(fine_x) - fine_mesh.nodes).rowwise().norm().maxCoeff();
  const auto difference = [&](const Eigen::Vector3d& X) {
    return (coarse.basis().at(X, 0).position(coarse_x) - fine.basis().at(X, 0).position(fine_x)).norm();
  };
  double sum = 0;
  for (Eigen::Index v = 0; v < coarse_mesh.surface_to_node.size(); ++v) {
    const double e = difference(coarse_mesh.nodes.row(coarse_mesh.surface_to_node(v)).transpose());
    sum += e * e;
    r.surface_max = std::max(r.surface_max, e);
  }
  r.surface_rms = std::sqrt(sum / static_cast<double>(std::max<Eigen::Index>(1, coarse_mesh.surface_to_node.size())));
  sum = 0;
  for (const TrackingCurve& c : d.tracking_curves)
    for (const Eigen::Vector3d& q :
         sample_tracking_curve(c.points, c.samples, c.weight_position, c.weight_orientation).points) {
      const double e = difference(q);
      sum += e * e;
      r.curves_max = std::max(r.curves_max, e);
      ++r.curve_samples;
    }
  r.curves_rms = r.curve_samples > 0 ? std::sqrt(sum / r.curve_samples) : 0;
  r.edge_length = mesh_quality(fine_mesh).mean_edge_length;
  return r;
}

} // namespace fibermold
