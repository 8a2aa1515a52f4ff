#include "fuzz.hpp"

#include <sys/wait.h>

#include <nlohmann/json.hpp>

#include "core/atomic_file.hpp"
#include "core/json_file.hpp"

namespace fibermold::test {

namespace fs = std::filesystem;

namespace {

struct Ran {
  int code = -1;
  std::string err;
};

/// The binary under test in `dir`, killed after `seconds` (SIGKILL: a SIGTERM would be honoured as
/// Ctrl-C, exit 130; timeout(1) then exits 137).
Ran run(const fs::path& dir, const std::string& arguments, int seconds)
{
  const fs::path err = dir / "stderr.txt";
  const std::string command = "cd '" + dir.string() + "' && timeout -s KILL " + std::to_string(seconds) +
                              " '" FIBERMOLD_BINARY "' " + arguments + " </dev/null >/dev/null 2>'" + err.string() +
                              "'";
  const int status = std::system(command.c_str());
  Ran r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.err = read_file(err).substr(0, 600);
  return r;
}

std::string describe(const char* command, const Ran& r)
{
  if (r.code == 124 || r.code == 137) return std::string(command) + " hung (killed after its time limit)";
  if (r.code >= 128) return std::string(command) + " died of signal " + std::to_string(r.code - 128) + ": " + r.err;
  return std::string(command) + " exited " + std::to_string(r.code) + ": " + r.err;
}

/// The first JSON output under `dir` that is not JSON, or holds NaN or null (nlohmann writes NaN as null).
std::string bad_json(const fs::path& dir)
{
  std::error_code ec;
  if (!fs::exists(dir, ec)) return {};
  for (const auto& entry : fs::recursive_directory_iterator(dir, ec)) {
    if (!entry.is_regular_file() || entry.path().extension() != ".json") continue;
    const std::string rel = fs::relative(entry.path(), dir).string();
    if (rel.find(".staging") != std::string::npos) continue; // a killed stage's leftovers, not outputs
    const auto j = nlohmann::json::parse(read_file(entry.path()), nullptr, false);
    if (j.is_discarded()) return rel + " is not JSON";
    if (const auto at = first_non_finite(j)) return rel + " holds null or a non-finite number at " + *at;
  }
  return {};
}

} // namespace

FuzzRun fuzz_run(const fs::path& dir, bool make_too, int check_seconds, int make_seconds)
{
  FuzzRun result;
  const Ran check = run(dir, "check design.toml", check_seconds);
  result.check = check.code;
  if (check.code != 0 && check.code != 2) {
    result.problem = describe("check", check);
    return result;
  }
  if (check.code != 0 || !make_too) return result;
  const Ran make = run(dir, "make design.toml --build-dir out", make_seconds);
  result.make = make.code;
  if (make.code > 2)
    result.problem = describe("make", make);
  else if (make.code == 2)
    result.problem = "check passed, but make refused the input: " + make.err;
  else if (const std::string bad = bad_json(dir / "out"); !bad.empty())
    result.problem = bad;
  return result;
}

} // namespace fibermold::test
