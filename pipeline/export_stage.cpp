#include "pipeline/export_stage.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "core/atomic_file.hpp"
#include "core/units.hpp"
#include "export/lay_flat.hpp"
#include "export/stl_writer.hpp"
#include "export/three_mf_writer.hpp"
#include "mesh/surface_import.hpp"

namespace fibermold {

namespace {

using Json = nlohmann::ordered_json;

std::string casting_guide(const std::string& design, const Json& shots, const std::string& format)
{
  const std::string ext = "." + format, FORMAT = format == "3mf" ? "3MF file" : "STL";
  const auto ml = [&](const char* shot) { return shots[shot]["silicone_volume_mL"].get<double>(); };
  const auto g = [&](const char* shot) { return shots[shot]["silicone_mass_g"].get<double>(); };
  return fmt::format(R"(fibermold mold parts for "{}"

Print every {} as it lies (each stands on its largest flat face; units mm).

Shot 1, the grooved body: shot1-lower{} and shot1-upper{}.
  Close the two halves on their keys, clamp them, inject about {:.1f} mL ({:.1f} g) of silicone
  through the sprue hole at the bottom until it rises out of the vents, and let it cure.
  Demold: the body has an open groove for each muscle.

Lay each muscle into its groove, its ends and supply tubes along the grooves' ends.

Shot 2, the overmold: shot2-lower{} and shot2-upper{}.
  Put the grooved body with its muscles into the lower half, route the supply tubes out through
  the channels at the fibers' ends, close, clamp, inject about {:.1f} mL ({:.1f} g) of silicone
  through the sprue until it rises out of the vents, and let it cure.

manifest.json lists each part's size, volume and checks.
)",
                     design, FORMAT, ext, ext, ml("shot1"), g("shot1"), ext, ext, ml("shot2"), g("shot2"));
}

} // namespace

void ExportStage::run(StageContext& ctx) const
{
  const Design& d = ctx.design;
  const Json molds = Json::parse(read_file(ctx.upstream("molds", "report.json")));
  Json parts = Json::array();
  for (const auto& [name, info] : molds["parts"].items()) {
    ctx.progress.checkpoint(-1, "laying out " + name);
    const SurfaceMesh part = import_surface(ctx.upstream("molds", info["file"].get<std::string>()), units::mm);
    const Placement placed = lay_flat(part, d.export_.printer_volume);
    Json files = Json::array();
    for (const std::string& format : d.export_.formats) {
      const std::string file = name + "." + format;
      if (format == "3mf") write_3mf(ctx.output_dir / file, placed.part, name);
      else write_stl(ctx.output_dir / file, placed.part, fmt::format("fibermold {} {} (mm)", d.design.name, name));
      files.push_back(file);
    }
    parts.push_back({{"name", name},
                     {"shot", info["shot"]},
                     {"file", files[0]},
                     {"files", files},
                     {"size_mm", {placed.size.x() / units::mm, placed.size.y() / units::mm, placed.size.z() / units::mm}},
                     {"lies_on_mm2", placed.flat_area / 1e-6},
                     {"fits_printer_as_placed", placed.fits},
                     {"volume_mL", info["volume_mL"]},
                     {"triangles", placed.part.num_faces()},
                     {"min_wall_mm", info["min_wall_mm"]},
                     {"checks_passed", info["checks_passed"]}});
    if (!placed.fits)
      ctx.log.warn("part {} does not fit the printer lying flat; its best fit turns it: axes {}", name, info["print_axes"].dump());
  }
  Json shots = Json::object();
  for (const auto& [shot, info] : molds["shots"].items())
    shots[shot] = {{"silicone_volume_mL", info["silicone_volume_mL"]}, {"silicone_mass_g", info["silicone_mass_g"]}};
  const Json manifest{{"design", d.design.name}, {"units", "mm"}, {"voxel_mm", molds["voxel_mm"]}, {"parts", parts}, {"shots", shots}};
  write_file_atomic(ctx.output_dir / "manifest.json", manifest.dump(2) + "\n");
  write_file_atomic(ctx.output_dir / "README.txt", casting_guide(d.design.name, molds["shots"], d.export_.formats.front()));
}

} // namespace fibermold
