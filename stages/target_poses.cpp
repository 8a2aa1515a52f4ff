#include "stages/target_poses.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/input_error.hpp"
#include "core/units.hpp"
#include "mesh/surface_distance.hpp"
#include "stages/design_simulation.hpp"
#include "stages/plausible_pose.hpp"

namespace fibermold {

std::vector<PosedRegion> target_poses(const Design& d, const Target& t, const TetMesh& mesh)
{
  const SimulationOptions held = simulation_options(d, mesh);
  std::vector<int> owner(static_cast<std::size_t>(mesh.nodes.rows()), -1); // -1 free, ≥ 0 a pose, -2 − r fixed r
  for (std::size_t r = 0; r < held.fixed_nodes.size(); ++r)
    for (int n : held.fixed_nodes[r]) owner[n] = -2 - static_cast<int>(r);
  std::vector<PosedRegion> out;
  for (std::size_t i = 0; i < t.poses.size(); ++i) {
    const Pose& p = t.poses[i];
    PosedRegion r;
    r.key = fmt::format("[target.{}].pose[{}]", t.name, i + 1);
    r.nodes = region_nodes(p.region, mesh, d, r.key);
    if (r.nodes.empty()) {
      const Eigen::Vector3d lo = mesh.nodes.colwise().minCoeff(), hi = mesh.nodes.colwise().maxCoeff();
      throw InputError(design_problem(
          d, r.key,
          p.region.box
              ? fmt::format(
                    "the box {} to {} selects no node of the mesh, which spans {} to {}: widen it to at least the "
                    "mesh's edge length, or give vertices = [...]",
                    format_mm((*p.region.box)[0]), format_mm((*p.region.box)[1]), format_mm(lo), format_mm(hi))
              : fmt::format("the region selects no node of the mesh, which spans {} to {}", format_mm(lo),
                            format_mm(hi))));
    }
    int shared = 0, with = -1;
    for (int n : r.nodes)
      if (owner[n] != -1) ++shared, with = owner[n];
    if (shared > 0) {
      const std::string other = with >= 0
                                    ? fmt::format("[target.{}].pose[{}]", t.name, with + 1)
                                    : fmt::format("[fixed.{}]", d.fixed[static_cast<std::size_t>(-2 - with)].name);
      throw InputError(design_problem(
          d, r.key,
          fmt::format("the region shares {} node(s) with {}: a node cannot be held in two places; shrink one of them",
                      shared, other)));
    }
    for (int n : r.nodes) owner[n] = static_cast<int>(i);
    r.axis = p.axis.normalized();
    r.angle = p.angle;
    r.translation = p.translation;
    if (p.about) {
      r.about = *p.about;
    } else {
      r.about = Eigen::Vector3d::Zero();
      for (int n : r.nodes) r.about += mesh.nodes.row(n).transpose();
      r.about /= static_cast<double>(r.nodes.size());
    }
    if (p.curl_from) r.translation = uniform_curl_translation(*p.curl_from, r.about, r.axis, r.angle);
    require_plausible_pose(d, r.key, p, mesh.nodes(r.nodes, Eigen::all), mesh.nodes);
    out.push_back(std::move(r));
  }
  return out;
}

namespace {

/// The pose of a set of nodes: the displacement of their centroid, the rotation fitted to them.
ReachedPose region_pose(std::string place, const std::vector<int>& nodes, const TetMesh& mesh,
                        const Eigen::MatrixX3d& deformed)
{
  ReachedPose p;
  p.place = std::move(place);
  p.nodes = static_cast<int>(nodes.size());
  Eigen::MatrixX3d X(nodes.size(), 3), x(nodes.size(), 3);
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    X.row(static_cast<Eigen::Index>(k)) = mesh.nodes.row(nodes[k]);
    x.row(static_cast<Eigen::Index>(k)) = deformed.row(nodes[k]);
  }
  p.motion = fitted_rigid_motion(X, x);
  if (!nodes.empty()) {
    p.rest = X.colwise().mean().transpose();
    p.displacement = x.colwise().mean().transpose() - p.rest;
  }
  return p;
}

/// The pose of the material at a point: its displacement, the rotation of F = R U there.
ReachedPose point_pose(std::string place, const Eigen::Vector3d& X, const Simulation& sim, const Eigen::VectorXd& x)
{
  ReachedPose p;
  p.place = std::move(place);
  p.rest = X;
  const ShapeEval e = sim.basis().at(X, 1);
  p.displacement = e.position(x) - X;
  p.motion.rotation = polar_rotation(e.deformation_gradient(x));
  p.motion.translation = e.position(x) - p.motion.rotation * X;
  return p;
}

nlohmann::ordered_json mm(const Eigen::Vector3d& v)
{
  return {v.x() / units::mm, v.y() / units::mm, v.z() / units::mm};
}

} // namespace

