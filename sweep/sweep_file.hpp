#pragma once
// The sweep file (sweep.toml, docs/sweep.md): a base design and the design-file keys to vary,
// as the full product of their [axes] or as listed [[case]]s, optionally with random restarts of
// the initial routing. Validated like a design file: every problem at once as file:line:column.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace fibermold {

/// One design-file key and its value, as TOML text ("4", "[[0, 0, 0], [60, 0, 0]]").
struct SweepValue {
  std::string key;   ///< "mold.wall", "fiber.m1.points"
  std::string value; ///< TOML
  int line = 0, column = 0;
};

struct SweepRestarts {
  int count = 0; ///< restarts 0..count-1; 0 is the routing as written
  std::uint64_t seed = 1;
  double amplitude = 2;            ///< mm: interior control points move this far at most
  std::vector<std::string> fibers; ///< empty: every fiber
  int line = 0;                    ///< of [restarts].fibers, for errors
};

struct SlurmOptions {
  std::string partition, time;    ///< empty: the cluster's defaults
  int cpus_per_task = 0;          ///< 0: the cluster's default
  std::vector<std::string> extra; ///< more sbatch flags, e.g. "--mem=4G"
};

struct SweepFile {
  std::filesystem::path file;                 ///< absolute
  std::filesystem::path base;                 ///< the base design, absolute
  std::string name;                           ///< [sweep] name, default the file's stem
  std::vector<std::string> axes;              ///< the keys varied, in order (plus "restart" with restarts)
  std::vector<std::vector<SweepValue>> cases; ///< each case's values (the product already taken)
  SweepRestarts restarts;
  SlurmOptions slurm;
};

/// True for a value that can go into an #SBATCH line: letters, digits, '-', '_', '.', ':', ','.
bool is_slurm_word(const std::string& value);

/// Parses and validates `path`. Throws InputError listing every problem.
SweepFile load_sweep(const std::filesystem::path& path);

} // namespace fibermold
