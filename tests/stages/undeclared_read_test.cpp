// A stage that reads a design value it did not declare fails (docs/architecture.md, "Stages"): the
// runner hands it a view (design/design_view.hpp) whose undeclared values make a use fail, so that
// the read shows at once instead of passing the default for the design's setting.

#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/json_file.hpp"
#include "core/units.hpp"
#include "design/design_file.hpp"
#include "make/runner.hpp"
#include "test_support.hpp"

namespace fibermold {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;
using ::testing::HasSubstr;

/// A stage that writes what `read` makes of the design it sees into read.json, declaring `keys`.
class ReadingStage final : public Stage {
public:
  ReadingStage(std::vector<std::string> keys, std::function<Json(const Design&)> read)
      : keys_(std::move(keys)), read_(std::move(read))
  {
  }
  std::string name() const override { return "reads"; }
  std::vector<std::string> design_keys() const override { return keys_; }
  void run(StageContext& ctx) const override
  {
    write_json_atomic(ctx.output_dir / "read.json", Json{{"read", read_(ctx.design)}});
  }

private:
  std::vector<std::string> keys_;
  std::function<Json(const Design&)> read_;
};

// What the stage reads: a number ([mold] wall), an array section (the [[fiber]]s' lengths) and a path
// (the surface's size).
Json mold_wall_mm(const Design& d) { return d.mold.block.wall / units::mm; }
Json fiber_lengths_mm(const Design& d)
{
  Json lengths = Json::array();
  for (const Fiber& f : d.fibers) {
    double length = 0;
    for (std::size_t i = 1; i < f.points.size(); ++i) length += (f.points[i] - f.points[i - 1]).norm();
    lengths.push_back(length / units::mm);
  }
  return lengths;
}
Json surface_bytes(const Design& d) { return fs::file_size(d.design.surface); }

class UndeclaredReadTest : public ::testing::Test {
protected:
  void SetUp() override
  {
    test::write_text(dir_ / "body.stl", "solid body\nendsolid body\n");
    test::write_text(dir_ / "design.toml", R"([design]
surface = "body.stl"
[[fiber]]
name = "m1"
points = [[0, 0, 0], [30, 40, 0]]
[mold]
wall = 5
)");
  }

  /// Makes the one stage `stage` with the design: what it wrote, or throws what make threw.
  Json make(std::unique_ptr<Stage> stage)
  {
    std::vector<std::unique_ptr<Stage>> stages;
    stages.push_back(std::move(stage));
    const Runner runner(std::move(stages), "fibermold test");
    build_ = dir_ / ("build" + std::to_string(++builds_)); // a fresh build folder: the stage runs
    runner.make(load_design(dir_ / "design.toml"), {build_, {}, false});
    return Json::parse(test::read_text(build_ / "reads" / "read.json")).at("read");
  }

  /// What make throws when the stage declares `keys` and reads `read`; empty when it does not throw.
  std::string failure(std::vector<std::string> keys, std::function<Json(const Design&)> read)
  {
    try {
      make(std::make_unique<ReadingStage>(std::move(keys), std::move(read)));
    } catch (const std::exception& e) {
      return e.what();
    }
    return "";
  }

  test::TempDir dir_;
  fs::path build_;
  int builds_ = 0;
};

TEST_F(UndeclaredReadTest, ANumberReadUndeclaredFailsTheStageAndDeclaredIsTheDesigns)
{
  EXPECT_EQ(make(std::make_unique<ReadingStage>(std::vector<std::string>{"mold.wall"}, mold_wall_mm)), Json(5.0));
  EXPECT_EQ(make(std::make_unique<ReadingStage>(std::vector<std::string>{"mold"}, mold_wall_mm)), Json(5.0));
  // Declaring the voxel is not declaring the wall: the wall is NaN, which read.json refuses.
  EXPECT_THAT(failure({"mold.voxel"}, mold_wall_mm), HasSubstr("read.json: /read is not a finite number"));
  EXPECT_THAT(failure({}, mold_wall_mm), HasSubstr("read.json: /read is not a finite number"));
  EXPECT_FALSE(fs::exists(build_ / "reads" / "read.json")) << "a failed stage writes nothing";
}

TEST_F(UndeclaredReadTest, AnArraySectionReadUndeclaredFailsTheStageAndDeclaredIsTheDesigns)
{
  EXPECT_EQ(make(std::make_unique<ReadingStage>(std::vector<std::string>{"fiber"}, fiber_lengths_mm)),
            Json::array({50.0}));
  // Undeclared, the fibers are not none (a loop over none would write [] and pass): one fiber of NaN.
  EXPECT_THAT(failure({"target"}, fiber_lengths_mm), HasSubstr("read.json: /read/0 is not a finite number"));
}

TEST_F(UndeclaredReadTest, APathReadUndeclaredFailsTheStageAndDeclaredIsTheDesigns)
{
  EXPECT_EQ(make(std::make_unique<ReadingStage>(std::vector<std::string>{"design.surface"}, surface_bytes)),
            Json(fs::file_size(dir_ / "body.stl")));
  EXPECT_THAT(failure({"design.units"}, surface_bytes), HasSubstr("<undeclared design.surface>"));
}

} // namespace
} // namespace fibermold
