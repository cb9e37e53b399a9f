#pragma once
// `weft sweep`: runs a scene over a grid of settings and measures the speed/accuracy trade —
// wall time against the error from the most accurate run — as sweep.csv, sweep.png and a table
// with the Pareto-optimal settings.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "app/cli/command.h"
#include "app/cli/options.h"

namespace weft::app {

struct SweepOptions {
  std::optional<std::filesystem::path> scene;  // empty: the built-in default scene
  std::vector<std::string> set;                // each "KEY=V1,V2,…" (app/scene/scene_patch.h)
  std::optional<std::filesystem::path> out;    // default: out/sweep-<scene name>
  std::vector<Setting> overrides;              // --frames: patched into every run (command.h)
  std::optional<int> threads;                  // --threads (command.h)
  // 1-based row of the run the others are compared with; default: the finished run with the
  // largest wall time (taken as the most accurate).
  std::optional<int> reference;
  std::string command_line;                    // recorded in run.txt
  // Slurm (docs/cluster.md): --slurm writes OUT/slurm/sweep.sbatch, an array of one task per
  // point, and OUT/slurm/collect.sbatch, which merges their results after them; the tasks run
  // --point K, the collect job --collect (app/sweep/sweep_point.h).
  bool slurm = false;
  bool dry_run = false;           // with slurm: write and print the scripts, submit nothing
  std::optional<int> point;       // run only this point (1-based) and leave its result
  bool collect = false;           // merge the points' results
};

// Adds `weft sweep` to the command line.
Command register_sweep(CLI::App& app, const std::string& command_line);

// Runs the sweep; returns an ExitCode (app/io/exit_code.h): exit_ok, exit_diverged when every
// run diverged, exit_failure when a run failed (it threw, or its Slurm task left no result: the
// others are still merged). Bad input (a --set key or value, --frames, --threads, --reference) throws InputError
// before anything is simulated or written.
int run_sweep(const SweepOptions& options);

}  // namespace weft::app
