#pragma once
// `weft measure`: simulate a scene without rendering and measure its drape frame by frame — the
// settle time, the drape coefficient, the outline r(θ) and the fold count (app/run/measure.h,
// docs/measure.md).

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "app/cli/command.h"
#include "app/cli/options.h"
#include "app/run/measure.h"

namespace weft::app {

struct MeasureOptions {
  std::optional<std::filesystem::path> scene;  // empty: the built-in default scene
  std::optional<std::filesystem::path> out;    // default: out/<scene name>
  std::vector<Setting> overrides;              // --set, --frames (scene patches, command.h)
  std::optional<int> threads;                  // --threads (command.h)
  bool require_drape = false;  // --drape: a scene without a support is an error
  // --until-settled [MAX]: simulate until settled (settled_for), at most MAX s of simulated
  // time instead of output.frames.
  std::optional<double> until_settled_max_s;
  // --static: solve the rest shape instead of simulating the motion (app/run/rest_shape.h);
  // --seeds N: that many imperfection seeds (1…N), their spread reported.
  bool static_solve = false;
  int seeds = 1;
  std::string command_line;    // recorded in measure.txt
};

// Adds `weft measure` to the command line (with --photo: app/run/drape_photo.h).
Command register_measure(CLI::App& app, const std::string& command_line);

// Runs the job; bad input throws InputError before anything is written.
int run_measure(const MeasureOptions& options);
// The --static job (measure_static.cpp): static.csv with one row per seed, outline.csv of the
// first, and the table with each measure's spread over the seeds.
int run_measure_static(const MeasureOptions& options);

}  // namespace weft::app
