#include "molds/two_shot_molds.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <fmt/format.h>

#include "core/elapsed.hpp"
#include "core/units.hpp"
#include "molds/draft.hpp"
#include "molds/fill_simulation.hpp"

namespace fibermold {

namespace {

using Clock = std::chrono::steady_clock;

SurfaceMesh scaled_about(SurfaceMesh m, const Eigen::Vector3d& centre, double factor)
{
  m.vertices = ((m.vertices.rowwise() - centre.transpose()) * factor).rowwise() + centre.transpose();
  return m;
}

/// An end of a fiber on the skin gets a channel out through the mold, square to the skin there (a
/// channel meeting the skin at an angle would leave a knife edge of mold): from a point 1 mm
/// inside, back along the fiber, to its nearest skin point. Where the fiber leaves the skin almost
/// along it (that point is not inside: the walking robot's bend fiber once left its end face 81°
/// off the face's normal, and its channel, laid along the fiber, cut the body diagonally and left a
/// 0.08 mm wall), the deepest of the points 1 mm in along ±x, ±y, ±z serves instead. `along`
/// points out of the fiber at `end`. Nothing for an end inside the body.
std::optional<Channel> end_channel(const Eigen::Vector3d& end, const Eigen::Vector3d& along,
                                   const SurfaceDistance& skin, double radius, const MoldOptions& m,
                                   double muscle_diameter)
{
  if (skin.closest(end).distance >= radius) return std::nullopt;
  const auto square_out = [&](const Eigen::Vector3d& in, double& depth) -> std::optional<Eigen::Vector3d> {
    const Eigen::Vector3d inside = end + 1e-3 * in;
    const auto at = skin.closest(inside);
    depth = at.distance;
    if (!(at.inside && at.distance > 1e-6)) return std::nullopt;
    return Eigen::Vector3d((at.point - inside).normalized());
  };
  double depth = 0, deepest = 0;
  std::optional<Eigen::Vector3d> out = square_out(-along.normalized(), depth), best;
  for (int axis = 0; !out && axis < 6; ++axis) {
    const Eigen::Vector3d in = (axis % 2 ? -1.0 : 1.0) * Eigen::Vector3d::Unit(axis / 2);
    if (const auto o = square_out(in, depth); o && depth > deepest) best = o, deepest = depth;
  }
  const Eigen::Vector3d dir = out ? *out : best.value_or(along.normalized());
  return Channel{end - 1e-3 * dir, dir, m.end_channel_diameter, 1e-3 + m.end_channel_length, muscle_diameter};
}

/// A shot's fill problems: a part no sprue reaches, or trapped air beyond the tolerance, each named
/// by where it is. `g3` maps a volume of the nominal body to the scaled cavity.
void fill_problems(const FillPlan& plan, const TwoShotMolds& molds, double g3, const std::string& shot,
                   std::vector<std::string>& problems)
{
  const FillResult& f = plan.fill;
  const double mm3 = units::mm3;
  const double unreached = f.fill_volume - f.reachable_volume - f.crevice_volume;
  if (g3 * unreached > kTrappedAirTolerance && !f.unreachable.empty())
    problems.push_back(
        fmt::format("{}: {:.1f} mm³ of the {:.1f} mm³ that the shot fills is reached by no sprue (the largest part, "
                    "{:.1f} mm³, lowest at {}) with {} sprue(s) placed: no other fits near it",
                    shot, g3 * unreached / mm3, g3 * f.fill_volume / mm3, g3 * f.unreachable.front().volume / mm3,
                    format_mm(molds.scaled(f.unreachable.front().at)), plan.ports.sprues.size()));
  if (g3 * f.trapped_volume > kTrappedAirTolerance && !f.pockets.empty()) {
    const AirPocket& worst = f.pockets.front();
    problems.push_back(fmt::format(
        "{}: the rising silicone traps {:.1f} mm³ of air, allowed {:.1f} mm³: the largest pocket, {:.1f} mm³, "
        "tops out at {} {}",
        shot, g3 * f.trapped_volume / mm3, kTrappedAirTolerance / mm3, g3 * worst.volume / mm3,
        format_mm(molds.scaled(worst.at)),
        worst.ventable
            ? fmt::format("with {} vents placed: no more fits near it (within 3 mm the skin slopes more than 35°, or "
                          "another vent let out no more air)",
                          plan.ports.vents.size())
            : std::string("under cured silicone, a muscle or an overhang of the body, where no "
                          "vent can reach it; another [mold] pull may open it upward")));
  }
}

/// The recipe's working state: the options, the body, and what the shots share.
class Recipe {
public:
  Recipe(const MoldJob& job, const MoldOptions& m, Progress& progress, const MoldLog& log)
      : job_(job), m_(m), progress_(progress), log_(log), skin_(job.body.vertices, job.body.faces),
        pull_(m.pull.normalized())
  {
    out_.groove_radius = groove_radius(job.muscle_diameter, m);
    block_ = m.block;
    block_.min_wall = job.min_wall;
    for (const MoldFiber& f : job.fibers) {
      lines_.push_back(f.line);
      muscle_volume_ += f.length * M_PI * std::pow(job.muscle_diameter / 2, 2);
      for (const auto& [end, along] :
           {std::pair{f.start, Eigen::Vector3d(-f.start_tangent)}, std::pair{f.end, f.end_tangent}})
        if (auto c = end_channel(end, along, skin_, out_.groove_radius, m, job.muscle_diameter)) {
          channels_.push_back(*c);
          channel_ends_.push_back(
              fmt::format("{} leaves the body at {}", f.name.empty() ? "a fiber" : f.name, format_mm(end)));
        }
    }
    out_.pull = pull_;
    // Shrink compensation: cavities (and channel starts) scaled up about the body's centre.
    out_.grow = m.shrink_growth();
    out_.centre = job.body.vertices.colwise().mean().transpose();
    for (Channel& c : channels_) c.start = out_.scaled(c.start);
    g3_ = out_.grow * out_.grow * out_.grow;
  }

