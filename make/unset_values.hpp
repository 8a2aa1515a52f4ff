#pragma once
// The house rule that no output holds a value nobody computed, kept by the runner: a stage's text
// outputs are read before they are committed, and a "nan" or "inf" where a number belongs (what
// fmt prints for a NaN or an infinity), or a JSON `null` (what nlohmann writes for one), fails the
// stage instead of reaching a user. Session 45's casting sheet said "a socket 4.0 mm wide reaching
// nan mm beyond the skin": the export stage read a design key it had not declared (design_view.hpp
// gives such keys NaN so that a use shows), and no test read that sentence.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "design/design.hpp"

namespace fibermold {

/// The first unset value in `text`, as "line L: …context…", or nothing: a design value the stage read
/// without declaring it ("<undeclared fiber.name>", HTML's "&lt;undeclared …", or the undeclared int
/// -2147483648), or the word "nan", "inf" (either after a '-') or, where `json_null`, "null", standing
/// alone (not inside a longer word: "info", "nano", "nullable" are words). A word inside a run of 40 or
/// more base64 characters (report.html's meshes) or inside one of `own` where it stands (the user's
/// names and paths: own_text) is not a value. JavaScript's "NaN" and "null" in report.html's script are
/// code: HTML is read with json_null false, and the match is lower case.
std::optional<std::string> unset_value(std::string_view text, bool json_null, const std::vector<std::string>& own = {});

/// unset_value over a file the runner commits: JSON with `null` counted, text, HTML, CSV, VTU and
/// OBJ without; every other kind (STL, 3MF: binary) is not read.
std::optional<std::string> unset_value_in(const std::filesystem::path& file, const std::vector<std::string>& own = {});

/// The text of `d` a user chose, which outputs quote: the design's name, its file's and surface's paths,
/// the build folder's, the names of its fibers, tracking curves, fixed regions and targets.
std::vector<std::string> own_text(const Design& d, const std::filesystem::path& build_dir);

} // namespace fibermold
