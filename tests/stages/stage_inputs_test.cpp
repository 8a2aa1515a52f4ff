// What each stage reads of the design (docs/architecture.md, "Stages"): the keys it declares,
// through its view (design/design_view.hpp), and nothing else; the runner hashes the same keys.

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "design/design_file.hpp"
#include "design/design_view.hpp"
#include "make/runner.hpp"
#include "stages/stages.hpp"

namespace fibermold {
namespace {

namespace fs = std::filesystem;

std::vector<fs::path> example_designs()
{
  std::vector<fs::path> out;
  for (const auto& entry : fs::recursive_directory_iterator(fs::path(FIBERMOLD_SOURCE_DIR) / "examples"))
    if (entry.path().extension() == ".toml" && entry.path().filename() != "sweep.toml") out.push_back(entry.path());
  std::sort(out.begin(), out.end());
  return out;
}

/// The view part that holds design value `key` ("[mold].wall" → "mold.wall"), or "".
std::string part_of(const std::string& key)
{
  for (const std::string& part : design_view_parts())
    if (design_key_matches(key, part)) return part;
  return "";
}

TEST(StageInputs, EveryKeyOfEveryExampleLiesInAViewPart)
{
  const std::vector<fs::path> designs = example_designs();
  ASSERT_GE(designs.size(), 9u);
  std::set<std::string> used;
  for (const fs::path& file : designs) {
    const Design d = load_design(file);
    for (const auto& [key, value] : d.values) {
      EXPECT_NE(part_of(key), "") << file << ": " << key << " is in no part of design_view.cpp: no stage could see it";
      used.insert(part_of(key));
    }
  }
  // Every part is a key of the file: each example records every key, given or defaulted.
  for (const std::string& part : design_view_parts())
    EXPECT_TRUE(used.contains(part)) << part << " matches no key of any example";
}

TEST(StageInputs, EveryDeclaredKeyIsAPartAndEveryPartIsReadBySomeStage)
{
  std::set<std::string> read;
  for (const auto& stage : shipped_stages())
    for (const std::string& prefix : stage->design_keys()) {
      bool selects = false;
      for (const std::string& part : design_view_parts())
        if (view_part_under(part, prefix)) selects = true, read.insert(part);
      EXPECT_TRUE(selects) << stage->name() << " declares \"" << prefix << "\", which is no key of the design file";
    }
  for (const std::string& part : design_view_parts())
    EXPECT_TRUE(read.contains(part)) << part << " is read by no stage: editing it would change nothing";
}

/// For every key of every example, edited: the stages whose hashed values change are exactly those
/// whose view holds the key's part. The two come from different places (the parts' copies of
/// struct members; the values' keys), so a part that copies a member under the wrong key, or a
/// value recorded under a key no part holds, fails here.
TEST(StageInputs, EditingEveryKeyMakesStaleExactlyTheStagesThatSeeIt)
{
  const auto stages = shipped_stages();
  int edits = 0;
  for (const fs::path& file : example_designs()) {
    const Design d = load_design(file);
    for (const auto& [key, value] : d.values) {
      Design edited = d;
      edited.values[key] = value + " (edited)";
      for (const auto& stage : stages) {
        const std::vector<std::string> keys = stage->design_keys_used(d);
        const bool stale = design_view(edited, keys).values != design_view(d, keys).values;
        bool sees = false;
        for (const std::string& prefix : keys) sees = sees || view_part_under(part_of(key), prefix);
        EXPECT_EQ(stale, sees) << file.filename() << ": editing " << key << " " << (stale ? "makes" : "leaves") << " "
                               << stage->name()
                               << (stale ? " stale, though its view does not hold it"
                                         : " fresh, though its view holds it");
      }
      ++edits;
    }
  }
  std::printf("stage inputs: %d keys edited across the examples\n", edits);
  EXPECT_GT(edits, 500);
}

/// A view holds what its stage declares and undeclared values (design/undeclared_value.hpp) for the rest.
TEST(StageInputs, AViewHoldsTheDeclaredValuesAndUndeclaredOnesForTheRest)
{
  const Design d = load_design(fs::path(FIBERMOLD_SOURCE_DIR) / "examples/walking-robot/design.toml");
  const Design defaults;
  ASSERT_NE(d.mold.block.sprue_diameter, defaults.mold.block.sprue_diameter);
  ASSERT_NE(d.collide.clearance, 0.0);
  ASSERT_FALSE(d.fibers.empty());
  const Design molds = design_view(d, {"mold", "muscle.diameter"});
  EXPECT_EQ(molds.mold.block.sprue_diameter, d.mold.block.sprue_diameter);
  EXPECT_EQ(molds.muscle.model.diameter, d.muscle.model.diameter);
  EXPECT_TRUE(std::isnan(molds.muscle.max_pressure));
  EXPECT_TRUE(std::isnan(molds.collide.clearance));
  ASSERT_EQ(molds.fibers.size(), 1u);
  EXPECT_EQ(molds.fibers[0].name, "<undeclared fiber>");
  ASSERT_EQ(molds.targets.size(), 1u);
  EXPECT_EQ(molds.targets[0].name, "<undeclared target>");
  EXPECT_EQ(molds.design.surface, fs::path("<undeclared design.surface>"));
  EXPECT_EQ(molds.file, d.file);
  EXPECT_EQ(molds.places, d.places);
  for (const auto& [key, value] : molds.values)
    EXPECT_TRUE(design_key_matches(key, "mold") || design_key_matches(key, "muscle.diameter")) << key;
  EXPECT_EQ(molds.values.count("[muscle].max_pressure"), 0u);
}

/// docs/architecture.md's stage table, row by row: each stage's upstream stages and the design keys
/// it declares are the code's (Stage::upstream, Stage::design_keys), so that the table cannot drift.
TEST(StageInputs, TheArchitectureDocsStageTableIsTheCodes)
{
  std::ifstream in(fs::path(FIBERMOLD_SOURCE_DIR) / "docs" / "architecture.md");
  const std::regex row(R"(^\| (\w+) \| ([^|]+) \| ([^|]+) \|$)"), key("`([a-z_.]+)`");
  std::map<std::string, std::pair<std::string, std::set<std::string>>> table; // stage → upstream, keys
  for (std::string line; std::getline(in, line);) {
    std::smatch m;
    if (!std::regex_match(line, m, row) || m[1] == "stage" || m[1] == "folder") continue;
    std::set<std::string> keys;
    const std::string listed = m[3].str().substr(0, m[3].str().find(" ("));
    for (auto it = std::sregex_iterator(listed.begin(), listed.end(), key); it != std::sregex_iterator(); ++it)
      keys.insert((*it)[1]);
    table[m[1]] = {m[2], keys};
  }
  const auto stages = shipped_stages();
  ASSERT_EQ(table.size(), stages.size()) << "docs/architecture.md's stage table has a row per stage";
  for (const auto& s : stages) {
    ASSERT_TRUE(table.contains(s->name())) << s->name() << " has no row";
    const auto& [upstream, keys] = table.at(s->name());
    const std::vector<std::string> declared = s->design_keys();
    EXPECT_EQ(keys, std::set<std::string>(declared.begin(), declared.end())) << s->name() << "'s design keys";
    std::string code = s->upstream().empty() ? "—" : "";
    for (const std::string& u : s->upstream()) code += (code.empty() ? "" : ", ") + u;
    if (s != stages.back()) {
      EXPECT_EQ(upstream, code) << s->name() << "'s upstream";
    }
  }
  EXPECT_EQ(table.at("export").first, "all") << "the last stage reads every stage's outputs";
}

} // namespace
} // namespace fibermold
