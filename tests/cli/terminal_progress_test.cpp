// Progress off a TTY (a log file, a pipe, a Slurm job's output): a line per tenth of the work or
// per new message, and a solver's iterations, whose messages differ only in their numbers, not each.
#include <cstdio>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "cli/terminal_progress.hpp"

namespace fibermold {
namespace {

/// What `updates` print off a TTY.
template <class F> std::string printed(F&& updates)
{
  std::FILE* out = std::tmpfile();
  {
    TerminalProgress progress("targets", out, false);
    updates(progress);
  }
  std::rewind(out);
  std::string text;
  for (int c; (c = std::fgetc(out)) != EOF;) text += static_cast<char>(c);
  std::fclose(out);
  return text;
}

TEST(TerminalProgress, OffATtyASolversIterationsPrintOneLineNotOneEach)
{
  const std::string text = printed([](Progress& p) {
    p.update(0, "target bend");
    for (int k = 0; k < 20; ++k)
      p.update(-1, fmt::format("Newton iteration {}: |∇E| = {:.3e} N{}", k, 1.0 / (k + 1), k % 2 ? ", reused" : ""));
    p.update(0.5, "target twist");
    p.update(-1, "checking shot1-lower");
    p.update(-1, "checking shot1-upper");
  });
  EXPECT_EQ(text, "[targets]   0% target bend\n"
                  "[targets] Newton iteration 0: |∇E| = 1.000e+00 N\n"
                  "[targets]  50% target twist\n"
                  "[targets] checking shot1-lower\n"
                  "[targets] checking shot1-upper\n");
}

TEST(TerminalProgress, OffATtyEveryLineWithAFractionPrints)
{
  const std::string text = printed([](Progress& p) {
    for (int k = 0; k <= 20; ++k) p.update(k / 20.0, fmt::format("iteration {}", k));
    p.update(1, "writing target pose1");
    p.update(1, "writing target pose2");
  });
  int lines = 0;
  for (char c : text) lines += c == '\n';
  EXPECT_EQ(lines, 23) << text;
}

} // namespace
} // namespace fibermold
