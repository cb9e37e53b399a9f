#pragma once
// weft sweep's results, however its points ran — one after another here, or as the tasks of a
// Slurm job array (app/sweep/sweep_point.h): each point's outcome (SweepRun), and the one merge that
// compares them with the reference run and writes sweep.csv, sweep.png and the table on stdout.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "app/scene/scene.h"
#include "app/scene/scene_patch.h"
#include "sim/grid.h"

namespace weft::app {

struct SweepRun {
  std::vector<Setting> settings;
  Scene scene;
  // Results.
  double wall_s = 0.0;  // simulation (advance) wall time, set-up excluded
  long steps = 0;
  double time_step_s = 0.0;  // the step the simulator used
  bool diverged = false;
  bool failed = false;      // no result: it threw, or its Slurm task did not finish
  std::string failure;      // the divergence or failure message
  sim::ClothMesh mesh;      // its rest shape and material coordinates
  sim::Matrix3X x;          // #V×3 positions at the last frame, metres
  double max_strain = 0.0;  // largest warp/weft strain at any frame end
  // Errors against the reference.
  double rms_error_m = 0.0;
  double silhouette_difference = 0.0;
  bool pareto = false;
};

// Simulates the run's scene (its frames through the frame stream, as `weft run` does) and fills
// its results; the wall time is advance()'s only. Throws what make_simulator throws.
void simulate(SweepRun& run);

struct SweepMerge {
  const Scene* base = nullptr;         // the scene swept (its name, source and text)
  std::vector<SettingValues> values;   // the --set options
  std::optional<int> reference;        // --reference
  std::string command_line;            // recorded in run.txt
  std::filesystem::path dir;           // the output folder
};

// Compares the runs with the reference run, writes DIR/{sweep.csv, sweep.png, scene.json,
// run.txt} and prints the table, the reference, the Pareto front and the failed runs. Returns
// exit_ok, exit_diverged when no run finished, exit_failure when a run failed. Throws InputError
// for a --reference run that did not finish.
int merge_sweep(std::vector<SweepRun>& runs, const SweepMerge& merge);

// A run's settings as the short label of the plot and progress lines: "resolution=[9,9] ...".
std::string sweep_label(const SweepRun& run, const std::vector<SettingValues>& values);

}  // namespace weft::app