  TwoShotMolds make();

private:
  void carve(double adaptivity, GrooveBody* drafted = nullptr)
  {
    const auto started = Clock::now();
    out_.groove = groove_body(job_.body, lines_, out_.groove_radius, pull_, m_.voxel, adaptivity,
                              draft_ ? &*draft_ : nullptr, drafted);
    const GrooveBody& g = out_.groove;
    log_.info(fmt::format(
        "groove body: {} triangles (adaptivity {}), {:.2f} mL (meshed {:.2f} mL), voxel {:.2f} mm, in {:.2f} s",
        g.mesh.num_faces(), g.adaptivity, g.volume / units::mL, signed_volume(g.mesh) / units::mL, m_.voxel / units::mm,
        since(started)));
  }

  /// Each part's labels (text, face, size) and those left out.
  void log_labels(const Mold& mold) const
  {
    for (const MoldPart& p : mold.parts) {
      for (const PlacedLabel& l : p.labels)
        log_.info(fmt::format("{}: \"{}\" engraved on its {} face (out of the part along ({:.3g}, {:.3g}, {:.3g})) "
                              "at {}, {:.1f} mm capitals, {:.1f} × {:.1f} mm, {:.1f} mm deep",
                              p.name, l.text, l.face, l.normal.x() + 0.0, l.normal.y() + 0.0, l.normal.z() + 0.0,
                              format_mm(l.centre), l.height / units::mm, l.extent.x() / units::mm,
                              l.extent.y() / units::mm, l.depth / units::mm));
      for (const std::string& why : p.unlabelled) log_.warn(fmt::format("{}: {}", p.name, why));
    }
  }

  /// The shot's thin deep ribs, in `shot` and, without a draft to taper them, as warnings that
  /// name each (the five deepest) and what to do.
  void warn_thin_ribs(ShotMold& shot, const SurfaceMesh& cavity, const Parting& parting) const
  {
    const auto started = Clock::now();
    shot.thin_ribs = thin_ribs(cavity, parting, kThinRib / 12, &progress_);
    log_.info(
        fmt::format("{}: {} thin deep rib(s) found in {:.2f} s", shot.name, shot.thin_ribs.size(), since(started)));
    if (m_.draft_deg > 0) return;
    for (std::size_t k = 0; k < shot.thin_ribs.size() && k < 5; ++k) {
      const ThinRib& r = shot.thin_ribs[k];
      log_.warn(fmt::format("{}: the {} half stands a rib {:.1f} mm thick {:.1f} mm deep into the cavity, its tip at "
                            "{} (the mold's side of a narrow slot or gap of the body): printed without draft it may "
                            "break, or tear the cast, as the half comes off; set [mold] draft_deg (1–3°), or print "
                            "that half solid",
                            shot.name, r.upper ? "upper" : "lower", r.thickness / units::mm, r.depth / units::mm,
                            format_mm(r.at)));
    }
    if (shot.thin_ribs.size() > 5)
      log_.warn(
          fmt::format("{}: and {} more thin deep ribs (molds/report.json)", shot.name, shot.thin_ribs.size() - 5));
  }