std::vector<ReachedPose> reached_poses(const Design& d, const Target& t, const Simulation& sim,
                                       const Eigen::VectorXd& x, const std::vector<PosedRegion>& asked)
{
  const TetMesh& mesh = sim.mesh();
  const Eigen::MatrixX3d deformed = sim.deformed_nodes(x);
  std::vector<ReachedPose> out;
  if (t.kind == TargetKind::forces)
    for (std::size_t i = 0; i < t.loads.size(); ++i) {
      const std::string place = fmt::format("load[{}]", i + 1);
      const Region& r = t.loads[i].region;
      if (r.point)
        out.push_back(point_pose(place, *r.point, sim, x));
      else
        out.push_back(region_pose(place, region_nodes(r, mesh, d, "[target." + t.name + "]." + place), mesh, deformed));
    }
  for (std::size_t i = 0; i < asked.size(); ++i) {
    out.push_back(region_pose(fmt::format("pose[{}]", i + 1), asked[i].nodes, mesh, deformed));
    out.back().asked = &asked[i];
  }
  // A curve's end outside the body (curves are held to the body only when the optimizer runs) has no pose.
  const SurfaceDistance skin(mesh.nodes, mesh.boundary_faces);
  for (const TrackingCurve& c : d.tracking_curves) {
    if (skin.holds(c.points.front(), 1e-6))
      out.push_back(point_pose(c.name + ", first point", c.points.front(), sim, x));
    if (skin.holds(c.points.back(), 1e-6)) out.push_back(point_pose(c.name + ", last point", c.points.back(), sim, x));
  }
  return out;
}

nlohmann::ordered_json pose_report(const ReachedPose& p)
{
  nlohmann::ordered_json j = {{"place", p.place}};
  if (p.nodes > 0) j["nodes"] = p.nodes;
  j["rest_mm"] = mm(p.rest);
  j["translation_mm"] = mm(p.displacement);
  j["rotation_deg"] = p.motion.angle() / units::degree;
  j["rotation_axis"] = {p.motion.axis().x(), p.motion.axis().y(), p.motion.axis().z()};
  if (p.asked) {
    const Eigen::Vector3d a = p.asked->axis;
    const double reached = p.motion.angle_about(a), angle = p.asked->angle;
    j["asked_rotation_deg"] = angle / units::degree;
    if (angle != 0) j["asked_axis"] = {a.x(), a.y(), a.z()};
    j["rotation_about_asked_axis_deg"] = reached / units::degree;
    if (angle != 0) j["rotation_reached_percent"] = 100 * reached / angle;
    j["asked_translation_mm"] = mm(p.asked->at(1).apply(p.rest) - p.rest);
  }
  return j;
}

nlohmann::ordered_json pose_report(const ReachedPose& p, const std::array<ReachedPose, 4>& varied)
{
  nlohmann::ordered_json j = pose_report(p);
  const auto each = [&](const auto& of) {
    nlohmann::ordered_json out = nlohmann::ordered_json::object();
    for (std::size_t k = 0; k < varied.size(); ++k) out[kPoseVariations[k]] = of(varied[k]);
    return out;
  };
  j["sensitivity"] = {
      {"change_percent", 100 * kSensitivityChange},
      {"rotation_deg", each([](const ReachedPose& q) { return q.motion.angle() / units::degree; })},
      {"displacement_mm", each([](const ReachedPose& q) { return q.displacement.norm() / units::mm; })}};
  if (p.asked)
    j["sensitivity"]["rotation_about_asked_axis_deg"] =
        each([&](const ReachedPose& q) { return q.motion.angle_about(p.asked->axis) / units::degree; });
  return j;
}

} // namespace fibermold