  void explain_close_channels(const std::string& name, const Mold& mold, const std::vector<Channel>& shot_channels,
                              bool thin_wall, std::vector<std::string>& problems) const;
  std::vector<std::string> make_shot(const std::string& name, const SurfaceMesh& shot_cavity, Parting parting,
                                     double silicone, const std::vector<Channel>& shot_channels);

  const MoldJob& job_;
  const MoldOptions& m_;
  Progress& progress_;
  const MoldLog& log_;
  const SurfaceDistance skin_;
  const Eigen::Vector3d pull_;
  MoldBlockOptions block_;
  std::vector<std::vector<Eigen::Vector3d>> lines_;
  std::vector<Channel> channels_;
  std::vector<std::string> channel_ends_; ///< per channel: "up leaves the body at (0.0, -3.0, 3.0) mm"
  double muscle_volume_ = 0, g3_ = 1;
  std::optional<Draft> draft_;
  FillRegions regions_; ///< what each shot fills, sampled once: both shots' from the body, drafted or not
  std::vector<std::string> fill_failures_; ///< apart from the parts': meshing the cavity again cannot help them
  std::vector<std::string> too_big_;       ///< parts too big for the printer: meshing again cannot help them either
  TwoShotMolds out_;
};

/// A thin wall between two fibers' end channels: the ends are too near each other for the channels
/// (a new user's two muscles left the tip 5.6 mm apart, and both 4 mm channels were laid onto the
/// parting plane, 2.5 mm apart: "a wall of 0.02 mm", and no word of why). Said as a line of its own
/// after the parts' problems, which it explains (appended to the last of them, it could land on
/// another part's, or on a problem of another kind), where one of the shot's parts has a thin wall.
void Recipe::explain_close_channels(const std::string& name, const Mold& mold,
                                    const std::vector<Channel>& shot_channels, bool thin_wall,
                                    std::vector<std::string>& problems) const
{
  if (thin_wall && shot_channels.size() == channel_ends_.size())
    for (const CloseChannels& close : mold.close_channels)
      problems.push_back(fmt::format(
          "{}: the end channels where {} and where {} leave {:.2f} mm of mold between them, under [export] min_wall = "
          "{:.2f} mm (each {:.1f} mm wide, laid parallel to the parting plane, and onto it within their radius + "
          "min_wall of it): move those ends further apart, or give a smaller [mold] end_channel_diameter",
          name, channel_ends_[static_cast<std::size_t>(close.a)], channel_ends_[static_cast<std::size_t>(close.b)],
          std::max(0.0, close.wall) / units::mm, job_.min_wall / units::mm, m_.end_channel_diameter / units::mm));
}

/// One shot's mold: its fill plan, its parts checked; the parts' problems found, one line each.
/// Shot 1 fills the grooved body from below; shot 2 the grooves around the laid muscles, over
/// cured silicone: its sprues come from above (ports.hpp).
std::vector<std::string> Recipe::make_shot(const std::string& name, const SurfaceMesh& shot_cavity, Parting parting,
                                           double silicone, const std::vector<Channel>& shot_channels)
{
  std::vector<std::string> problems;
  const bool first = name == "shot1";
  progress_.checkpoint(first ? 0.25 : 0.55, fmt::format("{}: fill simulation", name));
  auto started = Clock::now();
  const VoxelRegion& region = first ? regions_.shot1 : regions_.shot2;
  ShotMold shot;
  shot.name = name;
  shot.fill_voxel = region.voxel;
  shot.plan = plan_fill(region, shot_cavity,
                        first ? cavity_ports(shot_cavity, pull_, block_.sprue_diameter, block_.vents,
                                             block_.vent_diameter, block_.min_wall, name)
                              : Ports{},
                        block_.sprue_diameter, block_.vent_diameter, block_.min_wall, !first,
                        first ? &regions_.shot2 : nullptr, kTrappedAirTolerance / g3_);
  const FillPlan& plan = shot.plan;
  const double fill_seconds = since(started);
  std::erase_if(fill_failures_, [&](const std::string& f) { return f.starts_with(name); }); // a shot made again
  fill_problems(plan, out_, g3_, name, fill_failures_);
  for (std::size_t k = 0; k < plan.fill.pockets.size() && k < 5; ++k)
    log_.info(fmt::format("{}: air pocket of {:.2f} mm³ topping out at {}{}", name,
                          g3_ * plan.fill.pockets[k].volume / units::mm3,
                          format_mm(out_.scaled(plan.fill.pockets[k].at)),
                          plan.fill.pockets[k].ventable ? "" : " (under solid: no vent reaches it)"));
  log_.info(fmt::format("{}: sprues and vents placed in {:.2f} s, of which {} fill simulation(s) on {} voxels of "
                        "{:.2f} mm {:.2f} s: {} sprue(s), "
                        "{} vent(s), {:.1f} % reached, {:.2f} mm³ of air trapped",
                        name, fill_seconds, plan.simulations, region.count(), region.voxel / units::mm,
                        plan.simulation_seconds, plan.ports.sprues.size(), plan.ports.vents.size(),
                        plan.fill.fill_volume > 0 ? 100 * plan.fill.reachable_volume / plan.fill.fill_volume : 0.0,
                        g3_ * plan.fill.trapped_volume / units::mm3));
  for (const Port& p : plan.ports.sprues)
    log_.info(fmt::format("{}: sprue {} at {}, {:.1f} mm across", name, p.upward ? "from above" : "from below",
                          format_mm(out_.scaled(p.mouth)), p.diameter / units::mm));
  for (const Port& p : plan.ports.vents)
    log_.info(fmt::format("{}: vent at {}, {:.1f} mm across, cut {:.2f} mm into the cavity", name,
                          format_mm(out_.scaled(p.mouth)), p.diameter / units::mm, p.dip() / units::mm));
  Ports scaled_ports = plan.ports;
  for (Port& p : scaled_ports.sprues) p.mouth = out_.scaled(p.mouth);
  for (Port& p : scaled_ports.vents) p.mouth = out_.scaled(p.mouth);
  progress_.checkpoint(first ? 0.3 : 0.6, fmt::format("{}: mold block", name));
  const SurfaceMesh cavity = out_.grow != 1 ? scaled_about(shot_cavity, out_.centre, out_.grow) : shot_cavity;
  parting.point = out_.scaled(parting.point);
  parting.undercut_area = undercut_area(cavity, parting.point, parting.normal);
  log_.info(fmt::format("{}: parting plane through {} normal to pull, {:.1f} mm² of undercut", name,
                        format_mm(parting.point), parting.undercut_area / units::mm2));
  if (parting.undercut_area > kUndercutWarning)
    log_.warn(fmt::format(
        "{}: {:.1f} mm² of the cavity is an undercut for the parting plane: demolding relies on the silicone bending",
        name, parting.undercut_area / units::mm2));
  started = Clock::now();
  const PartLabels labels{job_.name, {}};
  const Mold mold =
      make_mold(cavity, parting, shot_channels, block_, name, &scaled_ports, m_.labels ? &labels : nullptr);
  log_.info(fmt::format("{}: mold block and parts in {:.2f} s, of which labels {:.2f} s", name, since(started),
                        mold.label_seconds));
  log_labels(mold);
  shot.upright_share = upright_share(cavity, parting.point, parting.normal, 3);
  log_.info(fmt::format(
      "{}: {:.0f} % of the upper half's contact lies within 3° of the pull (walls it slides along; draft_deg {})", name,
      100 * shot.upright_share, m_.draft_deg));
  warn_thin_ribs(shot, cavity, parting);
  shot.parting = parting;
  shot.cavity_volume = signed_volume(cavity);
  shot.silicone_volume = silicone;
  shot.sprues = mold.sprues.size();
  shot.vents = mold.vents.size();
  shot.keys = mold.keys.size();
  shot.screw_holes = mold.screws.size();
  if (static_cast<int>(mold.screws.size()) < block_.screw_holes)
    log_.warn(fmt::format(
        "{}: room for {} of the {} screw holes asked for (channels and keys take the other sites in the rim)", name,
        mold.screws.size(), block_.screw_holes));
  bool thin_wall = false;
  for (const MoldPart& p : mold.parts) {
    progress_.checkpoint(-1, "checking " + p.name);
    started = Clock::now();
    PartCheck c = check_part(p.mesh, job_.min_wall, job_.printer_volume);
    log_.info(fmt::format("{}: {} triangles, thinnest wall {:.2f} mm near {}, checked in {:.2f} s", p.name,
                          p.mesh.num_faces(), c.min_thickness / units::mm, format_mm(c.min_thickness_at),
                          since(started)));
    for (const std::string& problem : c.problems) problems.push_back(fmt::format("part {} {}", p.name, problem));
    if (!c.fits) too_big_.push_back(p.name);
    thin_wall = thin_wall || c.thin_wall;
    out_.parts.push_back(CheckedPart{name, p, std::move(c)});
  }
  explain_close_channels(name, mold, shot_channels, thin_wall, problems);
  std::erase_if(out_.shots, [&](const ShotMold& s) { return s.name == name; });
  out_.shots.push_back(std::move(shot));
  return problems;
}

TwoShotMolds Recipe::make()
{
  progress_.checkpoint(0.1, "carving the grooves (level set)");
  carve(kGrooveAdaptivity);
  const SurfaceMesh& body = job_.body;
  const double body_volume = signed_volume(body);
  // The silicone that fills each channel's socket around the muscle's end.
  const double sleeves = static_cast<double>(channels_.size()) * M_PI *
                         (std::pow(m_.end_channel_diameter / 2, 2) -
                          std::pow(std::min(m_.end_channel_diameter, job_.muscle_diameter) / 2, 2)) *
                         m_.end_channel_length;

  // Shot 1 fills the scaled-up groove cavity; its cured part shrinks back to nominal size. The
  // adaptive mesh of the groove body can leave a facet that a part's checks reject (a sliver wall):
  // then shot 1 is made again from the uniform mesh, which they have been proven on.
  const auto user_parting = [&] { return Parting{m_.parting->point, m_.parting->normal.normalized(), 0}; };
  const Parting parting1 = m_.parting ? user_parting() : choose_parting(out_.groove.mesh, pull_);
  Parting parting2 = m_.parting ? user_parting() : choose_parting(body, pull_);
  // With a draft both shots share shot 1's plane (see draft.hpp), and both cavities are made again drafted.
  SurfaceMesh shot2_cavity = body;
  double shot2_volume = body_volume;
  bool shot2_adaptive = false;
  if (m_.draft_deg > 0) {
    draft_ = draft_for(body, pull_, parting1.point, m_.draft_deg * units::degree, m_.voxel);
    parting2 = parting1;
    GrooveBody drafted;
    carve(kGrooveAdaptivity, &drafted);
    shot2_cavity = drafted.mesh;
    shot2_volume = drafted.volume;
    shot2_adaptive = drafted.adaptivity > 0;
    // The sockets reach end_channel_length beyond the drafted skin.
    for (Channel& c : channels_) c.socket += draft_->offset(c.start.dot(pull_));
    out_.draft_offset = draft_->most();
    log_.info(fmt::format(
        "draft {}°: cavities grown by up to {:.2f} mm at the parting plane; the body takes {:.2f} mL more silicone",
        m_.draft_deg, draft_->most() / units::mm, (shot2_volume - body_volume) / units::mL));
  }
  progress_.checkpoint(0.2, "sampling what each shot fills");
  auto started = Clock::now();
  regions_ = fill_regions(shot2_cavity, lines_, out_.groove_radius, job_.muscle_diameter / 2, pull_,
                          fill_voxel(m_.voxel, out_.groove_radius), draft_ ? draft_->slope : 0);
  log_.info(fmt::format("fill regions: {} and {} voxels of {:.2f} mm (shots 1 and 2) in {:.2f} s",
                        regions_.shot1.count(), regions_.shot2.count(), regions_.shot1.voxel / units::mm,
                        since(started)));
  std::vector<std::string> failures = make_shot("shot1", out_.groove.mesh, parting1, g3_ * out_.groove.volume, {});
  if (!failures.empty() && out_.groove.adaptivity > 0 && too_big_.empty()) {
    log_.info(fmt::format(
        "shot 1 from the adaptive groove body mesh failed its checks ({}); meshing the groove body uniformly",
        failures.front()));
    out_.parts.clear();
    carve(0);
    failures = make_shot("shot1", out_.groove.mesh, parting1, g3_ * out_.groove.volume, {});
  }
  const auto shot2_silicone = [&] {
    return std::max(0.0, g3_ * shot2_volume - out_.groove.volume - muscle_volume_ + sleeves);
  };
  std::vector<std::string> shot2 = make_shot("shot2", shot2_cavity, parting2, shot2_silicone(), channels_);
  if (!shot2.empty() && shot2_adaptive && too_big_.empty()) {
    log_.info(fmt::format("shot 2 from the adaptive drafted body mesh failed its checks ({}); meshing it uniformly",
                          shot2.front()));
    std::erase_if(out_.parts, [](const CheckedPart& p) { return p.shot == "shot2"; });
    const GrooveBody drafted = groove_body(body, {}, out_.groove_radius, pull_, m_.voxel, 0, &*draft_);
    shot2_cavity = drafted.mesh;
    shot2_volume = drafted.volume;
    shot2 = make_shot("shot2", shot2_cavity, parting2, shot2_silicone(), channels_);
  }
  failures.insert(failures.end(), shot2.begin(), shot2.end());
  failures.insert(failures.end(), fill_failures_.begin(), fill_failures_.end());

  // The cast silicone's thinnest places at the grooves; the stretches near an end on the skin are
  // exempt as in groove_problem.
  progress_.checkpoint(0.9, "measuring the silicone's thickness");
  started = Clock::now();
  out_.thickness = silicone_thickness(out_.groove.mesh, shot2_cavity, lines_, out_.groove_radius,
                                      job_.muscle_diameter / 2, pull_, m_.voxel, job_.exits);
  const SiliconeThickness& t = out_.thickness;
  // A thickness is +∞ where none was measured: no web thinner than the scan's depth, no muscle
  // outside its exit stretches. It then has no place.
  const auto thinnest = [&](double thickness, const Eigen::Vector3d& at, const std::string& otherwise) {
    return std::isfinite(thickness)
               ? fmt::format("{:.2f} mm near {}", thickness / units::mm, format_mm(out_.scaled(at)))
               : otherwise;
  };
  log_.info(fmt::format(
      "silicone: {} at the thinnest groove wall, {} over the muscles at the thinnest; in {:.2f} s",
      thinnest(t.groove_web, t.groove_web_at, fmt::format("over {:.0f} mm", kThickestMeasuredWeb / units::mm)),
      thinnest(t.overmold, t.overmold_at, "nothing measured"), since(started)));
  if (t.groove_web < m_.min_silicone - kPlacementTolerance)
    failures.push_back(
        fmt::format("shot1: the cast's silicone is {:.3f} mm thin between a groove and the skin near {}, below [mold] "
                    "min_silicone = {:.3f} mm: move the fiber away from the skin there",
                    t.groove_web / units::mm, format_mm(out_.scaled(t.groove_web_at)), m_.min_silicone / units::mm));
  if (t.overmold < m_.min_silicone)
    failures.push_back(fmt::format(
        "shot2: the overmold is {:.2f} mm thin over a muscle near {}, below [mold] min_silicone = {:.2f} mm: "
        "move the fiber deeper there",
        t.overmold / units::mm, format_mm(out_.scaled(t.overmold_at)), m_.min_silicone / units::mm));
  out_.failures = std::move(failures);
  return std::move(out_);
}

} // namespace

double groove_radius(double muscle_diameter, const MoldOptions& options)
{
  return muscle_diameter / 2 + options.groove_clearance;
}

double mold_line_step(const MoldOptions& options) { return std::min(0.5e-3, options.voxel * 2); }

std::optional<std::string> groove_problem(const std::vector<Eigen::Vector3d>& line, const SurfaceDistance& skin,
                                          double need, const std::string& terms, const Eigen::Vector3d& pull,
                                          const ExitStretches& exits)
{
  const std::vector<bool> beyond = beyond_skin_ends(line, exits);
  for (std::size_t k = 0; k < line.size(); ++k) {
    const Eigen::Vector3d& p = line[k];
    const auto at = skin.closest(p);
    const bool near_end = !beyond[k];
    if (!at.inside && !near_end)
      return fmt::format("the fiber (as routed in fibers.json) leaves the body at {}", format_mm(p));
    if (near_end) continue;
    const Eigen::Vector3d to_skin = at.point - p;
    if (at.distance < need - kPlacementTolerance && to_skin.dot(pull.normalized()) < 0.7 * at.distance)
      return fmt::format(
          "the fiber (as routed in fibers.json) passes {:.3f} mm from the skin at {}: its groove needs {:.3f} mm ({})",
          at.distance / units::mm, format_mm(p), need / units::mm, terms);
  }
  return std::nullopt;
}

TwoShotMolds two_shot_molds(const MoldJob& job, const MoldOptions& options, Progress& progress, const MoldLog& log)
{
  return Recipe(job, options, progress, log).make();
}

} // namespace fibermold
